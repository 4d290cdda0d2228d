//! Fluid (hydrodynamic) couplings between a DOL motor and its gearbox (`docs/drives.md`).
//!
//! A constant-fill coupling passes a torque that grows with the square of the pump speed
//! and with the slip: T = T_r·(n_p/n_r)²·φ(s), with n_p the speed of the faster shaft
//! (it pumps), s = (n_in − n_out)/n_p the slip and φ(s_r) = 1 at the rated slip s_r. The
//! characteristic is the saturating hyperbola through the rated point and the stall point
//! φ(1) = k (stall torque / rated torque at the same input speed):
//!
//!   φ(s) = (s/s_r)·(1 + b)/(1 + b·s/s_r),   b = (1 − k·s_r)/(k − 1),
//!
//! linear at small slip (as a coupling is near its running point) and flattening towards
//! stall; it needs 1 < k < 1/s_r (b > 0). It is odd in the slip: an overrunning belt drives
//! the motor back through the coupling.

use crate::error::{BeltError, BeltResult};
use crate::scene::check_finite;
use serde::{Deserialize, Serialize};

/// A constant-fill fluid coupling (`[pulleys.drive.motor.coupling]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FluidCoupling {
    /// Torque T_r passed at the rated slip and input speed, N·m, > 0. `None`: the motor's
    /// rated torque. Default `None`.
    pub rated_torque: Option<f64>,
    /// Input speed n_r of the rated point, rad/s, > 0. `None`: the motor's rated speed.
    /// Default `None`.
    pub rated_speed: Option<f64>,
    /// Slip s_r at the rated point, in (0, 1). Default 0.03.
    pub rated_slip: f64,
    /// Stall torque / rated torque k at the same input speed (output at rest), in
    /// (1, 1/s_r). Default 5.
    pub stall_torque_ratio: f64,
}

impl Default for FluidCoupling {
    fn default() -> Self {
        FluidCoupling {
            rated_torque: None,
            rated_speed: None,
            rated_slip: 0.03,
            stall_torque_ratio: 5.0,
        }
    }
}

impl FluidCoupling {
    /// Check every field; `f` names the table.
    pub fn validate(&self, f: &str) -> BeltResult<()> {
        for (k, v) in [
            ("rated_torque", self.rated_torque),
            ("rated_speed", self.rated_speed),
        ] {
            if let Some(v) = v {
                check_finite(&format!("{f}.{k}"), v)?;
                if v <= 0.0 {
                    return Err(BeltError::invalid(format!("{f}.{k}"), v, "must be > 0"));
                }
            }
        }
        check_finite(&format!("{f}.rated_slip"), self.rated_slip)?;
        if !(self.rated_slip > 0.0 && self.rated_slip < 1.0) {
            return Err(BeltError::invalid(
                format!("{f}.rated_slip"),
                self.rated_slip,
                "must be in (0, 1)",
            ));
        }
        let k = self.stall_torque_ratio;
        check_finite(&format!("{f}.stall_torque_ratio"), k)?;
        if !(k > 1.0 && k * self.rated_slip < 1.0) {
            return Err(BeltError::invalid(
                format!("{f}.stall_torque_ratio"),
                k,
                format!(
                    "must be in (1, 1/rated_slip = {}): the characteristic rises from the rated point to stall, and no faster than linearly",
                    1.0 / self.rated_slip
                ),
            ));
        }
        Ok(())
    }
}

/// A compiled coupling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CouplingModel {
    /// T_r, N·m.
    pub rated_torque: f64,
    /// n_r, rad/s.
    pub rated_speed: f64,
    /// s_r.
    pub rated_slip: f64,
    /// b of the characteristic.
    pub shape: f64,
}

impl CouplingModel {
    /// Compile `c` for a motor of rated torque and speed `motor_torque`, `motor_speed`.
    pub fn compile(c: &FluidCoupling, motor_torque: f64, motor_speed: f64) -> CouplingModel {
        let k = c.stall_torque_ratio;
        CouplingModel {
            rated_torque: c.rated_torque.unwrap_or(motor_torque),
            rated_speed: c.rated_speed.unwrap_or(motor_speed),
            rated_slip: c.rated_slip,
            shape: (1.0 - k * c.rated_slip) / (k - 1.0),
        }
    }

    /// φ(s) for s ≥ 0.
    #[inline]
    pub fn characteristic(&self, slip: f64) -> f64 {
        let x = slip / self.rated_slip;
        x * (1.0 + self.shape) / (1.0 + self.shape * x)
    }

    /// Torque passed from a shaft at `input` to one at `output` (rad/s, same sense), N·m.
    #[inline]
    pub fn torque(&self, input: f64, output: f64) -> f64 {
        let pump = input.abs().max(output.abs());
        if pump == 0.0 {
            return 0.0;
        }
        let slip = (input - output) / pump;
        let q = pump / self.rated_speed;
        self.rated_torque * q * q * self.characteristic(slip.abs()).copysign(slip)
    }

    /// Largest |∂T/∂(n_in − n_out)| up to a pump speed `top` (rad/s), N·m·s/rad: at zero
    /// slip, T_r·top·φ′(0)/n_r² with φ′(0) = (1 + b)/s_r.
    pub fn max_slope(&self, top: f64) -> f64 {
        self.rated_torque * top * (1.0 + self.shape)
            / (self.rated_slip * self.rated_speed * self.rated_speed)
    }
}
