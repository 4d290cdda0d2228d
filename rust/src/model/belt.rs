//! The node belt's discretisation: element count and length, placement on the path, and
//! the per-element and per-node arrays (thesis eq. 4.1–4.4, 4.11).

use crate::error::{BeltError, BeltResult};
use crate::geometry::BeltPath;
use crate::scene::{Scene, MAX_ELEMENTS};
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
    /// Initial speeds of a design start (`None`: at rest).
    pub motion: Option<super::design::InitialMotion>,
}

/// Discretise the scene's belt on `path`: the belt may be stretched or compressed onto
/// it by at most `belt.max_placement_strain`, and no element may be longer than the smallest pulley radius.
///
/// With a design state (`scene.initial`) the belt is placed stretched to its tensions
/// instead (`super::design`).
pub(super) fn compile(scene: &Scene, path: &BeltPath) -> BeltResult<NodeBelt> {
    if let Some(initial) = &scene.initial {
        let d = super::design::place(scene, initial, path)?;
        return Ok(arrays(
            scene,
            d.nodes,
            d.rest_length,
            d.positions,
            Some(d.motion),
        ));
    }
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
            let wanted = (belt_length / (belt.max_element_angle * min_radius)).ceil();
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
            "a closed belt needs at least 3 elements",
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
    let initial_positions = if belt.pulley_contact == crate::scene::PulleyContact::Wrap {
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

/// The per-element and per-node arrays of `n` elements of rest length `l0` (m).
fn arrays(
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
        motion,
    }
}
