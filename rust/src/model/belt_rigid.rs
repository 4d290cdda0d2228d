//! The rigid-body belt's discretisation (Kubas 2014 eq. 1–3, 20–23; Guo & Wang 2020 §2):
//! the same body count, length and placement rules as the node belt ([`super::belt`]),
//! with a body's mass centre where the node belt has a node, and its axis along the chord
//! through its neighbours. An open belt adds its two end points ([`open_chain`]).
//!
//! Parameters from the belt's EA, EI, ρA and damping ratio ζ, for bodies of length l:
//! - mass m = ρA·l, inertia I = m·l²/12 (a thin homogeneous link, Kubas eq. 2);
//! - translational SDE c_x = EA/l (the stiffness of a belt piece of length l: Kubas's
//!   c_tra read per unit strain, `docs/kubas.md`; Guo & Wang's c_x = EA/Δl), damping
//!   b_x = 2ζ√(c_x·m), the node belt's rule;
//! - torsional SDE c_φ = EI/l (Guo & Wang's c_φ, the node belt's bending spring), damping
//!   b_φ = 2ζ√(c_φ·I);
//! - or, with `belt.damping_time` τ (Guo & Wang's Voigt material σ = Eε + ηε̇, τ = η/E),
//!   b_x = τ·c_x and b_φ = τ·c_φ.

use super::belt::NodeBelt;
use crate::error::BeltResult;
use crate::geometry::BeltPath;
use crate::scene::Scene;

/// What the rigid-body belt adds to the node arrays.
pub(super) struct RigidParts {
    /// Body inertias about the mass centre, kg·m².
    pub inertia: Vec<f64>,
    /// Torsional SDE damping per joint, N·m·s/rad.
    pub torsional_damping: Vec<f64>,
    /// Initial body angles, rad.
    pub angles: Vec<f64>,
}

/// The rigid-body belt on `path`: the node belt's arrays read per belt point and per joint
/// (joint e joins point e and point e+1), plus the inertias, torsional damping and angles.
/// A closed belt's points are its bodies; an open belt's are its two end points and its
/// bodies between them ([`open_chain`]).
pub(super) fn compile(scene: &Scene, path: &BeltPath) -> BeltResult<(NodeBelt, RigidParts)> {
    let belt = if scene.belt.is_open() {
        open_chain(scene, path)?
    } else {
        super::belt::compile(scene, path)?
    };
    let n = belt.nodes;
    let zeta = scene.belt.damping_ratio;
    // An open belt's end point (length 0) is no rotational degree of freedom: nothing
    // turns it (no lever, no torsional spring), so its torque is always zero. It gets a
    // body's inertia all the same, so that an update over every body angle (0/I) stays 0.
    let body = belt.element_length;
    let inertia: Vec<f64> = (belt.mass.iter().zip(&belt.rest_length))
        .map(|(&m, &l)| crate::belt::rigid::link_inertia(m, if l > 0.0 { l } else { body }))
        .collect();
    let torsional_damping = (0..n)
        .map(|e| match scene.belt.damping_time {
            Some(tau) => tau * belt.bending_stiffness[e],
            None => 2.0 * zeta * (belt.bending_stiffness[e] * inertia[e]).sqrt(),
        })
        .collect();
    let x = &belt.initial_positions;
    let open = belt.ends.is_some();
    let angles = belt.angles.clone().unwrap_or_else(|| {
        (0..n)
            .map(|i| {
                // Along the chord through the neighbours; an open belt's end point (and the
                // bodies next to it) along the chord from the end point.
                let d = if open {
                    x[(i + 1).min(n - 1)] - x[i.max(1) - 1]
                } else {
                    x[(i + 1) % n] - x[(i + n - 1) % n]
                };
                d.y.atan2(d.x)
            })
            .collect()
    });
    Ok((
        belt,
        RigidParts {
            inertia,
            torsional_damping,
            angles,
        },
    ))
}

/// An open rigid-body belt (`belt.start`, `belt.end`): N bodies of length l = L/N (the
/// count and length by the node belt's rules, [`super::belt::discretise`]) between two end
/// points, N + 2 belt points in all: point 0 at `start.point`, the bodies' mass centres
/// one body length apart on the path (the first and the last half a body from the end
/// points), point N+1 at `end.point`.
///
/// - *Joints.* N − 1 joints between the bodies (c_x = EA/l, b_x, c_φ = EI/l, b_φ as for
///   the closed loop) and two end joints from an end point to the outer end of its body:
///   zero free length like every SDE, stiffness 2c_x and damping 2b_x (half a body's belt
///   piece: the same b/c, i.e. the same material), no torsional spring (the belt turns
///   freely about its end point, as at a pin, hook or clamp). The chain's compliance is
///   (N − 1)·l/EA + 2·l/(2EA) = L/EA and its unstretched length N·l = L, both exactly the
///   belt's.
/// - *Masses.* Each body ρA·l, so the bodies carry the whole belt, ρA·L. An end point
///   carries half a body's mass ρA·l/2 (as the node belt's end node; an explicit
///   integrator cannot move a massless point) plus a hanging mass: for a pull, the clamp
///   through which it acts; for an anchor, nothing that moves.
/// - *Arrays.* One entry per belt point; the joint arrays' last entry (point N+1 back to
///   point 0) is no joint. A point's rest length (the "body length") is 0.
fn open_chain(scene: &Scene, path: &BeltPath) -> BeltResult<NodeBelt> {
    let (bodies, l) = super::belt::discretise(scene, path)?;
    let n = bodies + 2;
    let positions = super::open::place(path, n, true)?;
    let ends = super::open::ends(scene, &positions);
    let mut b = super::belt::arrays(scene, n, l, positions, None);
    for e in [0, n - 2] {
        b.axial_stiffness[e] *= 2.0;
        b.axial_damping[e] *= 2.0;
        b.bending_stiffness[e] = 0.0;
    }
    (b.axial_stiffness[n - 1], b.axial_damping[n - 1]) = (0.0, 0.0);
    b.bending_stiffness[n - 1] = 0.0;
    b.rest_length[0] = 0.0;
    b.rest_length[n - 1] = 0.0;
    let body = b.mass[1];
    for (i, end) in [(0, ends.start), (n - 1, ends.end)] {
        b.mass[i] = 0.5 * body;
        if let super::open::EndModel::Mass(m) = end {
            b.mass[i] += m;
        }
    }
    b.inv_mass = b.mass.iter().map(|m| 1.0 / m).collect();
    b.ends = Some(ends);
    Ok(b)
}
