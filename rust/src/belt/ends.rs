//! The ends of an open belt (`belt.start`, `belt.end`; `crate::model::OpenEnds`): stage
//! functions acting on the belt's first and last points, whatever the formulation.

use crate::model::EndModel;
use crate::pipeline::StageContext;

/// The pulls on the ends held by a force (N, along the initial end span, away from the
/// pulley, `force` + `force_rate`·t), added to the end points' forces before contact and
/// friction.
pub fn end_pulls(cx: &mut StageContext<'_>) {
    let Some(ends) = cx.model.ends else {
        return;
    };
    let last = cx.scratch.force.len() - 1;
    for (i, end) in [(0, ends.start), (last, ends.end)] {
        cx.scratch.force[i] += end.pull(cx.state.time);
    }
}

/// The anchors: an anchored end point takes no net force (the anchor supplies the
/// reaction), so, starting at rest at its point, it stays there under every integrator
/// and relaxation. Runs after every other stage.
pub fn end_anchors(cx: &mut StageContext<'_>) {
    let Some(ends) = cx.model.ends else {
        return;
    };
    let last = cx.scratch.force.len() - 1;
    for (i, end) in [(0, ends.start), (last, ends.end)] {
        if let EndModel::Anchor(_) = end {
            cx.scratch.force[i] = nalgebra::Vector2::zeros();
        }
    }
}
