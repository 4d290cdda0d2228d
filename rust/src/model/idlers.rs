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
    /// Contact damping, N·s/m (the scene's absolute value, or 2ζ√(k·m) from its ratio).
    pub contact_damping: f64,
    /// Friction model.
    pub friction: FrictionModel,
    /// DIN 22101 running-resistance coefficient f, dimensionless.
    pub resistance: f64,
    /// Rotating mass of the roll, kg (its weight adds to the bearing load).
    pub rotating_mass: f64,
    /// Radius of the circle wrap contact measures the belt's path over
    /// ([`crate::contact::roll_wrap::wrap_radius`]), m; its top is the roll's top.
    pub wrap_radius: f64,
    /// Centre of that circle, m: the roll's centre moved away from the belt's path by
    /// `wrap_radius − radius` (set by the model from the placement path; straight down
    /// until then), so that the circle's top is the roll's.
    pub wrap_center: Vector2<f64>,
}

/// Compile the scene's idlers for elements of rest length `l0` (m) (a contact damping
/// ratio is taken on the element mass).
pub(super) fn compile(scene: &Scene, l0: f64) -> Vec<IdlerModel> {
    let element_mass = scene.belt.mass_per_length * l0;
    let speed = crate::contact::roll_wrap::scene_speed(scene);
    scene
        .idlers
        .iter()
        .map(|d| {
            let wrap_radius =
                crate::contact::roll_wrap::wrap_radius(d.radius, l0, speed, scene.gravity);
            IdlerModel {
                center: Vector2::new(d.center[0], d.center[1]),
                radius: d.radius,
                inertia: d.inertia,
                contact_stiffness: d.contact_stiffness,
                contact_damping: crate::scene::contact_damping(
                    d.contact_damping,
                    d.contact_damping_ratio,
                    d.contact_stiffness,
                    element_mass,
                ),
                friction: d.friction,
                resistance: d.resistance,
                rotating_mass: d.rotating_mass,
                wrap_radius,
                wrap_center: Vector2::new(d.center[0], d.center[1] - (wrap_radius - d.radius)),
            }
        })
        .collect()
}
