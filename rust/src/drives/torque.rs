//! Torque-controlled drives: the torque T(t, ω) of each driven pulley (thesis eq. 4.66).

use crate::pipeline::StageContext;

/// Drive torques T(t, ω) of every pulley with a drive (off in the static relaxation). A
/// speed-controlled drive's torque is added later by [`super::hold::speed_drives`].
pub fn torque_drives(cx: &mut StageContext<'_>) {
    if !cx.effects.drives {
        return;
    }
    let (m, s, sc) = (cx.model, &*cx.state, &mut *cx.scratch);
    for (j, p) in m.pulleys.iter().enumerate() {
        if let Some(d) = &p.drive {
            sc.drive_torque[j] = d.torque_at(s.time, s.pulley_omega[j]);
        }
    }
}
