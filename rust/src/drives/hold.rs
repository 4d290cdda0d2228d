//! Prescribed pulley motion with a limited torque: a brake holds its pulley at rest, a
//! speed-controlled drive on its starting curve (a pulley has at most one of them;
//! `docs/drives.md`). When the pulley has belt friction the hold is solved with it
//! (`crate::friction::pulley_stick_friction`) and these stages take the result.

use crate::friction::Prescribed;
use crate::model::PulleyModel;
use crate::pipeline::StageContext;

/// Speed-controlled drives: the torque that makes each pulley follow its starting curve
/// this step, within the motor's limit; it adds to the drive's load torque −b·ω.
pub fn speed_drives(cx: &mut StageContext<'_>) {
    let drift = cx.drift;
    hold_pulleys(cx, |p, time| p.speed_hold(time, drift), false);
}

/// Coulomb brakes with holding at rest: never reverse the motion.
pub fn brakes(cx: &mut StageContext<'_>) {
    hold_pulleys(cx, |p, time| p.brake_hold(time), true);
}

fn hold_pulleys(
    cx: &mut StageContext<'_>,
    hold_of: impl Fn(&PulleyModel, f64) -> Option<Prescribed>,
    brakes: bool,
) {
    if !cx.effects.drives {
        return;
    }
    let (m, s, sc, dt) = (cx.model, &*cx.state, &mut *cx.scratch, cx.dt);
    for (j, p) in m.pulleys.iter().enumerate() {
        let Some(hold) = hold_of(p, s.time) else {
            continue;
        };
        let (torque, holds) = match sc.friction[j].held_torque {
            // Solved with the belt friction.
            Some(t) => (t, sc.friction[j].holds),
            // Torque that gives the prescribed speed this step, within the capacity (a
            // brake never reverses the motion).
            None => {
                let other = sc.drive_torque[j] + sc.friction[j].torque + sc.bearing_torque[j];
                hold.limit(p.inertia * hold.alpha(s.pulley_omega[j], dt) - other)
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
