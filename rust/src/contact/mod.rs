//! Contact between the belt and pulleys (wrap contact, [`wrap`], with nodal penalty
//! contact, thesis eq. 4.70–4.75) and between the belt and idlers (on the element centre
//! line, thesis eq. 4.95–4.102).
//!
//! The thesis writes the pulley law as f = k_c (R − a)/R; here the stiffness is per metre
//! of penetration, f = k (R − a), so k = k_c / R. Contact damping (optional, not in the
//! thesis) acts on the normal approach speed and never pulls the belt onto the body.

pub mod nonlinear;
pub mod roll_wrap;
pub mod stage;
pub mod wrap;

use crate::state::ContactWindow;
use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// Contacts of one pulley found this step; reused every step without reallocating.
#[derive(Debug, Clone, Default)]
pub struct PulleyContacts {
    /// Node index of each contact.
    pub node: Vec<usize>,
    /// Outward unit normal at the node (from the pulley centre to the node).
    pub normal: Vec<V2>,
    /// Normal force on the node, N (≥ 0).
    pub normal_force: Vec<f64>,
    /// Penetration, m.
    pub penetration: Vec<f64>,
    /// Per window node: normal load from the wrapped elements and the penalty, N, and its
    /// load-weighted outward normal (scratch of [`pulley_wrap_contact`]).
    load: Vec<f64>,
    load_normal: Vec<V2>,
    /// Elements measured along their wrapped path this step: (element, path length, m).
    pub wrapped: Vec<(usize, f64)>,
    /// Tangential friction force of each contact on the pulley, N, along the
    /// counter-clockwise tangent (the normal turned by +90°): the contacts' share of
    /// `FrictionOutcome::tangential`. Filled by the friction stage only while a recording
    /// asks for contact forces (`Scratch::contact_detail`); empty otherwise, and when no
    /// friction acted in this evaluation.
    pub friction: Vec<f64>,
    /// Per contact, the pulley surface's speed along the friction's direction at the
    /// belt point per unit ω, m (rigid bodies resting on their ends,
    /// [`pulley_body_contact`]); empty: the pulley's radius for every contact.
    pub lever: Vec<f64>,
    /// Per contact, the moment about the pulley's centre of a unit force along the
    /// friction's direction at the belt point, m: (x − c) × t, where the friction acts on
    /// the belt (rigid bodies resting on their ends: at the mass centre,
    /// [`pulley_body_contact`]). Both friction laws give the pulley the friction's moment
    /// with these arms (`friction::creep`, `friction::pulley_stick_friction`, whose stick
    /// solve also couples each contact to the drum's angular acceleration through its
    /// `lever`), so that belt and pulley keep their angular momentum. The `lever` less a wrap
    /// joint's slide (`belt::rigid::wrap_joint`), which is kinematic and no arm. Empty:
    /// the pulley's radius for every contact.
    pub arm: Vec<f64>,
}

impl PulleyContacts {
    /// Forget last step's contacts, keep the capacity.
    pub fn clear(&mut self) {
        self.node.clear();
        self.normal.clear();
        self.normal_force.clear();
        self.penetration.clear();
        self.wrapped.clear();
        self.friction.clear();
        self.lever.clear();
        self.arm.clear();
    }
    /// The surface speed per unit ω along contact `k`'s friction direction, m:
    /// [`Self::lever`], or the pulley's radius `radius` when empty (nodes).
    #[inline]
    pub fn lever_at(&self, k: usize, radius: f64) -> f64 {
        self.lever.get(k).copied().unwrap_or(radius)
    }
    /// The moment about the pulley's centre of a unit friction force at contact `k`, m:
    /// [`Self::arm`], or the pulley's radius `radius` when empty (nodes).
    #[inline]
    pub fn arm_at(&self, k: usize, radius: f64) -> f64 {
        self.arm.get(k).copied().unwrap_or(radius)
    }
    /// Number of nodes in contact.
    pub fn len(&self) -> usize {
        self.node.len()
    }
    /// True if nothing touches.
    pub fn is_empty(&self) -> bool {
        self.node.is_empty()
    }
}

/// Inputs describing one pulley at this instant.
#[derive(Debug, Clone, Copy)]
pub struct PulleyBody {
    /// Centre, m.
    pub center: V2,
    /// Velocity of the centre, m/s.
    pub center_velocity: V2,
    /// Radius, m.
    pub radius: f64,
    /// Penalty stiffness, N/m.
    pub stiffness: f64,
    /// Normal damping, N·s/m.
    pub damping: f64,
    /// Extra distance beyond the radius within which nodes stay in the search window, m.
    pub margin: f64,
}

/// Keep the window on the run of nodes within `radius + margin` of the centre. The window
/// moves with the belt by at most a few nodes a step, so this is O(1) per step; only an
/// empty window (belt lifted clear, or the run just left) triggers a full scan, in the same
/// call, so no step is evaluated with a stale empty window.
///
/// A window follows one run of nodes. Belt that reaches the pulley somewhere else (a slack
/// loop folding back onto it) is caught by a full scan when `full_scan` is set (the stepper
/// sets it every [`FULL_SCAN_INTERVAL`] steps): the window is widened to take those nodes in.
/// A node must then cross the `margin` (one element length) within that many steps to go
/// unseen, i.e. move faster than a quarter of the axial wave speed.
pub fn update_window(window: &mut ContactWindow, x: &[V2], body: &PulleyBody, full_scan: bool) {
    let n = x.len();
    let reach = body.radius + body.margin;
    let reach2 = reach * reach;
    let near = |i: usize| (x[i] - body.center).norm_squared() < reach2;
    if window.len > 0 {
        track_run(window, n, near);
    }
    if window.len == 0 {
        if let Some(i) = (0..n).find(|&i| near(i)) {
            window.first = i;
            window.len = 1;
            track_run(window, n, near);
        }
    } else if full_scan {
        for i in 0..n {
            if near(i) && (i + n - window.first) % n >= window.len {
                widen(window, i, n);
            }
        }
    }
}

/// Steps between the full scans that catch a second run of belt reaching a pulley.
pub const FULL_SCAN_INTERVAL: u64 = 4;

/// Widen a non-empty window the shorter way round to include node `i`.
fn widen(window: &mut ContactWindow, i: usize, n: usize) {
    let last = (window.first + window.len - 1) % n;
    let forward = (i + n - last) % n;
    let backward = (window.first + n - i) % n;
    if forward <= backward {
        window.len = (window.len + forward).min(n);
    } else {
        window.first = i;
        window.len = (window.len + backward).min(n);
    }
}

/// Grow the window over near neighbours and drop far nodes at its ends.
fn track_run(window: &mut ContactWindow, n: usize, near: impl Fn(usize) -> bool) {
    // Grow backwards, shrink the front, grow forwards, shrink the back.
    while window.len < n && near((window.first + n - 1) % n) {
        window.first = (window.first + n - 1) % n;
        window.len += 1;
    }
    while window.len > 0 && !near(window.first) {
        window.first = (window.first + 1) % n;
        window.len -= 1;
    }
    while window.len > 0 && window.len < n && near((window.first + window.len) % n) {
        window.len += 1;
    }
    while window.len > 0 && !near((window.first + window.len - 1) % n) {
        window.len -= 1;
    }
}

/// Nodal penalty contact with one pulley (thesis eq. 4.70–4.75). Adds the contact forces
/// to `force`, records each contact in `out`, and returns the resultant force on the pulley.
pub fn pulley_contact(
    window: &ContactWindow,
    x: &[V2],
    v: &[V2],
    body: &PulleyBody,
    force: &mut [V2],
    out: &mut PulleyContacts,
) -> V2 {
    pulley_contact_law(window, x, v, body, force, out, |depth, approach| {
        penalty(body, depth, approach)
    })
}

/// The linear penalty's normal force on a node `depth` (m) inside `body` approaching it at
/// `approach` (m/s): k·depth + c·approach, never pulling, N.
#[inline(always)]
pub fn penalty(body: &PulleyBody, depth: f64, approach: f64) -> f64 {
    (body.stiffness * depth + body.damping * approach).max(0.0)
}

/// [`pulley_contact`] with the normal force given by `law`(penetration, approach speed)
/// (N, ≥ 0): the linear penalty, or Kubas's nonlinear law
/// ([`nonlinear::NonlinearContact::normal_force`]).
#[inline(always)]
pub fn pulley_contact_law(
    window: &ContactWindow,
    x: &[V2],
    v: &[V2],
    body: &PulleyBody,
    force: &mut [V2],
    out: &mut PulleyContacts,
    law: impl Fn(f64, f64) -> f64,
) -> V2 {
    out.clear();
    let n = x.len();
    let mut on_pulley = V2::zeros();
    for k in 0..window.len {
        let i = (window.first + k) % n;
        let Some((normal, depth)) =
            inside_circle(x[i], body.center, body.radius, V2::new(1.0, 0.0))
        else {
            continue;
        };
        let approach = -(v[i] - body.center_velocity).dot(&normal);
        let fn_ = law(depth, approach);
        let f = normal * fn_;
        force[i] += f;
        on_pulley -= f;
        out.node.push(i);
        out.normal.push(normal);
        out.normal_force.push(fn_);
        out.penetration.push(depth);
    }
    on_pulley
}

/// The rigid-body belt's points as [`pulley_body_contact`] reads them, one entry each.
#[derive(Debug, Clone, Copy)]
pub struct Bodies<'a> {
    /// Mass centres (an open belt's end points), m.
    pub position: &'a [V2],
    /// Their velocities, m/s.
    pub velocity: &'a [V2],
    /// Axis angles, rad.
    pub angle: &'a [f64],
    /// Angular velocities, rad/s.
    pub spin: &'a [f64],
    /// Body lengths, m (0 for an end point).
    pub length: &'a [f64],
}

/// The rigid-body belt's contact with one pulley ([`crate::belt::rigid::contact`]): each
/// body in the window rests on it with its two ends (an open belt's end points as points),
/// each end taking ½·`law`(depth, approach) along the body's normal; the force and its
/// moment go to `force` and `torque`, and each body in contact is recorded in `out` with
/// its ends' summed normal force and that normal, for the friction solve.
/// Returns the resultant force on the pulley and its moment about the pulley's centre, N
/// and N·m: the contact's forces act on the pulley at the body's ends, where they act on
/// the body, so that the contact keeps the angular momentum of belt and pulley. (The
/// ends' forces lie along the body's normal, not the pulley's radial: where a body's ends
/// press unequally, at the strand's boundary or landing, they have a moment about the
/// centre of (l/2)·(N_a − N_b) — about 300 N·m at v/l on case G's drums — that
/// the pulley takes back; docs/kubas.md, "The contact's moment on the drum".)
pub fn pulley_body_contact(
    window: &ContactWindow,
    bodies: &Bodies<'_>,
    body: &PulleyBody,
    force: &mut [V2],
    torque: &mut [f64],
    out: &mut PulleyContacts,
    law: impl Fn(f64, f64) -> f64,
) -> (V2, f64) {
    use crate::belt::rigid::contact::{body_contact_with, BodyOnPulley, Chord};
    let Bodies {
        position: x,
        velocity: v,
        angle,
        spin,
        length,
    } = *bodies;
    out.clear();
    let n = x.len();
    let mut on_pulley = V2::zeros();
    let mut moment = 0.0;
    // The chord's geometry of the last body's length (the bodies of a belt share one).
    let mut chord = Chord::new(0.0, body.radius);
    for k in 0..window.len {
        let i = (window.first + k) % n;
        if length[i].to_bits() != chord.length.to_bits() {
            chord = Chord::new(length[i], body.radius);
        }
        let b = BodyOnPulley {
            position: x[i],
            velocity: v[i],
            angle: angle[i],
            spin: spin[i],
            length: length[i],
        };
        let c = body_contact_with(
            &b,
            &chord,
            body.center,
            body.center_velocity,
            body.radius,
            &law,
        );
        if c.normal_force <= 0.0 {
            continue;
        }
        force[i] += c.force;
        torque[i] += c.torque;
        on_pulley -= c.force;
        let rel = x[i] - body.center;
        moment -= rel.x * c.force.y - rel.y * c.force.x + c.torque;
        out.node.push(i);
        // The speed along the friction's direction that the mass centre has when it turns
        // with the pulley, per unit ω: (ẑ × (x − c))·t, t = the body's axis. ρ for a body
        // resting on the drum; more for one landing or leaving (its mass centre off ρ,
        // its axis off the tangent), which would otherwise slide at the difference
        // (measured on case G's drums: 6 kN of drag).
        let t = V2::new(-c.normal.y, c.normal.x);
        let arm = V2::new(-rel.y, rel.x).dot(&t);
        out.lever.push(arm);
        out.arm.push(arm);
        out.normal.push(c.normal);
        out.normal_force.push(c.normal_force);
        out.penetration.push(c.penetration);
    }
    (on_pulley, moment)
}

/// Wrap contact with one pulley (the default pulley contact, see [`wrap`]): every element
/// between two nodes of the window whose path wraps the pulley is measured along that path
/// (its chord force from the axial pass replaced, its tension written to `tension`), the
/// nodes inside the circle get the nodal penalty force of [`pulley_contact`], and each node
/// that carries normal load (its share of its elements' arc loads T·φ, plus its penalty
/// force) is recorded in `out` with that load and its load-weighted outward normal, for the
/// friction solve; `excess` (the viscoelastic arms' only) gets each wrapped element with
/// its path length less its chord, m. Returns the resultant force on the pulley.
#[allow(clippy::too_many_arguments)]
pub fn pulley_wrap_contact(
    window: &ContactWindow,
    x: &[V2],
    v: &[V2],
    body: &PulleyBody,
    law: &wrap::ElementLaw,
    force: &mut [V2],
    tension: &mut [f64],
    out: &mut PulleyContacts,
    mut excess: Option<&mut Vec<(usize, f64)>>,
) -> V2 {
    out.clear();
    let n = x.len();
    let w = window.len;
    out.load.clear();
    out.load.resize(w, 0.0);
    out.load_normal.clear();
    out.load_normal.resize(w, V2::zeros());
    let mut on_pulley = V2::zeros();
    // Elements between consecutive window nodes (and the closing one if the window is the
    // whole loop). An element reaching outside the window cannot touch the circle: the
    // window holds every node within one element length (its margin) of it.
    let elements = if w == n { w } else { w.saturating_sub(1) };
    for k in 0..elements {
        let i = (window.first + k) % n;
        let j = (i + 1) % n;
        let Some(g) = wrap::wrap(x[i], x[j], body.center, body.radius) else {
            continue;
        };
        let (t, on) = wrap::apply_wrap(
            &g,
            i,
            (i, j),
            x,
            v,
            (body.center, body.center_velocity),
            (body.radius, 0.5 * body.stiffness),
            law,
            force,
        );
        tension[i] = t;
        out.wrapped.push((i, g.length));
        if let Some(excess) = excess.as_deref_mut() {
            excess.push((i, g.length - (x[j] - x[i]).norm()));
        }
        on_pulley += on;
        let load = t * g.angle;
        let kq = if k + 1 == w { 0 } else { k + 1 };
        out.load[k] += load * (1.0 - g.share_q);
        out.load_normal[k] += g.normal_p * (load * (1.0 - g.share_q));
        out.load[kq] += load * g.share_q;
        out.load_normal[kq] += g.normal_q * (load * g.share_q);
    }
    let r2 = body.radius * body.radius;
    for k in 0..w {
        let i = (window.first + k) % n;
        let rel = x[i] - body.center;
        let a2 = rel.norm_squared();
        let mut depth = 0.0;
        if a2 < r2 {
            let a = a2.sqrt();
            let normal = if a > 0.0 { rel / a } else { V2::new(1.0, 0.0) };
            depth = body.radius - a;
            let approach = -(v[i] - body.center_velocity).dot(&normal);
            let fn_ = (body.stiffness * depth + body.damping * approach).max(0.0);
            let f = normal * fn_;
            force[i] += f;
            on_pulley -= f;
            out.load[k] += fn_;
            out.load_normal[k] += f;
        }
        let load = out.load[k];
        if load > 0.0 {
            let s = out.load_normal[k];
            let norm = s.norm();
            let normal = if norm > 0.0 {
                s / norm
            } else {
                let a = rel.norm();
                if a > 0.0 {
                    rel / a
                } else {
                    V2::new(1.0, 0.0)
                }
            };
            out.node.push(i);
            out.normal.push(normal);
            out.normal_force.push(load);
            out.penetration.push(depth);
        }
    }
    on_pulley
}

/// A point `p` inside the circle (`center`, `radius`): the outward unit normal from the
/// centre through it (`fallback` if it sits on the centre) and its depth below the
/// surface, m; None if it is on or outside the circle.
#[inline]
pub fn inside_circle(p: V2, center: V2, radius: f64, fallback: V2) -> Option<(V2, f64)> {
    let rel = p - center;
    let a2 = rel.norm_squared();
    if a2 >= radius * radius {
        return None;
    }
    let a = a2.sqrt();
    let normal = if a > 0.0 { rel / a } else { fallback };
    Some((normal, radius - a))
}

/// Distance from `c` to the segment [p, q]: (distance, parameter γ ∈ [0, 1] of the closest
/// point, closest point).
#[inline]
pub fn segment_distance(c: V2, p: V2, q: V2) -> (f64, f64, V2) {
    let d = q - p;
    let len2 = d.norm_squared();
    let gamma = if len2 > 0.0 {
        ((c - p).dot(&d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let closest = p + d * gamma;
    ((c - closest).norm(), gamma, closest)
}

/// One idler contact found this step.
#[derive(Debug, Clone, Copy, Default)]
pub struct IdlerContact {
    /// True if the belt touches the idler.
    pub active: bool,
    /// Element in contact (joins `element` and `element + 1`).
    pub element: usize,
    /// Position of the contact point along the element, 0 at its first node (thesis γ).
    pub gamma: f64,
    /// Unit normal from the idler centre towards the belt.
    pub normal: V2,
    /// Normal force on the belt, N.
    pub normal_force: f64,
    /// Penetration of the deepest part, m.
    pub penetration: f64,
    /// Penalty energy ½·k·d² summed over every part pressing on the roll, J.
    pub energy: f64,
    /// Wrap contact ([`roll_wrap`]): the strain energy of the elements measured along their
    /// path over the roll less that at their chord, J (0 for the segment contact).
    pub strain: f64,
}

/// Inputs describing one idler.
#[derive(Debug, Clone, Copy)]
pub struct IdlerBody {
    /// Centre, m.
    pub center: V2,
    /// Radius, m.
    pub radius: f64,
    /// Penalty stiffness, N/m.
    pub stiffness: f64,
    /// Normal damping, N·s/m.
    pub damping: f64,
}

/// The element an idler starts tracking: the nearest element lying above the roll (its
/// closest point higher than the roll centre), since idlers carry the belt against gravity;
/// the nearest element of all if none lies above. Nearest alone can pick the other strand:
/// a carry roll between a sagging carry strand and the return strand just below it would
/// track the return strand and let the carry belt fall through it.
pub fn supported_element(center: V2, x: &[V2]) -> usize {
    let n = x.len();
    let key = |e: usize| {
        let (dist, _, closest) = segment_distance(center, x[e], x[(e + 1) % n]);
        (closest.y <= center.y, dist)
    };
    (0..n)
        .min_by(|&a, &b| {
            let (ka, kb) = (key(a), key(b));
            ka.0.cmp(&kb.0).then(ka.1.total_cmp(&kb.1))
        })
        .unwrap_or(0)
}

/// Centre-line contact with one idler (thesis eq. 4.95–4.102). The idler tracks the nearest
/// element by stepping to a neighbour while that is nearer, so the search is local. The
/// closest point on the element splits the force by the lever rule: (1 − γ) to the first
/// node and γ to the second (the thesis text swaps d and e in eq. 4.100–4.101; its code has
/// them right). The neighbours of the tracked element press too when they penetrate (a node
/// over the roll); the returned contact is the deepest part with the summed normal force.
pub fn idler_contact(
    element: &mut usize,
    x: &[V2],
    v: &[V2],
    body: &IdlerBody,
    force: &mut [V2],
) -> IdlerContact {
    let n = x.len();
    let (e, [db, best, df]) = track_element(element, x, body);
    // The tracked element and both neighbours may press on the roll. Near a node the belt
    // polygon kinks over the roll and two elements penetrate it; taking only the nearest
    // would flip the force between their two normals as the node passes (and chatter in
    // statics), while the sum turns smoothly from one to the other.
    let mut out = IdlerContact::default();
    for (k, (dist, gamma, closest)) in [((e + n - 1) % n, db), (e, best), ((e + 1) % n, df)] {
        if dist >= body.radius {
            continue;
        }
        let j = (k + 1) % n;
        let (normal, fn_, depth) = segment_penalty(body, x, v, k, (dist, gamma, closest));
        force[k] += normal * (fn_ * (1.0 - gamma));
        force[j] += normal * (fn_ * gamma);
        // The deepest part is the contact point for friction; it carries the total force.
        if !out.active || depth > out.penetration {
            out.element = k;
            out.gamma = gamma;
            out.normal = normal;
            out.penetration = depth;
        }
        out.active = true;
        out.normal_force += fn_;
        out.energy += 0.5 * body.stiffness * depth * depth;
    }
    out
}

/// Closest-point data of a segment: (distance, γ, closest point), as [`segment_distance`].
pub type SegmentPoint = (f64, f64, V2);

/// The element an idler tracks this step: from the one it tracked last (`element`, updated),
/// stepping to a neighbour while that is nearer, so the search is local. Returns it with the
/// closest points of the element before it, itself and the one after.
pub fn track_element(
    element: &mut usize,
    x: &[V2],
    body: &IdlerBody,
) -> (usize, [SegmentPoint; 3]) {
    let n = x.len();
    let dist_of = |e: usize| segment_distance(body.center, x[e], x[(e + 1) % n]);
    let mut e = *element % n;
    let mut best = dist_of(e);
    // Distances of the tracked element's two neighbours, reused for their contact.
    let mut around = None;
    for _ in 0..n {
        let back = (e + n - 1) % n;
        let fwd = (e + 1) % n;
        let db = dist_of(back);
        let df = dist_of(fwd);
        if db.0 < best.0 && db.0 <= df.0 {
            e = back;
            best = db;
        } else if df.0 < best.0 {
            e = fwd;
            best = df;
        } else {
            around = Some((db, df));
            break;
        }
    }
    *element = e;
    let (db, df) = around.unwrap_or_else(|| (dist_of((e + n - 1) % n), dist_of((e + 1) % n)));
    (e, [db, best, df])
}

/// Unit normal from the idler centre towards the closest point of element `k` at `dist`.
#[inline]
fn contact_normal(body: &IdlerBody, x: &[V2], k: usize, (dist, closest): (f64, V2)) -> V2 {
    if dist > 0.0 {
        (closest - body.center) / dist
    } else {
        // The centre line passes through the idler centre: push along the element normal.
        let d = x[(k + 1) % x.len()] - x[k];
        V2::new(-d.y, d.x).normalize()
    }
}

/// The penalty contact of element `k` whose closest point (from [`segment_distance`]) lies
/// inside the idler: (unit normal from the centre, normal force k·depth + c·approach ≥ 0 N,
/// depth m). The caller splits the force by the lever rule.
#[inline]
pub fn segment_penalty(
    body: &IdlerBody,
    x: &[V2],
    v: &[V2],
    k: usize,
    (dist, gamma, closest): SegmentPoint,
) -> (V2, f64, f64) {
    let j = (k + 1) % x.len();
    let normal = contact_normal(body, x, k, (dist, closest));
    let depth = body.radius - dist;
    let vc = v[k] * (1.0 - gamma) + v[j] * gamma;
    let approach = -vc.dot(&normal);
    let fn_ = (body.stiffness * depth + body.damping * approach).max(0.0);
    (normal, fn_, depth)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pulley_takes_back_the_rigid_contacts_moment() {
        // Case G's drum (R = 0.4 m) with 0.2 m bodies: a wrap of bodies resting as chords,
        // the first pressed in at one end only (landing), the others at both ends but by
        // different depths. The contact's forces lie along each body's normal, so its
        // moment about the drum's centre is not zero; the pulley gets the opposite force
        // and the opposite moment, so belt and pulley keep their momentum and angular
        // momentum (`pulley_body_contact`).
        let (l, r) = (0.2, 0.4);
        let a = l / r;
        let rho = crate::belt::rigid::contact::contact_radius(l, r);
        let center = V2::new(0.3, -0.1);
        let n = 6;
        let mut x = Vec::new();
        let mut angle = Vec::new();
        for i in 0..n {
            let phi = 0.3 + a * i as f64;
            let depth = 1e-5 * (1.0 + 0.7 * i as f64);
            x.push(center + V2::new(phi.cos(), phi.sin()) * (rho - depth));
            // Tilted by up to 3 mrad: unequal ends; the first body lands on one end.
            let tilt = if i == 0 {
                0.02
            } else {
                3e-3 * (i as f64 - 2.5)
            };
            angle.push(phi + std::f64::consts::FRAC_PI_2 + tilt);
        }
        let v: Vec<V2> = (0..n).map(|i| V2::new(0.1 * i as f64, -0.2)).collect();
        let (spin, length) = (vec![0.3; n], vec![l; n]);
        let bodies = Bodies {
            position: &x,
            velocity: &v,
            angle: &angle,
            spin: &spin,
            length: &length,
        };
        let pulley = PulleyBody {
            center,
            center_velocity: V2::zeros(),
            radius: r,
            stiffness: 1e8,
            damping: 1e3,
            margin: 0.1,
        };
        let (mut force, mut torque) = (vec![V2::zeros(); n], vec![0.0; n]);
        let mut out = PulleyContacts::default();
        let window = ContactWindow { first: 0, len: n };
        let law = |d: f64, rate: f64| 1e8 * d + 1e3 * rate;
        let (on_pulley, moment) = pulley_body_contact(
            &window,
            &bodies,
            &pulley,
            &mut force,
            &mut torque,
            &mut out,
            law,
        );
        assert_eq!(out.len(), n);
        let total: V2 = force.iter().sum();
        let belt_moment: f64 = (0..n)
            .map(|i| {
                let rel = x[i] - center;
                rel.x * force[i].y - rel.y * force[i].x + torque[i]
            })
            .sum();
        assert!((total + on_pulley).norm() < 1e-9 * total.norm());
        // The moment is there (tens of N·m here) and the pulley takes it back.
        assert!(belt_moment.abs() > 1.0, "{belt_moment}");
        assert!(
            (belt_moment + moment).abs() < 1e-9 * belt_moment.abs().max(1.0),
            "{belt_moment} {moment}"
        );
    }
}
