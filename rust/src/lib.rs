//! # beltrs
//!
//! Transient dynamics of belt conveyors and belt drives with discrete belt models.
//!
//! Data flows one way: a [`scene::Scene`] (plain data) is validated and compiled into a
//! read-only [`model::Model`] holding only the stages the scene needs; a [`state::State`]
//! holds everything that changes (generalized coordinates, velocities, memory); a
//! [`simulation::Simulation`] advances (model, state) with the model's
//! [`integrate::Integrator`], each force evaluation running the stage list of
//! [`pipeline::evaluate`], and records [`record::Recording`] buffers. The layout and the
//! recipes for a new stage, integrator or belt formulation are in `docs/architecture.md`.
//!
//! The first formulation is Hustrulid's (1993) node model: Kelvin-Voigt axial elements,
//! rotational bending springs, nodal penalty contact with pulleys, centre-line contact with
//! idlers and stick-force friction.

#![warn(missing_docs)]

pub mod belt;
pub mod checkpoint;
pub mod contact;
pub mod drives;
pub mod error;
pub mod friction;
pub mod geometry;
pub mod integrate;
pub mod interrupt;
pub mod loads;
pub mod model;
pub mod pipeline;
pub mod presets;
pub mod record;
pub mod scene;
pub mod simulation;
pub mod state;
pub mod suggest;

#[cfg(feature = "python")]
mod python;

/// The node belt's kernels under their historical path (`beltrs::forces::axial`, ...).
pub use belt::node as forces;
/// Starting curves under their historical path.
pub use drives::start_curve;
pub use error::{BeltError, BeltResult};
pub use integrate::relax::{Relaxation, StabiliseOptions, StabiliseReport};
pub use integrate::Integrator;
pub use model::{Model, Stage};
pub use scene::Scene;
pub use simulation::Simulation;
pub use start_curve::{StartCurve, StartShape};
