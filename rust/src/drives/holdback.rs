//! Holdbacks (backstops): a one-way clutch on a pulley that lets it turn forwards freely
//! and stops it turning backwards, up to its capacity (`docs/stops-takeups.md`).
//!
//! It is a unilateral constraint on the pulley speed, ω·s ≥ 0 with s = ±1 the forward
//! sense, and is solved as a prescribed motion ([`Prescribed`]) with the target ω = 0 and a
//! one-sided torque range (0 to s·capacity): each step the holdback supplies the torque
//! that would bring the pulley to rest by the end of the step if that torque pushes
//! forwards (the pulley would otherwise end the step turning backwards), and nothing
//! otherwise. So it never drives the pulley, never lets it reverse by more than rounding,
//! and holds it at rest exactly (the integrator sets ω = 0) without chatter. With a brake
//! on the same pulley the two ranges add when the pulley is to stop.

use crate::friction::Prescribed;
use crate::pipeline::StageContext;
use crate::scene::HoldbackSpec;

/// Compiled holdback.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Holdback {
    /// Forward sense, +1 (counter-clockwise) or −1 (clockwise).
    pub forward: f64,
    /// Largest torque against reverse rotation, N·m (may be +∞).
    pub capacity: f64,
}

impl Holdback {
    /// From the scene's table (validated: `forward` is given).
    pub fn compile(spec: &HoldbackSpec) -> Holdback {
        Holdback {
            forward: spec.forward.map_or(1.0, |w| w.sign()),
            capacity: spec.capacity,
        }
    }

    /// The holdback's torque range when the pulley is to come to rest: [0, capacity]
    /// forwards counter-clockwise, [−capacity, 0] clockwise.
    #[inline]
    fn range(&self) -> (f64, f64) {
        if self.forward > 0.0 {
            (0.0, self.capacity)
        } else {
            (-self.capacity, 0.0)
        }
    }

    /// The prescribed motion of a pulley with this holdback and, possibly, a brake's
    /// prescription `brake` this step. Alone: rest, with the one-sided range. With a brake
    /// that stops the pulley (target 0) the ranges add; with a brake that decelerates it
    /// forwards (target ≠ 0, same sense as forward) the brake alone acts; a brake target
    /// backwards is replaced by rest (the holdback allows no reverse speed).
    #[inline]
    pub fn combine(&self, brake: Option<Prescribed>) -> Prescribed {
        let (lo, hi) = self.range();
        match brake {
            None => Prescribed {
                omega: 0.0,
                min_torque: lo,
                max_torque: hi,
            },
            Some(b) if b.omega * self.forward > 0.0 => b,
            Some(b) => {
                let capacity = b.max_torque.max(-b.min_torque);
                Prescribed {
                    omega: 0.0,
                    min_torque: lo - capacity,
                    max_torque: hi + capacity,
                }
            }
        }
    }
}

/// The `holdbacks` stage: the holdbacks of pulleys without a brake (a brake's pulley is
/// held by the `brakes` stage, holdback included). Off in the static relaxation with the
/// drives and brakes.
pub fn holdbacks(cx: &mut StageContext<'_>) {
    super::hold::hold_pulleys(cx, |p| p.brake.is_none() && p.holdback.is_some(), true);
}
