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
            total.then(r);
            if !r.converged {
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
        let stiffest_element = m
            .axial_stiffness
            .iter()
            .zip(&m.rest_length)
            .map(|(ea, l)| ea / l)
            .fold(0.0, f64::max);
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
