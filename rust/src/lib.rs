//! # beltrs
//!
//! Transient dynamics of belt conveyors and belt drives with discrete belt models.
//!
//! Data flows one way: a [`scene::Scene`] (plain data) is validated and compiled into a
//! read-only [`model::Model`] holding only the stages the scene needs; a [`state::State`]
//! holds everything that changes; a [`simulation::Simulation`] steps (model, state) with
//! explicit central differences and records [`record::Recording`] buffers.
//!
//! The first formulation is Hustrulid's (1993) node model: Kelvin-Voigt axial elements,
//! rotational bending springs, nodal penalty contact with pulleys, centre-line contact with
//! idlers and stick-force friction.

#![warn(missing_docs)]

pub mod checkpoint;
pub mod contact;
pub mod error;
pub mod forces;
pub mod friction;
pub mod geometry;
pub mod interrupt;
pub mod loads;
pub mod model;
pub mod presets;
pub mod record;
pub mod scene;
pub mod simulation;
pub mod start_curve;
pub mod state;
pub mod suggest;

#[cfg(feature = "python")]
mod python;

pub use error::{BeltError, BeltResult};
pub use model::{Model, Stage};
pub use scene::Scene;
pub use simulation::{Relaxation, Simulation, StabiliseOptions, StabiliseReport};
pub use start_curve::{StartCurve, StartShape};
