//! Wrap contact on idler rolls: an element whose straight segment cuts a roll's circle is
//! measured along the belt's path over the roll (tangent, arc, tangent), as [`super::wrap`]
//! measures an element on a pulley: `belt.idler_contact = "wrap"` (node belt, closed loop;
//! opt-in).
//!
//! Why (issue 12, docs/wrap-contact.md "The rolls' chordal action"). With centre-line
//! segment contact a straight element resting on a roll under its middle holds its two nodes
//! about θ·l/4 above the continuous belt's curve (θ = q·a/T the slope change over the roll),
//! and a node over the roll does not: each roll acts on the belt like a roll bobbing at the
//! node-passing frequency v/l, the chordal action that wrap contact removed on the drums.
//! It showed in the steady drive torque of the 300 m conveyor as lines at v/l and its
//! harmonics (57–59 Hz at the default 0.2094 m elements: moving to 13 and 27 Hz at 0.15 m
//! elements and to 42 Hz at 1.5 m/s). Measured along its path over the roll, an element's
//! length and forces are continuous in the node positions whatever the phase: a node lies on
//! the belt's continuous curve whether the roll is under it or under an element's middle.
//!
//! The roll receives T·(∂L/∂p + ∂L/∂q) through its centre (the element's tension T from its
//! path length, with the axial law's damper on dL/dt); a node inside the circle (a node over
//! the roll pressed into it) also gets the penalty force of the segment contact on the
//! approach speed. The friction and running-resistance stages see one contact point: the
//! load-weighted middle of the parts pressing on the roll (each wrapped arc's middle and each
//! pressed node), with the resultant's direction as its normal and magnitude as its normal
//! force, so the rolls' rotation, friction and DIN f resistance work as before.
//!
//! An element that a pulley or another roll has already measured along its path this
//! evaluation (a roll within an element length of a drum or of another roll) keeps the
//! centre-line segment contact on that roll: the path round two bodies is not measured.

use super::wrap::{self, ElementLaw};
use super::{IdlerBody, IdlerContact};
use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// Radius of the circle the wrap contact measures the belt's path over, in element rest
/// lengths, at low speed: [`wrap_radius`].
pub const ARC_SPREAD: f64 = 3.0;

/// Margin k of [`wrap_radius`]'s speed term R_w ≥ k·v²/g: a node on the circle needs v²/R_w
/// towards its centre, and gravity alone gives it, so at k = 1.4 it is held with
/// (1 − 1/k) = 29 % of its weight to spare (the spare stays positive on inclines up to
/// 44°), and the radius at 2 m/s stays session 9's 3·l for elements down to 0.2 m
/// (1.4·v²/g = 0.571 m). Chosen by measurement (docs/wrap-contact.md, "Session 10: roll
/// wrap at speed"): on the 50 m builder conveyor at 3 m/s the rolls unload at no node
/// passing from k = 1.2 on (4.7 % of the roll samples at 3·l); k = 1, 1.2, 1.4, 1.7, 2, 3
/// read 823, 366, 385, 553, 1242, 2071 N·m of drive torque rms above 2 Hz (990 at 3·l).
pub const FLIGHT_MARGIN: f64 = 1.4;

/// Largest radius of the speed term of [`wrap_radius`], in element rest lengths. The
/// contact measures the four nodes nearest a roll (`contact::track_element`): the belt's
/// arc over the circle, R_w·θ (θ the belt's turn over the roll), must stay within them, or
/// the elements beyond press into the circle unmeasured. At 20·l the arc is 2·l at
/// θ = 0.1. Measured: the 50 m builder conveyor was destroyed at R_w ≥ 7.3 m = 35·l (k = 2
/// at 6 m/s, k = 1.4 at 8 m/s) and ran at 7.0 m; capped at 20·l it runs at 8 m/s.
pub const ARC_SPREAD_MAX: f64 = 20.0;

/// Largest steady force of the wrap contact's tangent-line damping on a node, in the node's
/// weights: [`tangent_damping`]. Chosen by measurement (docs/wrap-contact.md, "Session 11:
/// the tangent-line damping at speed"): on the 50 m builder conveyor (carry rolls 1.2 m
/// apart, return rolls 3 m) no roll unloads at 2–8 m/s at 1.4 (nor 1.43); at 2.0 the
/// rolls unload at 6 m/s (1.3 % of the roll samples), at 2.9 at 6 and 8 m/s (8.5, 13.4 %);
/// case G (2 m/s, 50 kN: c·v/(2T) = 0.99) is unchanged above 1, and at about 0.9 its
/// 10 Hz line rises (ripple 0.084 → 0.106 with the ideal follower).
pub const TANGENT_DAMPING_WEIGHTS: f64 = 1.4;

/// Damping coefficient (N·s/m) of the wrap contact's tangent-line damping on a node moving
/// along the belt at `speed` (m/s) in an element at tension `tension` (N), on a roll of
/// contact damping `damping` (N·s/m): `min(c, 2·η·T/|v|)`, η =
/// [`TANGENT_DAMPING_WEIGHTS`]; `c` at rest or without tension.
///
/// Why: a lumped node in the span is kinked by its weight, Δθ = m·g/T, and travels along
/// its locus, which bisects the kink; the wrapped piece beside the roll is the kink's
/// downstream side, so the node approaching the roll crosses the piece's line at
/// v·m·g/(2T) in steady running, though the belt does not approach the roll at all. The
/// damper, on only while a node approaches, is switched on at each node passing (v/l) with
/// the steady force F_s = c·v·m·g/(2T): in the node's weights, F_s/(m·g) = c·v/(2T),
/// whatever the element's length, the belt's mass and the roll pitch (against the roll's
/// load, l/a times that). It is the lumping's (the kink vanishes with l: F_s → 0 with the
/// node's weight), grows with the speed and falls with the tension. On the 50 m builder
/// conveyor it reads 2.9 (carry) at 2 m/s and 8.1 at 5 m/s, where the rolls unloaded at
/// the passings; case G reads 0.99. The coefficient is limited so that F_s ≤ η·m·g: the
/// damping of a real approach stays c where the steady part is small (low speed, high
/// tension) and falls as T/v above.
pub fn tangent_damping(damping: f64, tension: f64, speed: f64) -> f64 {
    let v = speed.abs();
    if v > 0.0 && tension > 0.0 {
        damping.min(2.0 * TANGENT_DAMPING_WEIGHTS * tension / v)
    } else {
        damping
    }
}

/// Radius (m) of the circle the belt's path over a roll of `radius` (m) is measured on, for
/// elements of rest length `element` (m), a belt running at up to `speed` (m/s,
/// [`scene_speed`]) under `gravity` (m/s²):
/// `max(radius, ARC_SPREAD·element, min(FLIGHT_MARGIN·speed²/gravity, ARC_SPREAD_MAX·element))`
/// (the speed term 0 without gravity), the circle's top the roll's top
/// (`contact::stage`; the sag placement bends the spans over the same circle,
/// `model::sag`).
///
/// Why: a lumped node cannot follow a roll's own arc (R·θ, about 2 mm on a 0.0665 m roll)
/// at speed. On the arc the element's path tension has no component towards the roll (the
/// path's gradient is its tangent), so nothing gives the node the m·v²/R it needs there
/// (1.2 kN at 2 m/s) but gravity; it flies over the arc by h ≈ m²v⁴/(8T²R) and the roll
/// unloads at each node passing, the worse the lower the tension (a 50 m builder conveyor:
/// rms of the drive torque above 2 Hz 1414 N·m against 1164 with the segment contact). On
/// a circle of radius R_w gravity holds the node while v² < g·R_w. Session 9 took
/// R_w = 3·l (measured on that conveyor at 2 m/s, the circle 1, 2, 3, 5, 10 elements: rms
/// 1340, 738, 284, 343, 557 N·m; 2·l = 0.42 m ≈ v²/g); above about √(3·g·l) = 2.5 m/s the
/// nodes flew again (3 m/s: 990 N·m, rolls unloaded in 4.7 % of the samples), hence the
/// speed term (385 N·m, none unloaded). The continuum belt would not fly (a string leaves a
/// support only if T < m'v²): the term is the lumping's, and it vanishes as the speed does.
/// The cost of the larger circle: the belt's path over it lies (R_w − R)·(1/cos(θ/2) − 1)
/// ≈ (R_w − R)·θ²/8 below the path over the roll (0.45 mm at θ = 0.08 and R_w = 0.63 m;
/// 2.6 mm at R_w = 3.6 m, 5 m/s) and is shorter by (R_w − R)·θ³/12 per roll, the placement
/// and the contact measuring the same circle; the roll's load is spread over the arc R_w·θ.
pub fn wrap_radius(radius: f64, element: f64, speed: f64, gravity: f64) -> f64 {
    let r = radius.max(ARC_SPREAD * element);
    if gravity > 0.0 && speed.is_finite() {
        r.max((FLIGHT_MARGIN * speed * speed / gravity).min(ARC_SPREAD_MAX * element))
    } else {
        r
    }
}

/// The largest belt speed the scene's drives and start give, m/s, for [`wrap_radius`]: the
/// design start's `initial.speed`, each speed-controlled drive's start curve (`speed`, and
/// its creep speed), and each direct-on-line motor's no-load belt speed (synchronous speed
/// / gear ratio × the pulley's radius). 0 if none gives one (torque-table drives only, no
/// design start at speed): the radius is then the low-speed one, `max(R, 3·l)`.
pub fn scene_speed(scene: &crate::scene::Scene) -> f64 {
    let mut v = scene.initial.as_ref().map_or(0.0, |i| i.speed.abs());
    for p in &scene.pulleys {
        let Some(d) = p.drive.as_ref() else { continue };
        if let Some(c) = d.start_curve.as_ref() {
            v = v.max(c.speed.abs()).max(c.creep_speed_or_default().abs());
        }
        if let Some(m) = d.motor.as_ref() {
            if m.gear_ratio > 0.0 {
                v = v.max(m.synchronous_speed.abs() / m.gear_ratio * p.radius);
            }
        }
    }
    if v.is_finite() {
        v
    } else {
        0.0
    }
}

/// Wrap contact with one roll. `element` is the roll's tracked element (updated as for the
/// segment contact, [`super::idler_contact`]); `claimed[e] == stamp` marks an element already
/// measured along a wrapped path this evaluation (it gets the segment contact here), and the
/// elements wrapped here are marked. Each wrapped element's tension is written to `tension`.
/// `excess` (the viscoelastic arms' only): each wrapped element with its path length less
/// its chord, m. Returns the contact (its `strain`: the wrapped elements' strain energy at
/// their path length less that at their chord, J).
#[allow(clippy::too_many_arguments)]
pub fn idler_wrap_contact(
    element: &mut usize,
    x: &[V2],
    v: &[V2],
    body: &IdlerBody,
    law: &ElementLaw,
    claimed: &mut [u64],
    stamp: u64,
    force: &mut [V2],
    tension: &mut [f64],
    mut excess: Option<&mut Vec<(usize, f64)>>,
) -> IdlerContact {
    let n = x.len();
    let (e, near) = super::track_element(element, x, body);
    let first = (e + n - 1) % n;
    // The resultant on the belt and the load-weighted position of its parts, in elements
    // from node `first`.
    let mut total = V2::zeros();
    let (mut weight, mut moment) = (0.0, 0.0);
    let mut out = IdlerContact::default();
    for (off, &(dist, gamma, closest)) in near.iter().enumerate() {
        let k = (first + off) % n;
        let j = (k + 1) % n;
        if claimed[k] == stamp {
            // Measured along another body's path already: the segment contact.
            if dist < body.radius {
                let (normal, fn_, depth) =
                    super::segment_penalty(body, x, v, k, (dist, gamma, closest));
                let f = normal * fn_;
                force[k] += f * (1.0 - gamma);
                force[j] += f * gamma;
                total += f;
                weight += fn_;
                moment += fn_ * (off as f64 + gamma);
                out.penetration = out.penetration.max(depth);
                out.energy += 0.5 * body.stiffness * depth * depth;
            }
            continue;
        }
        if dist >= body.radius {
            continue; // clear of the roll, both nodes too
        }
        let Some(g) = wrap::wrap(x[k], x[j], body.center, body.radius) else {
            continue;
        };
        claimed[k] = stamp;
        let (t, on_roll) = wrap::apply_wrap(
            &g,
            k,
            (k, j),
            x,
            v,
            (body.center, V2::zeros()),
            (body.radius, 0.5 * body.stiffness),
            law,
            force,
        );
        tension[k] = t;
        let chord = (x[j] - x[k]).norm();
        if let Some(excess) = excess.as_deref_mut() {
            excess.push((k, g.length - chord));
        }
        // The roll's contact damping on a node moving towards the roll across its tangent
        // line (never pulling), its coefficient limited at speed (`tangent_damping`): in
        // steady running the node approaching the roll crosses the line at v·m·g/(2T).
        let mut on_roll = on_roll;
        for (i, grad, tangent) in [(k, g.grad_p, g.tangent_p), (j, g.grad_q, g.tangent_q)] {
            if tangent <= 0.0 || body.damping == 0.0 {
                continue;
            }
            let mut u = V2::new(-grad.y, grad.x);
            if u.dot(&(x[i] - body.center)) < 0.0 {
                u = -u;
            }
            let approach = -v[i].dot(&u);
            if approach > 0.0 {
                let c = tangent_damping(body.damping, t, v[i].dot(&grad));
                let f = u * (c * approach);
                force[i] += f;
                on_roll -= f;
            }
        }
        total -= on_roll;
        let w = on_roll.norm();
        weight += w;
        moment += w * (off as f64 + g.share_q);
        out.strain += law.energy(k, g.length) - law.energy(k, chord);
    }
    // Nodes pressed into the roll: the penalty keeps them out.
    for off in 0..4 {
        let i = (first + off) % n;
        let Some((normal, depth)) =
            super::inside_circle(x[i], body.center, body.radius, V2::new(0.0, 1.0))
        else {
            continue;
        };
        let approach = -v[i].dot(&normal);
        let fn_ = (body.stiffness * depth + body.damping * approach).max(0.0);
        force[i] += normal * fn_;
        total += normal * fn_;
        weight += fn_;
        moment += fn_ * off as f64;
        out.penetration = out.penetration.max(depth);
        out.energy += 0.5 * body.stiffness * depth * depth;
    }
    let load = total.norm();
    if load > 0.0 && weight > 0.0 {
        let s = (moment / weight).clamp(0.0, 3.0);
        let off = (s.floor() as usize).min(2);
        out.active = true;
        out.element = (first + off) % n;
        out.gamma = s - off as f64;
        out.normal = total / load;
        out.normal_force = load;
    }
    out
}
