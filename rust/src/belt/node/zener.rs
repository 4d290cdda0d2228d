//! Viscoelastic (Zener, standard linear solid) belt elements: `belt.loss_factor` > 0.
//!
//! Each element's Kelvin-Voigt spring k (and damper) gets a Maxwell arm in parallel: a
//! spring k₁ = r·k in series with a dashpot of relaxation time τ. The arm's force σ (N) is
//! an internal variable per element, dσ/dt = k₁·dl/dt − σ/τ. The complex stiffness is
//!
//! k*(ω) = k·(1 + r·iωτ/(1 + iωτ)),  tan δ(ω) = r·ωτ / (1 + (1 + r)·ω²τ²),
//!
//! the relaxed (static) stiffness is k (so the static state, the design start and the
//! relaxation do not change), the instantaneous one (1 + r)·k (which the explicit step
//! bound uses), and the loss factor peaks at ω₀τ = 1/√(1 + r) with
//! tan δ_max = r / (2√(1 + r)). [`Zener::from_loss_factor`] places the peak
//! (`belt.loss_factor`) at `belt.loss_frequency`; the loss factor stays above half the
//! peak over about a factor 3.7 either side of it (the band documented in
//! docs/wrap-contact.md), and falls as 1/(ωτ) above, so the element's high-frequency
//! damping, which limits the explicit step, is not raised.
//!
//! The arm is advanced exactly over each step for an element length that changes
//! linearly over it (positions move linearly within a central-difference step):
//! σ ← a·σ + k₁·τ·(1 − a)·Δl/Δt, a = e^(−Δt/τ): unconditionally stable. Its state (σ and the
//! length it was advanced to) is part of [`crate::state::State`] and of checkpoints.
//! The element tension is [`crate::contact::wrap::ElementLaw::tension`], the one law that
//! the wrap contact uses too; [`arm_stage`] adds the arm's share to the axial pass's forces.

use crate::pipeline::StageContext;
use crate::state::State;

/// The Maxwell arm of the Zener element, as a fraction of the element's stiffness.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Zener {
    /// r = k₁/k: the arm's stiffness over the element's (relaxed) stiffness.
    pub ratio: f64,
    /// τ, the arm's relaxation time, s.
    pub time: f64,
}

impl Zener {
    /// The arm whose loss factor peaks at `loss_factor` (tan δ_max > 0) at `frequency`
    /// (Hz): r = 2η² + 2η√(1 + η²), τ = 1/(2πf·√(1 + r)).
    pub fn from_loss_factor(loss_factor: f64, frequency: f64) -> Zener {
        let eta = loss_factor;
        let ratio = 2.0 * eta * eta + 2.0 * eta * (1.0 + eta * eta).sqrt();
        let time = 1.0 / (2.0 * std::f64::consts::PI * frequency * (1.0 + ratio).sqrt());
        Zener { ratio, time }
    }

    /// Complex stiffness over the relaxed stiffness at angular frequency `omega` (rad/s):
    /// (storage, loss) = (1 + r·ω²τ²/(1 + ω²τ²), r·ωτ/(1 + ω²τ²)).
    pub fn complex_modulus(&self, omega: f64) -> (f64, f64) {
        let wt = omega * self.time;
        let d = 1.0 + wt * wt;
        (1.0 + self.ratio * wt * wt / d, self.ratio * wt / d)
    }

    /// Loss factor tan δ at angular frequency `omega`, rad/s.
    pub fn loss_factor(&self, omega: f64) -> f64 {
        let (storage, loss) = self.complex_modulus(omega);
        loss / storage
    }

    /// Instantaneous over relaxed stiffness, 1 + r (the explicit step bound's factor).
    pub fn stiffening(&self) -> f64 {
        1.0 + self.ratio
    }
}

/// The factors (a, b) of the exact step over `dt` (s) of an arm of relaxation time `tau`
/// (s): σ ← a·σ + b·k₁·Δl, a = e^(−Δt/τ), b = τ(1 − a)/Δt (1 for Δt = 0).
#[inline]
pub fn step_factors(tau: f64, dt: f64) -> (f64, f64) {
    if dt <= 0.0 {
        return (1.0, 1.0);
    }
    let x = dt / tau;
    // τ(1 − a)/Δt = (1 − a)/x, with −expm1 for accuracy at small x.
    ((-x).exp(), -(-x).exp_m1() / x)
}

/// One exact step of an arm of stiffness `k1` (N/m) and relaxation time `tau` (s) whose
/// element length changes by `dl` (m) linearly over `dt` (s): the new arm force, N.
#[inline]
pub fn advance(sigma: f64, k1: f64, tau: f64, dl: f64, dt: f64) -> f64 {
    let (a, b) = step_factors(tau, dt);
    sigma * a + b * k1 * dl
}

/// The second node of element `e` of a belt of `n` nodes (a closed belt's last element ends
/// at node 0; an open belt has fewer elements than nodes and never gets there).
#[inline]
fn second(e: usize, n: usize) -> usize {
    if e + 1 == n {
        0
    } else {
        e + 1
    }
}

/// Advance every element's arm over a step of `drift` (s), to the current positions: the
/// arm forces relax and follow the length change since the last step. In the static
/// relaxation (`physical` false: fictitious masses, no time) the arms hold no force and
/// only follow the lengths.
///
/// The length is the one the element's spring sees: its chord, plus, for an element the
/// last evaluation measured along a pulley's or a roll's path (`excess`: element, path
/// minus chord, m, emptied once used; `dense` a zeroed scratch of one entry per element,
/// left zeroed), that excess. An arm following the chord alone would see every element shorten by its wrap
/// excess as it runs onto a roll or a drum and lengthen as it leaves: a tension swing of
/// the arm stiffness times the excess at the node-passing frequency, a chordal action of
/// the arms. At the first step (`s.step` 0: the arms started at the chord lengths) the
/// excess is taken as already there.
pub fn advance_all(
    zener: &Zener,
    stiffness: &[f64],
    elements: usize,
    s: &mut State,
    drift: f64,
    physical: bool,
    (excess, dense): (&mut Vec<(usize, f64)>, &mut Vec<f64>),
) {
    let n = s.position.len();
    let (a, b) = step_factors(zener.time, drift);
    let (a, b) = if physical {
        (a, b * zener.ratio)
    } else {
        (0.0, 0.0)
    };
    if dense.len() != elements {
        *dense = vec![0.0; elements];
    }
    for &(e, x) in excess.iter() {
        if e < elements {
            dense[e] = x;
        }
    }
    let first = s.step == 0;
    let arms = s.arm_force.iter_mut().zip(s.arm_length.iter_mut());
    for (e, ((force, length), &k)) in arms.zip(stiffness).take(elements).enumerate() {
        let chord = (s.position[second(e, n)] - s.position[e]).norm();
        let l = chord + dense[e];
        let start = if first { *length + dense[e] } else { *length };
        *force = a * *force + b * k * (l - start);
        *length = l;
    }
    for &(e, _) in excess.iter() {
        if e < elements {
            dense[e] = 0.0;
        }
    }
    excess.clear();
}

/// The element lengths of the state's positions (the arms' starting lengths).
pub fn lengths(position: &[nalgebra::Vector2<f64>], elements: usize) -> Vec<f64> {
    let n = position.len();
    (0..elements)
        .map(|e| (position[second(e, n)] - position[e]).norm())
        .collect()
}

/// The arm forces' stage, after the axial pass: each element's tension becomes
/// [`crate::contact::wrap::ElementLaw::tension`] with its arm force (the Zener law, clipped as the axial pass
/// clips), and the difference from the axial pass's Kelvin-Voigt tension is added along
/// the element. Skipped when damping is off (the static relaxation: arms hold nothing).
pub fn arm_stage(cx: &mut StageContext<'_>) {
    if !cx.effects.damping {
        return;
    }
    let (m, s, sc) = (cx.model, &*cx.state, &mut *cx.scratch);
    let law = m.element_law(true, &s.arm_force);
    let voigt = m.element_law(true, &[]);
    let (x, v, n) = (&s.position, &s.velocity, s.position.len());
    for e in 0..m.elements {
        let j = second(e, n);
        let d = x[j] - x[e];
        let l = d.norm();
        let rate = d.dot(&(v[j] - v[e])) / l;
        let t = law.tension(e, l, rate);
        let extra = d * ((t - voigt.tension(e, l, rate)) / l);
        sc.force[e] += extra;
        sc.force[j] -= extra;
        sc.tension[e] = t;
    }
}
