//! A PI speed controller with a torque limit, droop and a torque (current) loop lag: the
//! real VFD beside the ideal speed follower of [`super::hold`] (`docs/drives.md`).
//!
//! The motor torque at the pulley is
//!
//!   T = clamp((K_p·(ω_ref − ω) + K_i·I)/(1 + K_p·δ), ±T_max),   İ = ω_ref − ω − δ·T,
//!
//! with ω_ref = v(t)/r from the drive's starting curve, δ the droop (rad/s per N·m: the
//! speed falls by `droop`·|ω₀| at `rated_torque`), and I the integral of the error. While
//! the torque is limited the integral stops growing in the direction of the limit
//! (conditional integration, the usual anti-windup). With a torque time constant τ the
//! applied torque follows the command through a first-order lag (the current loop).
//!
//! **Default gains.** With J the rigid-body inertia the drive moves (the whole conveyor
//! reflected to this pulley, shared among the speed-controlled drives), ω_c the
//! `bandwidth` and ζ the `damping_ratio`, K_p = 2ζω_c·J and K_i = ω_c²·J place both poles
//! of the rigid loop J·s² + K_p·s + K_i at −ω_c for ζ = 1 (critically damped). A linear
//! ramp of slope α is then tracked with the error e(t) = α·t·e^(−ω_c·t) (zero in steady
//! running), the closed form the tests check.
//!
//! **Time stepping.** The stage uses the stored half-step speed ω(t − Δt/2) against
//! ω_ref(t − Δt/2); after each step [`advance`] adds the error at the new half step times
//! the step to I, which is exactly ∫ω_ref dt − Δθ of the integrator's own angle update.
//! The proportional gain acts on the pulley like a damper and the integral gain like a
//! spring: `model::stable_step` keeps Δt within their explicit limit.

use crate::error::{BeltError, BeltResult};
use crate::model::{IdlerModel, Model, PulleyModel};
use crate::pipeline::{Scratch, StageContext};
use crate::scene::{check_finite, DriveSpec, Scene};
use crate::start_curve::StartCurve;
use crate::state::State;
use serde::{Deserialize, Serialize};

/// Default speed-loop bandwidth ω_c, rad/s (1.6 Hz): a conveyor VFD's outer speed loop.
/// A starting ramp's tracking error is about its jerk/ω_c² (0.05 % of the speed for a
/// 10 s Harrison ramp, 1.2 % for a 2 s one).
pub const DEFAULT_BANDWIDTH: f64 = 10.0;

/// A PI speed controller (`[pulleys.drive.controller]`); the drive's `start_curve` is its
/// reference and its `max_torque` the torque limit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SpeedController {
    /// Speed-loop bandwidth ω_c, rad/s, > 0. Default [`DEFAULT_BANDWIDTH`] (10).
    pub bandwidth: f64,
    /// Damping ratio ζ of the rigid loop, > 0. Default 1 (critically damped).
    pub damping_ratio: f64,
    /// Inertia J the default gains are tuned on, kg·m², > 0. `None`: the rigid-body
    /// inertia of the whole conveyor reflected to this pulley (belt, material at the start,
    /// pulleys, drives and idler rolls, each rotating body as I·(r/r_k)²), divided by the
    /// torque the drives produce per unit of this controller's output (the number of
    /// speed-controlled drives plus their followers' ratios). Default `None`.
    pub inertia: Option<f64>,
    /// K_p, N·m·s/rad, > 0. `None`: 2ζω_c·J. Default `None`.
    pub proportional_gain: Option<f64>,
    /// K_i, N·m/rad, ≥ 0. `None`: ω_c²·J. Default `None`.
    pub integral_gain: Option<f64>,
    /// Time constant τ of the torque (current) loop, s, ≥ 0: the applied torque follows
    /// the limited command as a first-order lag. Must be below K_p/K_i (else the loop on a
    /// rigid load is unstable). Default 0 (instantaneous).
    pub torque_time_constant: f64,
    /// Speed droop, dimensionless, in [0, 1): the speed reference falls by droop·|ω₀| at
    /// `rated_torque` (ω₀ the curve's final pulley speed), so that speed-controlled drives
    /// on one belt share load in proportion to rated_torque/droop. Default 0.
    pub droop: f64,
    /// Torque at which the speed falls by `droop`, N·m, > 0. Required with droop > 0,
    /// refused without. Default `None`.
    pub rated_torque: Option<f64>,
}

impl Default for SpeedController {
    fn default() -> Self {
        SpeedController {
            bandwidth: DEFAULT_BANDWIDTH,
            damping_ratio: 1.0,
            inertia: None,
            proportional_gain: None,
            integral_gain: None,
            torque_time_constant: 0.0,
            droop: 0.0,
            rated_torque: None,
        }
    }
}

fn positive(field: String, v: f64) -> BeltResult<()> {
    check_finite(&field, v)?;
    if v > 0.0 {
        Ok(())
    } else {
        Err(BeltError::invalid(field, v, "must be > 0"))
    }
}

fn non_negative(field: String, v: f64) -> BeltResult<()> {
    check_finite(&field, v)?;
    if v >= 0.0 {
        Ok(())
    } else {
        Err(BeltError::invalid(field, v, "must be ≥ 0"))
    }
}

impl SpeedController {
    /// Check every field on its own; `f` names the table (`pulleys[0].drive.controller`).
    pub fn validate(&self, f: &str) -> BeltResult<()> {
        positive(format!("{f}.bandwidth"), self.bandwidth)?;
        positive(format!("{f}.damping_ratio"), self.damping_ratio)?;
        if let Some(j) = self.inertia {
            positive(format!("{f}.inertia"), j)?;
        }
        if let Some(k) = self.proportional_gain {
            positive(format!("{f}.proportional_gain"), k)?;
        }
        if let Some(k) = self.integral_gain {
            non_negative(format!("{f}.integral_gain"), k)?;
        }
        non_negative(
            format!("{f}.torque_time_constant"),
            self.torque_time_constant,
        )?;
        non_negative(format!("{f}.droop"), self.droop)?;
        if self.droop >= 1.0 {
            return Err(BeltError::invalid(
                format!("{f}.droop"),
                self.droop,
                "must be below 1 (a fraction of the speed)",
            ));
        }
        match (self.droop > 0.0, self.rated_torque) {
            (true, None) => Err(BeltError::invalid(
                format!("{f}.rated_torque"),
                "missing",
                format!(
                    "needed with {f}.droop > 0: the torque (N·m) at which the speed falls by droop"
                ),
            )),
            (false, Some(t)) => Err(BeltError::invalid(
                format!("{f}.rated_torque"),
                t,
                format!(
                    "has no effect without droop (give {f}.droop > 0, or leave rated_torque out)"
                ),
            )),
            (true, Some(t)) => positive(format!("{f}.rated_torque"), t),
            (false, None) => Ok(()),
        }
    }
}

/// A compiled PI controller.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ControlModel {
    /// K_p, N·m·s/rad.
    pub kp: f64,
    /// K_i, N·m/rad.
    pub ki: f64,
    /// Droop δ, rad/s per N·m (0: none).
    pub droop: f64,
    /// Torque time constant τ, s (0: none).
    pub tau: f64,
    /// Inertia the gains were tuned on, kg·m² (the given or the computed J).
    pub inertia: f64,
    /// Torque limit, N·m (may be +∞).
    pub max_torque: f64,
}

impl ControlModel {
    /// Gains for `c` on a drive of torque limit `max_torque` whose final pulley speed is
    /// `omega_final` (rad/s), tuned on `inertia` (kg·m², used unless `c.inertia` is given).
    /// `field` names the controller in errors.
    pub fn compile(
        c: &SpeedController,
        inertia: f64,
        max_torque: f64,
        omega_final: f64,
        field: &str,
    ) -> BeltResult<ControlModel> {
        let j = c.inertia.unwrap_or(inertia);
        let (kp, ki) = gains(c.bandwidth, c.damping_ratio, j);
        let kp = c.proportional_gain.unwrap_or(kp);
        let ki = c.integral_gain.unwrap_or(ki);
        let tau = c.torque_time_constant;
        if tau > 0.0 && ki > 0.0 && tau >= kp / ki {
            return Err(BeltError::invalid(
                format!("{field}.torque_time_constant"),
                tau,
                format!("must be below K_p/K_i = {:.6e} s: with a longer torque lag the PI loop on a rigid load is unstable (Routh: J·τ·s³ + J·s² + K_p·s + K_i)", kp / ki),
            ));
        }
        let droop = match c.rated_torque {
            Some(t) if c.droop > 0.0 => c.droop * omega_final.abs() / t,
            _ => 0.0,
        };
        Ok(ControlModel {
            kp,
            ki,
            droop,
            tau,
            inertia: j,
            max_torque,
        })
    }

    /// The limited torque command (N·m) for a speed error `error` = ω_ref − ω (rad/s) and
    /// the error integral `integral` (rad); and whether the limit cut it.
    #[inline]
    pub fn command(&self, error: f64, integral: f64) -> (f64, bool) {
        let raw = (self.kp * error + self.ki * integral) / (1.0 + self.kp * self.droop);
        if raw.abs() <= self.max_torque {
            (raw, false)
        } else {
            (self.max_torque.copysign(raw), true)
        }
    }
}

/// K_p = 2ζω_c·J and K_i = ω_c²·J, N·m·s/rad and N·m/rad: both poles of the rigid loop
/// J·s² + K_p·s + K_i at −ω_c for ζ = 1 (−ζω_c ± ω_c√(ζ² − 1) in general).
pub fn gains(bandwidth: f64, damping_ratio: f64, inertia: f64) -> (f64, f64) {
    (
        2.0 * damping_ratio * bandwidth * inertia,
        bandwidth * bandwidth * inertia,
    )
}

/// A drive's memory in the state: a PI controller's error integral and lagged torque, a
/// fluid-coupled motor's speed.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DriveMemory {
    /// ∫(ω_ref − ω − δ·T) dt since the start, rad.
    pub integral: f64,
    /// Torque applied by the lagged torque loop, N·m (only with τ > 0).
    pub torque: f64,
    /// Speed of a motor behind a fluid coupling, rad/s at the motor shaft, positive in the
    /// motor's sense of rotation, at the integrator's half step (`super::motor`).
    pub motor_speed: f64,
}

/// What the stage decided this evaluation, for [`advance`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ControlOutput {
    /// Limited command, N·m.
    pub command: f64,
    /// The limit cut the command.
    pub limited: bool,
    /// Torque applied this step, N·m.
    pub applied: f64,
    /// The stage ran with drives on (false in the static relaxation: nothing to advance).
    pub active: bool,
}

/// A pulley under a PI speed controller: index `j`, its model, controller, drive and the
/// drive's start curve (the reference speed).
struct Controlled<'a> {
    j: usize,
    p: &'a PulleyModel,
    c: &'a ControlModel,
    d: &'a DriveSpec,
    curve: &'a StartCurve,
}

/// The pulleys of `m` under a PI speed controller with a start curve, in pulley order: what
/// [`speed_control`], [`advance_all`] and [`prime`] each walk over (each treats an unpowered
/// drive its own way: zero output, no advance, no priming).
fn controlled(m: &Model) -> impl Iterator<Item = Controlled<'_>> {
    m.pulleys.iter().enumerate().filter_map(|(j, p)| {
        let (c, d) = (p.control.as_ref()?, p.drive.as_ref()?);
        let curve = d.start_curve.as_ref()?;
        Some(Controlled { j, p, c, d, curve })
    })
}

/// The `speed_control` stage: the PI controllers' torques, then the torque followers'
/// (`super::sharing`). Off in the static relaxation with the other drives.
pub fn speed_control(cx: &mut StageContext<'_>) {
    let (m, s, sc) = (cx.model, &*cx.state, &mut *cx.scratch);
    if !cx.effects.drives {
        sc.control.iter_mut().for_each(|c| c.active = false);
        return;
    }
    let reference_time = s.time - 0.5 * m.dt;
    for Controlled { j, p, c, d, curve } in controlled(m) {
        if !d.powered(s.time) {
            // Power failure (`power_off`): no torque, and the controller stops integrating.
            sc.control[j] = ControlOutput::default();
            continue;
        }
        let mem = s.drive_memory[j];
        let omega_ref = curve.speed_at(reference_time) / p.radius;
        let (command, limited) = c.command(omega_ref - s.pulley_omega[j], mem.integral);
        let applied = if c.tau > 0.0 { mem.torque } else { command };
        sc.drive_torque[j] += applied;
        sc.control[j] = ControlOutput {
            command,
            limited,
            applied,
            active: true,
        };
    }
    super::sharing::follow_torques(m, s, sc);
}

/// After a step of `drift` (s) from the state's time: [`advance`] every PI controller
/// whose stage ran with drives on (the integrator calls this when the model has any).
pub fn advance_all(m: &Model, s: &mut State, sc: &Scratch, drift: f64) {
    let time = s.time + 0.5 * drift;
    for Controlled { j, p, c, curve, .. } in controlled(m) {
        if !sc.control[j].active {
            continue;
        }
        let omega_ref = curve.speed_at(time) / p.radius;
        advance(
            c,
            omega_ref,
            s.pulley_omega[j],
            sc.control[j],
            drift,
            &mut s.drive_memory[j],
        );
    }
}

/// After a step of `drift` (s) from `time` that left the pulley at `omega` (rad/s, its new
/// half-step speed): add the error at the half step to the integral (unless the torque is
/// limited and the error would drive it further into the limit), and move the lagged
/// torque towards the command (exactly, for a command held over the step).
#[inline]
pub fn advance(
    c: &ControlModel,
    omega_ref: f64,
    omega: f64,
    out: ControlOutput,
    drift: f64,
    mem: &mut DriveMemory,
) {
    let error = omega_ref - omega - c.droop * out.applied;
    if !(out.limited && error * out.command > 0.0) {
        mem.integral += drift * error;
    }
    if c.tau > 0.0 {
        mem.torque += (out.command - mem.torque) * -(-drift / c.tau).exp_m1();
    }
}

/// Start every powered PI controller of `m` so that its first command is the torque that
/// holds its pulley (and its followers' pulleys) in the state `s`: `holding[j]` is pulley
/// j's holding torque, N·m (`super::prime`, which explains the choice).
pub fn prime(m: &Model, s: &mut State, holding: &[f64]) {
    for Controlled { j, p, c, d, curve } in controlled(m) {
        if !d.powered(s.time) {
            continue;
        }
        // Least squares over the master (factor 1) and its followers (their factors).
        let (mut num, mut den) = (holding[j], 1.0);
        for (k, q) in m.pulleys.iter().enumerate() {
            if let Some(f) = q.follow.filter(|f| f.master == j) {
                num += f.factor * holding[k];
                den += f.factor * f.factor;
            }
        }
        let torque = (num / den).clamp(-c.max_torque, c.max_torque);
        let error = curve.speed_at(s.time - 0.5 * m.dt) / p.radius - s.pulley_omega[j];
        let mem = &mut s.drive_memory[j];
        if c.ki > 0.0 {
            mem.integral = (torque * (1.0 + c.kp * c.droop) - c.kp * error) / c.ki;
        }
        if c.tau > 0.0 {
            mem.torque = torque;
        }
    }
}

/// Explicit stability limit of central differences for a PI controller on a pulley of
/// inertia `inertia` (kg·m²): the damper K_p and the spring K_i on the pulley alone,
/// Δt = (2/ω)(√(1+ζ²) − ζ) with ω² = K_i/I and ζ = K_p/(2√(K_i·I)); the damper alone
/// (K_i = 0) gives 2I/K_p, halved as for the bearing drag (a drag that reverses the speed
/// in one step is wrong even where it is stable).
pub fn stable_step(c: &ControlModel, inertia: f64) -> f64 {
    let damper = inertia / c.kp;
    if c.ki <= 0.0 {
        return damper;
    }
    let omega = (c.ki / inertia).sqrt();
    let zeta = c.kp / (2.0 * (c.ki * inertia).sqrt());
    let oscillator = 2.0 / omega * ((1.0 + zeta * zeta).sqrt() - zeta);
    oscillator.min(damper)
}

/// Compile the PI controllers and torque followers of `scene` onto `pulleys`: the gains
/// (from each controller's inertia, or the rigid-body inertia of the whole conveyor
/// reflected to its pulley: `belt_mass` (kg, belt and material) at the pulley radius,
/// every pulley and idler roll as I·(r/r_k)², shared among the controllers as
/// [`SpeedController::inertia`] says).
pub fn compile(
    scene: &Scene,
    pulleys: &mut [PulleyModel],
    idlers: &[IdlerModel],
    belt_mass: f64,
) -> BeltResult<()> {
    for (i, p) in pulleys.iter_mut().enumerate() {
        p.follow = super::sharing::compile(scene, i);
    }
    // Torque the drives produce per unit of one controller's output: each controller
    // counts once, plus the ratios of its followers.
    let mut per_unit = 0.0;
    for (i, p) in scene.pulleys.iter().enumerate() {
        if p.drive.as_ref().is_some_and(|d| d.controller.is_some()) {
            per_unit += 1.0;
            per_unit += pulleys
                .iter()
                .filter_map(|q| q.follow)
                .filter(|f| f.master == i)
                .map(|f| f.factor.abs())
                .sum::<f64>();
        }
    }
    let rotating: Vec<(f64, f64)> = pulleys
        .iter()
        .map(|p| (p.inertia, p.radius))
        .chain(idlers.iter().map(|d| (d.inertia, d.radius)))
        .collect();
    for (i, spec) in scene.pulleys.iter().enumerate() {
        let Some(d) = &spec.drive else { continue };
        let (Some(c), Some(curve)) = (&d.controller, &d.start_curve) else {
            continue;
        };
        let r = pulleys[i].radius;
        let reflected: f64 = belt_mass * r * r
            + rotating
                .iter()
                .map(|&(inertia, rk)| inertia * (r / rk) * (r / rk))
                .sum::<f64>();
        pulleys[i].control = Some(ControlModel::compile(
            c,
            reflected / per_unit.max(1.0),
            d.max_torque,
            curve.speed / r,
            &format!("pulleys[{i}].drive.controller"),
        )?);
    }
    Ok(())
}
