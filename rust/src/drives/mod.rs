//! Drives and everything else that turns or moves a pulley besides the belt: torque
//! drives, speed-controlled drives following a starting curve, brakes, and gravity
//! takeups.
//!
//! - [`torque`]: the `drives` stage, T(t, ω).
//! - [`bearing`]: the `bearing_drag` stage, viscous drag −b·ω in the pulley bearings.
//! - [`hold`]: the `speed_drives` and `brakes` stages, prescribed motion within a torque.
//! - [`takeup`]: the gravity takeup's translation, moved by the integrator.
//! - [`start_curve`]: conveyor starting curves (Harrison, Nordell, cubic, linear).
//! - [`controller`]: the `speed_control` stage, PI speed controllers (torque limit, droop,
//!   torque lag) and their gains from physics.
//! - [`sharing`]: load sharing, master–slave torque followers.
//! - [`motor`]: the `motors` stage, induction motors started direct on line (Kloss curve
//!   or a table) through a gearbox; [`coupling`]: fluid couplings.

pub mod bearing;
pub mod controller;
pub mod coupling;
pub mod hold;
pub mod motor;
pub mod resistance;
pub mod sharing;
pub mod start_curve;
pub mod takeup;
pub mod torque;
