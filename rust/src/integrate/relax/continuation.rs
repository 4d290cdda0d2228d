//! Continuation in contact stiffness: a relaxation with contact much stiffer than the
//! belt starts soft and stiffens stage by stage, each from the previous equilibrium. The
//! stages scale the contact in the force evaluation and get their own step and masses;
//! the model is not touched.

use super::{StabiliseOptions, StabiliseReport};
use crate::error::BeltResult;
use crate::pipeline::Scratch;
use crate::simulation::Simulation;

/// Contact stiffness, as a multiple of the stiffest belt element (EA/l), at which the
/// static relaxation starts its continuation in contact stiffness.
pub const CONTINUATION_START: f64 = 100.0;
/// Factor between successive contact stiffnesses of the continuation.
pub const CONTINUATION_FACTOR: f64 = 10.0;
/// Most stages of the continuation (it starts no softer than 10^-8 of the scene's contact).
pub const CONTINUATION_STAGES: i32 = 8;

impl Simulation {
    /// Relax at each contact-stiffness scale of `scales` in turn, each stage from the
    /// previous one's equilibrium, stopping at the first that does not converge.
    pub(super) fn relax_softened(
        &mut self,
        scales: &[f64],
        options: &StabiliseOptions,
    ) -> BeltResult<StabiliseReport> {
        let mut total = StabiliseReport {
            steps: 0,
            residual: f64::INFINITY,
            converged: false,
            resets: 0,
            interrupted: false,
            holding_torque: Vec::new(),
        };
        for &scale in scales {
            self.scratch = Scratch::new(&self.model);
            let r = self.relax(
                &StabiliseOptions {
                    max_steps: options.max_steps - total.steps,
                    ..*options
                },
                scale,
            )?;
            let converged = r.converged;
            total.then(r);
            if !converged {
                break;
            }
        }
        Ok(total)
    }

    /// Contact-stiffness scales (< 1) of the continuation stages, softest first; empty if
    /// the contact is not much stiffer than the belt.
    pub(super) fn contact_continuation(&self) -> Vec<f64> {
        let m = &self.model;
        let stiffest_contact = m
            .pulleys
            .iter()
            .map(|p| p.contact_bound(1.0).0)
            .chain(m.idlers.iter().map(|d| d.contact_stiffness))
            .fold(0.0, f64::max);
        // `axial_stiffness` is EA/l⁰ already (N/m, like the contact stiffness).
        let stiffest_element = m.axial_stiffness.iter().copied().fold(0.0, f64::max);
        // At most CONTINUATION_STAGES stages: an absurdly soft belt (EA → 0) must not ask
        // for an endless ladder (found by the fuzzer: EA = 5e-324 allocated without end).
        let floor = CONTINUATION_FACTOR.powi(-CONTINUATION_STAGES);
        let start = (CONTINUATION_START * stiffest_element / stiffest_contact).max(floor);
        let mut ladder = Vec::new();
        let mut scale = start;
        while scale < 1.0 / CONTINUATION_FACTOR.sqrt() {
            ladder.push(scale);
            scale *= CONTINUATION_FACTOR;
        }
        ladder
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The ladder starts where the contact is CONTINUATION_START × the stiffest element,
    /// EA/l⁰ (N/m, like the contact): case H at 400 elements (l⁰ ≈ 0.58 m, so dividing
    /// by l⁰ once more, N/m², would start it 1.7× too stiff) and 1e11 N/m contact.
    #[test]
    fn the_ladder_starts_at_the_element_stiffness_in_newtons_per_metre() {
        let mut scene = crate::presets::case_h(400);
        for p in &mut scene.pulleys {
            p.contact_stiffness = 1e11;
        }
        let sim = Simulation::new(&scene).unwrap();
        let l0 = sim.model.rest_length[0];
        assert!(
            (l0 - 1.0).abs() > 0.3,
            "l⁰ = {l0} m would not tell N/m from N/m²"
        );
        let element = scene.belt.axial_stiffness / l0;
        let ladder = sim.contact_continuation();
        let start = CONTINUATION_START * element / 1e11;
        assert!(
            (ladder[0] - start).abs() <= 1e-12 * start,
            "ladder {ladder:?}, expected to start at {start:e}"
        );
        // Then ×10 per stage while below 1/√10: 0.0132, 0.132.
        assert_eq!(ladder.len(), 2, "{ladder:?}");
        assert!((ladder[1] - CONTINUATION_FACTOR * start).abs() <= 1e-12 * ladder[1]);
    }
}
