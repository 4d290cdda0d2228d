//! The node belt's discretisation: element count and length, placement on the path, and
//! the per-element and per-node arrays (thesis eq. 4.1–4.4, 4.11).

use crate::error::{BeltError, BeltResult};
use crate::geometry::BeltPath;
use crate::scene::{BeltParams, Scene, MAX_ELEMENTS};
use nalgebra::Vector2;

/// The compiled node belt.
pub(super) struct NodeBelt {
    pub nodes: usize,
    pub element_length: f64,
    pub initial_positions: Vec<Vector2<f64>>,
    pub rest_length: Vec<f64>,
    pub axial_stiffness: Vec<f64>,
    pub axial_damping: Vec<f64>,
    pub mass: Vec<f64>,
    pub inv_mass: Vec<f64>,
    pub bending_stiffness: Vec<f64>,
    /// The ends of an open belt; `None` for a closed loop.
    pub ends: Option<super::open::OpenEnds>,
    /// Initial speeds of a design start (`None`: at rest).
    pub motion: Option<super::design::InitialMotion>,
    /// The rigid-body belt's body angles of a design start, rad (`None`: along the chord
    /// through the neighbours, `super::belt_rigid`).
    pub angles: Option<Vec<f64>>,
}

/// Largest error of the tension ratio over a pulley's wrap that the default element
/// count allows, from the node discretisation of Euler–Eytelwein: 0.5 %.
///
/// A node on a pulley turns the belt by the element angle Δθ and carries the friction
/// µ·N with N = (T_a + T_b)·sin(Δθ/2); at the friction limit its tension ratio is
/// T_b/T_a = (1 + µ·tan(Δθ/2))/(1 − µ·tan(Δθ/2)), whose logarithm is
/// µΔθ·(1 + (1 + µ²)Δθ²/12 + O(Δθ⁴)). Over a wrap θ the ratio e^{µθ} is therefore
/// overestimated by the factor exp(µθ(1 + µ²)Δθ²/12): 4.6 % for µ = 0.5, θ = π at the
/// thesis's 30° elements.
pub const FRICTION_RATIO_ERROR: f64 = 0.005;

/// The rigid-body belt's default body angle as a fraction of the default
/// `max_element_angle` (π/6): bodies of at most 15° on the smallest pulley, unless the
/// scene sets `max_element_angle` or `elements`.
///
/// Rigid bodies touch a pulley at their mass centres, so on a wrap they form the polygon
/// circumscribed about the rim (joints outside it), whose length exceeds the arc by a²/12
/// for bodies of angle a: 2.3 % at 30°, twice the node belt's inscribed deficit a²/24
/// (1.1 %), and the first body on the rim takes a span's pull at up to its whole angle
/// from its tangent (the node belt's junction node: half the element angle). Measured on
/// the hoist of `tests/test_open_belts.py` (frictionless sheave): the anchored span's
/// tension 4.0 % off the continuum at 30° bodies, 0.014 % at 15°, 0.010 % at 7.5°; the
/// bounce frequency −1.4 %, −0.06 %, −0.05 %. At 15° the polygon's excess is 0.57 %, half
/// the node belt's deficit at its 30°.
pub const RIGID_BODY_ANGLE_FACTOR: f64 = 0.5;

/// The longest element (m) that keeps the node-discrete tension ratio over the wrap of
/// every pulley with friction within [`FRICTION_RATIO_ERROR`]: Δθ ≤ √(12ε/(µsθ(1 + µs²)))
/// on a pulley of radius R, wrap θ and static coefficient µs; +∞ without friction.
fn friction_element(scene: &Scene, path: &BeltPath) -> f64 {
    let eps = FRICTION_RATIO_ERROR.ln_1p();
    (scene.pulleys.iter().zip(&path.wrap_angles))
        .filter_map(|(p, &theta)| {
            let mu = p.friction.static_coefficient();
            (mu > 0.0 && theta > 0.0 && p.contact_stiffness > 0.0)
                .then(|| p.radius * (12.0 * eps / (mu * theta * (1.0 + mu * mu))).sqrt())
        })
        .fold(f64::INFINITY, f64::min)
}

/// Discretise the scene's belt on `path`: the belt may be stretched or compressed onto
/// it by at most `belt.max_placement_strain`, and no element may be longer than the smallest pulley radius.
///
/// With a design state (`scene.initial`) the belt is placed stretched to its tensions
/// instead (`super::design`).
pub(super) fn compile(scene: &Scene, path: &BeltPath) -> BeltResult<NodeBelt> {
    if let Some(initial) = &scene.initial {
        let d = super::design::place(scene, initial, path)?;
        let mut b = arrays(scene, d.nodes, d.rest_length, d.positions, Some(d.motion));
        b.angles = d.angles;
        return Ok(b);
    }
    let (n, l0) = discretise(scene, path)?;
    if scene.belt.is_open() {
        return open_belt(scene, path, n, l0);
    }
    let initial_positions = if scene.belt.pulley_contact == crate::scene::PulleyContact::Wrap {
        // Wrap contact measures an element on a pulley along its path round it
        // (contact::wrap): nodes at equal arc length strain every element equally.
        let step = path.length / n as f64;
        (0..n).map(|k| path.point(k as f64 * step)).collect()
    } else {
        // Nodal contact: the chord polygon on a pulley is the belt; equal chords.
        path.equal_chord_nodes(n)?.0
    };
    Ok(arrays(scene, n, l0, initial_positions, None))
}

/// The element count and rest length (m) of the scene's belt on `path` (no design state):
/// `belt.elements`, or the fewest elements of at most `max_element_angle` of arc on the
/// smallest pulley and within the friction rule ([`FRICTION_RATIO_ERROR`]). Refuses a
/// belt stretched or compressed onto its path by more than `belt.max_placement_strain`,
/// fewer than 3 elements and elements longer than the smallest pulley radius. The
/// rigid-body belt reads the count as bodies and the length as the body length.
pub(super) fn discretise(scene: &Scene, path: &BeltPath) -> BeltResult<(usize, f64)> {
    let belt = &scene.belt;
    let belt_length = belt.length.unwrap_or(path.length);
    let min_radius = scene
        .pulleys
        .iter()
        .map(|p| p.radius)
        .fold(f64::INFINITY, f64::min);
    // Strain needed to stretch the belt onto the path.
    let strain = path.length / belt_length - 1.0;
    let max_strain = belt.max_placement_strain;
    if strain > max_strain {
        return Err(BeltError::invalid(
            "belt.length",
            belt_length,
            format!(
                "the belt is too short for its path of {:.6} m: it would be stretched by {:.2} % (limit belt.max_placement_strain = {} %; raise it for a pre-strained belt)",
                path.length,
                100.0 * strain,
                100.0 * max_strain
            ),
        ));
    }
    if strain < -max_strain {
        return Err(BeltError::invalid(
            "belt.length",
            belt_length,
            format!(
                "the belt is too long for its path of {:.6} m: it would be compressed by {:.2} % (limit belt.max_placement_strain = {} %)",
                path.length,
                -100.0 * strain,
                100.0 * max_strain
            ),
        ));
    }
    let n = match belt.elements {
        Some(n) => n,
        None => {
            // The friction rule belongs to the default mesh: a scene that sets
            // max_element_angle has chosen its mesh.
            let default_mesh = belt.max_element_angle == BeltParams::default().max_element_angle;
            let friction = if default_mesh {
                friction_element(scene, path)
            } else {
                f64::INFINITY
            };
            // The rigid-body belt's default bodies span half the default angle
            // ([`RIGID_BODY_ANGLE_FACTOR`]).
            let angle = if default_mesh && belt.formulation == crate::scene::Formulation::RigidBody
            {
                RIGID_BODY_ANGLE_FACTOR * belt.max_element_angle
            } else {
                belt.max_element_angle
            };
            let longest = (angle * min_radius).min(friction);
            let wanted = (belt_length / longest).ceil();
            if wanted > MAX_ELEMENTS as f64 {
                return Err(BeltError::invalid(
                    "belt.max_element_angle",
                    belt.max_element_angle,
                    format!(
                        "a {belt_length} m belt needs {wanted:e} elements of at most this arc on the smallest pulley (radius {min_radius} m), more than {MAX_ELEMENTS}; give belt.elements or check the units"
                    ),
                ));
            }
            wanted as usize
        }
    };
    if n < 3 {
        return Err(BeltError::invalid(
            "belt.elements",
            n,
            "a belt needs at least 3 elements",
        ));
    }
    let l0 = belt_length / n as f64;
    // An element longer than the smallest radius spans more than 60° of that pulley: the
    // chord then cuts deep into the pulley between the nodes and nodal contact fails.
    if l0 > min_radius {
        return Err(BeltError::invalid(
            "belt.elements",
            n,
            format!(
                "elements of {l0:.6} m are longer than the smallest pulley radius {min_radius} m can hold (limit: one radius, a 60° chord); use more elements"
            ),
        ));
    }
    Ok((n, l0))
}

/// The per-element and per-node arrays of `n` elements of rest length `l0` (m).
pub(super) fn arrays(
    scene: &Scene,
    n: usize,
    l0: f64,
    initial_positions: Vec<Vector2<f64>>,
    motion: Option<super::design::InitialMotion>,
) -> NodeBelt {
    let belt = &scene.belt;
    let rho = belt.mass_per_length;
    let k = belt.axial_stiffness / l0;
    let m_el = rho * l0;
    let c = match belt.damping_time {
        // Voigt: b = τ·k (Guo & Wang's σ = Eε + ηε̇ with τ = η/E).
        Some(tau) => tau * k,
        None => 2.0 * m_el * belt.damping_ratio * (k / m_el).sqrt(),
    };
    let rest_length = vec![l0; n];
    let axial_stiffness = vec![k; n];
    let axial_damping = vec![c; n];
    let mass = vec![m_el; n];
    let inv_mass = mass.iter().map(|m| 1.0 / m).collect();
    let bending_stiffness = vec![belt.bending_stiffness / l0; n];
    NodeBelt {
        nodes: n,
        element_length: l0,
        initial_positions,
        rest_length,
        axial_stiffness,
        axial_damping,
        mass,
        inv_mass,
        bending_stiffness,
        ends: None,
        motion,
        angles: None,
    }
}

/// An open belt of `elements` elements of rest length `l0` on its open `path`:
/// `elements + 1` nodes from the start point to the end point with equal chords. The
/// arrays keep one entry per node; the last element entry (node n−1 back to node 0) is no
/// element (zero stiffness and damping; the axial pass skips it). The end nodes carry half
/// an element's mass plus a hanging mass; they have no bending spring.
fn open_belt(scene: &Scene, path: &BeltPath, elements: usize, l0: f64) -> BeltResult<NodeBelt> {
    let n = elements + 1;
    let initial_positions = super::open::place(path, n, false)?;
    let ends = super::open::ends(scene, &initial_positions);
    let mut b = arrays(scene, n, l0, initial_positions, None);
    (b.axial_stiffness[n - 1], b.axial_damping[n - 1]) = (0.0, 0.0);
    let m_el = b.mass[0];
    b.mass[0] = 0.5 * m_el;
    b.mass[n - 1] = 0.5 * m_el;
    for (i, e) in [(0, ends.start), (n - 1, ends.end)] {
        if let super::open::EndModel::Mass(m) = e {
            b.mass[i] += m;
        }
    }
    b.inv_mass = b.mass.iter().map(|m| 1.0 / m).collect();
    b.bending_stiffness[0] = 0.0;
    b.bending_stiffness[n - 1] = 0.0;
    b.ends = Some(ends);
    Ok(b)
}
