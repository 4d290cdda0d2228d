//! Drives and everything else that turns or moves a pulley besides the belt: torque
//! drives, speed-controlled drives following a starting curve, brakes, holdbacks, and
//! gravity, winch and screw takeups.
//!
//! - [`torque`]: the `drives` stage, T(t, ω).
//! - [`bearing`]: the `bearing_drag` stage, viscous drag −b·ω in the pulley bearings.
//! - [`hold`]: the `speed_drives` stage and the shared solve of a prescribed motion within
//!   a torque range.
//! - [`brake`]: the `brakes` stage, brakes with a torque or a deceleration target, and the
//!   combination of a pulley's holders.
//! - [`holdback`]: the `holdbacks` stage, one-way clutches against reverse rotation.
//! - [`takeup`]: the takeups' translation (moved by the integrator): stops, locks, winch
//!   speed limit.
//! - [`start_curve`]: conveyor starting curves (Harrison, Nordell, cubic, linear).
//! - [`controller`]: the `speed_control` stage, PI speed controllers (torque limit, droop,
//!   torque lag) and their gains from physics.
//! - [`sharing`]: load sharing, master–slave torque followers.
//! - [`motor`]: the `motors` stage, induction motors started direct on line (Kloss curve
//!   or a table) through a gearbox; [`coupling`]: fluid couplings.
//! - [`prime`]: the drives' memory at a design start (PI integrals at the holding torque,
//!   coupled motors at their running point).

pub mod bearing;
pub mod brake;
pub mod controller;
pub mod coupling;
pub mod hold;
pub mod holdback;
pub mod motor;
pub mod prime;
pub mod resistance;
pub mod sharing;
pub mod start_curve;
pub mod takeup;
pub mod torque;
