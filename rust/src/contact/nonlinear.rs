//! Kubas's (2014) damped nonlinear penalty contact between a belt body's mass centre and a
//! pulley (Kubas eq. 4–11):
//!
//! N(p, ṗ) = c₁p² + c₂p + δ(p)·b·ṗ  for p > 0, and N = 0 for p ≤ 0 (eq. 9),
//!
//! where p = r_p − |r| is the penetration of the mass centre into the pulley circle (eq. 6),
//! ṗ = −(v − v_c)·r̂ its rate (eq. 7, with the pulley centre's velocity v_c, zero in the
//! paper), and δ(p) the smooth cubic damping ramp of eq. 11 that brings damping in from 0 at
//! p = 0 to full at p = p_max, so that a body arriving fast is not "stuck" to the pulley by a
//! damping force at first touch.
//!
//! Beyond the paper: the total normal force is clamped at zero from below. Eq. 9 alone lets
//! a body leaving the pulley fast (ṗ ≪ 0) be pulled back by the damping term; a contact
//! never pulls (the same rule as the node model's contact damping).

use crate::error::{BeltError, BeltResult};
use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// Smooth step of Kubas eq. 10: `y0` for x ≤ x0, `y1` for x ≥ x1 and
/// y0 + (y1 − y0)·d²(3 − 2d) with d = (x − x0)/(x1 − x0) between. Continuous with a
/// continuous first derivative (zero slope at both ends). Needs x1 > x0.
#[inline]
pub fn cubic_step(x: f64, x0: f64, y0: f64, x1: f64, y1: f64) -> f64 {
    if x <= x0 {
        y0
    } else if x >= x1 {
        y1
    } else {
        let d = (x - x0) / (x1 - x0);
        y0 + (y1 - y0) * d * d * (3.0 - 2.0 * d)
    }
}

/// dy/dx of [`cubic_step`]: 6(y1 − y0)·d(1 − d)/(x1 − x0) inside, 0 outside; the largest
/// slope is 1.5·(y1 − y0)/(x1 − x0) at the middle.
#[inline]
pub fn cubic_step_slope(x: f64, x0: f64, y0: f64, x1: f64, y1: f64) -> f64 {
    if x <= x0 || x >= x1 {
        0.0
    } else {
        let w = x1 - x0;
        let d = (x - x0) / w;
        6.0 * (y1 - y0) * d * (1.0 - d) / w
    }
}

/// Parameters of the nonlinear contact law (Kubas eq. 9 and 11). Defaults: case K's values
/// (Kubas section 4). In a scene it is a pulley's `nonlinear_contact` table.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct NonlinearContact {
    /// c₁: quadratic stiffness, N/m², ≥ 0. Default 3.0256·10⁹.
    pub quadratic_stiffness: f64,
    /// c₂: linear stiffness, N/m, ≥ 0 (c₁ + c₂ > 0). Default 6.5·10⁵.
    pub linear_stiffness: f64,
    /// b: full damping coefficient, N·s/m, ≥ 0. Default 300.
    pub damping: f64,
    /// p_max: penetration at which damping is fully in, m, > 0. Default 0.001.
    pub damping_depth: f64,
}

impl Default for NonlinearContact {
    fn default() -> Self {
        NonlinearContact {
            quadratic_stiffness: 3.0256e9,
            linear_stiffness: 6.5e5,
            damping: 300.0,
            damping_depth: 1e-3,
        }
    }
}

impl NonlinearContact {
    /// Check the ranges; `field` prefixes the field names in the error (e.g. `pulleys[0].contact`).
    pub fn validate(&self, field: &str) -> BeltResult<()> {
        let checks = [
            (
                "quadratic_stiffness",
                self.quadratic_stiffness,
                "must be finite and ≥ 0 (N/m²)",
            ),
            (
                "linear_stiffness",
                self.linear_stiffness,
                "must be finite and ≥ 0 (N/m)",
            ),
            ("damping", self.damping, "must be finite and ≥ 0 (N·s/m)"),
        ];
        for (name, v, rule) in checks {
            if !v.is_finite() || v < 0.0 {
                return Err(BeltError::invalid(format!("{field}.{name}"), v, rule));
            }
        }
        if self.quadratic_stiffness + self.linear_stiffness <= 0.0 {
            return Err(BeltError::invalid(
                format!("{field}.linear_stiffness"),
                self.linear_stiffness,
                "c₁ and c₂ are both zero: the contact would not push",
            ));
        }
        if !self.damping_depth.is_finite() || self.damping_depth <= 0.0 {
            return Err(BeltError::invalid(
                format!("{field}.damping_depth"),
                self.damping_depth,
                "must be finite and > 0 (m)",
            ));
        }
        Ok(())
    }

    /// δ(p): the damping ramp of Kubas eq. 11 (eq. 10 with x0 = 0, y0 = 0, x1 = p_max, y1 = 1).
    #[inline]
    pub fn damping_ramp(&self, penetration: f64) -> f64 {
        cubic_step(penetration, 0.0, 0.0, self.damping_depth, 1.0)
    }

    /// dδ/dp.
    #[inline]
    pub fn damping_ramp_slope(&self, penetration: f64) -> f64 {
        cubic_step_slope(penetration, 0.0, 0.0, self.damping_depth, 1.0)
    }

    /// Elastic part c₁p² + c₂p for p > 0, else 0, N.
    #[inline]
    pub fn elastic_force(&self, penetration: f64) -> f64 {
        if penetration <= 0.0 {
            0.0
        } else {
            (self.quadratic_stiffness * penetration + self.linear_stiffness) * penetration
        }
    }

    /// Tangent contact stiffness dN/dp = 2c₁p + c₂ for p > 0, else 0, N/m.
    #[inline]
    pub fn stiffness_at(&self, penetration: f64) -> f64 {
        if penetration <= 0.0 {
            0.0
        } else {
            2.0 * self.quadratic_stiffness * penetration + self.linear_stiffness
        }
    }

    /// Stored elastic energy c₁p³/3 + c₂p²/2 for p > 0, else 0, J.
    #[inline]
    pub fn energy(&self, penetration: f64) -> f64 {
        if penetration <= 0.0 {
            0.0
        } else {
            let p = penetration;
            (self.quadratic_stiffness * p / 3.0 + 0.5 * self.linear_stiffness) * p * p
        }
    }

    /// The law with both stiffnesses times `scale` (the relaxation's contact continuation).
    #[inline]
    pub fn scaled(&self, scale: f64) -> NonlinearContact {
        NonlinearContact {
            quadratic_stiffness: self.quadratic_stiffness * scale,
            linear_stiffness: self.linear_stiffness * scale,
            ..*self
        }
    }

    /// N(p, ṗ) of Kubas eq. 9, ≥ 0: zero when separated (p ≤ 0) and never pulling, N.
    #[inline]
    pub fn normal_force(&self, penetration: f64, penetration_rate: f64) -> f64 {
        if penetration <= 0.0 {
            return 0.0;
        }
        let n = self.elastic_force(penetration)
            + self.damping_ramp(penetration) * self.damping * penetration_rate;
        n.max(0.0)
    }

    /// The penetration at which the elastic force equals `force` (N ≥ 0): the positive root
    /// of c₁p² + c₂p = N, m.
    pub fn penetration_for(&self, force: f64) -> f64 {
        if force <= 0.0 {
            return 0.0;
        }
        let (c1, c2) = (self.quadratic_stiffness, self.linear_stiffness);
        if c1 == 0.0 {
            force / c2
        } else {
            // Written to avoid cancellation when c₂² ≫ 4c₁N.
            2.0 * force / (c2 + (c2 * c2 + 4.0 * c1 * force).sqrt())
        }
    }
}

/// Geometry of a body's mass centre against a pulley circle (Kubas eq. 4–7).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CircleGap {
    /// r̂: unit vector from the pulley centre to the mass centre (eq. 5).
    pub normal: V2,
    /// |r|: distance from the pulley centre, m.
    pub distance: f64,
    /// p = r_p − |r| (eq. 6), m; positive when penetrating.
    pub penetration: f64,
    /// ṗ = −(v − v_c)·r̂ (eq. 7), m/s.
    pub penetration_rate: f64,
}

/// Gap of a point at `position` moving with `velocity` against a circle of `radius` centred
/// at `center` moving with `center_velocity` (Kubas eq. 4–7). `None` at the centre itself,
/// where r̂ is undefined (a body there is deep inside the pulley: the scene is broken).
#[inline]
pub fn circle_gap(
    position: V2,
    velocity: V2,
    center: V2,
    center_velocity: V2,
    radius: f64,
) -> Option<CircleGap> {
    let r = position - center;
    let distance = r.norm();
    if distance <= 0.0 {
        return None;
    }
    let normal = r / distance;
    Some(CircleGap {
        normal,
        distance,
        penetration: radius - distance,
        penetration_rate: -(velocity - center_velocity).dot(&normal),
    })
}
