//! Compiled pulleys and their takeups, drives and brakes.

use crate::contact::nonlinear::NonlinearContact;
use crate::drives::controller::ControlModel;
use crate::drives::holdback::Holdback;
use crate::drives::motor::MotorModel;
use crate::drives::sharing::Follower;
use crate::friction::Prescribed;
use crate::scene::{BrakeSpec, DriveSpec, FrictionModel, Scene, TakeupKind};
use nalgebra::Vector2;

/// Compiled gravity takeup.
#[derive(Debug, Clone, PartialEq)]
pub struct TakeupModel {
    /// Unit vector of the takeup line (direction of the counterweight pull).
    pub direction: Vector2<f64>,
    /// Translating mass: pulley + counterweight, kg.
    pub moving_mass: f64,
    /// Constant force along `direction` from the counterweight and the pulley weight, N.
    pub pull: f64,
    /// Travel limits from the initial position, m.
    pub travel_min: f64,
    /// Travel limits from the initial position, m.
    pub travel_max: f64,
    /// Largest carriage speed along the line, m/s (a winch's limit; +∞ otherwise).
    pub max_speed: f64,
    /// Time from which the carriage is locked in dynamic runs, s: −∞ for a fixed (screw)
    /// takeup, the scene's first stop with `lock_on_stop`, else +∞.
    pub lock_time: f64,
}

/// Compiled pulley.
#[derive(Debug, Clone, PartialEq)]
pub struct PulleyModel {
    /// Name for messages.
    pub name: String,
    /// Initial centre, m.
    pub center: Vector2<f64>,
    /// Radius, m.
    pub radius: f64,
    /// Polar inertia including drive inertia, kg·m².
    pub inertia: f64,
    /// Linear viscous drag in the bearings, N·m·s/rad (0: none).
    pub bearing_damping: f64,
    /// Contact stiffness, N/m.
    pub contact_stiffness: f64,
    /// Contact damping, N·s/m (the scene's absolute value, or 2ζ√(k·m) from its ratio).
    pub contact_damping: f64,
    /// Kubas's nonlinear contact law (eq. 4–11), replacing `contact_stiffness` and
    /// `contact_damping`, if the scene gives one.
    pub nonlinear: Option<NonlinearContact>,
    /// Friction model.
    pub friction: FrictionModel,
    /// Takeup, if the pulley translates.
    pub takeup: Option<TakeupModel>,
    /// Drive, if any.
    pub drive: Option<DriveSpec>,
    /// Brake, if any.
    pub brake: Option<BrakeSpec>,
    /// Holdback, if any.
    pub holdback: Option<Holdback>,
    /// Search margin beyond the radius for the contact window, m.
    pub window_margin: f64,
    /// PI speed controller of the drive, if it has one (`crate::drives::controller`).
    pub control: Option<ControlModel>,
    /// Torque follower of another drive, if the drive is one (`crate::drives::sharing`).
    pub follow: Option<Follower>,
    /// DOL motor of the drive, if it has one (`crate::drives::motor`).
    pub motor: Option<MotorModel>,
}

impl PulleyModel {
    /// The stiffest contact (N/m) and its damping (N·s/m) a belt point can meet on this
    /// pulley, every stiffness times `scale`: the linear law's, or the nonlinear law's
    /// tangent 2c₁p + c₂ at p_max (where its damping is fully in) with its full damping b.
    #[inline]
    pub fn contact_bound(&self, scale: f64) -> (f64, f64) {
        match &self.nonlinear {
            None => (self.contact_stiffness * scale, self.contact_damping),
            Some(law) => (
                law.scaled(scale).stiffness_at(law.damping_depth),
                law.damping,
            ),
        }
    }

    /// The speed-controlled drive's hold for the step from `time` to `time + dt` (s): the
    /// pulley speed at the mid-step, where central differences place it, is the curve's
    /// belt speed there over the radius, ω(t + Δt/2) = v(t + Δt/2)/r, up to `max_torque`.
    /// `None` after the drive's `power_off`.
    #[inline]
    pub fn speed_hold(&self, time: f64, dt: f64) -> Option<Prescribed> {
        let drive = self.drive.as_ref()?;
        if drive.controller.is_some() {
            return None; // a PI controller: a torque, not a hold
        }
        let curve = drive.start_curve.as_ref()?;
        if !drive.powered(time) {
            return None;
        }
        Some(Prescribed::within(
            curve.speed_at(time + 0.5 * dt) / self.radius,
            drive.max_torque,
        ))
    }
}

/// Compile the scene's pulleys for elements of rest length `l0` (m): the contact window
/// reaches one element beyond the radius.
pub(super) fn compile(scene: &Scene, l0: f64) -> Vec<PulleyModel> {
    let element_mass = scene.belt.mass_per_length * l0;
    let wrap = scene.belt.pulley_contact == crate::scene::PulleyContact::Wrap;
    let stop_time = scene.stop_time().unwrap_or(f64::INFINITY);
    scene
        .pulleys
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let motor = p
                .drive
                .as_ref()
                .and_then(|d| d.motor.as_ref())
                .map(MotorModel::compile);
            // Motor and gearbox, the rotor when rigidly geared, the flywheel.
            let drive_inertia = p.drive.as_ref().map_or(0.0, |d| {
                let ratio = d.motor.as_ref().map_or(1.0, |m| m.gear_ratio);
                d.inertia
                    + ratio * ratio * d.flywheel
                    + motor.as_ref().map_or(0.0, |m| m.reflected_inertia())
            });
            PulleyModel {
                name: if p.name.is_empty() {
                    format!("pulleys[{i}]")
                } else {
                    p.name.clone()
                },
                center: Vector2::new(p.center[0], p.center[1]),
                radius: p.radius,
                inertia: p.polar_inertia() + drive_inertia,
                bearing_damping: p.bearing_damping,
                contact_stiffness: p.contact_stiffness,
                contact_damping: match &p.nonlinear_contact {
                    Some(law) => law.damping,
                    None => crate::scene::contact_damping(
                        p.contact_damping,
                        p.contact_damping_ratio,
                        p.contact_stiffness,
                        element_mass,
                    ),
                },
                nonlinear: p.nonlinear_contact,
                friction: p.friction,
                takeup: p.takeup.as_ref().map(|t| {
                    let dir = Vector2::new(t.direction[0], t.direction[1]);
                    // A winch or a screw pulls with its set force, a counterweight with
                    // its weight (it moves with the pulley); the pulley's own weight acts
                    // along −y.
                    let pull = t.force.unwrap_or(t.counterweight * scene.gravity);
                    TakeupModel {
                        direction: dir,
                        moving_mass: p.mass + t.counterweight,
                        pull: pull - p.mass * scene.gravity * dir.y,
                        travel_min: t.travel_min,
                        travel_max: t.travel_max,
                        max_speed: t.max_speed,
                        lock_time: match t.kind {
                            TakeupKind::Fixed => f64::NEG_INFINITY,
                            _ if t.lock_on_stop => stop_time,
                            _ => f64::INFINITY,
                        },
                    }
                }),
                drive: p.drive.clone(),
                brake: p.brake.clone(),
                holdback: p.holdback.as_ref().map(Holdback::compile),
                // Wrap contact: one and a half elements, so that an element that can reach the
                // circle has both nodes in the window, stretched or not.
                window_margin: if wrap { 1.5 * l0 } else { l0 },
                control: None,
                follow: None,
                motor,
            }
        })
        .collect()
}
