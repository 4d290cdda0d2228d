//! The rigid-body belt's discretisation (Kubas 2014 eq. 1–3, 20–23; Guo & Wang 2020 §2):
//! the same body count, length and placement rules as the node belt ([`super::belt`]),
//! with a body's mass centre where the node belt has a node, and its axis along the chord
//! through its neighbours.
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

/// The rigid-body belt on `path`: the node belt's arrays read per body and per joint
/// (joint e joins body e and body e+1), plus the inertias, torsional damping and angles.
pub(super) fn compile(scene: &Scene, path: &BeltPath) -> BeltResult<(NodeBelt, RigidParts)> {
    let belt = super::belt::compile(scene, path)?;
    let n = belt.nodes;
    let zeta = scene.belt.damping_ratio;
    let inertia: Vec<f64> = (belt.mass.iter().zip(&belt.rest_length))
        .map(|(&m, &l)| crate::belt::rigid::link_inertia(m, l))
        .collect();
    let torsional_damping = (0..n)
        .map(|e| match scene.belt.damping_time {
            Some(tau) => tau * belt.bending_stiffness[e],
            None => 2.0 * zeta * (belt.bending_stiffness[e] * inertia[e]).sqrt(),
        })
        .collect();
    let x = &belt.initial_positions;
    let angles = (0..n)
        .map(|i| {
            let d = x[(i + 1) % n] - x[(i + n - 1) % n];
            d.y.atan2(d.x)
        })
        .collect();
    Ok((
        belt,
        RigidParts {
            inertia,
            torsional_damping,
            angles,
        },
    ))
}
