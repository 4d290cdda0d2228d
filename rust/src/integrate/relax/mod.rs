//! Static relaxation (thesis §6.2): the belt and takeups move to static equilibrium on
//! fictitious masses, with their own step and contact scale; simulated time does not
//! advance and the model is never written.
//!
//! - [`fire`]: FIRE (default), [`kinetic`]: kinetic-energy damping per degree of freedom.
//! - [`continuation`]: stiff contact is relaxed through a ladder of softer contacts.

mod continuation;
mod fire;
mod kinetic;

pub use continuation::{CONTINUATION_FACTOR, CONTINUATION_STAGES, CONTINUATION_START};

use super::Inertia;
use crate::error::{BeltError, BeltResult};
use crate::model::{Model, StableStep};
use crate::pipeline::{Effects, Scratch};
use crate::simulation::Simulation;
use crate::state::Rigid;

/// Static relaxation method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Relaxation {
    /// Kinetic-energy damping (thesis §6.2): velocities are zeroed at kinetic-energy
    /// peaks. Each degree of freedom is reset at its own peak (the thesis resets all at the
    /// peak of the total, which stalls with stiff contact; see `docs/statics.md`).
    #[default]
    KineticEnergy,
    /// FIRE (Bitzek et al. 2006): inertial relaxation that mixes the velocity towards the
    /// force and restarts when the power turns negative: same equilibrium, ~100× fewer steps.
    Fire,
}

/// Options of [`Simulation::stabilise`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StabiliseOptions {
    /// Method. Default [`Relaxation::Fire`].
    pub method: Relaxation,
    /// Keep belt friction on while relaxing (thesis §6.3 / fig. 6.6 locks in lower
    /// tensions). Default false.
    pub friction: bool,
    /// Converged when the largest out-of-balance force on any node or takeup is below this
    /// fraction of the largest element tension. Default 1e-7.
    pub tolerance: f64,
    /// Give up after this many steps. Default 5·10⁶.
    pub max_steps: u64,
}

impl Default for StabiliseOptions {
    fn default() -> Self {
        StabiliseOptions {
            method: Relaxation::Fire,
            friction: false,
            tolerance: 1e-7,
            max_steps: 5_000_000,
        }
    }
}

/// What [`Simulation::stabilise`] did.
#[derive(Debug, Clone, PartialEq)]
pub struct StabiliseReport {
    /// Relaxation steps taken.
    pub steps: u64,
    /// Final out-of-balance force relative to the largest tension.
    pub residual: f64,
    /// Whether the tolerance was met.
    pub converged: bool,
    /// Number of times the velocities were zeroed.
    pub resets: u64,
    /// Whether the caller's interrupt hook stopped it ([`crate::interrupt`]); the state is
    /// the last relaxation step's, at rest.
    pub interrupted: bool,
    /// Torque on each pulley from its holder at the last evaluation, N·m
    /// (counter-clockwise positive): with friction the relaxation holds a stopped
    /// conveyor's drives, brakes and holdbacks at rest ([`PulleyModel::rest_hold`]) and this
    /// is what each takes; 0 for a free pulley and without friction. Empty when not known
    /// (interrupted inside a recompile).
    ///
    /// [`PulleyModel::rest_hold`]: crate::model::PulleyModel::rest_hold
    pub holding_torque: Vec<f64>,
}

impl StabiliseReport {
    /// Continue this report with a later relaxation `r`: steps and resets add up, the
    /// residual and the verdict are the later one's.
    fn then(&mut self, r: StabiliseReport) {
        self.steps += r.steps;
        self.resets += r.resets;
        self.residual = r.residual;
        self.converged = r.converged;
        self.interrupted = r.interrupted;
        self.holding_torque = r.holding_torque;
    }
}

/// The relaxation's own settings for one stage: its step and contact scale (the model's
/// stay as compiled).
#[derive(Debug, Clone, Copy)]
struct RelaxStep {
    /// The step the fictitious masses are scaled for, s.
    dt: f64,
    /// Factor on every contact stiffness.
    contact_scale: f64,
}

impl Inertia {
    /// Fictitious masses m̃ = K·Δt² that put every degree of freedom at the same distance
    /// from its stability limit (ωΔt ≤ 1), as in Underwood's dynamic relaxation, for the
    /// stiffness bounds and step of `stable` (the model's contact scaled by
    /// `contact_scale`). K is the Gershgorin row sum: a node touching a moving (takeup)
    /// pulley is coupled to it through the contact stiffness, which adds an off-diagonal
    /// term to both rows, so the node bound gains one contact stiffness and the takeup
    /// bound doubles. Without those terms the node–takeup mode sits at ωΔt ≈ √2 and FIRE's
    /// longer steps turn it unstable.
    fn fictitious(model: &Model, stable: &StableStep, contact_scale: f64) -> Inertia {
        let dt2 = stable.dt * stable.dt;
        let takeup_contact = model
            .pulleys
            .iter()
            .filter(|p| p.takeup.is_some())
            .map(|p| p.contact_bound(contact_scale).0)
            .fold(0.0, f64::max);
        let mass: Vec<f64> = stable
            .node_stiffness_bound
            .iter()
            .map(|k| (k + takeup_contact) * dt2)
            .collect();
        let inv_mass: Vec<f64> = mass.iter().map(|m| 1.0 / m).collect();
        let takeup_mass = model
            .pulleys
            .iter()
            .enumerate()
            .map(|(j, p)| match &p.takeup {
                // A takeup without pulley contact feels only its pull: keep its true mass.
                Some(t) if stable.takeup_stiffness_bound[j] == 0.0 => t.moving_mass,
                Some(_) => 2.0 * stable.takeup_stiffness_bound[j] * dt2,
                None => f64::INFINITY,
            })
            .collect();
        // A rigid body's rotation keeps its body's ratio of inertia to mass, so that the
        // coupled translation-rotation modes of a body sit where its translation does.
        let body_inertia = (model.body_inertia.iter().enumerate())
            .map(|(i, inertia)| inertia * mass[i] / model.mass[i])
            .collect();
        Inertia {
            mass,
            same_inv_mass: crate::forces::all_same(&inv_mass),
            inv_mass,
            takeup_mass,
            body_inertia,
            physical: false,
        }
    }
}

impl Simulation {
    /// Relax to static equilibrium (thesis §6.2). Drives and brakes are off; friction is
    /// off unless `options.friction`, and with it the pulleys a stopped conveyor holds
    /// (drives, brakes, holdbacks: [`crate::model::PulleyModel::rest_hold`]) are held at
    /// rest. Both methods run on fictitious masses m̃ = K·Δt²
    /// (Underwood's dynamic relaxation), since time is not physical here; gravity still acts
    /// on the true masses. Simulated time does not advance. On return all velocities are zero.
    ///
    /// Stiff contact makes the relaxation ill-conditioned (the slow takeup mode moves the
    /// contact nodes, whose fictitious masses scale with the contact stiffness). When the
    /// contact is more than [`CONTINUATION_START`]× stiffer than the stiffest belt element,
    /// the relaxation is continued in contact stiffness: it starts at that ratio and
    /// multiplies the stiffness by [`CONTINUATION_FACTOR`] per stage up to the scene's
    /// value, each stage starting from the previous equilibrium. The report sums the steps.
    pub fn stabilise(&mut self, options: &StabiliseOptions) -> BeltResult<StabiliseReport> {
        if !(options.tolerance.is_finite() && options.tolerance > 0.0) {
            return Err(BeltError::invalid(
                "tolerance",
                options.tolerance,
                "must be > 0",
            ));
        }
        if !options.friction {
            self.check_downhill_pull()?;
        }
        let ladder = self.contact_continuation();
        if ladder.is_empty() {
            return self.relax(options, 1.0);
        }
        let stages = self.relax_softened(&ladder, options);
        self.scratch = Scratch::new(&self.model);
        self.inertia = Inertia::physical(&self.model, &self.state.node_mass);
        let mut total = stages?;
        let remaining = options.max_steps - total.steps;
        // Converged only once the scene's own stiffness has relaxed too.
        if total.converged {
            total.converged = false;
            if remaining > 0 {
                let r = self.relax(
                    &StabiliseOptions {
                        max_steps: remaining,
                        ..*options
                    },
                    1.0,
                )?;
                total.then(r);
            }
        }
        Ok(total)
    }

    /// Without belt friction nothing holds a closed node belt from running round its
    /// pulleys, so it has a static equilibrium only if gravity has no net pull along it.
    /// The belt's own weight has none (the loop is closed); bulk material on an incline or
    /// decline has m'_L·g·Δh/L per metre: the belt would run downhill for ever (a decline
    /// conveyor's carry strand, `docs/statics.md`). Refuse it up front: relative to the
    /// belt's weight, a pull above 1e-3 (a 40 m conveyor falling 6 m at 400 t/h: 0.08).
    /// With friction the drive, brake and holdback pulleys are held at rest
    /// (`Effects::hold_at_rest`) and friction on them holds it: not checked then.
    fn check_downhill_pull(&self) -> BeltResult<()> {
        let m = &self.model;
        let s = &self.state;
        let n = s.position.len();
        if m.ends.is_some() || m.is_rigid() || n < 3 {
            return Ok(());
        }
        let (mut pull, mut weight) = (0.0, 0.0);
        for i in 0..n {
            let t = s.position[(i + 1) % n] - s.position[(i + n - 1) % n];
            let len = t.norm();
            let w = s.node_mass[i] * m.gravity;
            weight += w;
            if len > 0.0 {
                pull += -w * t.y / len;
            }
        }
        if weight > 0.0 && pull.abs() > 1e-3 * weight {
            return Err(BeltError::invalid(
                "friction",
                false,
                format!(
                    "gravity pulls the belt round its pulleys with {:.4e} N (bulk material on \
                     an incline or decline) and without belt friction nothing holds it: no \
                     static equilibrium; start from the design state (no stabilise(): \
                     docs/design-start.md)",
                    pull.abs()
                ),
            ));
        }
        Ok(())
    }

    /// One relaxation with every contact stiffness scaled by `contact_scale`.
    fn relax(
        &mut self,
        options: &StabiliseOptions,
        contact_scale: f64,
    ) -> BeltResult<StabiliseReport> {
        let stable = self.model.stable_step(contact_scale)?;
        let step = RelaxStep {
            dt: stable.dt,
            contact_scale,
        };
        let (time, step_count) = (self.state.time, self.state.step);
        let effects = Effects {
            friction: options.friction,
            drives: false,
            quasi_static_friction: true,
            damping: false,
            // With friction, the drums of a stopped conveyor's drives and brakes stand
            // still (`PulleyModel::rest_hold`): friction on them holds the belt.
            hold_at_rest: options.friction,
        };
        self.state.zero_velocities();
        self.inertia = Inertia::fictitious(&self.model, &stable, contact_scale);
        let mut result = match options.method {
            Relaxation::KineticEnergy => self.relax_kinetic(effects, step, options),
            Relaxation::Fire => self.relax_fire(effects, step, options),
        };
        if let Ok(r) = &mut result {
            r.holding_torque.clone_from(&self.scratch.brake_torque);
        }
        self.inertia = Inertia::physical(&self.model, &self.state.node_mass);
        self.state.zero_velocities();
        self.state.time = time;
        self.state.step = step_count;
        result
    }

    /// Evaluate the forces of relaxation step `k` and, every 32 steps, the residual (kept
    /// in `residual`): the converged report once it is below the tolerance, or the
    /// interrupted one if the caller's interrupt hook ([`crate::interrupt`]) fires.
    fn relax_evaluate(
        &mut self,
        effects: Effects,
        step: RelaxStep,
        k: u64,
        options: &StabiliseOptions,
        residual: &mut f64,
        resets: u64,
    ) -> Option<StabiliseReport> {
        crate::interrupt::report(k);
        if crate::interrupt::check(self.model.nodes as u64).is_err() {
            return Some(StabiliseReport {
                steps: k,
                residual: *residual,
                converged: false,
                resets,
                interrupted: true,
                holding_torque: Vec::new(),
            });
        }
        self.evaluate_scaled(effects, step.dt, step.contact_scale, false);
        if !k.is_multiple_of(32) {
            return None;
        }
        *residual = self.residual();
        (*residual < options.tolerance).then_some(StabiliseReport {
            steps: k,
            residual: *residual,
            converged: true,
            resets,
            interrupted: false,
            holding_torque: Vec::new(),
        })
    }

    /// Largest out-of-balance force on a node or takeup relative to the largest tension.
    pub(crate) fn residual(&self) -> f64 {
        let sc = &self.scratch;
        let m = &self.model;
        let mut worst = sc.force.iter().map(|f| f.norm()).fold(0.0, f64::max);
        for &d in &m.dofs.rigid {
            match d {
                Rigid::Takeup(j) => {
                    let force = sc.rigid_force(m, d);
                    // A takeup resting on a travel stop that it is pushed into is in balance:
                    // the stop takes the difference.
                    let on_stop = m.pulleys[j].takeup.as_ref().is_some_and(|t| {
                        let x = self.state.takeup_travel[j];
                        (x >= t.travel_max && force > 0.0) || (x <= t.travel_min && force < 0.0)
                    });
                    if !on_stop {
                        worst = worst.max(force.abs());
                    }
                }
                // A body torque as the pair of end forces that make it.
                Rigid::Body(i) => {
                    worst = worst.max(sc.rigid_force(m, d).abs() / m.rest_length[i]);
                }
                _ => {}
            }
        }
        let scale = sc
            .tension
            .iter()
            .map(|t| t.abs())
            .fold(0.0, f64::max)
            .max(
                m.mass
                    .iter()
                    .fold(0.0, |a: f64, &mass| a.max(mass * m.gravity)),
            )
            .max(f64::MIN_POSITIVE);
        worst / scale
    }

    /// Relaxation moves are fictitious and can build up speed; a node that moved further
    /// than a quarter of the smallest idler radius, pulley radius or element length in one
    /// step `dt` could tunnel through a roll (centre-line contact only sees penetration).
    /// Scale the node's velocity so that its next move (after the coming force update)
    /// stays within that bound.
    fn limit_relaxation_move(&mut self, dt: f64) {
        let cap = 0.25 * self.model.relaxation_move_limit;
        let s = &mut self.state;
        for ((v, f), im) in s
            .velocity
            .iter_mut()
            .zip(&self.scratch.force)
            .zip(&self.inertia.inv_mass)
        {
            let next = *v + f * (dt * im);
            let step = next.norm() * dt;
            if step > cap {
                *v = next * (cap / step) - f * (dt * im);
            }
        }
    }
}
