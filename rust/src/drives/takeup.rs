//! Takeups (thesis eq. 4.63–4.65): a pulley that translates along a line under a pull (a
//! counterweight's weight, a winch's or a screw's set force) and the belt's force, between
//! travel stops (`docs/stops-takeups.md`). The force is the belt's on the pulley (the
//! contact and friction stages) plus the pull; the integrator moves the travel like any
//! other degree of freedom, with the carriage speed passed through [`carriage_speed`]
//! (locks, winch speed limit) before the move and the stops applied after it.

use crate::model::TakeupModel;

/// The carriage speed (m/s) the takeup `t` allows at time `time` (s) for a new speed
/// `speed` from its equation of motion: 0 once locked (a fixed screw takeup always, a
/// takeup that locks on stopping from the scene's first stop), else `speed` within the
/// winch's speed limit (the winch holds the rope speed at the limit, so the tension departs
/// from its set force). A gravity takeup that never locks gets `speed` unchanged.
#[inline]
pub fn carriage_speed(t: &TakeupModel, time: f64, speed: f64) -> f64 {
    if time >= t.lock_time {
        0.0
    } else if speed > t.max_speed {
        t.max_speed
    } else if speed < -t.max_speed {
        -t.max_speed
    } else {
        speed
    }
}

/// Keep a takeup between its stops: at a stop the travel is clamped and a speed into the
/// stop is removed (an inelastic impact). Against a stop that the belt pushes it into, the
/// carriage stays there: each step's speed into the stop is removed again.
#[inline]
pub fn apply_stops(t: &TakeupModel, travel: &mut f64, speed: &mut f64) {
    if *travel < t.travel_min {
        *travel = t.travel_min;
        *speed = speed.max(0.0);
    } else if *travel > t.travel_max {
        *travel = t.travel_max;
        *speed = speed.min(0.0);
    }
}
