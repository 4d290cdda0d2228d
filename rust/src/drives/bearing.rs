//! Linear viscous drag in the pulley bearings: a torque −b·ω on each pulley whose
//! `bearing_damping` b (N·m·s/rad) is nonzero. A free pulley then spins down as
//! ω(t) = ω₀·exp(−b·t/I); a conveyor coasting to a stop loses speed to it besides the
//! idlers' running resistance.
//!
//! With central differences the torque is evaluated at the stored half-step speed, so a
//! free pulley decays by the factor (1 − b·Δt/I) per step: first-order accurate, stable
//! while b·Δt/I < 2, which the stable step (`model::stable_step`) keeps.

use crate::pipeline::StageContext;

/// The `bearing_drag` stage: −b·ω on every pulley with bearing damping. Off in the static
/// relaxation with the other dampers (it does not change the equilibrium).
pub fn bearing_drag(cx: &mut StageContext<'_>) {
    if !cx.effects.damping {
        return;
    }
    let (m, s, sc) = (cx.model, &*cx.state, &mut *cx.scratch);
    for (j, p) in m.pulleys.iter().enumerate() {
        if p.bearing_damping != 0.0 {
            sc.bearing_torque[j] = -p.bearing_damping * s.pulley_omega[j];
        }
    }
}
