//! FIRE (Bitzek et al. 2006) in mass-weighted coordinates, with its own adaptive step.

use super::{RelaxStep, StabiliseOptions, StabiliseReport};
use crate::error::BeltResult;
use crate::pipeline::Effects;
use crate::simulation::Simulation;

impl Simulation {
    pub(super) fn relax_fire(
        &mut self,
        effects: Effects,
        step: RelaxStep,
        options: &StabiliseOptions,
    ) -> BeltResult<StabiliseReport> {
        const N_MIN: u32 = 5;
        const F_INC: f64 = 1.1;
        const F_DEC: f64 = 0.5;
        const ALPHA_START: f64 = 0.1;
        const F_ALPHA: f64 = 0.99;
        let dt0 = step.dt;
        // The scaled masses put every degree of freedom at ωΔt ≤ 1 for Δt = dt0; allow
        // FIRE to grow the step up to 1.5·dt0 (still below the limit ωΔt = 2).
        let dt_max = 1.5 * dt0;
        let mut dt = dt0;
        let mut alpha = ALPHA_START;
        let mut positive = 0u32;
        let mut resets = 0;
        let mut residual = f64::INFINITY;
        for k in 0..options.max_steps {
            if let Some(done) =
                self.relax_evaluate(effects, step, k, options, &mut residual, resets)
            {
                return Ok(done);
            }
            // FIRE mixing on every degree of freedom.
            let (power, vnorm2, fnorm2) = self.fire_norms();
            if power > 0.0 {
                let mix = alpha * (vnorm2 / fnorm2.max(f64::MIN_POSITIVE)).sqrt();
                self.fire_mix(1.0 - alpha, mix);
                positive += 1;
                if positive > N_MIN {
                    dt = (dt * F_INC).min(dt_max);
                    alpha *= F_ALPHA;
                }
            } else {
                self.state.zero_velocities();
                resets += 1;
                positive = 0;
                dt = (dt * F_DEC).max(dt0);
                alpha = ALPHA_START;
            }
            self.limit_relaxation_move(dt);
            self.integrate(dt)?;
        }
        Ok(StabiliseReport {
            steps: options.max_steps,
            residual,
            converged: false,
            resets,
            interrupted: false,
            holding_torque: Vec::new(),
        })
    }

    /// FIRE works in mass-weighted coordinates (p = √m̃·v, g = F/√m̃), so that mixing the
    /// velocity towards the force never puts a light degree of freedom out of step.
    /// Returns (power F·v, |p|², |g|²).
    fn fire_norms(&self) -> (f64, f64, f64) {
        let (m, s, sc) = (&self.model, &self.state, &self.scratch);
        let (mut p, mut vv, mut ff) = (0.0, 0.0, 0.0);
        for ((v, f), mass) in s.velocity.iter().zip(&sc.force).zip(&self.inertia.mass) {
            p += v.dot(f);
            vv += mass * v.norm_squared();
            ff += f.norm_squared() / mass;
        }
        for &d in &m.dofs.rigid {
            let (f, v, mass) = (
                sc.rigid_force(m, d),
                s.rigid_speed(d),
                self.inertia.rigid(m, d),
            );
            p += v * f;
            vv += mass * v * v;
            ff += f * f / mass;
        }
        (p, vv, ff)
    }

    /// p ← keep·p + mix·g in mass-weighted coordinates: v ← keep·v + mix·F/m̃.
    fn fire_mix(&mut self, keep: f64, mix: f64) {
        let (m, s, sc) = (&self.model, &mut self.state, &self.scratch);
        for ((v, f), im) in s
            .velocity
            .iter_mut()
            .zip(&sc.force)
            .zip(&self.inertia.inv_mass)
        {
            *v = *v * keep + f * (mix * im);
        }
        for &d in &m.dofs.rigid {
            let (f, mass) = (sc.rigid_force(m, d), self.inertia.rigid(m, d));
            let v = s.rigid_speed_mut(d);
            *v = *v * keep + f * mix / mass;
        }
    }
}
