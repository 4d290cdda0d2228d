//! Prescribed pulley motion with a limited torque: a brake holds its pulley at rest (or
//! slows it at a set rate), a holdback stops it turning backwards, a speed-controlled drive
//! keeps it on its starting curve (`docs/drives.md`, `docs/stops-takeups.md`). A pulley's
//! holders are combined by [`PulleyModel::hold`]. When the pulley has belt friction the
//! hold is solved with it (`crate::friction::pulley_stick_friction`) and these stages take
//! the result.

use super::brake::Holder;
use crate::model::PulleyModel;
use crate::pipeline::StageContext;

/// Speed-controlled drives: the torque that makes each pulley follow its starting curve
/// this step, within the motor's limit; it adds to the drive's load torque −b·ω.
pub fn speed_drives(cx: &mut StageContext<'_>) {
    hold_pulleys(cx, |_| true, false);
}

/// Hold the pulleys that `select` picks with the holder of kind Brake (`brakes`) or Drive
/// (not `brakes`), if that holder holds them this step.
pub(super) fn hold_pulleys(
    cx: &mut StageContext<'_>,
    select: impl Fn(&PulleyModel) -> bool,
    brakes: bool,
) {
    if !cx.effects.drives {
        return;
    }
    let (m, s, sc, dt, drift) = (cx.model, &*cx.state, &mut *cx.scratch, cx.dt, cx.drift);
    let kind = if brakes { Holder::Brake } else { Holder::Drive };
    for (j, p) in m.pulleys.iter().enumerate() {
        if !select(p) {
            continue;
        }
        let omega = s.pulley_omega[j];
        let Some((hold, holder)) = p.hold(s.time, drift, dt, omega, s.brake_ramp[j]) else {
            continue;
        };
        if holder != kind {
            continue;
        }
        let (torque, holds) = match sc.friction[j].held_torque {
            // Solved with the belt friction.
            Some(t) => (t, sc.friction[j].holds),
            // Torque that gives the prescribed speed this step, within the holder's range
            // (a brake or a holdback never reverses the motion).
            None => {
                let other = sc.drive_torque[j]
                    + sc.friction[j].torque
                    + sc.bearing_torque[j]
                    + sc.contact_torque[j];
                hold.limit(p.inertia * hold.alpha(omega, dt) - other)
            }
        };
        if brakes {
            sc.brake_torque[j] = torque;
        } else {
            sc.drive_torque[j] += torque;
        }
        if holds {
            sc.held[j] = Some(hold.omega);
        }
    }
}
