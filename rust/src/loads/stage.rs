//! The `loads` stage: bulk material zones move with the belt and change node masses.

use crate::pipeline::StageContext;

/// Track each load's zone and update the masses of the nodes at its edges (runs first, so
/// every later stage sees them). In dynamics the integrator's masses follow the node
/// masses; the relaxation's fictitious masses are left alone.
pub fn update_loads(cx: &mut StageContext<'_>) {
    let (m, s, inertia) = (cx.model, &mut *cx.state, &mut *cx.inertia);
    let physical = inertia.physical;
    super::update(
        &m.loads,
        &m.mass,
        m.load_belt(),
        &s.position,
        &mut s.velocity,
        &mut s.load_edges,
        &mut super::MassArrays {
            node_mass: &mut s.node_mass,
            inertia: physical.then_some((&mut inertia.mass, &mut inertia.inv_mass)),
            bodies: (physical && m.is_rigid()).then_some(super::Bodies {
                belt_inertia: &m.body_inertia,
                inertia: &mut inertia.body_inertia,
                spin: &mut s.body_spin,
            }),
        },
    );
}
