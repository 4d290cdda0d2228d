//! Kinetic-energy damping (thesis §6.2), each degree of freedom reset at its own peak.

use super::{RelaxStep, StabiliseOptions, StabiliseReport};
use crate::error::BeltResult;
use crate::pipeline::Effects;
use crate::simulation::Simulation;
use nalgebra::Vector2;

impl Simulation {
    pub(super) fn relax_kinetic(
        &mut self,
        effects: Effects,
        step: RelaxStep,
        options: &StabiliseOptions,
    ) -> BeltResult<StabiliseReport> {
        let mut resets = 0;
        let mut residual = f64::INFINITY;
        for k in 0..options.max_steps {
            if let Some(done) =
                self.relax_evaluate(effects, step, k, options, &mut residual, resets)
            {
                return Ok(done);
            }
            // Thesis §6.2 zeroes every velocity at a peak of the total kinetic energy. With
            // stiff contact the total is dominated by fast contact modes and the global
            // reset stalls the slow ones, so each degree of freedom is reset at its own
            // kinetic-energy peak (where its power F·v turns negative).
            resets += self.reset_at_local_peaks();
            self.limit_relaxation_move(step.dt);
            self.integrate(step.dt)?;
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

    /// Zero the speed of every degree of freedom whose power F·v is negative; returns how
    /// many were reset.
    fn reset_at_local_peaks(&mut self) -> u64 {
        let (m, s, sc) = (&self.model, &mut self.state, &self.scratch);
        let mut resets = 0;
        for (v, f) in s.velocity.iter_mut().zip(&sc.force) {
            if v.dot(f) < 0.0 {
                *v = Vector2::zeros();
                resets += 1;
            }
        }
        for &d in &m.dofs.rigid {
            let force = sc.rigid_force(m, d);
            let speed = s.rigid_speed_mut(d);
            if *speed * force < 0.0 {
                *speed = 0.0;
                resets += 1;
            }
        }
        resets
    }
}
