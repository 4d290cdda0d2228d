//! Compiled idlers (rolls): centre-line contact, friction, running resistance.

use crate::scene::{FrictionModel, Scene};
use nalgebra::Vector2;

/// Compiled idler.
#[derive(Debug, Clone, PartialEq)]
pub struct IdlerModel {
    /// Centre, m.
    pub center: Vector2<f64>,
    /// Radius, m.
    pub radius: f64,
    /// Polar inertia, kg·m².
    pub inertia: f64,
    /// Contact stiffness, N/m.
    pub contact_stiffness: f64,
    /// Contact damping, N·s/m.
    pub contact_damping: f64,
    /// Friction model.
    pub friction: FrictionModel,
    /// DIN 22101 running-resistance coefficient f, dimensionless.
    pub resistance: f64,
    /// Rotating mass of the roll, kg (its weight adds to the bearing load).
    pub rotating_mass: f64,
}

/// Compile the scene's idlers.
pub(super) fn compile(scene: &Scene) -> Vec<IdlerModel> {
    scene
        .idlers
        .iter()
        .map(|d| IdlerModel {
            center: Vector2::new(d.center[0], d.center[1]),
            radius: d.radius,
            inertia: d.inertia,
            contact_stiffness: d.contact_stiffness,
            contact_damping: d.contact_damping,
            friction: d.friction,
            resistance: d.resistance,
            rotating_mass: d.rotating_mass,
        })
        .collect()
}
