//! Drives at a design start (`[initial]`, `docs/design-start.md`): their memory begins in
//! the steady state of the design state instead of empty, so that a run started at speed
//! holds its speed from t = 0 (an empty PI integral would let the drive sag until the
//! integral had built the holding torque up; a coupled motor at rest would brake a
//! running belt through its coupling).
//!
//! - **PI speed controllers** ([`super::controller::prime`]): the integral I (and a lagged
//!   torque) is set so that the first step commands the torque T that holds the pulley in
//!   the design state: K_i·I = T·(1 + K_p·δ) − K_p·e₀, e₀ = ω_ref − ω the speed error of
//!   the first step (0 when the design speed is the curve's). A master shares T with its
//!   torque followers: T = Σ c_k·T_k / Σ c_k² over the master (c = 1) and its followers
//!   (c the factor on the master's torque), the least-squares split, exact when the design
//!   state's shares are the followers' ratios. A controller without an integral
//!   (K_i = 0) keeps its proportional droop.
//! - **Motors behind a fluid coupling** ([`super::motor::prime`]): with the belt moving at
//!   t = 0 the rotor starts at its running point on the coupling, T_motor(n) =
//!   T_coupling(n, n_out) (no torque if the motor is off at t = 0: then n = n_out).
//!
//! **Holding torque.** The torque that keeps a pulley at its speed with the belt stuck to
//! it, quasi-statically: T_hold = −T_load − r·Σ t_i·F_i over the nodes touching it, F_i
//! every force on node i but friction (elastic, gravity, contact) at t = 0, t_i the
//! counter-clockwise tangent there, T_load the bearing drag and the drive's load torque
//! −b·ω. It is the friction solve's held torque ([`crate::friction::pulley_stick_friction`])
//! for α = 0 and nodes at rest on the surface. A pulley without friction transmits
//! nothing: T_hold = −T_load.

use crate::belt::node::perp;
use crate::model::Model;
use crate::pipeline::{Effects, Scratch};
use crate::simulation::Simulation;
use crate::state::State;

impl Simulation {
    /// Start the drives' memory in the steady state of a design start (module docs);
    /// nothing without a design start or without a drive that has memory.
    pub(crate) fn prime_drives(&mut self) {
        if self.model.initial_motion.is_none() || !self.model.has_drive_memory {
            return;
        }
        if self.model.pulleys.iter().any(|p| p.control.is_some()) {
            // Every force but friction, with the drives off: what the belt asks of each
            // pulley. The evaluation only updates contact windows and idler tracking,
            // which the first step's evaluation would find the same.
            self.evaluate(Effects {
                friction: false,
                drives: false,
                quasi_static_friction: false,
                damping: true,
                hold_at_rest: false,
            });
            let holding: Vec<f64> = (0..self.model.pulleys.len())
                .map(|j| holding_torque(&self.model, &self.state, &self.scratch, j))
                .collect();
            super::controller::prime(&self.model, &mut self.state, &holding);
            self.scratch = Scratch::new(&self.model);
        }
        super::motor::prime(&self.model, &mut self.state);
    }
}

/// The torque (N·m, counter-clockwise positive) that holds pulley `j` at its speed in the
/// state `s`, from an evaluation without friction in `sc` (module docs).
pub fn holding_torque(m: &Model, s: &State, sc: &Scratch, j: usize) -> f64 {
    let p = &m.pulleys[j];
    let load = sc.bearing_torque[j]
        + sc.contact_torque[j]
        + p.drive
            .as_ref()
            .map_or(0.0, |d| d.torque_at(s.time, s.pulley_omega[j]));
    let belt = if p.friction.is_none() {
        0.0
    } else {
        let c = &sc.contacts[j];
        let tangential: f64 = (0..c.len())
            .map(|k| perp(c.normal[k]).dot(&sc.force[c.node[k]]))
            .sum();
        m.friction_radius(j) * tangential
    };
    -load - belt
}
