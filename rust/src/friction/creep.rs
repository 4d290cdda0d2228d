//! Kubas's (2014) creep-rate friction (Kubas eq. 12–19, figures 5 and 6).
//!
//! The friction force on a belt body in contact with a pulley is T = µ(Δ, v)·N along the
//! tangent τ̂ = Ẑ × r̂ (eq. 16–17, 19), where v = (v_p − v_body)·τ̂ is the tangential speed of
//! the pulley surface relative to the body (eq. 14, 15, 18) and Δ the creep displacement,
//! the relative tangential displacement accumulated since the body touched the pulley.
//!
//! Magnitudes (eq. 13 and figure 6, every ramp being the smooth step of eq. 10):
//! - |v| < Δv: µ = (1 − β(|v|))·µ₁(|Δ|) + β(|v|)·µs, with β rising from 0 at v = 0 to 1 at
//!   Δv (figure 6a) and µ₁ rising from 0 at Δ = 0 to µs at Δmax (figure 6b);
//! - Δv ≤ |v| ≤ 1.5Δv: µ falls smoothly from µs to µk (figure 6c);
//! - |v| > 1.5Δv: µ = µk.
//!
//! Directions, where the paper is silent: eq. 19 gives every term the direction of v. Read
//! literally, the force jumps from +µ₁N to −µ₁N as v changes sign with a creep Δ ≠ 0 in
//! place, and the creep part would not act as the spring that figure 6b describes. Here the
//! creep part acts along Δ and the speed part along v:
//!
//! µ(Δ, v) = (1 − β(|v|))·µ₁(|Δ|)·sgn Δ + β(|v|)·µs·sgn v   (|v| < Δv),
//!
//! which equals eq. 13 in magnitude whenever Δ and v agree in sign, is continuous in (Δ, v)
//! everywhere, odd (µ(−Δ, −v) = −µ(Δ, v)), and turns a sticking contact into a stiff
//! tangential spring of reach Δmax. The creep displacement obeys dΔ/dt = v, held at ±Δmax
//! while v pushes it further out ("creep up to Δmax"), so that it unwinds as soon as the
//! contact reverses; it is reset to zero when the body leaves the pulley. The paper writes
//! Δ = v·Δt with the "elementary time" Δt; read as one integration step this would make µ
//! depend on the step size, so Δ is taken as the accumulated creep.

use crate::contact::nonlinear::cubic_step;
use crate::error::{BeltError, BeltResult};

/// Parameters of the creep-rate friction law. Defaults: case K's values (Kubas section 4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CreepFriction {
    /// µs: static friction coefficient, ≥ µk. Default 1.05.
    pub static_coefficient: f64,
    /// µk: kinetic friction coefficient, ≥ 0. Default 1.0.
    pub kinetic_coefficient: f64,
    /// Δv: relative speed at which the static coefficient is reached, m/s, > 0. Default 10⁻⁵.
    pub transition_speed: f64,
    /// Δmax: creep displacement at which the creep part reaches µs, m, > 0. Default 10⁻⁴.
    pub creep_limit: f64,
}

impl Default for CreepFriction {
    fn default() -> Self {
        CreepFriction {
            static_coefficient: 1.05,
            kinetic_coefficient: 1.0,
            transition_speed: 1e-5,
            creep_limit: 1e-4,
        }
    }
}

impl CreepFriction {
    /// Check the ranges; `field` prefixes the field names in the error.
    pub fn validate(&self, field: &str) -> BeltResult<()> {
        let (ms, mk) = (self.static_coefficient, self.kinetic_coefficient);
        if !mk.is_finite() || mk < 0.0 {
            return Err(BeltError::invalid(
                format!("{field}.kinetic_coefficient"),
                mk,
                "must be finite and ≥ 0",
            ));
        }
        if !ms.is_finite() || ms < mk {
            return Err(BeltError::invalid(
                format!("{field}.static_coefficient"),
                ms,
                format!("must be finite and ≥ the kinetic coefficient {mk}"),
            ));
        }
        for (name, v) in [
            ("transition_speed", self.transition_speed),
            ("creep_limit", self.creep_limit),
        ] {
            if !v.is_finite() || v <= 0.0 {
                return Err(BeltError::invalid(
                    format!("{field}.{name}"),
                    v,
                    "must be finite and > 0 (SI units)",
                ));
            }
        }
        Ok(())
    }

    /// β(|v|): figure 6a, the share of µs in the creep range, 0 at v = 0, 1 at |v| ≥ Δv.
    #[inline]
    pub fn speed_share(&self, speed: f64) -> f64 {
        cubic_step(speed.abs(), 0.0, 0.0, self.transition_speed, 1.0)
    }

    /// µ₁(|Δ|): figure 6b, the creep part, 0 at Δ = 0, µs at |Δ| ≥ Δmax.
    #[inline]
    pub fn creep_part(&self, creep: f64) -> f64 {
        cubic_step(
            creep.abs(),
            0.0,
            0.0,
            self.creep_limit,
            self.static_coefficient,
        )
    }

    /// |µ| of eq. 13 and figure 6c for creep magnitude |Δ| and relative speed |v|.
    #[inline]
    pub fn magnitude(&self, creep: f64, speed: f64) -> f64 {
        let v = speed.abs();
        let dv = self.transition_speed;
        if v < dv {
            let beta = self.speed_share(v);
            (1.0 - beta) * self.creep_part(creep) + beta * self.static_coefficient
        } else {
            cubic_step(
                v,
                dv,
                self.static_coefficient,
                1.5 * dv,
                self.kinetic_coefficient,
            )
        }
    }

    /// Signed coefficient µ(Δ, v) along the tangent (module docs): the friction force on the
    /// belt body is µ·N along τ̂. Odd and continuous in (Δ, v).
    #[inline]
    pub fn coefficient(&self, creep: f64, speed: f64) -> f64 {
        let v = speed.abs();
        if v < self.transition_speed {
            let beta = self.speed_share(v);
            (1.0 - beta) * self.creep_part(creep) * sign(creep)
                + beta * self.static_coefficient * sign(speed)
        } else {
            self.magnitude(creep, speed) * sign(speed)
        }
    }

    /// dΔ/dt for creep Δ and relative speed v: v, or 0 while |Δ| ≥ Δmax and v pushes
    /// further out, m/s.
    #[inline]
    pub fn creep_rate(&self, creep: f64, speed: f64) -> f64 {
        if creep.abs() >= self.creep_limit && creep * speed > 0.0 {
            0.0
        } else {
            speed
        }
    }
}

#[inline]
fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// The friction memory: the creep displacement Δ of every (body, pulley) contact point, m.
/// Plain state data: the integrator advances it with [`CreepFriction::creep_rate`], and it is
/// saved and restored as a flat slice (checkpoints).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CreepMemory {
    /// Number of pulleys (the row length).
    pub pulleys: usize,
    /// Δ of body i at pulley j at `creep[i * pulleys + j]`, m.
    pub creep: Vec<f64>,
}

impl CreepMemory {
    /// Zero memory for `bodies` bodies and `pulleys` pulleys.
    pub fn new(bodies: usize, pulleys: usize) -> Self {
        CreepMemory {
            pulleys,
            creep: vec![0.0; bodies * pulleys],
        }
    }
    /// Δ of body `i` at pulley `j`, m.
    #[inline]
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.creep[i * self.pulleys + j]
    }
    /// Set Δ of body `i` at pulley `j`, m.
    #[inline]
    pub fn set(&mut self, i: usize, j: usize, creep: f64) {
        self.creep[i * self.pulleys + j] = creep;
    }
    /// Forget the creep of a contact that has separated.
    #[inline]
    pub fn release(&mut self, i: usize, j: usize) {
        self.set(i, j, 0.0);
    }
    /// The memory as a flat slice (for a checkpoint or an integrator state).
    pub fn as_slice(&self) -> &[f64] {
        &self.creep
    }
    /// Restore from a flat slice written by [`Self::as_slice`]; the length must match.
    pub fn restore(&mut self, data: &[f64]) -> BeltResult<()> {
        if data.len() != self.creep.len() {
            return Err(BeltError::Usage(format!(
                "creep memory of {} values cannot be restored from {} values",
                self.creep.len(),
                data.len()
            )));
        }
        self.creep.copy_from_slice(data);
        Ok(())
    }
}
