//! Induction motors started direct on line (DOL): a torque–speed curve at the motor shaft,
//! through a gearbox (and optionally a fluid coupling, [`super::coupling`]) to the pulley
//! (`docs/drives.md`).
//!
//! **Kloss curve.** With n_s the synchronous speed, slip s = (n_s − n)/n_s, T_b the
//! breakdown torque and s_b the breakdown slip, T(s) = 2·T_b/(s/s_b + s_b/s). Through the
//! rated point (rated power P_r and speed n_r, T_r = P_r/n_r, s_r = (n_s − n_r)/n_s) and
//! k = T_b/T_r, s_b = s_r·(k + √(k² − 1)). The curve is odd in s: above n_s the motor
//! brakes (generates). Kloss's formula is exact for a motor without stator resistance and
//! with a single-cage rotor; real deep-bar and double-cage motors start with far more
//! torque (locked-rotor torque 1.5–2.5 T_r, against about 2k·s_b·T_r here): give the
//! data sheet's curve as a table for those.
//!
//! **Through the gearbox.** With i the gear ratio (motor speed / pulley speed) and σ = ±1
//! the motor's sense of rotation at the pulley (`rotation`), the motor turns at n = σ·i·ω
//! and the pulley receives σ·i·T. Without a coupling the rotor's inertia counts i²·J_r at
//! the pulley; behind a coupling the motor is a body of its own ([`advance_all`]).

use super::coupling::{CouplingModel, FluidCoupling};
use crate::error::{BeltError, BeltResult};
use crate::model::Model;
use crate::pipeline::{Scratch, StageContext};
use crate::scene::{check_finite, Wrap};
use crate::state::State;
use serde::{Deserialize, Serialize};

/// An induction motor started direct on line (`[pulleys.drive.motor]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Motor {
    /// Rated (shaft) power P_r, W, > 0. Required.
    #[serde(deserialize_with = "crate::scene::required")]
    pub rated_power: f64,
    /// Rated speed n_r at the motor shaft, rad/s, > 0 (1485 rpm = 155.5 rad/s). Required.
    #[serde(deserialize_with = "crate::scene::required")]
    pub rated_speed: f64,
    /// Synchronous speed n_s, rad/s, > `rated_speed` (4-pole, 50 Hz: 157.08 rad/s).
    /// Required.
    #[serde(deserialize_with = "crate::scene::required")]
    pub synchronous_speed: f64,
    /// Breakdown torque / rated torque k of the Kloss curve, > 1. Default 2.5.
    #[serde(default = "default_breakdown")]
    pub breakdown_torque_ratio: f64,
    /// Torque–speed table instead of the Kloss curve: motor speeds, rad/s, strictly
    /// increasing (linear between points, held beyond the ends). Default none.
    #[serde(default)]
    pub speed: Option<Vec<f64>>,
    /// The table's torques at the motor shaft, N·m. With `speed`. Default none.
    #[serde(default)]
    pub torque: Option<Vec<f64>>,
    /// Gear ratio i = motor speed / pulley speed, > 0. Default 1.
    #[serde(default = "one")]
    pub gear_ratio: f64,
    /// Sense in which the motor turns the pulley: `"ccw"` (default) or `"cw"`.
    #[serde(default)]
    pub rotation: Wrap,
    /// Inertia of the rotor (and of a coupling's pump side), kg·m² at the motor shaft, ≥ 0;
    /// > 0 with a coupling. Default 0.
    #[serde(default)]
    pub rotor_inertia: f64,
    /// Time the motor is switched on (the contactor closes), s. Default 0.
    #[serde(default)]
    pub start: f64,
    /// Fluid coupling between motor and gearbox. Default none (rigid).
    #[serde(default)]
    pub coupling: Option<FluidCoupling>,
}

fn default_breakdown() -> f64 {
    2.5
}

fn one() -> f64 {
    1.0
}

impl Default for Motor {
    fn default() -> Self {
        Motor {
            rated_power: 0.0,
            rated_speed: 0.0,
            synchronous_speed: 0.0,
            breakdown_torque_ratio: 2.5,
            speed: None,
            torque: None,
            gear_ratio: 1.0,
            rotation: Wrap::CounterClockwise,
            rotor_inertia: 0.0,
            start: 0.0,
            coupling: None,
        }
    }
}

impl Motor {
    /// Keys a scene must give.
    pub const REQUIRED: [&'static str; 3] = ["rated_power", "rated_speed", "synchronous_speed"];

    /// Rated torque T_r = P_r/n_r, N·m.
    pub fn rated_torque(&self) -> f64 {
        self.rated_power / self.rated_speed
    }

    /// Check every field; `f` names the table (`pulleys[0].drive.motor`).
    pub fn validate(&self, f: &str) -> BeltResult<()> {
        let positive = |k: &str, v: f64| -> BeltResult<()> {
            check_finite(&format!("{f}.{k}"), v)?;
            if v > 0.0 {
                Ok(())
            } else {
                Err(BeltError::invalid(format!("{f}.{k}"), v, "must be > 0"))
            }
        };
        positive("rated_power", self.rated_power)?;
        positive("rated_speed", self.rated_speed)?;
        positive("synchronous_speed", self.synchronous_speed)?;
        if self.synchronous_speed <= self.rated_speed {
            return Err(BeltError::invalid(
                format!("{f}.synchronous_speed"),
                self.synchronous_speed,
                format!(
                    "must exceed rated_speed ({} rad/s): an induction motor runs below its synchronous speed",
                    self.rated_speed
                ),
            ));
        }
        check_finite(
            &format!("{f}.breakdown_torque_ratio"),
            self.breakdown_torque_ratio,
        )?;
        if self.breakdown_torque_ratio <= 1.0 {
            return Err(BeltError::invalid(
                format!("{f}.breakdown_torque_ratio"),
                self.breakdown_torque_ratio,
                "must be > 1 (breakdown torque / rated torque)",
            ));
        }
        positive("gear_ratio", self.gear_ratio)?;
        check_finite(&format!("{f}.rotor_inertia"), self.rotor_inertia)?;
        if self.rotor_inertia < 0.0 {
            return Err(BeltError::invalid(
                format!("{f}.rotor_inertia"),
                self.rotor_inertia,
                "must be ≥ 0",
            ));
        }
        check_finite(&format!("{f}.start"), self.start)?;
        match (&self.speed, &self.torque) {
            (None, None) => {}
            (Some(x), Some(y)) => {
                if x.len() != y.len() || x.len() < 2 {
                    return Err(BeltError::invalid(
                        format!("{f}.torque"),
                        format!("{} values", y.len()),
                        format!(
                            "needs as many values as {f}.speed ({}), at least 2",
                            x.len()
                        ),
                    ));
                }
                for (i, (&a, &b)) in x.iter().zip(y).enumerate() {
                    check_finite(&format!("{f}.speed[{i}]"), a)?;
                    check_finite(&format!("{f}.torque[{i}]"), b)?;
                    if i > 0 && a <= x[i - 1] {
                        return Err(BeltError::invalid(
                            format!("{f}.speed[{i}]"),
                            a,
                            format!("must increase strictly (previous value {})", x[i - 1]),
                        ));
                    }
                }
            }
            (Some(_), None) => {
                return Err(BeltError::invalid(
                    format!("{f}.torque"),
                    "missing",
                    format!("needed with {f}.speed"),
                ))
            }
            (None, Some(_)) => {
                return Err(BeltError::invalid(
                    format!("{f}.speed"),
                    "missing",
                    format!("needed with {f}.torque"),
                ))
            }
        }
        if let Some(c) = &self.coupling {
            c.validate(&format!("{f}.coupling"))?;
            if self.rotor_inertia <= 0.0 {
                return Err(BeltError::invalid(
                    format!("{f}.rotor_inertia"),
                    self.rotor_inertia,
                    format!("must be > 0 with {f}.coupling: the motor is then a body of its own"),
                ));
            }
        }
        Ok(())
    }
}

/// A torque–speed curve at the motor shaft.
#[derive(Debug, Clone, PartialEq)]
pub enum MotorCurve {
    /// Kloss: breakdown torque T_b (N·m), breakdown slip s_b, synchronous speed n_s (rad/s).
    Kloss {
        /// T_b, N·m.
        breakdown_torque: f64,
        /// s_b.
        breakdown_slip: f64,
        /// n_s, rad/s.
        synchronous_speed: f64,
    },
    /// A table (speeds rad/s, torques N·m).
    Table(crate::scene::Table),
}

impl MotorCurve {
    /// The Kloss curve through the rated point of `m`.
    pub fn kloss(m: &Motor) -> MotorCurve {
        let k = m.breakdown_torque_ratio;
        let rated_slip = (m.synchronous_speed - m.rated_speed) / m.synchronous_speed;
        MotorCurve::Kloss {
            breakdown_torque: k * m.rated_torque(),
            breakdown_slip: rated_slip * (k + (k * k - 1.0).sqrt()),
            synchronous_speed: m.synchronous_speed,
        }
    }

    /// Motor torque at motor speed `n` (rad/s), N·m.
    #[inline]
    pub fn torque(&self, n: f64) -> f64 {
        match self {
            MotorCurve::Kloss {
                breakdown_torque,
                breakdown_slip,
                synchronous_speed,
            } => {
                let s = (synchronous_speed - n) / synchronous_speed;
                // 2·T_b/(s/s_b + s_b/s) written without the division by s.
                2.0 * breakdown_torque * s * breakdown_slip
                    / (s * s + breakdown_slip * breakdown_slip)
            }
            MotorCurve::Table(t) => t.eval(n),
        }
    }

    /// Largest |dT/dn|, N·m·s/rad: the damping the curve adds (at s = 0 for Kloss).
    pub fn max_slope(&self) -> f64 {
        match self {
            MotorCurve::Kloss {
                breakdown_torque,
                breakdown_slip,
                synchronous_speed,
            } => 2.0 * breakdown_torque / (breakdown_slip * synchronous_speed),
            MotorCurve::Table(t) => {
                t.x.windows(2)
                    .zip(t.y.windows(2))
                    .map(|(x, y)| ((y[1] - y[0]) / (x[1] - x[0])).abs())
                    .fold(0.0, f64::max)
            }
        }
    }
}

/// A compiled motor.
#[derive(Debug, Clone, PartialEq)]
pub struct MotorModel {
    /// Torque–speed curve at the motor shaft.
    pub curve: MotorCurve,
    /// σ·i: motor speed per pulley speed (signed by the sense of rotation).
    pub factor: f64,
    /// Switch-on time, s.
    pub start: f64,
    /// Rotor inertia at the motor shaft, kg·m².
    pub rotor_inertia: f64,
    /// Fluid coupling, if any.
    pub coupling: Option<CouplingModel>,
}

impl MotorModel {
    /// Compile a validated motor.
    pub fn compile(m: &Motor) -> MotorModel {
        let curve = match (&m.speed, &m.torque) {
            (Some(x), Some(y)) => MotorCurve::Table(crate::scene::Table {
                x: x.clone(),
                y: y.clone(),
            }),
            _ => MotorCurve::kloss(m),
        };
        MotorModel {
            curve,
            factor: m.rotation.sign() * m.gear_ratio,
            start: m.start,
            rotor_inertia: m.rotor_inertia,
            coupling: m
                .coupling
                .as_ref()
                .map(|c| CouplingModel::compile(c, m.rated_torque(), m.rated_speed)),
        }
    }

    /// Inertia the motor adds to its pulley, kg·m²: i²·J_r when rigidly geared, 0 behind a
    /// coupling (the rotor is then a body of its own).
    pub fn reflected_inertia(&self) -> f64 {
        if self.coupling.is_some() {
            0.0
        } else {
            self.factor * self.factor * self.rotor_inertia
        }
    }

    /// Explicit stability limit, s, on a pulley of inertia `inertia` (kg·m², with the
    /// reflected rotor): the curve's slope is a damper, on the pulley (i²·slope) when
    /// rigid, on the rotor behind a coupling, whose slope couples rotor and pulley.
    /// Half the limit 2·I/c, as for the bearing drag.
    pub fn stable_step(&self, inertia: f64) -> f64 {
        let i2 = self.factor * self.factor;
        match &self.coupling {
            None => inertia / (i2 * self.curve.max_slope()),
            Some(c) => {
                let slope = c.max_slope(self.top_speed());
                let motor = self.rotor_inertia / (self.curve.max_slope() + slope);
                let pair = 1.0 / (slope * (1.0 / self.rotor_inertia + i2 / inertia));
                motor.min(pair)
            }
        }
    }

    /// Highest motor speed the stable-step estimate allows for, rad/s: 1.2 × the
    /// synchronous speed (the table's last speed for a table).
    fn top_speed(&self) -> f64 {
        1.2 * match &self.curve {
            MotorCurve::Kloss {
                synchronous_speed, ..
            } => *synchronous_speed,
            MotorCurve::Table(t) => t.x.last().copied().unwrap_or(0.0).abs(),
        }
    }
}

/// What the `motors` stage decided, for [`advance_all`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MotorOutput {
    /// Motor torque at the motor shaft, N·m.
    pub motor_torque: f64,
    /// Torque the coupling passes on (= the motor torque without one), N·m at the shaft.
    pub coupling_torque: f64,
    /// Torque on the pulley, N·m (σ·i × the coupling torque).
    pub pulley_torque: f64,
    /// The stage ran with drives on.
    pub active: bool,
}

/// The `motors` stage: each DOL motor's torque on its pulley (off in the relaxation).
pub fn motors(cx: &mut StageContext<'_>) {
    let (m, s, sc) = (cx.model, &*cx.state, &mut *cx.scratch);
    if !cx.effects.drives {
        sc.motor.iter_mut().for_each(|o| o.active = false);
        return;
    }
    for (j, p) in m.pulleys.iter().enumerate() {
        let Some(mm) = &p.motor else { continue };
        // Switched on at `start`, off again at the drive's `power_off` (the rotor then coasts).
        let on = s.time >= mm.start && p.drive.as_ref().is_none_or(|d| d.powered(s.time));
        let shaft = mm.factor * s.pulley_omega[j];
        let (motor_torque, coupling_torque) = match &mm.coupling {
            None => {
                let t = if on { mm.curve.torque(shaft) } else { 0.0 };
                (t, t)
            }
            Some(c) => {
                let n = s.drive_memory[j].motor_speed;
                let t = if on { mm.curve.torque(n) } else { 0.0 };
                (t, c.torque(n, shaft))
            }
        };
        let pulley_torque = mm.factor * coupling_torque;
        sc.drive_torque[j] += pulley_torque;
        sc.motor[j] = MotorOutput {
            motor_torque,
            coupling_torque,
            pulley_torque,
            active: true,
        };
    }
}

/// After a step with velocity update `kick` (s): each coupled motor's speed moves by
/// kick·(T_motor − T_coupling)/J_r (central differences, like every rigid speed).
pub fn advance_all(m: &Model, s: &mut State, sc: &Scratch, kick: f64) {
    for (j, p) in m.pulleys.iter().enumerate() {
        let Some(mm) = &p.motor else { continue };
        let out = sc.motor[j];
        if mm.coupling.is_some() && out.active {
            s.drive_memory[j].motor_speed +=
                kick * (out.motor_torque - out.coupling_torque) / mm.rotor_inertia;
        }
    }
}

/// Start the rotor of every fluid-coupled motor of `m` whose pulley turns in the state `s`
/// at its running point on the coupling (`super::prime`): the speed n where the motor's
/// torque (0 if it is off at this time) equals the coupling's, T_motor(n) =
/// T_coupling(n, σ·i·ω). A pulley at rest leaves the rotor at rest (a motor switched on at
/// t = 0 starts from standstill).
pub fn prime(m: &Model, s: &mut State) {
    for (j, p) in m.pulleys.iter().enumerate() {
        let Some(mm) = &p.motor else { continue };
        let Some(c) = &mm.coupling else { continue };
        if s.pulley_omega[j] == 0.0 {
            continue;
        }
        let on = s.time >= mm.start && p.drive.as_ref().is_none_or(|d| d.powered(s.time));
        let shaft = mm.factor * s.pulley_omega[j];
        let excess = |n: f64| {
            let motor = if on { mm.curve.torque(n) } else { 0.0 };
            motor - c.torque(n, shaft)
        };
        if let Some(n) = root_from(shaft, excess) {
            s.drive_memory[j].motor_speed = n;
        }
    }
}

/// The root of `f` nearest `x0` on the side where f(x0) points (f decreasing through it, as
/// the rotor's excess torque through a running point), by doubling steps then bisection;
/// `None` if no sign change is found within 2⁶⁰ × the first step.
fn root_from(x0: f64, f: impl Fn(f64) -> f64) -> Option<f64> {
    let f0 = f(x0);
    if f0 == 0.0 {
        return Some(x0);
    }
    let side = f0.signum();
    let mut step = 1e-3 * x0.abs().max(1e-3);
    let mut far = x0 + side * step;
    let mut near = x0;
    let mut tries = 0;
    while f(far).signum() == side {
        near = far;
        step *= 2.0;
        far = x0 + side * step;
        tries += 1;
        if tries > 60 {
            return None;
        }
    }
    // f(near) has f0's sign, f(far) the other.
    for _ in 0..200 {
        let mid = 0.5 * (near + far);
        if mid == near || mid == far {
            break;
        }
        if f(mid).signum() == side {
            near = mid;
        } else {
            far = mid;
        }
    }
    Some(0.5 * (near + far))
}
