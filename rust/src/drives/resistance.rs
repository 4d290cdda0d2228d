//! Pulley equation of motion and speed-dependent resistance torque (Kubas eq. 24).
//!
//! I·θ̈ = M_d − Σᵢ M_T,i, where M_d is the set torque (a resistance is a negative M_d,
//! "constant or dependent on θ̇") and M_T,i the torque of the friction force T_i on belt
//! body i about the pulley centre. The paper writes M_T = r̂ × T with the unit vector r̂;
//! that is a force, not a torque. Here the lever is the full vector r from the pulley centre
//! to the mass centre where T acts (eq. 4), so that belt and pulley exchange exactly the
//! angular momentum that friction moves.

use crate::contact::nonlinear::cubic_step;
use crate::error::{BeltError, BeltResult};
use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// A resistance torque against the pulley's rotation, M_r(ω) = −(M₀·s(ω) + c·ω), N·m, where
/// s(ω) is a smooth sign (eq. 10 from −1 at −ω_ε to +1 at +ω_ε) so that the right-hand side
/// stays continuous for an adaptive integrator. Default: no resistance.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpeedResistance {
    /// M₀: constant (Coulomb-like) part, N·m, ≥ 0. Default 0.
    pub constant: f64,
    /// c: viscous part, N·m·s/rad, ≥ 0. Default 0.
    pub viscous: f64,
    /// ω_ε: speed over which the constant part builds up, rad/s, > 0 when M₀ > 0.
    pub smoothing_speed: f64,
}

impl SpeedResistance {
    /// A purely viscous resistance that reaches `torque` (N·m) at `speed` (rad/s), e.g. case
    /// K's 15 N·m at 8π rad/s.
    pub fn viscous_reaching(torque: f64, speed: f64) -> BeltResult<Self> {
        if !torque.is_finite() || torque < 0.0 {
            return Err(BeltError::invalid(
                "resistance.torque",
                torque,
                "must be finite and ≥ 0 (N·m)",
            ));
        }
        if !speed.is_finite() || speed <= 0.0 {
            return Err(BeltError::invalid(
                "resistance.speed",
                speed,
                "must be finite and > 0 (rad/s)",
            ));
        }
        Ok(SpeedResistance {
            constant: 0.0,
            viscous: torque / speed,
            smoothing_speed: 0.0,
        })
    }

    /// Check the ranges; `field` prefixes the field names in the error.
    pub fn validate(&self, field: &str) -> BeltResult<()> {
        for (name, v) in [("constant", self.constant), ("viscous", self.viscous)] {
            if !v.is_finite() || v < 0.0 {
                return Err(BeltError::invalid(
                    format!("{field}.{name}"),
                    v,
                    "must be finite and ≥ 0",
                ));
            }
        }
        if self.constant > 0.0 && !(self.smoothing_speed.is_finite() && self.smoothing_speed > 0.0)
        {
            return Err(BeltError::invalid(
                format!("{field}.smoothing_speed"),
                self.smoothing_speed,
                "must be finite and > 0 (rad/s) with a constant resistance",
            ));
        }
        Ok(())
    }

    /// M_r(ω), N·m: always opposes ω (zero at ω = 0).
    #[inline]
    pub fn torque(&self, omega: f64) -> f64 {
        let coulomb = if self.constant > 0.0 {
            let e = self.smoothing_speed;
            self.constant * cubic_step(omega, -e, -1.0, e, 1.0)
        } else {
            0.0
        };
        -(coulomb + self.viscous * omega)
    }
}

/// M_T: torque about the pulley centre of a friction force `friction_on_body` (N) acting on a
/// belt body at `lever` = P_body − P_pulley (m), as felt by the pulley (the reaction), N·m.
/// Eq. 24 subtracts the torque on the body; this returns it with the sign already applied.
#[inline]
pub fn friction_torque_on_pulley(lever: V2, friction_on_body: V2) -> f64 {
    -(lever.x * friction_on_body.y - lever.y * friction_on_body.x)
}

/// θ̈ = (M_d + Σ torques on the pulley)/I (Kubas eq. 24), rad/s².
#[inline]
pub fn pulley_acceleration(inertia: f64, set_torque: f64, belt_torque: f64) -> f64 {
    (set_torque + belt_torque) / inertia
}
