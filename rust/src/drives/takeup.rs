//! Gravity takeups (thesis eq. 4.63–4.65): a pulley that translates along a line under a
//! counterweight's pull and the belt's force, between travel stops. The force is the
//! belt's on the pulley (the contact and friction stages) plus the pull; the integrator
//! moves the travel like any other degree of freedom and then applies the stops here.

use crate::model::TakeupModel;

/// Keep a takeup between its stops: at a stop the travel is clamped and a speed into the
/// stop is removed (an inelastic impact).
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
