//! The scene's model choices (the belt formulation, a pulley's contact law, the integrator
//! and its tolerances) and the rules that tie them to the rest of the scene. Each rule
//! refuses, by name, a combination that the engine cannot simulate as asked, instead of
//! ignoring part of it.

use super::{FrictionModel, PulleySpec, Scene};
use crate::error::{BeltError, BeltResult};

/// Which discrete belt model to use.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Formulation {
    /// Hustrulid (1993): lumped node masses joined by Kelvin-Voigt axial elements and
    /// rotational bending springs (thesis eq. 4.1–4.60).
    #[default]
    NodeKelvinVoigt,
    /// Kubas (2014) and Guo & Wang (2020): a chain of rigid bodies (x, y, φ each), joined by
    /// translational and torsional Kelvin–Voigt spring-dampers with c_x = EA/l,
    /// c_φ = EI/l (`docs/kubas.md`, `crate::belt::rigid`).
    RigidBody,
}

impl Formulation {
    /// Name used in scene files and in Python.
    pub fn name(self) -> &'static str {
        match self {
            Formulation::NodeKelvinVoigt => "node_kelvin_voigt",
            Formulation::RigidBody => "rigid_body",
        }
    }
}

/// The time integrator a scene asks for (`solver.integrator`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum IntegratorKind {
    /// `"central_difference"`: explicit central differences at the automatic stable step.
    #[default]
    CentralDifference,
    /// `"rkf45"`: adaptive Runge–Kutta–Fehlberg 4(5) with `solver.relative_tolerance` and
    /// `solver.absolute_tolerance` (`docs/kubas.md`).
    Rkf45,
}

/// Default of [`SolverParams::relative_tolerance`](super::SolverParams::relative_tolerance):
/// 10⁻⁸. The coordinates are positions of the size of the scene, while the physics is in
/// deformations of order strain × element length, 10⁻³ to 10⁻⁵ of them: a relative error
/// of 10⁻⁶ per step on the positions drifted a conservative rigid-body drive's energy by
/// 1.8·10⁻⁴ in 2 ms, 10⁻⁸ by 8·10⁻⁷ (`rust/tests/rigid_body.rs`).
pub const DEFAULT_RELATIVE_TOLERANCE: f64 = 1e-8;
/// Default of [`SolverParams::absolute_tolerance`](super::SolverParams::absolute_tolerance):
/// 10⁻¹¹ in each component's SI unit, for components near zero.
pub const DEFAULT_ABSOLUTE_TOLERANCE: f64 = 1e-11;

impl Scene {
    /// The rules of the formulation and of each pulley's contact law (called by
    /// [`Scene::validate`]).
    pub(super) fn validate_choices(&self) -> BeltResult<()> {
        for (i, p) in self.pulleys.iter().enumerate() {
            check_contact_law(&format!("pulleys[{i}]"), p)?;
            if p.nonlinear_contact.is_some()
                && self.belt.pulley_contact == super::PulleyContact::Wrap
            {
                return Err(BeltError::invalid(
                    "belt.pulley_contact",
                    "wrap",
                    format!("pulleys[{i}].nonlinear_contact is a nodal contact law (Kubas eq. 4–11); wrap contact applies the linear penalty along the wrapped path: use pulley_contact = \"nodes\" with nonlinear_contact"),
                ));
            }
        }
        if self.belt.formulation == Formulation::RigidBody
            && self.belt.idler_contact == super::IdlerContactKind::Wrap
        {
            return Err(BeltError::invalid(
                "belt.idler_contact",
                "wrap",
                "wrap contact measures node-belt elements along their path over a roll; the rigid_body formulation's bodies touch the rolls along their axes: use idler_contact = \"segment\"",
            ));
        }
        if let Some(tau) = self.belt.damping_time {
            if !(tau.is_finite() && tau >= 0.0) {
                return Err(BeltError::invalid(
                    "belt.damping_time",
                    tau,
                    "must be a finite number ≥ 0 (s)",
                ));
            }
            if self.belt.damping_ratio > 0.0 {
                return Err(BeltError::invalid(
                    "belt.damping_time",
                    tau,
                    format!(
                        "give belt.damping_time (Voigt, b = τ·k) or belt.damping_ratio (here {}, fraction of critical), not both",
                        self.belt.damping_ratio
                    ),
                ));
            }
        }
        let eta = self.belt.loss_factor;
        if !(eta.is_finite() && (0.0..=1.0).contains(&eta)) {
            return Err(BeltError::invalid(
                "belt.loss_factor",
                eta,
                "must be a finite loss factor tan δ in [0, 1] (conveyor-belt rubber: about 0.05 to 0.3)",
            ));
        }
        let f = self.belt.loss_frequency;
        if !(f.is_finite() && f > 0.0) {
            return Err(BeltError::invalid(
                "belt.loss_frequency",
                f,
                "must be a finite frequency > 0 (Hz)",
            ));
        }
        if eta > 0.0 {
            if self.belt.formulation == Formulation::RigidBody {
                return Err(BeltError::invalid(
                    "belt.loss_factor",
                    eta,
                    "the viscoelastic (Zener) belt law is built for the node formulation only; with belt.formulation = \"rigid_body\" use belt.damping_time (Voigt) or belt.damping_ratio",
                ));
            }
            if self.solver.integrator == IntegratorKind::Rkf45 {
                return Err(BeltError::invalid(
                    "belt.loss_factor",
                    eta,
                    "the viscoelastic arms are advanced exactly over each fixed step of central differences and cannot run under solver.integrator = \"rkf45\"; use solver.integrator = \"central_difference\" or loss_factor = 0",
                ));
            }
        }
        if self.belt.formulation == Formulation::RigidBody {
            if self.initial.is_some() {
                if let Some(j) = self
                    .pulleys
                    .iter()
                    .position(|p| p.nonlinear_contact.is_some())
                {
                    return Err(BeltError::invalid(
                        format!("pulleys[{j}].nonlinear_contact"),
                        "Kubas's law",
                        "the rigid-body design placement rests the bodies on their ends under the linear penalty (belt::rigid::contact); under the nonlinear law they touch at their mass centres: drop [initial] and relax the placement, or use the linear penalty",
                    ));
                }
            }
            if self.belt.tension_only {
                return Err(BeltError::invalid(
                    "belt.tension_only",
                    true,
                    "the rigid_body formulation has zero-free-length spring-dampers between its bodies (Kubas eq. 20), which carry no compression along the belt by construction; tension_only applies to the node formulation only",
                ));
            }
        }
        // Checked whatever the integrator: a value that is wrong is refused, not kept for later.
        let s = &self.solver;
        if !(s.relative_tolerance.is_finite() && s.relative_tolerance > 0.0) {
            return Err(BeltError::invalid(
                "solver.relative_tolerance",
                s.relative_tolerance,
                "must be a finite number > 0",
            ));
        }
        if !(s.absolute_tolerance.is_finite() && s.absolute_tolerance >= 0.0) {
            return Err(BeltError::invalid(
                "solver.absolute_tolerance",
                s.absolute_tolerance,
                "must be a finite number ≥ 0",
            ));
        }
        if self.solver.integrator == IntegratorKind::Rkf45 {
            self.validate_adaptive()?;
        }
        Ok(())
    }

    /// The rules of the adaptive integrator: valid tolerances, and none of the effects that
    /// are solved for a fixed step (their force is whatever stops a contact or holds a
    /// pulley within the coming step, which an adaptive step cannot know in advance).
    fn validate_adaptive(&self) -> BeltResult<()> {
        let s = &self.solver;
        if let Some(dt) = s.time_step {
            return Err(BeltError::invalid(
                "solver.time_step",
                dt,
                "sets the step of central differences; solver.integrator = \"rkf45\" chooses its own steps from solver.relative_tolerance and solver.absolute_tolerance (drop time_step)",
            ));
        }
        let fixed = |field: String, what: &str| {
            Err(BeltError::invalid(
                field,
                "given",
                format!("{what} is solved for a fixed time step and cannot run under solver.integrator = \"rkf45\"; use solver.integrator = \"central_difference\""),
            ))
        };
        let stick = |field: String| {
            Err(BeltError::invalid(
                field,
                "\"stick_force\"",
                "stick-force friction is solved for a fixed time step (the force that stops a contact within the step) and cannot run under solver.integrator = \"rkf45\"; use the creep-rate friction model (model = \"creep\", Kubas eq. 12–19: a friction law of the state, whose creep memory RKF45 integrates with the state), or solver.integrator = \"central_difference\"",
            ))
        };
        for (i, p) in self.pulleys.iter().enumerate() {
            if matches!(p.friction, FrictionModel::StickForce { .. }) && !p.friction.is_none() {
                return stick(format!("pulleys[{i}].friction.model"));
            }
            if let Some(d) = &p.drive {
                // Their memory (PI integral, lagged torque, a coupled motor's speed) is
                // advanced once per central-difference step.
                let memory = [
                    ("controller", d.controller.is_some()),
                    ("follow", d.follow.is_some()),
                    (
                        "motor.coupling",
                        d.motor.as_ref().is_some_and(|m| m.coupling.is_some()),
                    ),
                ];
                if let Some((key, _)) = memory.iter().find(|(_, on)| *on) {
                    return fixed(
                        format!("pulleys[{i}].drive.{key}"),
                        "a drive with memory (a PI controller's integral and torque lag, a torque follower, a fluid-coupled motor's speed), advanced once per step,",
                    );
                }
                if d.start_curve.is_some() {
                    return fixed(
                        format!("pulleys[{i}].drive.start_curve"),
                        "a speed-controlled drive (the torque that puts the pulley on its curve within the step)",
                    );
                }
            }
            if p.brake.is_some() {
                return fixed(
                    format!("pulleys[{i}].brake"),
                    "a brake (the torque that holds the pulley at rest within the step)",
                );
            }
            if p.holdback.is_some() {
                return fixed(
                    format!("pulleys[{i}].holdback"),
                    "a holdback (the torque that stops the pulley turning backwards within the step)",
                );
            }
            if let Some(t) = &p.takeup {
                if t.kind != super::TakeupKind::Gravity || t.lock_on_stop {
                    return fixed(
                        format!("pulleys[{i}].takeup.kind"),
                        "a winch or screw takeup, or one that locks on stopping (the carriage speed is limited or held once per step),",
                    );
                }
            }
        }
        for (i, d) in self.idlers.iter().enumerate() {
            if matches!(d.friction, FrictionModel::StickForce { .. }) && !d.friction.is_none() {
                return stick(format!("idlers[{i}].friction.model"));
            }
            if d.resistance > 0.0 {
                return fixed(
                    format!("idlers[{i}].resistance"),
                    "the idlers' running resistance (a stick-capable force that stops the belt within the step)",
                );
            }
        }
        if !self.loads.is_empty() {
            return fixed(
                "loads".into(),
                "a bulk material load (node masses updated once per step)",
            );
        }
        Ok(())
    }
}

/// A pulley's nonlinear contact: valid parameters, and not mixed with the linear law's
/// settings (which it replaces).
fn check_contact_law(f: &str, p: &PulleySpec) -> BeltResult<()> {
    let Some(law) = &p.nonlinear_contact else {
        return Ok(());
    };
    law.validate(&format!("{f}.nonlinear_contact"))?;
    for (key, value) in [
        ("contact_damping", p.contact_damping),
        ("contact_damping_ratio", p.contact_damping_ratio),
    ] {
        if let Some(v) = value {
            return Err(BeltError::invalid(
                format!("{f}.{key}"),
                v,
                format!("belongs to the linear contact law, which {f}.nonlinear_contact replaces: give the damping as nonlinear_contact.damping (N·s/m), or drop nonlinear_contact"),
            ));
        }
    }
    let linear_default = PulleySpec::default().contact_stiffness;
    if p.contact_stiffness != linear_default {
        return Err(BeltError::invalid(
            format!("{f}.contact_stiffness"),
            p.contact_stiffness,
            format!("belongs to the linear contact law, which {f}.nonlinear_contact replaces (its stiffness is c₁p² + c₂p); leave contact_stiffness at its default {linear_default:e}, or drop nonlinear_contact"),
        ));
    }
    Ok(())
}
