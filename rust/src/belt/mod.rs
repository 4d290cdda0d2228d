//! Belt formulations. Each one turns belt positions and velocities into element tensions
//! and node forces; contact, friction, drives and recording see only belt points.
//!
//! - [`node`]: Hustrulid's (1993) discrete node model (Kelvin-Voigt axial elements,
//!   rotational bending springs, node weights).

pub mod node;
