//! Belt formulations. Each one turns belt positions and velocities into element tensions
//! and node forces; contact, friction, drives and recording see only belt points.
//!
//! - [`node`]: Hustrulid's (1993) discrete node model (Kelvin-Voigt axial elements,
//!   rotational bending springs, node weights).
//! - [`rigid`]: Kubas's (2014) chain of rigid bodies joined by Kelvin–Voigt spring-dampers.
//! - [`ends`]: the ends of an open belt (anchors, pulls), acting on the first and last
//!   belt points.

pub mod ends;
pub mod node;
pub mod rigid;
