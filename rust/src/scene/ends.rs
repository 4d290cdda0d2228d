//! The ends of an open belt (`belt.start`, `belt.end`): a belt with both is open, one
//! without is a closed loop. Formulation-agnostic: an end is a point where the belt's
//! first (or last) material point is placed and what holds it there, so any belt model
//! whose first and last material points carry the end conditions can use it.

use super::forms::Named;
use super::validate::{check_finite, check_positive};
use crate::error::{BeltError, BeltResult};
use serde::{Deserialize, Serialize};

/// What holds an end of an open belt.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EndHold {
    /// `"anchor"`: the end is fixed at its point (the anchor takes whatever force the belt
    /// puts on it).
    #[default]
    Anchor,
    /// `"force"`: a constant force of `force` N pulls the end, along the initial span from
    /// its pulley's tangent point to the end point (away from the pulley).
    Force,
    /// `"mass"`: a mass of `mass` kg hangs at the end (a hoist's load): it moves with the
    /// end, with its weight under the scene's gravity.
    Mass,
}

/// One end of an open belt (`[belt.start]` or `[belt.end]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct BeltEndSpec {
    /// Where the end is placed, (x, y) m: the belt runs straight from here to its tangent
    /// point on the first pulley (`start`), or from the last pulley to here (`end`). Must
    /// lie outside every pulley. Required.
    pub point: Option<[f64; 2]>,
    /// What holds the end. Default `"anchor"`.
    pub hold: EndHold,
    /// With `hold = "force"`: the pull at t = 0, N, finite, > 0. Default `None`.
    pub force: Option<f64>,
    /// With `hold = "force"`: the rate at which the pull rises (or falls), N/s, finite:
    /// F(t) = `force` + `force_rate`·t, held at 0 from below (a slowly loaded capstan, a
    /// winch taking up load). `None`: a constant pull. Default `None`.
    pub force_rate: Option<f64>,
    /// With `hold = "mass"`: the hanging mass, kg, finite, > 0. Default `None`.
    pub mass: Option<f64>,
}

impl Default for BeltEndSpec {
    fn default() -> Self {
        BeltEndSpec {
            point: None,
            hold: EndHold::Anchor,
            force: None,
            force_rate: None,
            mass: None,
        }
    }
}

impl BeltEndSpec {
    /// The end point, m (validated: present and finite).
    pub fn at(&self) -> [f64; 2] {
        self.point.unwrap_or([f64::NAN; 2])
    }

    /// Check the end named `f` (`belt.start` or `belt.end`): a finite point, and exactly the
    /// value its hold needs.
    pub(crate) fn validate(&self, f: &str) -> BeltResult<()> {
        let Some(p) = self.point else {
            return Err(BeltError::invalid(
                format!("{f}.point"),
                "missing",
                "required: where the belt's end is placed, [x, y] in m",
            ));
        };
        check_finite(&format!("{f}.point[0]"), p[0])?;
        check_finite(&format!("{f}.point[1]"), p[1])?;
        let needs = |key: &str, value: Option<f64>, unit: &str| -> BeltResult<()> {
            match value {
                Some(v) => check_positive(&format!("{f}.{key}"), v),
                None => Err(BeltError::invalid(
                    format!("{f}.{key}"),
                    "missing",
                    format!(
                        "required with {f}.hold = \"{}\" ({unit}, > 0)",
                        self.hold.scene_name()
                    ),
                )),
            }
        };
        let refuses = |key: &str, value: Option<f64>| -> BeltResult<()> {
            match value {
                // It would be silently ignored.
                Some(v) => Err(BeltError::invalid(
                    format!("{f}.{key}"),
                    v,
                    format!(
                        "has no effect with {f}.hold = \"{}\" (leave it out)",
                        self.hold.scene_name()
                    ),
                )),
                None => Ok(()),
            }
        };
        match self.hold {
            EndHold::Anchor => {
                refuses("force", self.force)?;
                refuses("force_rate", self.force_rate)?;
                refuses("mass", self.mass)
            }
            EndHold::Force => {
                needs("force", self.force, "N")?;
                if let Some(rate) = self.force_rate {
                    check_finite(&format!("{f}.force_rate"), rate)?;
                }
                refuses("mass", self.mass)
            }
            EndHold::Mass => {
                needs("mass", self.mass, "kg")?;
                refuses("force_rate", self.force_rate)?;
                refuses("force", self.force)
            }
        }
    }
}
