//! Friction stages: stick-force friction on pulleys and idlers, and the idlers' running
//! resistance. Each is on only when the evaluation's effects include friction.

use super::{FrictionIdler, FrictionPulley};
use crate::pipeline::StageContext;
use crate::scene::FrictionModel;

/// DIN 22101 running resistance at the idlers: a friction-like force up to
/// f·(N + m_R·g), quasi-static in the relaxation (where the friction step is infinite).
pub fn running_resistance(cx: &mut StageContext<'_>) {
    if !cx.effects.friction {
        return;
    }
    let friction_dt = cx.friction_dt();
    let (m, s, sc) = (cx.model, &*cx.state, &mut *cx.scratch);
    for (k, d) in m.idlers.iter().enumerate() {
        let c = sc.idler_contacts[k];
        if !c.active || d.resistance == 0.0 {
            continue;
        }
        let limit = d.resistance * (c.normal_force + d.rotating_mass * m.gravity);
        let (f, _) = super::running_resistance(
            &c,
            limit,
            &s.velocity,
            &cx.inertia.mass,
            friction_dt,
            &mut sc.force,
        );
        sc.idler_resistance[k] = f;
    }
}

/// Stick-force friction between belt and pulleys (thesis eq. 4.76–4.94, figure 4.9),
/// solved together with a brake's or speed-controlled drive's hold when the pulley has one.
pub fn pulley_friction(cx: &mut StageContext<'_>) {
    if !cx.effects.friction {
        return;
    }
    let (friction_dt, drift, drives) = (cx.friction_dt(), cx.drift, cx.effects.drives);
    let kick = cx.dt;
    let (m, s, sc) = (cx.model, &*cx.state, &mut *cx.scratch);
    for (j, p) in m.pulleys.iter().enumerate() {
        let FrictionModel::StickForce {
            static_coefficient,
            kinetic_coefficient,
        } = p.friction
        else {
            continue;
        };
        if static_coefficient == 0.0 || sc.contacts[j].is_empty() {
            continue;
        }
        let fp = FrictionPulley {
            radius: p.radius,
            inertia: p.inertia,
            omega: s.pulley_omega[j],
            center_velocity: s.pulley_center_velocity(m, j),
            applied_torque: sc.drive_torque[j] + sc.bearing_torque[j],
            mu_static: static_coefficient,
            mu_kinetic: kinetic_coefficient,
            prescribed: if drives {
                p.hold(s.time, drift, kick, s.pulley_omega[j], s.brake_ramp[j])
                    .map(|h| h.0)
            } else {
                None
            },
        };
        let out = super::pulley_stick_friction(
            &sc.contacts[j],
            &fp,
            &s.velocity,
            &cx.inertia.mass,
            friction_dt,
            &mut sc.force,
            &mut sc.stick[j],
        );
        sc.pulley_force[j] += out.force;
        sc.friction[j] = out;
    }
}

/// Stick-force friction between belt and idlers (thesis eq. 4.103–4.117, re-derived).
pub fn idler_friction(cx: &mut StageContext<'_>) {
    if !cx.effects.friction {
        return;
    }
    let friction_dt = cx.friction_dt();
    let (m, s, sc) = (cx.model, &*cx.state, &mut *cx.scratch);
    for (k, d) in m.idlers.iter().enumerate() {
        let FrictionModel::StickForce {
            static_coefficient,
            kinetic_coefficient,
        } = d.friction
        else {
            continue;
        };
        let c = sc.idler_contacts[k];
        if !c.active || static_coefficient == 0.0 {
            continue;
        }
        let fi = FrictionIdler {
            radius: d.radius,
            inertia: d.inertia,
            omega: s.idler_omega[k],
            mu_static: static_coefficient,
            mu_kinetic: kinetic_coefficient,
        };
        let (f, _) = super::idler_stick_friction(
            &c,
            &fi,
            &s.velocity,
            &cx.inertia.mass,
            friction_dt,
            &mut sc.force,
        );
        sc.idler_torque[k] = d.radius * f;
    }
}
