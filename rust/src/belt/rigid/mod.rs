//! Kubas's (2014) rigid-body belt: a chain of rigid bodies with three coordinates each
//! (x, y of the mass centre and the angle φ, Kubas eq. 1), homogeneous thin links of mass
//! mᵢ and length lᵢ with Iᵢ = mᵢlᵢ²/12 (eq. 2), joined by translational and torsional
//! Kelvin–Voigt spring-dampers (SDEs, eq. 20–23).
//!
//! - [`sdes`]: the SDE forces and torques between neighbouring bodies.
//! - [`stage`]: the stage the pipeline calls (`Stage::RigidChain`) and the chain's energy.
//! - [`contact`]: a body on a pulley, touching it with its two ends (a chord on a circle).
//! - [`wrap_joint`]: the joint where a strand meets a drum measured along the string's path
//!   (`belt.pulley_contact = "wrap"`).
//!
//! The same machinery is Guo & Wang's (2020) rigid finite element belt: c_x = EA/Δl,
//! c_φ = EI/Δl (`crate::model`'s `belt_rigid` part, `docs/kubas.md`).

pub mod contact;
pub mod sdes;
pub mod stage;
pub mod wrap_joint;

/// Mass moment of inertia of a thin homogeneous link about its mass centre, mᵢlᵢ²/12
/// (Kubas eq. 2), kg·m².
#[inline]
pub fn link_inertia(mass: f64, length: f64) -> f64 {
    mass * length * length / 12.0
}
