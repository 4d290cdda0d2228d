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
//!
//! **A table** (`slip`, `torque`) replaces the hyperbola with the maker's curve: the torque
//! T_n(s) passed at the input speed n_r (`rated_speed`), linear between the points, from
//! (0, 0) to the first point and held beyond the last; T = (n_p/n_r)²·T_n(s), odd in s.
//! It must rise with the slip (a constant-fill coupling passes more torque the more it
//! slips) and start from no torque at no slip.

use crate::error::{BeltError, BeltResult};
use crate::scene::{check_finite, Table};
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
    /// Slips of a torque table that replaces the hyperbola (module docs), dimensionless,
    /// strictly increasing in [0, 1], at least two. Default none.
    pub slip: Option<Vec<f64>>,
    /// The table's torques, N·m, passed at input speed `rated_speed` (the motor's rated
    /// speed by default): finite, ≥ 0, non-decreasing, 0 at a slip of 0, > 0 at the last
    /// slip. With `slip`; `rated_torque`, `rated_slip` and `stall_torque_ratio` are then
    /// the hyperbola's and must be left out. Default none.
    pub torque: Option<Vec<f64>>,
}

impl Default for FluidCoupling {
    fn default() -> Self {
        FluidCoupling {
            rated_torque: None,
            rated_speed: None,
            rated_slip: 0.03,
            stall_torque_ratio: 5.0,
            slip: None,
            torque: None,
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
        if self.slip.is_some() || self.torque.is_some() {
            return self.validate_table(f);
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

    /// The rules of a torque table (`slip`, `torque`; `rated_speed` checked by `validate`).
    fn validate_table(&self, f: &str) -> BeltResult<()> {
        let (x, y) = match (&self.slip, &self.torque) {
            (Some(x), Some(y)) => (x, y),
            (Some(_), None) => {
                return Err(BeltError::invalid(
                    format!("{f}.torque"),
                    "missing",
                    format!("needed with {f}.slip: the torque (N·m) at each slip"),
                ))
            }
            _ => {
                return Err(BeltError::invalid(
                    format!("{f}.slip"),
                    "missing",
                    format!("needed with {f}.torque: the slip (0 to 1) of each torque"),
                ))
            }
        };
        let defaults = FluidCoupling::default();
        for (key, given, default) in [
            ("rated_slip", self.rated_slip, defaults.rated_slip),
            (
                "stall_torque_ratio",
                self.stall_torque_ratio,
                defaults.stall_torque_ratio,
            ),
        ]
        .into_iter()
        .chain(self.rated_torque.map(|t| ("rated_torque", t, f64::NAN)))
        {
            if given.to_bits() != default.to_bits() {
                return Err(BeltError::invalid(
                    format!("{f}.{key}"),
                    given,
                    format!("has no effect with a torque table ({f}.slip/torque replace the characteristic): leave it out"),
                ));
            }
        }
        if x.len() != y.len() || x.len() < 2 {
            return Err(BeltError::invalid(
                format!("{f}.torque"),
                format!("{} values", y.len()),
                format!("needs as many values as {f}.slip ({}), at least 2", x.len()),
            ));
        }
        for (i, (&s, &t)) in x.iter().zip(y).enumerate() {
            check_finite(&format!("{f}.slip[{i}]"), s)?;
            check_finite(&format!("{f}.torque[{i}]"), t)?;
            if !(0.0..=1.0).contains(&s) {
                return Err(BeltError::invalid(
                    format!("{f}.slip[{i}]"),
                    s,
                    "must be in [0, 1] (slip = (n_in − n_out)/n_in, dimensionless)",
                ));
            }
            if i > 0 && s <= x[i - 1] {
                return Err(BeltError::invalid(
                    format!("{f}.slip[{i}]"),
                    s,
                    format!("must increase strictly (previous value {})", x[i - 1]),
                ));
            }
            if t < 0.0 {
                return Err(BeltError::invalid(
                    format!("{f}.torque[{i}]"),
                    t,
                    "must be ≥ 0 (N·m passed from the motor to the load at this slip)",
                ));
            }
            if i > 0 && t < y[i - 1] {
                return Err(BeltError::invalid(
                    format!("{f}.torque[{i}]"),
                    t,
                    format!(
                        "must not fall as the slip grows (previous value {} N·m): a fluid coupling passes more torque the more it slips",
                        y[i - 1]
                    ),
                ));
            }
            if s == 0.0 && t != 0.0 {
                return Err(BeltError::invalid(
                    format!("{f}.torque[{i}]"),
                    t,
                    "must be 0 at a slip of 0: a fluid coupling passes torque only by slipping",
                ));
            }
        }
        let last = y[y.len() - 1];
        if last <= 0.0 {
            return Err(BeltError::invalid(
                format!("{f}.torque[{}]", y.len() - 1),
                last,
                "must be > 0 (N·m): a coupling that passes no torque drives nothing",
            ));
        }
        Ok(())
    }
}

/// A compiled coupling.
#[derive(Debug, Clone, PartialEq)]
pub struct CouplingModel {
    /// T_r, N·m.
    pub rated_torque: f64,
    /// n_r, rad/s.
    pub rated_speed: f64,
    /// s_r.
    pub rated_slip: f64,
    /// b of the characteristic.
    pub shape: f64,
    /// The torque table T_n(s) at input speed n_r (slip, N·m), starting at (0, 0); `None`:
    /// the hyperbola.
    pub table: Option<Table>,
}

impl CouplingModel {
    /// Compile `c` for a motor of rated torque and speed `motor_torque`, `motor_speed`.
    pub fn compile(c: &FluidCoupling, motor_torque: f64, motor_speed: f64) -> CouplingModel {
        let k = c.stall_torque_ratio;
        let table = c.slip.as_ref().zip(c.torque.as_ref()).map(|(x, y)| {
            let mut t = Table {
                x: x.clone(),
                y: y.clone(),
            };
            if t.x[0] > 0.0 {
                t.x.insert(0, 0.0);
                t.y.insert(0, 0.0);
            }
            t
        });
        CouplingModel {
            rated_torque: c.rated_torque.unwrap_or(motor_torque),
            rated_speed: c.rated_speed.unwrap_or(motor_speed),
            rated_slip: c.rated_slip,
            shape: (1.0 - k * c.rated_slip) / (k - 1.0),
            table,
        }
    }

    /// Torque passed at the input speed n_r and slip `slip` ≥ 0, N·m: T_r·φ(s), or the
    /// table's T_n(s).
    #[inline]
    pub fn torque_at_rated_speed(&self, slip: f64) -> f64 {
        match &self.table {
            None => self.rated_torque * self.characteristic(slip),
            Some(t) => t.eval(slip),
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
        q * q * self.torque_at_rated_speed(slip.abs()).copysign(slip)
    }

    /// Largest |∂T/∂(n_in − n_out)| up to a pump speed `top` (rad/s), N·m·s/rad:
    /// top·max T_n′(s)/n_r², at zero slip for the hyperbola (T_n′(0) = T_r·(1 + b)/s_r), on
    /// the steepest segment for a table.
    pub fn max_slope(&self, top: f64) -> f64 {
        let steepest = match &self.table {
            None => self.rated_torque * (1.0 + self.shape) / self.rated_slip,
            Some(t) => {
                t.x.windows(2)
                    .zip(t.y.windows(2))
                    .map(|(x, y)| (y[1] - y[0]) / (x[1] - x[0]))
                    .fold(0.0, f64::max)
            }
        };
        top * steepest / (self.rated_speed * self.rated_speed)
    }
}
