//! Spring-damping elements (SDEs) between neighbouring rigid belt bodies (Kubas eq. 20–23).
//!
//! The translational SDE joins the right end of body i−1, P_{i−1} + l′_{i−1}, to the left end
//! of body i, P_i − l′_i, where l′ = (l/2)(cos φ, sin φ) is the half-length vector (eq. 22).
//! Its deformation is the distance between those ends, Δl = |d| with
//! d = (P_i − l′_i) − (P_{i−1} + l′_{i−1}) (eq. 22): the SDE has zero free length, so the belt's
//! unstretched length is the sum of the body lengths. Its force is the Kelvin–Voigt
//! F = c_tra·Δl + b_tra·Δl̇ along d (eq. 20), with Δl̇ = d̂·ḋ the difference of the ends'
//! velocities projected on d̂. It pulls body i towards body i−1 at the end points, so it also
//! turns them: M = l′ × F (eq. 23). Because the free length is zero, the elastic part is the
//! linear vector spring c_tra·d with potential ½c_tra|d|², which the kernel tests check by
//! finite differences.
//!
//! The torsional SDE resists the relative angle: M = c_tor(φ_i − φ_{i−1}) + b_tor(φ̇_i − φ̇_{i−1})
//! (eq. 21), acting −M on body i and +M on body i−1 (potential ½c_tor(φ_i − φ_{i−1})²). The
//! relative angle is wrapped to (−π, π], so that the joint that closes a loop (where the
//! body angles differ by a full turn) needs no special case.
//!
//! Where d vanishes its direction is undefined; the paper takes last step's direction. Here
//! the mean axis of the two bodies is used instead: no history, and the elastic force is
//! zero there anyway.
//!
//! Units: c_tra is the stiffness of one SDE, N/m (EA = c_tra·l for bodies of length l), b_tra
//! N·s/m, c_tor N·m/rad, b_tor N·m·s/rad.

use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// Stiffness and damping of the SDEs between two bodies (Kubas eq. 20–21).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SdeParams {
    /// c_tra: stiffness of one translational SDE, N/m, ≥ 0.
    pub translational_stiffness: f64,
    /// b_tra: damping of one translational SDE, N·s/m, ≥ 0.
    pub translational_damping: f64,
    /// c_tor: stiffness of one torsional SDE, N·m/rad, ≥ 0.
    pub torsional_stiffness: f64,
    /// b_tor: damping of one torsional SDE, N·m·s/rad, ≥ 0.
    pub torsional_damping: f64,
}

/// Position, angle, velocities and length of one rigid body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkState {
    /// P: mass centre, m.
    pub position: V2,
    /// φ: angle of the body's axis from the x axis, rad.
    pub angle: f64,
    /// Ṗ: velocity of the mass centre, m/s.
    pub velocity: V2,
    /// φ̇: angular velocity, rad/s (counter-clockwise positive).
    pub angular_velocity: f64,
    /// l: body length, m.
    pub length: f64,
}

impl LinkState {
    /// l′ = (l/2)(cos φ, sin φ): the half-length vector (Kubas eq. 22).
    #[inline]
    pub fn half_vector(&self) -> V2 {
        let (s, c) = self.angle.sin_cos();
        V2::new(c, s) * (0.5 * self.length)
    }
}

/// Everything one joint (the SDEs between body i−1, "left", and body i, "right") exerts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointLoad {
    /// Δl = |d|: elongation of the translational SDE, m.
    pub elongation: f64,
    /// F = c_tra·Δl + b_tra·Δl̇ (eq. 20), N; positive in tension.
    pub tension: f64,
    /// d̂: unit vector from the left body's right end to the right body's left end.
    pub direction: V2,
    /// Force on the right body (at its left end), N; the left body gets the opposite.
    pub force_on_right: V2,
    /// Torque on the left body about its mass centre (translational and torsional SDE), N·m.
    pub torque_on_left: f64,
    /// Torque on the right body about its mass centre, N·m.
    pub torque_on_right: f64,
    /// M = c_tor·Δφ + b_tor·Δφ̇ (eq. 21), N·m.
    pub bending_moment: f64,
}

#[inline]
fn cross(a: V2, b: V2) -> f64 {
    a.x * b.y - a.y * b.x
}

/// ω × r for an angular velocity ω about z.
#[inline]
fn spin(omega: f64, r: V2) -> V2 {
    V2::new(-omega * r.y, omega * r.x)
}

/// φ wrapped to (−π, π].
#[inline]
pub fn wrap_angle(phi: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    // Neighbouring bodies' angles differ by little (or by a whole turn at the joint where
    // the initial angles wrapped): no division and rounding then.
    if phi > -PI && phi <= PI {
        return phi;
    }
    if phi > PI && phi <= 3.0 * PI {
        return phi - TAU;
    }
    if phi > -3.0 * PI && phi <= -PI {
        return phi + TAU;
    }
    let w = phi - TAU * (phi / TAU).round();
    if w <= -PI {
        w + TAU
    } else {
        w
    }
}

/// Loads of the SDEs between `left` (body i−1) and `right` (body i), Kubas eq. 20–23.
#[inline]
pub fn joint(left: &LinkState, right: &LinkState, p: &SdeParams) -> JointLoad {
    joint_with(left, left.half_vector(), right, right.half_vector(), p)
}

/// [`joint`] with the bodies' half-length vectors `hl`, `hr` (l′ of eq. 22) given, so that
/// a chain computes each body's once.
#[inline]
pub fn joint_with(left: &LinkState, hl: V2, right: &LinkState, hr: V2, p: &SdeParams) -> JointLoad {
    let d = (right.position - hr) - (left.position + hl);
    let d_dot = (right.velocity - spin(right.angular_velocity, hr))
        - (left.velocity + spin(left.angular_velocity, hl));
    let elongation = d.norm();
    let direction = if elongation > 1e-12 * (left.length + right.length) {
        d / elongation
    } else {
        let axis =
            hl / left.length.max(f64::MIN_POSITIVE) + hr / right.length.max(f64::MIN_POSITIVE);
        let n = axis.norm();
        if n > 0.0 {
            axis / n
        } else {
            V2::new(1.0, 0.0)
        }
    };
    let tension =
        p.translational_stiffness * elongation + p.translational_damping * direction.dot(&d_dot);
    let pull = direction * tension;
    let relative_angle = wrap_angle(right.angle - left.angle);
    let bending_moment = p.torsional_stiffness * relative_angle
        + p.torsional_damping * (right.angular_velocity - left.angular_velocity);
    // The negations written per component, and l′ × F for (−l′) × (−F) (the same
    // products, so the same bits): nalgebra's `Neg` on a vector is a loop over its
    // components that a build without cross-crate inlining (maturin develop with LTO off)
    // kept, flipping each sign bit in memory and stalling the loads that follow.
    JointLoad {
        elongation,
        tension,
        direction,
        force_on_right: V2::new(-pull.x, -pull.y),
        torque_on_left: cross(hl, pull) + bending_moment,
        torque_on_right: cross(hr, pull) - bending_moment,
        bending_moment,
    }
}

/// Stored energy of one joint, ½c_tra|d|² + ½c_tor·Δφ², J (damping has none).
pub fn joint_energy(left: &LinkState, right: &LinkState, p: &SdeParams) -> f64 {
    let d = (right.position - right.half_vector()) - (left.position + left.half_vector());
    let a = wrap_angle(right.angle - left.angle);
    0.5 * p.translational_stiffness * d.norm_squared() + 0.5 * p.torsional_stiffness * a * a
}

/// Add the SDE forces and torques of a chain of bodies to `force` and `torque`, and write
/// each joint's tension to `tension`. Joint e joins body e (left) and body e+1 (right); a
/// `closed` chain has n joints (the last joins body n−1 to body 0), an open one n − 1.
pub fn chain_loads(
    links: &[LinkState],
    p: &SdeParams,
    closed: bool,
    force: &mut [V2],
    torque: &mut [f64],
    tension: &mut [f64],
) {
    let n = links.len();
    let joints = if closed { n } else { n.saturating_sub(1) };
    debug_assert!(force.len() == n && torque.len() == n && tension.len() >= joints);
    for e in 0..joints {
        let r = if e + 1 == n { 0 } else { e + 1 };
        let j = joint(&links[e], &links[r], p);
        force[r] += j.force_on_right;
        force[e] -= j.force_on_right;
        torque[e] += j.torque_on_left;
        torque[r] += j.torque_on_right;
        tension[e] = j.tension;
    }
}
