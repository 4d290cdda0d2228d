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

/// Default Δv of a scene's creep friction ([`CreepFriction::transition_speed`]), m/s:
/// 10⁻³ (1 mm/s). Below Δv the contact creeps (µ rises to µs with the creep displacement
/// and the speed), above 1.5·Δv it slides at µk. Physics sets both sides of the choice:
/// rubber on steel passes from creep to sliding at speeds of the order of mm/s, and the
/// sliding speeds that matter in belt drives and conveyors, those of the slip arcs
/// (belt speed × the strain difference across the pulley, 10⁻² m/s and more for a drive
/// near its capacity at ≥ 1 m/s), lie well above 1.5·Δv, so slip arcs slide at µk as in
/// creep theory; while a belt held on a pulley creeps at far less. Kubas's 10⁻⁵ m/s is
/// accepted too: under central differences the law is applied with a stick limit (see
/// [`pulley_creep_friction`]), so Δv does not limit the step. Under RKF45 the law is
/// applied as it is, and Δv sets the step of a sticking contact (its speed part is a
/// damper of up to 1.5·µs·N/Δv, so explicit steps of about m·Δv/(µs·N)): the smaller Δv,
/// the more steps (docs/kubas.md measures them).
pub const DEFAULT_TRANSITION_SPEED: f64 = 1e-3;

/// Default Δmax of a scene's creep friction ([`CreepFriction::creep_limit`]), m: 10⁻⁴
/// (0.1 mm, Kubas's value): the tangential displacement over which a rubber cover's
/// contact builds up its full static friction (presliding displacement, of the order of
/// the cover's shear deflection, 10⁻⁵–10⁻⁴ m).
pub const DEFAULT_CREEP_LIMIT: f64 = 1e-4;

/// Parameters of the creep-rate friction law. Defaults: case K's values (Kubas section 4);
/// a scene's creep friction defaults to [`DEFAULT_TRANSITION_SPEED`] and
/// [`DEFAULT_CREEP_LIMIT`] instead.
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
/// Plain state data: the integrator advances it with [`CreepFriction::creep_rate`] (central
/// differences by one explicit step per step, RKF45 as components of its state vector,
/// with their error in the step control), and it is saved and restored as a flat slice
/// (checkpoints).
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

use crate::contact::PulleyContacts;
use crate::forces::perp;
use crate::friction::FrictionOutcome;
use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// The pulley seen by the creep friction of its contacts.
#[derive(Debug, Clone, Copy)]
pub struct CreepPulley {
    /// Radius, m.
    pub radius: f64,
    /// Polar inertia, kg·m² (`f64::INFINITY` for a pulley whose speed is prescribed this
    /// step: a brake or a speed-controlled drive holds it).
    pub inertia: f64,
    /// Angular speed, rad/s (counter-clockwise positive), at the velocities' instant.
    pub omega: f64,
    /// Centre velocity, m/s.
    pub center_velocity: V2,
}

/// Where one pulley's creep memory lives in the state's flat memory: Δ of belt point `i`
/// at `memory[i * stride + column]`, m.
#[derive(Debug, Clone, Copy)]
pub struct MemoryColumn {
    /// Row length (number of pulleys).
    pub stride: usize,
    /// This pulley's column.
    pub column: usize,
}

/// Creep friction (Kubas eq. 12–19, [`CreepFriction::coefficient`]) at the belt points
/// touching one pulley. Formulation-agnostic: it reads belt points (`contacts.node`
/// indexes `v`, `mass`, `force` and the memory rows), their velocities and the forces
/// on them so far, and adds the friction force to `force`.
///
/// For contact k at point i with outward normal n and tangent t = Ẑ × n, the speed of the
/// pulley surface relative to the point is v = Rω + t·v_c − t·v_i (Kubas's v_T, eq. 18),
/// and the law gives the force µ(Δ, v)·N·t on the point (−µ(Δ, v)·N·t on the pulley).
/// dΔ/dt = [`CreepFriction::creep_rate`] is pushed to `rates` as (memory index, rate):
/// the integrator advances the memory with it, so the law is an ODE on the state.
///
/// `dt` is the velocity update of the coming explicit step (s), or `None` for an
/// integrator that resolves the law itself (RKF45, `integrate::adaptive`: the law is
/// applied as it is, and the memory is a part of its state vector with these rates). With `Some(dt)` the law gets a **stick limit**, the stiff limit of solving it
/// implicitly for the end-of-step speed: in the creep range the force changes by up to
/// 1.5·µs·N/Δv per m/s, a damping that an explicit step resolves only below
/// m·Δv/(µs·N) (10⁻¹⁰ s for case K). Where the law's force would reverse the relative
/// speed within the step, the point instead takes the stick force, the force that brings
/// that speed to zero (or µk·N along it beyond µs·N); the pulley's share of the motion is
/// included through the effective mass m/(1 + R²Σm/I). Friction then stops a slip but
/// never reverses it, whatever Δv. With `dt = Some(∞)` (the static relaxation) every point
/// takes the stick force within µs·N (a quasi-static limit) and the memory is not
/// advanced.
///
/// The pulley's torque is the moment of its share, Σ −f·arm over the contacts
/// ([`PulleyContacts::arm`], the radius for nodes): the moment the belt points receive,
/// so belt and pulley keep their angular momentum. For rigid bodies resting on their ends
/// the arm is the mass centre's, ρ for a body resting on the drum, more or less for one
/// landing or leaving (the same measure as the surface speed's lever, less a wrap joint's
/// slide); a torque of ρ·Σ(−f) left the difference on the belt as an external torque.
///
/// `per_contact`, when given, receives each contact's friction force on the pulley along
/// t, N, in contact order (a recording of contact forces; `None` costs nothing).
#[allow(clippy::too_many_arguments)]
pub fn pulley_creep_friction(
    law: &CreepFriction,
    contacts: &PulleyContacts,
    pulley: &CreepPulley,
    v: &[V2],
    mass: &[f64],
    dt: Option<f64>,
    memory: &[f64],
    at: MemoryColumn,
    force: &mut [V2],
    rates: &mut Vec<(usize, f64)>,
    mut per_contact: Option<&mut Vec<f64>>,
) -> FrictionOutcome {
    let r = pulley.radius;
    let (mu_s, mu_k) = (law.static_coefficient, law.kinetic_coefficient);
    let mut out = FrictionOutcome::default();
    let quasi_static = dt.is_some_and(|dt| !dt.is_finite());
    let mut moment = 0.0;
    // The pulley's share of a stick: R²·Σm/I over the points on it (0 if it is held).
    let share = if pulley.inertia.is_finite() {
        let m_sum: f64 = contacts.node.iter().map(|&i| mass[i]).sum();
        r * r * m_sum / pulley.inertia
    } else {
        0.0
    };
    for k in 0..contacts.len() {
        let i = contacts.node[k];
        let t = perp(contacts.normal[k]);
        let normal = contacts.normal_force[k];
        let lever = contacts.lever_at(k, r);
        let speed = lever * pulley.omega + t.dot(&pulley.center_velocity) - t.dot(&v[i]);
        let idx = i * at.stride + at.column;
        let creep = memory[idx];
        let mut f = law.coefficient(creep, speed) * normal;
        let mut sliding = speed.abs() >= law.transition_speed;
        if let Some(dt) = dt {
            // The force along t that gives the point the pulley's surface speed at the end
            // of the step (the other forces on it included).
            let stick = if quasi_static {
                -t.dot(&force[i])
            } else {
                mass[i] / (1.0 + share) * speed / dt - t.dot(&force[i])
            };
            if quasi_static || (speed != 0.0 && (f - stick) * speed > 0.0) {
                if stick.abs() <= mu_s * normal {
                    f = stick;
                    sliding = false;
                } else {
                    f = mu_k * normal * stick.signum();
                    sliding = true;
                }
            }
        }
        if !quasi_static {
            rates.push((idx, law.creep_rate(creep, speed)));
        }
        force[i] += t * f;
        // On the pulley: −f along t, with the moment the belt point receives.
        out.force -= t * f;
        out.tangential -= f;
        moment -= contacts.arm_at(k, r) * f;
        out.slipping += usize::from(sliding);
        if let Some(list) = per_contact.as_deref_mut() {
            list.push(-f);
        }
    }
    // The nodes' arms are all the radius: the sum as before, to the last bit.
    out.torque = if contacts.arm.is_empty() {
        r * out.tangential
    } else {
        moment
    };
    out
}
