//! Conveyor starting curves (Guo & Wang 2020 §4): the belt speed a speed-controlled drive
//! (a VFD) prescribes while it starts a conveyor, with an optional pre-start (creep)
//! section. See `docs/drives.md` for the formulas, the derivation of the continuous
//! Nordell curve and the control semantics.
//!
//! With τ = (t − t₀)/T the fraction of a ramp of duration T that began at t₀, every shape
//! is v₀·s(τ) with s(0) = 0, s(1) = 1, s non-decreasing:
//!
//! | shape | s(τ) | s′(τ) |
//! |---|---|---|
//! | Harrison | (1 − cos πτ)/2 | (π/2)·sin πτ |
//! | Nordell | 2τ² (τ ≤ ½); −1 + 4τ − 2τ² (τ > ½) | 4τ; 4 − 4τ |
//! | cubic | 3τ² − 2τ³ | 6τ − 6τ² |
//! | linear | τ | 1 |

use crate::error::{BeltError, BeltResult};
use crate::scene::check_finite;
use serde::{Deserialize, Serialize};

/// Shape of a starting ramp, s(τ) on τ ∈ [0, 1].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum StartShape {
    /// Harrison: s = (1 − cos πτ)/2, zero acceleration at both ends.
    #[default]
    Harrison,
    /// Nordell: two parabolas, s = 2τ² for τ ≤ ½ and −1 + 4τ − 2τ² beyond; speed and
    /// acceleration continuous at ½, zero acceleration at τ = 1 (the continuous form of the
    /// curve Guo & Wang print garbled).
    Nordell,
    /// Cubic step: s = 3τ² − 2τ³ (zero acceleration at both ends).
    Cubic,
    /// Linear: s = τ, constant acceleration (steps at both ends).
    Linear,
}

impl StartShape {
    /// Every shape, in the order of the names in [`StartShape::NAMES`].
    pub const ALL: [StartShape; 4] = [
        StartShape::Harrison,
        StartShape::Nordell,
        StartShape::Cubic,
        StartShape::Linear,
    ];
    /// Names used in scene files and in Python.
    pub const NAMES: [&'static str; 4] = ["harrison", "nordell", "cubic", "linear"];

    /// Name used in scene files and in Python.
    pub fn name(self) -> &'static str {
        match self {
            StartShape::Harrison => "harrison",
            StartShape::Nordell => "nordell",
            StartShape::Cubic => "cubic",
            StartShape::Linear => "linear",
        }
    }

    /// The shape called `name`, if any.
    pub fn from_name(name: &str) -> Option<StartShape> {
        Self::ALL.into_iter().find(|s| s.name() == name)
    }

    /// (s(τ), ds/dτ) for τ in [0, 1).
    #[inline]
    pub fn unit(self, tau: f64) -> (f64, f64) {
        use std::f64::consts::PI;
        match self {
            StartShape::Harrison => (0.5 * (1.0 - (PI * tau).cos()), 0.5 * PI * (PI * tau).sin()),
            StartShape::Nordell => {
                if tau <= 0.5 {
                    (2.0 * tau * tau, 4.0 * tau)
                } else {
                    (-1.0 + 4.0 * tau - 2.0 * tau * tau, 4.0 - 4.0 * tau)
                }
            }
            StartShape::Cubic => (tau * tau * (3.0 - 2.0 * tau), 6.0 * tau * (1.0 - tau)),
            StartShape::Linear => (tau, 1.0),
        }
    }
}

/// A starting curve: the belt speed at the drive pulley surface against time.
///
/// Before `start` the speed is 0. With `prestart` > 0 the drive first runs up to
/// `creep_speed` over `creep_ramp` seconds (same shape) and holds it until
/// `start + prestart`; the main ramp then takes the speed from the creep speed (0 without
/// a pre-start) to `speed` over `ramp` seconds, after which the speed stays at `speed`.
///
/// In a scene (`[pulleys.drive.start_curve]`) `speed` and `ramp` are required; every other
/// key defaults as [`StartCurve::default`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StartCurve {
    /// Shape of both ramps. Default [`StartShape::Harrison`].
    #[serde(default)]
    pub shape: StartShape,
    /// Final belt speed v₀ at the drive pulley surface, m/s, counter-clockwise positive
    /// (pulley speed ω = v/r). Required: finite and non-zero (the default 0 is refused).
    #[serde(deserialize_with = "crate::scene::required")]
    pub speed: f64,
    /// Duration T of the main ramp, s, > 0. Required (the default 0 is refused).
    #[serde(deserialize_with = "crate::scene::required")]
    pub ramp: f64,
    /// Time the curve begins (absolute simulated time), s, finite. Default 0.
    #[serde(default)]
    pub start: f64,
    /// Duration of the pre-start (delay) section, s, ≥ 0. Default 0 (none).
    #[serde(default)]
    pub prestart: f64,
    /// Creep speed held during the pre-start, m/s: between 0 and `speed` (same sign).
    /// `None`: 10 % of `speed`. Only with `prestart` > 0. Default `None`.
    #[serde(default)]
    pub creep_speed: Option<f64>,
    /// Duration of the run-up to the creep speed, s, in (0, `prestart`]. `None`:
    /// `prestart`/2. Only with `prestart` > 0. Default `None`.
    #[serde(default)]
    pub creep_ramp: Option<f64>,
}

impl StartCurve {
    /// Keys a scene must give (they have no default).
    pub const REQUIRED: [&'static str; 2] = ["speed", "ramp"];
}

impl Default for StartCurve {
    fn default() -> Self {
        StartCurve {
            shape: StartShape::Harrison,
            speed: 0.0,
            ramp: 0.0,
            start: 0.0,
            prestart: 0.0,
            creep_speed: None,
            creep_ramp: None,
        }
    }
}

impl StartCurve {
    /// Creep speed in use, m/s (0 without a pre-start).
    pub fn creep_speed_or_default(&self) -> f64 {
        if self.prestart > 0.0 {
            self.creep_speed.unwrap_or(0.1 * self.speed)
        } else {
            0.0
        }
    }

    /// Duration of the run-up to the creep speed in use, s (0 without a pre-start).
    pub fn creep_ramp_or_default(&self) -> f64 {
        if self.prestart > 0.0 {
            self.creep_ramp.unwrap_or(0.5 * self.prestart)
        } else {
            0.0
        }
    }

    /// Belt speed (m/s) and acceleration (m/s²) at time `t` (s). Exact: the analytic
    /// formulas of the shape. Ramps are half-open intervals [begin, end): at a ramp's end
    /// the acceleration is that of what follows (0 after the main ramp).
    pub fn evaluate(&self, t: f64) -> (f64, f64) {
        let creep = self.creep_speed_or_default();
        if self.prestart > 0.0 {
            let creep_ramp = self.creep_ramp_or_default();
            if t < self.start {
                return (0.0, 0.0);
            }
            if t < self.start + creep_ramp {
                let (s, ds) = self.shape.unit((t - self.start) / creep_ramp);
                return (creep * s, creep * ds / creep_ramp);
            }
            if t < self.start + self.prestart {
                return (creep, 0.0);
            }
        }
        let begin = self.start + self.prestart;
        if t < begin {
            return (0.0, 0.0);
        }
        if t >= begin + self.ramp {
            return (self.speed, 0.0);
        }
        let (s, ds) = self.shape.unit((t - begin) / self.ramp);
        let rise = self.speed - creep;
        (creep + rise * s, rise * ds / self.ramp)
    }

    /// Belt speed at time `t`, m/s.
    #[inline]
    pub fn speed_at(&self, t: f64) -> f64 {
        self.evaluate(t).0
    }

    /// Belt acceleration at time `t`, m/s².
    pub fn acceleration_at(&self, t: f64) -> f64 {
        self.evaluate(t).1
    }

    /// Time the speed reaches `speed` for good, s.
    pub fn end(&self) -> f64 {
        self.start + self.prestart + self.ramp
    }

    /// Check every field; `field` names the curve in messages (e.g.
    /// `pulleys[0].drive.start_curve`).
    pub fn validate(&self, field: &str) -> BeltResult<()> {
        let key = |k: &str| format!("{field}.{k}");
        check_finite(&key("speed"), self.speed)?;
        if self.speed == 0.0 {
            return Err(BeltError::invalid(
                key("speed"),
                self.speed,
                "must be non-zero (the final belt speed, m/s, counter-clockwise positive)",
            ));
        }
        check_finite(&key("ramp"), self.ramp)?;
        if self.ramp <= 0.0 {
            return Err(BeltError::invalid(key("ramp"), self.ramp, "must be > 0"));
        }
        check_finite(&key("start"), self.start)?;
        check_finite(&key("prestart"), self.prestart)?;
        if self.prestart < 0.0 {
            return Err(BeltError::invalid(
                key("prestart"),
                self.prestart,
                "must be ≥ 0",
            ));
        }
        if self.prestart == 0.0 {
            // They would be silently ignored.
            for (name, value) in [
                ("creep_speed", self.creep_speed),
                ("creep_ramp", self.creep_ramp),
            ] {
                if let Some(v) = value {
                    return Err(BeltError::invalid(
                        key(name),
                        v,
                        format!("has no effect without a pre-start (give {field}.prestart > 0, or leave {name} out)"),
                    ));
                }
            }
            return Ok(());
        }
        if let Some(c) = self.creep_speed {
            check_finite(&key("creep_speed"), c)?;
            let fraction = c / self.speed;
            if !(0.0..=1.0).contains(&fraction) {
                return Err(BeltError::invalid(
                    key("creep_speed"),
                    c,
                    format!(
                        "must be between 0 and speed ({}), with the same sign",
                        self.speed
                    ),
                ));
            }
        }
        if let Some(r) = self.creep_ramp {
            check_finite(&key("creep_ramp"), r)?;
            if !(r > 0.0 && r <= self.prestart) {
                return Err(BeltError::invalid(
                    key("creep_ramp"),
                    r,
                    format!("must be > 0 and ≤ prestart ({})", self.prestart),
                ));
            }
        }
        Ok(())
    }
}
