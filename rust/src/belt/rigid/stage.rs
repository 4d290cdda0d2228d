//! The rigid-body belt's stage: the spring-dampers between neighbouring bodies (Kubas
//! eq. 20–23) and the body weights. Contact, friction, drives and recording see the bodies'
//! mass centres as the belt points (`State::position`, `State::velocity`), as Kubas applies
//! contact and friction there (section 2.1).

use super::sdes::{joint_energy, joint_with, LinkState, SdeParams};
use crate::model::Model;
use crate::pipeline::StageContext;
use crate::state::State;
use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// Body `i` as the SDE kernels see it.
#[inline]
fn link(m: &Model, s: &State, i: usize) -> LinkState {
    LinkState {
        position: s.position[i],
        angle: s.body_angle[i],
        velocity: s.velocity[i],
        angular_velocity: s.body_spin[i],
        length: m.rest_length[i],
    }
}

/// The SDEs of joint `e` (between body e and body e+1), dampers on if `damped`.
#[inline]
fn params(m: &Model, e: usize, damped: bool) -> SdeParams {
    SdeParams {
        translational_stiffness: m.axial_stiffness[e],
        translational_damping: if damped { m.axial_damping[e] } else { 0.0 },
        torsional_stiffness: m.bending_stiffness[e],
        torsional_damping: if damped { m.torsional_damping[e] } else { 0.0 },
    }
}

/// The unit axis of a body from its half-length vector `h` and length `l`; zero for an
/// open belt's end point (length 0).
#[inline]
fn unit_axis(h: V2, l: f64) -> V2 {
    if l > 0.0 {
        h / l
    } else {
        V2::zeros()
    }
}

/// SDE forces and torques of the chain and the body weights −m·g ŷ. **Writes**
/// every body force and torque (the first stage that touches them) and each joint's
/// tension: the SDE force along the mean axis of its two bodies, N, negative when the
/// ends overlap (the spring then pushes the bodies apart). The relaxation runs the
/// dampers off ([`crate::pipeline::Effects::damping`]). A closed chain has a joint per
/// body (the last joins body n−1 to body 0); an open one (`crate::model`'s
/// `belt_rigid::open_chain`) joins its end points (length 0: their half-length vector is
/// zero, so an end joint acts at the point itself) to the end bodies, n − 1 joints.
pub fn chain(cx: &mut StageContext<'_>) {
    let (m, s, sc) = (cx.model, &*cx.state, &mut *cx.scratch);
    let n = m.nodes;
    let g = if m.gravity > 0.0 { m.gravity } else { 0.0 };
    for (i, (f, t)) in sc.force.iter_mut().zip(&mut sc.body_torque).enumerate() {
        *f = V2::new(0.0, -s.node_mass[i] * g);
        *t = 0.0;
    }
    let damped = cx.effects.damping;
    // Each body's half-length vector (a sine and a cosine) and unit axis once, carried to
    // the next joint.
    let first = link(m, s, 0);
    let first_half = first.half_vector();
    let first_axis = unit_axis(first_half, first.length);
    let (mut left, mut hl, mut al) = (first, first_half, first_axis);
    for e in 0..m.elements {
        let r = if e + 1 == n { 0 } else { e + 1 };
        let (right, hr, ar) = if r == 0 {
            (first, first_half, first_axis)
        } else {
            let b = link(m, s, r);
            let h = b.half_vector();
            (b, h, unit_axis(h, b.length))
        };
        let j = joint_with(&left, hl, &right, hr, &params(m, e, damped));
        sc.force[r] += j.force_on_right;
        sc.force[e] -= j.force_on_right;
        sc.body_torque[e] += j.torque_on_left;
        sc.body_torque[r] += j.torque_on_right;
        sc.tension[e] = if j.direction.dot(&(al + ar)) < 0.0 {
            -j.tension
        } else {
            j.tension
        };
        (left, hl, al) = (right, hr, ar);
    }
    if m.rigid_wrap {
        wrap_joints(m, s, sc, damped);
    }
}

/// Every active wrap joint of every drum (`super::wrap_joint`), searched in the drum's
/// contact window of the last evaluation (it holds every body within 1.5 l of the circle):
/// `visit(pulley, joint, links, joint parameters)`.
fn for_each_drum_wrap(
    m: &Model,
    s: &State,
    damped: bool,
    mut visit: impl FnMut(
        usize,
        &super::wrap_joint::ActiveWrap,
        &dyn Fn(usize) -> LinkState,
        &dyn Fn(usize) -> SdeParams,
    ),
) {
    let n = m.nodes;
    let closed = m.elements == n;
    let links = |i: usize| link(m, s, i);
    let sdes = |e: usize| params(m, e, damped);
    for (j, p) in m.pulleys.iter().enumerate() {
        if p.contact_stiffness == 0.0 || !m.rests_on_ends(j) {
            continue;
        }
        // Before the first contact evaluation the window is empty: the whole chain then.
        let w = s.pulley_window[j];
        let (first, len) = if w.len == 0 { (0, n) } else { (w.first, w.len) };
        super::wrap_joint::for_each_wrap(
            &links,
            n,
            closed,
            first,
            len,
            s.pulley_center(m, j),
            p.radius,
            &sdes,
            |a| visit(j, &a, &links, &sdes),
        );
    }
}

/// Each drum's active wrap joints' forces, and which body each lets slide on the drum.
fn wrap_joints(m: &Model, s: &State, sc: &mut crate::pipeline::Scratch, damped: bool) {
    sc.wrap_slide.clear();
    let (force, torque, tension, slide) = (
        &mut sc.force,
        &mut sc.body_torque,
        &mut sc.tension,
        &mut sc.wrap_slide,
    );
    for_each_drum_wrap(m, s, damped, |j, a, links, sdes| {
        super::wrap_joint::apply(a, links, &sdes(a.joint), force, torque, tension);
        slide.push((j, a.slider(), a.load.slide));
    });
}

/// The wrap joints' energy less the plain joints' they replace (½c_x(|g|² − |d|²) summed),
/// J: what [`chain_energy`]'s strain misses with `belt.pulley_contact = "wrap"`.
pub fn wrap_energy(m: &Model, s: &State) -> f64 {
    if !m.rigid_wrap {
        return 0.0;
    }
    let mut total = 0.0;
    for_each_drum_wrap(m, s, false, |_, a, links, _| {
        let (l, r) = (links(a.left), links(a.right));
        let d = (r.position - r.half_vector()) - (l.position + l.half_vector());
        total += a.load.energy - 0.5 * m.axial_stiffness[a.joint] * d.norm_squared();
    });
    total
}

/// Stored energy of the chain: (translational ½c_x|d|², torsional ½c_φΔφ²), J.
pub fn chain_energy(m: &Model, s: &State) -> (f64, f64) {
    let n = m.nodes;
    let (mut strain, mut bending) = (0.0, 0.0);
    for e in 0..m.elements {
        let (l, r) = (link(m, s, e), link(m, s, (e + 1) % n));
        let p = params(m, e, false);
        let elastic = SdeParams {
            torsional_stiffness: 0.0,
            ..p
        };
        let total = joint_energy(&l, &r, &p);
        let translational = joint_energy(&l, &r, &elastic);
        strain += translational;
        bending += total - translational;
    }
    (strain, bending)
}
