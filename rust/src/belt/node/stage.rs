//! The node formulation's stages: the axial pass (with the node weights) and bending.

use crate::pipeline::StageContext;
use std::cell::Cell;

/// Axial Kelvin-Voigt elements and node weights (thesis eq. 4.40, 4.56, 4.49). The pass
/// writes every node force (no reset pass) and adds the weights (no gravity pass): see
/// [`super::axial_pass`] and docs/performance.md. The relaxation runs damped elements
/// undamped (see [`crate::pipeline::Effects::damping`]).
pub fn axial(cx: &mut StageContext<'_>) {
    let (m, s, sc) = (cx.model, &mut *cx.state, &mut *cx.scratch);
    let _ = super::axial_pass(
        &m.axial_belt(cx.effects.damping, &s.node_mass),
        s.position.iter().zip(&s.velocity).map(|(&x, &v)| (x, v)),
        &mut sc.tension.as_mut_slice(),
        Cell::from_mut(sc.force.as_mut_slice()).as_slice_of_cells(),
    );
}

/// Rotational bending springs (thesis eq. 4.47, signs re-derived); interior nodes only on
/// an open belt.
pub fn bending(cx: &mut StageContext<'_>) {
    if cx.model.ends.is_some() {
        return super::bending_open(
            &cx.state.position,
            &cx.model.bending_stiffness,
            &mut cx.scratch.force,
        );
    }
    super::bending(
        &cx.state.position,
        &cx.model.bending_stiffness,
        &mut cx.scratch.force,
    );
}
