//! The rigid "wrap joint": the joint where a strand meets a drum measured along the string's
//! path instead of the chain's (`belt.pulley_contact = "wrap"` with the rigid-body belt,
//! issue 12; `docs/kubas.md`, "Wrap joints").
//!
//! *Why.* A chain of bodies of length l on a drum of radius R is drawn onto it like a chain
//! onto a sprocket: the bodies on the drum turn with it as chords, their joints on the
//! circle through the corners of their polygon, R_e = ρ/cos(a/2) (a = l/R, ρ =
//! [`contact_radius`]). The strand stays straight up to the boundary joint C, the end of
//! the drum's body A: the strand's last body B is in line with the strand, and the chain
//! bends at C only (measured on case G's head drum: the joint beyond C bends by at most
//! 3 % of a, C by 0 … a). With the drum's tangent parallel to the strand at polar angle 0,
//! C runs from −a/2 to a/2 while it bends from ψ = 0 to ψ = a (θ = ψ − a/2), and it draws
//! the strand by R_e·(sin θ + sin(a/2)), where a string would be drawn by R·(θ + a/2). The
//! difference
//! x(θ) = R_e·sin θ − R·θ ([`draw_offset`])
//! is 0 at both ends (R_e·sin(a/2) = l/2 = R·a/2), where the next joint takes over; in
//! between the strand's draw speed R_e·ω·cos θ varies by 1 − cos(a/2) at v/l: ±0.40 mm on
//! case G's 0.2 m bodies on 0.4 m drums, the chordal action of the rigid belt
//! (docs/case-g.md).
//!
//! *Ends.* x′ is ρ − R (−8.4 mm/rad on case G) at both ends of the bend, where one joint
//! hands the strand to the next: cut there, the joints on the drum (bent by a, give or
//! take the contact's 10⁻⁴ rad) and the strand's (bent by 0, give or take its vibration)
//! would take a torque T·(R − ρ) whenever their bend crossed the end (the relaxation did not
//! converge: residual 1.6·10⁻² on case G at 60 m). So x fades in over the first and out
//! over the last [`FADE`] = 1 % of the bend (4.9 mrad on case G, far above that noise) by
//! a C² step: the energy is C², and the draw is the string's but for those two ends.
//!
//! *The joint.* The boundary joint's spring sees g = d − x(θ)·t_C instead of d, with d its
//! gap (Kubas eq. 22) and t_C the drum's tangent at C in the bodies' order (A's axis turned
//! by a/2 towards B): B's end stands off A's by x along the drum, so that the strand is
//! drawn by R·(θ + a/2) (to O(x·θ²/2), 1.3 % of x) and B's end stays on the drum (to
//! O(x²/R)). Its energy is ½c_x·|g|² and every force is that energy's gradient: the gap's
//! (as the plain joint's, with g for d), the tangent's (a torque x·(G·t_C⊥) on A) and the
//! bend's (couples ∓x′(θ)·(G·t_C) on A and B). So the chain stays conservative (checked by
//! finite differences in the tests) and, its energy being invariant under rigid motions,
//! keeps its momentum and angular momentum: the joint is internal to the belt. The damper
//! acts on the rate of |g| through the same gradient, G = (c_x|g| + b_x·ĝ·ġ)·ĝ: it only
//! dissipates.
//!
//! B's end slides along the drum at ẋ against A's: where B touches the drum, the friction
//! that holds a sticking body to the speed it has turning with the drum is told so (B's
//! lever takes ∓x′(θ)·t_C·t per unit ω, [`WrapLoad::slide`]).
//!
//! *Which joints.* Each joint of a drum's contact window, in both roles: entering (in the
//! bodies' order the strand comes first: B = the joint's left body, A its right) and
//! leaving (A left, B right). A role holds where the joint bends by 0 < ψ < a in the
//! chain's sense σ round the drum (σ = ±1, the sense of A's axis about the drum's centre),
//! its joint lies within l/2 of the corner circle, and A's other neighbour Z (right of A
//! entering, left of A leaving) is on the drum: the joint between A and Z bends by more
//! than a/2. That gate tells the entering boundary from the leaving one (both bend by
//! 0 … a); it never shuts while x ≠ 0 (A and Z are both on the drum, bent by a), so the
//! energy is continuous.

use super::contact::contact_radius;
use super::sdes::{joint_with, wrap_angle, LinkState, SdeParams};
use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// The geometry of bodies of one length on one drum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WrapChord {
    /// l: body length, m.
    pub length: f64,
    /// R: drum radius, m.
    pub radius: f64,
    /// R_e = ρ/cos(a/2): the circle through the corners of the bodies' polygon, m.
    pub corner: f64,
    /// a = l/R, rad.
    pub pitch: f64,
}

impl WrapChord {
    /// Bodies of `length` (m) on a drum of `radius` (m).
    pub fn new(length: f64, radius: f64) -> WrapChord {
        let pitch = length / radius;
        WrapChord {
            length,
            radius,
            corner: contact_radius(length, radius) / (0.5 * pitch).cos(),
            pitch,
        }
    }
}

/// The share of the pitch over which a wrap joint's offset fades in and out at both ends of
/// its bend (module docs, "Ends").
///
/// 1 %: the chordal residue lives in the fades and falls as they shorten (case G's 60 m
/// start, T1 above 2 Hz rms over the ramp's second second: 1310 N at 4 % with the former
/// C¹ step, 914 N at 1 % with this C² one; docs/kubas.md, "The fades' share"); 4.9 mrad on
/// case G is still 49 times the drum joints' 10⁻⁴ rad.
pub const FADE: f64 = 0.01;

/// x and dx/dψ (m, m/rad) for a boundary joint bent by ψ: how much further the chain
/// than the string has drawn the strand, x = R_e·sin θ − R·θ with θ = ψ − a/2 (module
/// docs), faded in over the first and out over the last [`FADE`]·a of the bend by a
/// C² step (6u⁵ − 15u⁴ + 10u³); (0, 0) outside 0 < ψ < a.
#[inline]
pub fn draw_offset(bend: f64, w: &WrapChord) -> (f64, f64) {
    if !(bend > 0.0 && bend < w.pitch) {
        return (0.0, 0.0);
    }
    let theta = bend - 0.5 * w.pitch;
    let (s, c) = theta.sin_cos();
    let (x, dx) = (w.corner * s - w.radius * theta, w.corner * c - w.radius);
    let band = FADE * w.pitch;
    let step = |u: f64| {
        if u >= 1.0 {
            (1.0, 0.0)
        } else {
            (
                u * u * u * (10.0 + u * (6.0 * u - 15.0)),
                30.0 * u * u * (1.0 - u) * (1.0 - u),
            )
        }
    };
    let (s0, d0) = step(bend / band);
    let (s1, d1) = step((w.pitch - bend) / band);
    let fade = s0 * s1;
    let dfade = (d0 * s1 - s0 * d1) / band;
    (x * fade, dx * fade + x * dfade)
}

/// Which body of a wrap joint's pair lies on the drum.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// The chain enters the drum in the bodies' order: B = left, A = right.
    Entering,
    /// The chain leaves it: A = left, B = right.
    Leaving,
}

/// What a wrap joint exerts on its three bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WrapLoad {
    /// The bend ψ, rad.
    pub bend: f64,
    /// x(θ), m.
    pub offset: f64,
    /// c_x|g| + b_x·ĝ·ġ, N (the joint's tension).
    pub tension: f64,
    /// ĝ.
    pub direction: V2,
    /// Force on the right body, N (the left body gets the opposite).
    pub force_on_right: V2,
    /// Torque on the left body, N·m.
    pub torque_on_left: f64,
    /// Torque on the right body, N·m.
    pub torque_on_right: f64,
    /// ½c_x|g|², J.
    pub energy: f64,
    /// t_C: the drum's tangent at the joint in the bodies' order.
    pub tangent: V2,
    /// B's velocity against the drum's surface per unit of the drum's angular velocity
    /// that the offset asks for, m/rad (the friction's lever for B takes it in:
    /// `crate::contact::pulley_body_contact`).
    pub slide: V2,
}

/// The wrap joint between `left` and `right` in `role` on a drum centred at `center`, with
/// `gate` A's other neighbour (right of A entering, left of A leaving); `None` where the
/// role does not hold (module docs). The translational SDE only (the torsional one is the
/// plain joint's).
pub fn wrap_joint(
    left: &LinkState,
    right: &LinkState,
    gate: &LinkState,
    role: Role,
    center: V2,
    w: &WrapChord,
    p: &SdeParams,
) -> Option<WrapLoad> {
    let (hl, hr) = (left.half_vector(), right.half_vector());
    let (a_body, b_body, joint) = match role {
        Role::Entering => (right, left, right.position - hr),
        Role::Leaving => (left, right, left.position + hl),
    };
    let u = joint - center;
    if (u.norm() - w.corner).abs() > 0.5 * w.length {
        return None;
    }
    let ta = V2::new(a_body.angle.cos(), a_body.angle.sin());
    let sense = if u.x * ta.y - u.y * ta.x >= 0.0 {
        1.0
    } else {
        -1.0
    };
    // dψ/dφ_A; dψ/dφ_B is its opposite. Z bends from A by σ·a on the drum (in the
    // bodies' order: Z after A entering, before it leaving).
    let (dbend, z_bend) = match role {
        Role::Entering => (sense, sense * wrap_angle(gate.angle - a_body.angle)),
        Role::Leaving => (-sense, sense * wrap_angle(a_body.angle - gate.angle)),
    };
    let bend = dbend * wrap_angle(a_body.angle - b_body.angle);
    if !(bend > 0.0 && bend < w.pitch && z_bend > 0.5 * w.pitch) {
        return None;
    }
    let (x, dx) = draw_offset(bend, w);
    // The drum's tangent at C in the bodies' order: A's axis turned by a/2 (A rests as a
    // chord), towards B.
    let tangent_angle = a_body.angle - dbend * 0.5 * w.pitch;
    let tc = V2::new(tangent_angle.cos(), tangent_angle.sin());
    let tc_perp = V2::new(-tc.y, tc.x);
    let d = (right.position - hr) - (left.position + hl);
    let spin = |omega: f64, r: V2| V2::new(-omega * r.y, omega * r.x);
    let d_dot = (right.velocity - spin(right.angular_velocity, hr))
        - (left.velocity + spin(left.angular_velocity, hl));
    let g = d - tc * x;
    let bend_rate = dbend * (a_body.angular_velocity - b_body.angular_velocity);
    let g_dot = d_dot - tc * (dx * bend_rate) - tc_perp * (x * a_body.angular_velocity);
    let length = g.norm();
    let direction = if length > 0.0 { g / length } else { tc };
    let tension =
        p.translational_stiffness * length + p.translational_damping * direction.dot(&g_dot);
    let pull = direction * tension;
    let cross = |a: V2, b: V2| a.x * b.y - a.y * b.x;
    let mut torque_on_left = cross(hl, pull);
    let mut torque_on_right = cross(hr, pull);
    // A's axis turns the tangent at C: ∂U/∂φ_A ∋ −x·G·t_C⊥; and the bend: ∂U/∂ψ =
    // −x′·G·t_C, ψ = dbend·(φ_A − φ_B).
    let k = -dx * pull.dot(&tc);
    let torque_a = x * pull.dot(&tc_perp) - k * dbend;
    let torque_b = k * dbend;
    // B's end stands off A's by ∓x·t_C: it moves against the drum's surface at ∓x′·ψ̇
    // along t_C, ψ̇ = dbend·ω for A turning with the drum and B not turning.
    let side = match role {
        Role::Entering => {
            torque_on_right += torque_a;
            torque_on_left += torque_b;
            -1.0
        }
        Role::Leaving => {
            torque_on_left += torque_a;
            torque_on_right += torque_b;
            1.0
        }
    };
    Some(WrapLoad {
        bend,
        offset: x,
        tension,
        direction,
        force_on_right: -pull,
        torque_on_left,
        torque_on_right,
        energy: 0.5 * p.translational_stiffness * length * length,
        tangent: tc,
        slide: tc * (side * dx * dbend),
    })
}

/// One active wrap joint of a chain: the joint's index, its left and right bodies, E and
/// the load.
#[derive(Debug, Clone, Copy)]
pub struct ActiveWrap {
    /// Joint index e (joins body e and its right neighbour).
    pub joint: usize,
    /// Left body.
    pub left: usize,
    /// Right body.
    pub right: usize,
    /// Z, A's other neighbour (the gate).
    pub gate: usize,
    /// Which of the pair is on the drum.
    pub role: Role,
    /// The wrap joint's load.
    pub load: WrapLoad,
}

impl ActiveWrap {
    /// B: the body whose end stands off the drum's body A.
    pub fn slider(&self) -> usize {
        match self.role {
            Role::Entering => self.left,
            Role::Leaving => self.right,
        }
    }

    /// −1 entering, +1 leaving: B's end at the joint stands off A's by side·x·t_C.
    pub fn side(&self) -> f64 {
        match self.role {
            Role::Entering => -1.0,
            Role::Leaving => 1.0,
        }
    }
}

/// Every wrap joint active on one drum (centre `center`, radius `radius`) among the joints
/// of the window of bodies `first .. first + len` (mod n) of a chain of `links` (`closed`:
/// a loop), with the SDEs `params`(e) of joint e; calls `out` for each.
#[allow(clippy::too_many_arguments)]
pub fn for_each_wrap(
    links: &dyn Fn(usize) -> LinkState,
    n: usize,
    closed: bool,
    first: usize,
    len: usize,
    center: V2,
    radius: f64,
    params: &dyn Fn(usize) -> SdeParams,
    mut out: impl FnMut(ActiveWrap),
) {
    if n < 3 || len < 2 {
        return;
    }
    let joints = if len >= n { n } else { len - 1 };
    let mut chord: Option<WrapChord> = None;
    for k in 0..joints {
        let l = (first + k) % n;
        if !closed && l + 1 >= n {
            continue;
        }
        let r = (l + 1) % n;
        let (left, right) = (links(l), links(r));
        if left.length <= 0.0 || left.length.to_bits() != right.length.to_bits() {
            continue;
        }
        let w = match chord {
            Some(w) if w.length.to_bits() == left.length.to_bits() => w,
            _ => {
                let w = WrapChord::new(left.length, radius);
                chord = Some(w);
                w
            }
        };
        // A drum too small for its bodies (a ≥ 1 rad) has no strand line to draw along.
        if w.pitch >= 1.0 {
            continue;
        }
        for role in [Role::Entering, Role::Leaving] {
            let z = match role {
                Role::Entering if closed || r + 1 < n => (r + 1) % n,
                Role::Leaving if closed || l >= 1 => (l + n - 1) % n,
                _ => continue,
            };
            let gate = links(z);
            if gate.length.to_bits() != left.length.to_bits() {
                continue;
            }
            if let Some(load) = wrap_joint(&left, &right, &gate, role, center, &w, &params(l)) {
                out(ActiveWrap {
                    joint: l,
                    left: l,
                    right: r,
                    gate: z,
                    role,
                    load,
                });
                break;
            }
        }
    }
}

/// Replace the plain translational SDE of each active wrap joint by the wrap joint: its
/// plain loads (`joint_with` of the translational SDE) are taken off `force`/`torque`
/// and the wrap joint's added; `tension` gets the wrap joint's (its sign as the chain's:
/// negative where g points against the bodies' mean axis).
pub fn apply(
    active: &ActiveWrap,
    links: &dyn Fn(usize) -> LinkState,
    p: &SdeParams,
    force: &mut [V2],
    torque: &mut [f64],
    tension: &mut [f64],
) {
    let (l, r) = (links(active.left), links(active.right));
    let (hl, hr) = (l.half_vector(), r.half_vector());
    let plain = joint_with(
        &l,
        hl,
        &r,
        hr,
        &SdeParams {
            torsional_stiffness: 0.0,
            torsional_damping: 0.0,
            ..*p
        },
    );
    let w = &active.load;
    force[active.right] += w.force_on_right - plain.force_on_right;
    force[active.left] -= w.force_on_right - plain.force_on_right;
    torque[active.left] += w.torque_on_left - plain.torque_on_left;
    torque[active.right] += w.torque_on_right - plain.torque_on_right;
    let axis = hl / l.length + hr / r.length;
    tension[active.joint] = if w.direction.dot(&axis) < 0.0 {
        -w.tension
    } else {
        w.tension
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Case G's drums and bodies: R = 0.4 m, l = 0.2 m (a = 0.5 rad).
    fn case_g() -> WrapChord {
        WrapChord::new(0.2, 0.4)
    }

    #[test]
    fn the_offset_is_the_chain_less_the_string_and_vanishes_at_both_ends() {
        let w = case_g();
        // Direct construction: the strand in line with B through C, C on the corner circle
        // at polar angle θ from the top (−a/2 … a/2): the strand's end is C's x.
        let draw = |theta: f64| w.corner * theta.sin() - w.corner * (-0.5 * w.pitch).sin();
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for k in 1..200 {
            // (between the grid of the fades' ends, where x″ jumps)
            let bend = w.pitch * (k as f64 + 0.5) / 200.0;
            let theta = bend - 0.5 * w.pitch;
            let (x, dx) = draw_offset(bend, &w);
            let h = 1e-6;
            let fd = (draw_offset(bend + h, &w).0 - draw_offset(bend - h, &w).0) / (2.0 * h);
            assert!((dx - fd).abs() < 1e-8, "{bend}: {dx} {fd}");
            if bend < FADE * w.pitch || bend > (1.0 - FADE) * w.pitch {
                continue;
            }
            assert!((x - (draw(theta) - w.radius * bend)).abs() < 1e-15);
            lo = lo.min(x);
            hi = hi.max(x);
        }
        // A whole pitch draws l, as the string's R·a: the offset closes at both ends.
        assert!((draw(0.5 * w.pitch) - w.length).abs() < 1e-15);
        // At both ends value and slope vanish (and, the step being C², the curvature).
        for bend in [1e-9, w.pitch - 1e-9] {
            let (x, dx) = draw_offset(bend, &w);
            assert!(x.abs() < 1e-15 && dx.abs() < 1e-6, "{bend}: {x} {dx}");
        }
        // ±0.40 mm on case G (odd about the middle of the bend).
        assert!(
            (hi - 0.4034e-3).abs() < 1e-6 && (lo + hi).abs() < 1e-9,
            "{lo} {hi}"
        );
        // The strand's draw speed with the offset taken off is R·ω: the chain's
        // R_e·cos θ·ω less x′·ω (but in the fades at both ends).
        for k in 1..20 {
            let bend = w.pitch * (FADE + (1.0 - 2.0 * FADE) * k as f64 / 20.0);
            let theta = bend - 0.5 * w.pitch;
            let corrected = w.corner * theta.cos() - draw_offset(bend, &w).1;
            assert!((corrected - w.radius).abs() < 1e-15);
        }
    }

    /// A chain entering case G's drum (centre 0, the strand along +x in line with B, the
    /// drum turning clockwise): B from the strand to C at polar angle θ (−a/2 … a/2) from
    /// the top, A on the drum as a chord from C, Z the chord after A; each coordinate
    /// moved by up to `jitter`.
    fn entering(theta: f64, jitter: f64) -> [LinkState; 3] {
        let w = case_g();
        let on = |t: f64| V2::new(w.corner * t.sin(), w.corner * t.cos());
        let c = on(theta);
        let body = |from: V2, to: V2, k: f64| {
            let axis = to - from;
            let wobble = |i: f64| jitter * (1.7 * k + 0.9 * i).sin();
            LinkState {
                position: 0.5 * (from + to) + V2::new(wobble(1.0), wobble(2.0)),
                angle: axis.y.atan2(axis.x) + wobble(3.0) / w.length,
                velocity: V2::new(wobble(4.0), wobble(5.0)) * 1e3,
                angular_velocity: wobble(6.0) * 1e4,
                length: w.length,
            }
        };
        let b = body(c - V2::new(w.length, 0.0), c, 2.0);
        let a = body(c, on(theta + w.pitch), 3.0);
        let z = body(on(theta + w.pitch), on(theta + 2.0 * w.pitch), 4.0);
        [b, a, z]
    }

    fn sdes(damping: f64) -> SdeParams {
        SdeParams {
            translational_stiffness: 4e8,
            translational_damping: damping,
            torsional_stiffness: 0.0,
            torsional_damping: 0.0,
        }
    }

    #[test]
    fn the_bend_holds_the_phase_and_the_role_holds_only_at_the_boundary() {
        let w = case_g();
        for k in 1..20 {
            let theta = w.pitch * (k as f64 / 20.0 - 0.5);
            let [b, a, z] = entering(theta, 0.0);
            let j = wrap_joint(&b, &a, &z, Role::Entering, V2::zeros(), &w, &sdes(0.0)).unwrap();
            assert!(
                (j.bend - (theta + 0.5 * w.pitch)).abs() < 1e-12,
                "{theta}: {}",
                j.bend
            );
            // Not as a leaving joint (the gate, B, is off the drum), nor A–Z (bent by a).
            assert!(wrap_joint(&b, &a, &b, Role::Leaving, V2::zeros(), &w, &sdes(0.0)).is_none());
            assert!(wrap_joint(&a, &z, &z, Role::Entering, V2::zeros(), &w, &sdes(0.0)).is_none());
            // The strand's joint before B: in line, bent by 0.
            let mut e = b;
            e.position.x -= w.length;
            assert!(wrap_joint(&e, &b, &a, Role::Entering, V2::zeros(), &w, &sdes(0.0)).is_none());
        }
    }

    #[test]
    fn the_wrap_joints_loads_are_its_energys_gradient() {
        let w = case_g();
        let p = sdes(0.0);
        for &theta in &[-0.2, -0.05, 0.06, 0.2] {
            let base = entering(theta, 2e-4);
            let energy = |s: &[LinkState; 3]| {
                wrap_joint(&s[0], &s[1], &s[2], Role::Entering, V2::zeros(), &w, &p)
                    .unwrap()
                    .energy
            };
            let j = wrap_joint(
                &base[0],
                &base[1],
                &base[2],
                Role::Entering,
                V2::zeros(),
                &w,
                &p,
            )
            .unwrap();
            assert!(j.offset.abs() > 1e-4, "{theta}: {}", j.offset);
            // (body, generalised force): B (left) and A (right) forces and torques, Z none.
            let want = [
                (
                    0,
                    [-j.force_on_right.x, -j.force_on_right.y, j.torque_on_left],
                ),
                (
                    1,
                    [j.force_on_right.x, j.force_on_right.y, j.torque_on_right],
                ),
                (2, [0.0, 0.0, 0.0]),
            ];
            let scale = j.tension.abs() + 1.0;
            for (body, gen) in want {
                for (c, &g) in gen.iter().enumerate() {
                    let h = if c == 2 { 1e-8 } else { 1e-9 };
                    let moved = |sign: f64| {
                        let mut s = base;
                        match c {
                            0 => s[body].position.x += sign * h,
                            1 => s[body].position.y += sign * h,
                            _ => s[body].angle += sign * h,
                        }
                        energy(&s)
                    };
                    let fd = -(moved(1.0) - moved(-1.0)) / (2.0 * h);
                    let tol = 1e-6 * scale * if c == 2 { w.length } else { 1.0 };
                    assert!(
                        (fd - g).abs() < tol,
                        "θ {theta} body {body} coord {c}: {g} vs {fd}"
                    );
                }
            }
        }
    }

    #[test]
    fn the_wrap_joints_damper_only_dissipates() {
        // Power of the loads on the bodies' velocities = −(elastic rate) − b·(ĝ·ġ)².
        let w = case_g();
        let b = 3e4;
        for &theta in &[-0.2, 0.0, 0.2] {
            let s = entering(theta, 2e-4);
            let load = |damping: f64| {
                wrap_joint(
                    &s[0],
                    &s[1],
                    &s[2],
                    Role::Entering,
                    V2::zeros(),
                    &w,
                    &sdes(damping),
                )
                .unwrap()
            };
            let (damped, elastic) = (load(b), load(0.0));
            let power = |j: &WrapLoad| {
                -j.force_on_right.dot(&s[0].velocity)
                    + j.torque_on_left * s[0].angular_velocity
                    + j.force_on_right.dot(&s[1].velocity)
                    + j.torque_on_right * s[1].angular_velocity
            };
            let rate = (damped.tension - elastic.tension) / b; // ĝ·ġ
            let extra = power(&damped) - power(&elastic);
            assert!(extra < 0.0, "{theta}: {extra}");
            assert!(
                (extra + b * rate * rate).abs() < 1e-9 * (b * rate * rate).max(1.0),
                "{theta}: {extra} {}",
                b * rate * rate
            );
        }
    }
}
