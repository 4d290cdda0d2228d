//! Drives: torque drives, speed-controlled drives following a starting curve, brakes and
//! gravity takeups.

pub mod resistance;
pub mod start_curve;
