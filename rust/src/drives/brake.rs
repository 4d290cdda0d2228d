//! Brakes: a friction torque on a pulley that opposes its rotation and holds it at rest up
//! to the brake's capacity (`docs/stops-takeups.md`). A brake is a prescribed motion with a
//! limited torque ([`Prescribed`]), solved with the belt friction when the pulley has any
//! (`crate::friction::pulley_stick_friction`), else by the `brakes` stage
//! (`super::hold`):
//!
//! - **Torque target** (a `time`/`capacity` table, or `torque` from `applied`, built up over
//!   `rise`): the target is rest, ω = 0 at the end of the step, with the range
//!   ±capacity. While the torque that would stop the pulley this step exceeds the capacity
//!   the brake slides and supplies −capacity·sign(ω) (Coulomb); once it can stop the pulley
//!   within one step it holds it at rest exactly, with whatever torque up to the capacity
//!   the belt asks for. It never reverses the motion and never chatters about ω = 0.
//! - **Deceleration target** a (m/s² at the pulley surface, radius r): a controller that
//!   tracks the speed ramp ω_ref(t) = ω_a − (a/r)·(t − t_applied) towards 0, ω_a the pulley
//!   speed when the brake was applied (`State::brake_ramp`). The brake may only oppose the
//!   motion (range [−capacity, 0] for ω > 0): above the ramp it brings the pulley onto it,
//!   below it (the load slowing the pulley faster, or the pulley rocking on the belt) it
//!   supplies nothing until the pulley is back above the ramp; at most its capacity. Once
//!   the ramp reaches 0 it holds at rest like a torque brake. Tracking a ramp, not the
//!   current speed less a·Δt, keeps the stop at ω_a·r/a: a rate limit on the current speed
//!   would also swallow every elastic rebound and stop early.
//!
//! [`PulleyModel::hold`] combines a pulley's holders: a powered speed-controlled drive
//! holds alone (with the holdback's range added while it holds the pulley at rest, e.g.
//! before its start); otherwise its brake and its holdback (`super::holdback`) act
//! together.

use crate::friction::Prescribed;
use crate::model::PulleyModel;
use crate::pipeline::StageContext;
use crate::scene::BrakeSpec;

/// Who holds a pulley this step (where its torque is recorded).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Holder {
    /// A speed-controlled drive (`drive_torque`).
    Drive,
    /// A brake and/or a holdback (`brake_torque`).
    Brake,
}

/// The brake's prescription for the step from `time` (s) with the velocity update `kick`
/// (s), for a pulley of radius `radius` (m) turning at `omega` (rad/s, at t − Δt/2), whose
/// deceleration ramp began at `ramp` (rad/s; 0: not begun, it begins at `omega`). `None`
/// while the brake is released.
#[inline]
pub fn brake_prescription(
    brake: &BrakeSpec,
    time: f64,
    kick: f64,
    radius: f64,
    omega: f64,
    ramp: f64,
) -> Option<Prescribed> {
    if brake.released(time) {
        return None;
    }
    let capacity = brake.capacity_at(time);
    let Some(a) = brake.deceleration else {
        return Some(Prescribed::at_rest(capacity));
    };
    let start = if ramp != 0.0 { ramp } else { omega };
    // The ramp at t + Δt/2, from its start at the application time.
    let reference = start.abs() - a / radius * (time - brake.applied + kick);
    if !(reference > 0.0 && omega * start > 0.0 && kick.is_finite()) {
        // The ramp has reached rest (or the pulley turns against it, or quasi-static):
        // hold at rest.
        return Some(Prescribed::at_rest(capacity));
    }
    // Onto the ramp, opposing the motion only.
    let (min_torque, max_torque) = if omega > 0.0 {
        (-capacity, 0.0)
    } else {
        (0.0, capacity)
    };
    Some(Prescribed {
        omega: reference.copysign(omega),
        min_torque,
        max_torque,
    })
}

/// Begin the deceleration ramps of brakes applied this step: `ramp` takes the pulley speed
/// `omega` in the first step from the brake's `applied` time (the stage runs once per
/// evaluation; the value does not change within a step, so repeated evaluations agree).
#[inline]
fn begin_ramp(brake: &BrakeSpec, time: f64, omega: f64, ramp: &mut f64) {
    if *ramp == 0.0 && brake.deceleration.is_some() && !brake.released(time) {
        *ramp = omega;
    }
}

impl PulleyModel {
    /// The prescribed motion of this pulley for the step from `time` (s) with position
    /// update `drift` and velocity update `kick` (s), at speed `omega` (rad/s), a deceleration
    /// brake's ramp having begun at `ramp` (rad/s, 0: not yet): a powered
    /// speed-controlled drive's curve, else its brake and holdback together; `None` if
    /// nothing holds it.
    #[inline]
    pub fn hold(
        &self,
        time: f64,
        drift: f64,
        kick: f64,
        omega: f64,
        ramp: f64,
    ) -> Option<(Prescribed, Holder)> {
        if let Some(h) = self.speed_hold(time, drift) {
            // A holdback helps a drive that holds its pulley at rest (before its start).
            return match &self.holdback {
                Some(hb) if h.omega == 0.0 => Some((hb.combine(Some(h)), Holder::Drive)),
                _ => Some((h, Holder::Drive)),
            };
        }
        let brake = self
            .brake
            .as_ref()
            .and_then(|b| brake_prescription(b, time, kick, self.radius, omega, ramp));
        match &self.holdback {
            None => brake.map(|b| (b, Holder::Brake)),
            Some(h) => Some((h.combine(brake), Holder::Brake)),
        }
    }

    /// How this pulley is held on a stopped conveyor: the static relaxation with friction
    /// (`Effects::hold_at_rest`, `super::hold::rest_holds`) holds it so, since it looks for
    /// the state of a conveyor standing still with its drives stopped and its brakes set
    /// (`docs/engine.md`, "Relaxing with friction"). A pulley with a drive (of any kind) or
    /// a brake stands still with whatever torque the belt asks for: a stopped drive is held
    /// by its motor brake or gearbox, which the scene does not describe, and a brake's
    /// `capacity`/`torque` is its torque in a dynamic stop (a table may be 0 before its
    /// application); the relaxation reports the torque each takes
    /// (`StabiliseReport::holding_torque`) to compare with what the holder can give. A
    /// holdback alone stops it turning backwards, up to its capacity, and lets it turn
    /// forwards. Any other pulley turns freely (`None`).
    #[inline]
    pub fn rest_hold(&self) -> Option<Prescribed> {
        if self.drive.is_some() || self.brake.is_some() {
            Some(Prescribed::at_rest(f64::INFINITY))
        } else {
            self.holdback.map(|h| h.combine(None))
        }
    }
}

/// The `brakes` stage: brakes (with the holdback of the same pulley, if any) hold their
/// pulleys, and deceleration brakes applied this step begin their ramps. Off in the static
/// relaxation.
pub fn brakes(cx: &mut StageContext<'_>) {
    super::hold::hold_pulleys(cx, |p| p.brake.is_some(), true);
    if !cx.effects.drives {
        return;
    }
    let (m, s) = (cx.model, &mut *cx.state);
    for (j, p) in m.pulleys.iter().enumerate() {
        if let Some(b) = &p.brake {
            begin_ramp(b, s.time, s.pulley_omega[j], &mut s.brake_ramp[j]);
        }
    }
}
