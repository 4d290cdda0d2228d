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

/// Belt friction on the pulleys: stick-force friction (thesis eq. 4.76–4.94, figure 4.9),
/// solved together with a brake's or speed-controlled drive's hold when the pulley has one,
/// or creep friction (Kubas eq. 12–19, [`super::creep::pulley_creep_friction`]).
pub fn pulley_friction(cx: &mut StageContext<'_>) {
    if !cx.effects.friction {
        return;
    }
    let (friction_dt, drift, drives) = (cx.friction_dt(), cx.drift, cx.effects.drives);
    let at_rest = cx.effects.hold_at_rest;
    let creep_step = cx.creep_step();
    let kick = cx.dt;
    let (m, s, sc) = (cx.model, &mut *cx.state, &mut *cx.scratch);
    for (j, p) in m.pulleys.iter().enumerate() {
        // (the prescription, whether it holds the pulley rigidly for the creep law)
        let (prescribed, rigid) = if drives {
            let hold = p.hold(s.time, drift, kick, s.pulley_omega[j], s.brake_ramp[j]);
            (hold.map(|h| h.0), creep_held(p, hold.map(|h| h.1), s.time))
        } else if at_rest {
            // A stopped conveyor's holders (`crate::drives::hold::rest_holds`): rigid
            // both ways for a drive or brake, one way (not rigid) for a holdback alone.
            let hold = p.rest_hold();
            (
                hold,
                hold.is_some_and(|h| h.min_torque < 0.0 && h.max_torque > 0.0),
            )
        } else {
            (None, false)
        };
        let (static_coefficient, kinetic_coefficient) = match p.friction {
            FrictionModel::StickForce {
                static_coefficient,
                kinetic_coefficient,
            } => (static_coefficient, kinetic_coefficient),
            FrictionModel::Creep(law) => {
                if law.static_coefficient > 0.0 {
                    creep_on_pulley(&law, j, rigid, creep_step, m, s, sc, &cx.inertia.mass);
                }
                s.sliding[j].clear();
                continue;
            }
            FrictionModel::None => {
                s.sliding[j].clear();
                continue;
            }
        };
        if static_coefficient == 0.0 || sc.contacts[j].is_empty() {
            s.sliding[j].clear();
            continue;
        }
        let fp = FrictionPulley {
            radius: m.friction_radius(j),
            inertia: p.inertia,
            omega: s.pulley_omega[j],
            center_velocity: s.pulley_center_velocity(m, j),
            applied_torque: sc.drive_torque[j] + sc.bearing_torque[j] + sc.contact_torque[j],
            mu_static: static_coefficient,
            mu_kinetic: kinetic_coefficient,
            prescribed,
        };
        // The memory of which points slid (Coulomb's µk for them), in and out.
        std::mem::swap(&mut sc.stick[j].sliding, &mut s.sliding[j]);
        let out = super::pulley_stick_friction(
            &sc.contacts[j],
            &fp,
            &s.velocity,
            &cx.inertia.mass,
            friction_dt,
            &mut sc.force,
            &mut sc.stick[j],
        );
        std::mem::swap(&mut sc.stick[j].sliding, &mut s.sliding[j]);
        if sc.contact_detail {
            // Each contact's force on the pulley along its tangent, as the solve left it.
            sc.contacts[j]
                .friction
                .extend_from_slice(&sc.stick[j].force);
        }
        sc.pulley_force[j] += out.force;
        sc.friction[j] = out;
    }
}

/// Whether a pulley with creep friction is held rigidly this step: by a speed-controlled
/// drive, or by an applied brake. A holdback alone is one-way (the pulley turns freely
/// forwards), so it does not make the pulley rigid for the creep law; the holdback's own
/// stage still stops reverse rotation.
fn creep_held(
    p: &crate::model::PulleyModel,
    holder: Option<crate::drives::brake::Holder>,
    time: f64,
) -> bool {
    match holder {
        None => false,
        Some(crate::drives::brake::Holder::Drive) => true,
        Some(crate::drives::brake::Holder::Brake) => {
            p.brake.as_ref().is_some_and(|b| !b.released(time))
        }
    }
}

/// Creep friction on pulley `j` (`held`: a brake or speed-controlled drive prescribes its
/// speed this step; `step`: the step the law is solved for, [`StageContext::creep_step`];
/// `mass`: the integrator's point masses). First forgets the creep of the points in the
/// pulley's search window that no longer touch it (a contact that separates starts
/// afresh), then applies the law.
#[allow(clippy::too_many_arguments)]
fn creep_on_pulley(
    law: &super::creep::CreepFriction,
    j: usize,
    held: bool,
    step: Option<f64>,
    m: &crate::model::Model,
    s: &mut crate::state::State,
    sc: &mut crate::pipeline::Scratch,
    mass: &[f64],
) {
    let stride = m.pulleys.len();
    let n = s.position.len();
    let window = s.pulley_window[j];
    let contacts = &sc.contacts[j];
    // Contacts are listed in window order: walk both together.
    let mut next = 0;
    for w in 0..window.len {
        let i = (window.first + w) % n;
        if next < contacts.len() && contacts.node[next] == i {
            next += 1;
        } else {
            s.creep[i * stride + j] = 0.0;
        }
    }
    if contacts.is_empty() {
        return;
    }
    let p = &m.pulleys[j];
    let pulley = super::creep::CreepPulley {
        radius: m.friction_radius(j),
        inertia: if held { f64::INFINITY } else { p.inertia },
        omega: s.pulley_omega[j],
        center_velocity: s.pulley_center_velocity(m, j),
    };
    // The contacts' own list, taken out while the kernel reads the contacts.
    let mut per_contact = sc
        .contact_detail
        .then(|| std::mem::take(&mut sc.contacts[j].friction));
    let contacts = &sc.contacts[j];
    let out = super::creep::pulley_creep_friction(
        law,
        contacts,
        &pulley,
        &s.velocity,
        mass,
        step,
        &s.creep,
        super::creep::MemoryColumn { stride, column: j },
        &mut sc.force,
        &mut sc.creep_rate,
        per_contact.as_mut(),
    );
    if let Some(list) = per_contact {
        sc.contacts[j].friction = list;
    }
    sc.pulley_force[j] += out.force;
    sc.friction[j] = out;
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
