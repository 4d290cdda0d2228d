//! Prescribed pulley motion with a limited torque: a brake holds its pulley at rest (or
//! slows it at a set rate), a holdback stops it turning backwards, a speed-controlled drive
//! keeps it on its starting curve (`docs/drives.md`, `docs/stops-takeups.md`). A pulley's
//! holders are combined by [`PulleyModel::hold`]. When the pulley has belt friction the
//! hold is solved with it (`crate::friction::pulley_stick_friction`) and these stages take
//! the result.

use super::brake::Holder;
use crate::friction::Prescribed;
use crate::model::PulleyModel;
use crate::pipeline::{Scratch, StageContext};

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
        let (torque, holds) = holding(p, j, hold, omega, dt, sc);
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

/// The static relaxation with friction (`Effects::hold_at_rest`; run after the stages,
/// with the drives off): every pulley a stopped conveyor holds
/// ([`PulleyModel::rest_hold`]: one with a drive or a brake, or a holdback against
/// reverse rotation) is held at rest as a brake holds it, its torque in `brake_torque`.
/// The belt friction was solved with the pulley held (`crate::friction::stage`), so
/// friction on the held drums carries the belt's out-of-balance pull (bulk material on an
/// incline or decline), as on a real conveyor standing on its brakes.
pub fn rest_holds(cx: &mut StageContext<'_>) {
    let (m, s, sc, dt) = (cx.model, &*cx.state, &mut *cx.scratch, cx.dt);
    for (j, p) in m.pulleys.iter().enumerate() {
        let Some(hold) = p.rest_hold() else {
            continue;
        };
        let (torque, holds) = holding(p, j, hold, s.pulley_omega[j], dt, sc);
        sc.brake_torque[j] = torque;
        if holds {
            sc.held[j] = Some(hold.omega);
        }
    }
}

/// The torque of the holder of pulley `j` (prescription `hold`, the pulley turning at
/// `omega` rad/s, step `dt` s) and whether it holds the pulley this step: the friction
/// solve's when it solved the hold with the belt friction, else the torque that gives
/// the prescribed speed this step, within the holder's range (a brake or a holdback never
/// reverses the motion).
fn holding(
    p: &PulleyModel,
    j: usize,
    hold: Prescribed,
    omega: f64,
    dt: f64,
    sc: &Scratch,
) -> (f64, bool) {
    match sc.friction[j].held_torque {
        // Solved with the belt friction.
        Some(t) => (t, sc.friction[j].holds),
        None => {
            let other = sc.drive_torque[j]
                + sc.friction[j].torque
                + sc.bearing_torque[j]
                + sc.contact_torque[j];
            hold.limit(p.inertia * hold.alpha(omega, dt) - other)
        }
    }
}
