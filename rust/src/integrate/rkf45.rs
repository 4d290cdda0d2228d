//! Adaptive Runge–Kutta–Fehlberg 4(5) over a flat state vector (Fehlberg 1969; the
//! integrator of Kubas 2014, section 2).
//!
//! Each step evaluates the derivative six times and forms a 4th- and a 5th-order solution
//! from the same stages. Their difference estimates the local error of the 4th-order
//! solution, which is the one propagated (Fehlberg's choice: his coefficients minimise the
//! 4th-order error terms), so the estimate is asymptotically the true local error of what
//! is kept. `local_extrapolation` propagates the 5th-order solution instead (more accurate,
//! the estimate then bounds the error from above).
//!
//! Error norm (Hairer, Nørsett & Wanner, Solving ODEs I, II.4): the root mean square over
//! the components of eᵢ/(atol + rtol·max(|yᵢ|, |ŷᵢ|)). A step is accepted when the norm is
//! ≤ 1. The next step is h·min(max_growth, max(max_shrink, safety·err^(−1/5))), and it does
//! not grow right after a rejection; a step shortened to land on `t_end` keeps the
//! unshortened one (raised to that product at most, never grown by it). A step that would fall below `min_step` is an error
//! naming the time and the step, never a silent loss of accuracy.
//!
//! The first stage k₀ = f(t, y) depends only on the step's start, so it is evaluated once
//! per step, not once per attempt: a rejected attempt costs five evaluations, an accepted
//! step six. A caller that has f(t, y) already (it evaluated the state for its own
//! reasons) can hand it over with [`Rkf45::known_first_stage`].
//!
//! Dormant components ([`Rkf45::set_dormant_from`]): components of a sparse memory (e.g.
//! the creep displacement of every belt point at every pulley, of which only the points in
//! contact are live) that are zero at both ends of a step with zero error are left out of
//! the mean, so that the memory of the points not in contact does not dilute the norm.

// Index loops over components read like the tableau they implement.
#![allow(clippy::needless_range_loop)]

use crate::error::{BeltError, BeltResult};

/// Settings of the adaptive integrator. Build with
/// `Rkf45Params { relative_tolerance: 1e-8, ..Default::default() }`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rkf45Params {
    /// rtol: relative tolerance on each component's local error, > 0. Default 10⁻⁶.
    pub relative_tolerance: f64,
    /// atol: absolute tolerance on each component's local error (state units), ≥ 0.
    /// Default 10⁻⁹.
    pub absolute_tolerance: f64,
    /// Safety factor on the optimal step, in (0, 1). Default 0.9.
    pub safety: f64,
    /// Largest growth of the step from one step to the next, > 1. Default 5.
    pub max_growth: f64,
    /// Smallest factor a rejected step is cut by, in (0, 1). Default 0.2.
    pub max_shrink: f64,
    /// First step, s; 0 chooses it from the derivative (Hairer's starting-step rule).
    /// Default 0.
    pub initial_step: f64,
    /// Largest step, s, > 0 (may be +∞). Default +∞.
    pub max_step: f64,
    /// Smallest step, s, ≥ 0; a smaller step is an error. 0: 64 ulp of the time. Default 0.
    pub min_step: f64,
    /// Propagate the 5th-order solution (local extrapolation). Default false (Fehlberg).
    pub local_extrapolation: bool,
}

impl Default for Rkf45Params {
    fn default() -> Self {
        Rkf45Params {
            relative_tolerance: 1e-6,
            absolute_tolerance: 1e-9,
            safety: 0.9,
            max_growth: 5.0,
            max_shrink: 0.2,
            initial_step: 0.0,
            max_step: f64::INFINITY,
            min_step: 0.0,
            local_extrapolation: false,
        }
    }
}

impl Rkf45Params {
    /// Check the ranges; errors name the field (`rkf45.<field>`).
    pub fn validate(&self) -> BeltResult<()> {
        let bad =
            |f: &str, v: f64, rule: &str| Err(BeltError::invalid(format!("rkf45.{f}"), v, rule));
        if !(self.relative_tolerance.is_finite() && self.relative_tolerance > 0.0) {
            return bad(
                "relative_tolerance",
                self.relative_tolerance,
                "must be finite and > 0",
            );
        }
        if !(self.absolute_tolerance.is_finite() && self.absolute_tolerance >= 0.0) {
            return bad(
                "absolute_tolerance",
                self.absolute_tolerance,
                "must be finite and ≥ 0",
            );
        }
        if !(self.safety > 0.0 && self.safety < 1.0) {
            return bad("safety", self.safety, "must lie in (0, 1)");
        }
        if !(self.max_growth.is_finite() && self.max_growth > 1.0) {
            return bad("max_growth", self.max_growth, "must be finite and > 1");
        }
        if !(self.max_shrink > 0.0 && self.max_shrink < 1.0) {
            return bad("max_shrink", self.max_shrink, "must lie in (0, 1)");
        }
        if !(self.initial_step.is_finite() && self.initial_step >= 0.0) {
            return bad(
                "initial_step",
                self.initial_step,
                "must be finite and ≥ 0 (0: automatic)",
            );
        }
        if self.max_step.is_nan() || self.max_step <= 0.0 {
            return bad("max_step", self.max_step, "must be > 0 (s)");
        }
        if !(self.min_step.is_finite() && self.min_step >= 0.0 && self.min_step <= self.max_step) {
            return bad(
                "min_step",
                self.min_step,
                "must be finite, ≥ 0 and ≤ max_step",
            );
        }
        Ok(())
    }
}

/// Why a step could not be taken.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StepError {
    /// The error control asked for a step below the minimum.
    #[error(
        "RKF45 step {step:e} s at t = {time} s is below the minimum {min_step:e} s \
         (error norm {error_norm:.3e} at rtol {relative_tolerance:e}, atol {absolute_tolerance:e}): \
         the problem is too stiff or discontinuous for these tolerances"
    )]
    StepTooSmall {
        /// Time at the start of the step, s.
        time: f64,
        /// The step that was needed, s.
        step: f64,
        /// The smallest step allowed, s.
        min_step: f64,
        /// Error norm of the last attempt (1 = at tolerance).
        error_norm: f64,
        /// rtol in force.
        relative_tolerance: f64,
        /// atol in force.
        absolute_tolerance: f64,
    },
    /// A derivative or the state became non-finite.
    #[error("RKF45: state component {index} became non-finite at t = {time} s (step {step:e} s)")]
    NonFinite {
        /// Time at the start of the step, s.
        time: f64,
        /// The step tried, s.
        step: f64,
        /// Index of the first non-finite component.
        index: usize,
    },
}

impl From<StepError> for BeltError {
    fn from(e: StepError) -> Self {
        match e {
            StepError::NonFinite { time, index, .. } => BeltError::Diverged {
                time,
                step: 0,
                quantity: "RKF45 state".into(),
                location: format!("component {index}"),
            },
            other => BeltError::Usage(other.to_string()),
        }
    }
}

/// Counters of a run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Rkf45Stats {
    /// Steps accepted.
    pub accepted: u64,
    /// Steps rejected (each retried with a smaller step).
    pub rejected: u64,
    /// Derivative evaluations.
    pub evaluations: u64,
    /// Smallest accepted step, s (+∞ before the first).
    pub smallest_step: f64,
    /// Largest accepted step, s.
    pub largest_step: f64,
}

// Fehlberg's tableau.
const C: [f64; 6] = [0.0, 0.25, 0.375, 12.0 / 13.0, 1.0, 0.5];
const A: [[f64; 5]; 6] = [
    [0.0; 5],
    [0.25, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 32.0, 9.0 / 32.0, 0.0, 0.0, 0.0],
    [1932.0 / 2197.0, -7200.0 / 2197.0, 7296.0 / 2197.0, 0.0, 0.0],
    [439.0 / 216.0, -8.0, 3680.0 / 513.0, -845.0 / 4104.0, 0.0],
    [
        -8.0 / 27.0,
        2.0,
        -3544.0 / 2565.0,
        1859.0 / 4104.0,
        -11.0 / 40.0,
    ],
];
const B4: [f64; 6] = [
    25.0 / 216.0,
    0.0,
    1408.0 / 2565.0,
    2197.0 / 4104.0,
    -0.2,
    0.0,
];
const B5: [f64; 6] = [
    16.0 / 135.0,
    0.0,
    6656.0 / 12825.0,
    28561.0 / 56430.0,
    -9.0 / 50.0,
    2.0 / 55.0,
];

/// `out` = `y` + h·Σⱼ aⱼ·kⱼ per component, the sum taken in j order from 0: one stage's
/// state, or a solution of the step. The same arithmetic as the loop over components with
/// the sum inside, written with the stage count a constant and the slices cut to one
/// length, so that it compiles without bounds checks and vectorised across components
/// (each component's operations and their order unchanged: the same bits).
#[inline(always)]
fn combine<const S: usize>(out: &mut [f64], y: &[f64], h: f64, a: [f64; S], k: [&[f64]; S]) {
    let n = out.len();
    let y = &y[..n];
    let k = k.map(|kj| &kj[..n]);
    for i in 0..n {
        let mut acc = 0.0;
        for j in 0..S {
            acc += a[j] * k[j][i];
        }
        out[i] = y[i] + h * acc;
    }
}

/// The adaptive integrator with its work arrays, step size and counters.
#[derive(Debug, Clone)]
pub struct Rkf45 {
    /// Settings.
    pub params: Rkf45Params,
    /// Counters since construction.
    pub stats: Rkf45Stats,
    /// Error norm of the last attempted step (≤ 1 when accepted).
    pub last_error_norm: f64,
    h: f64,
    scales: Vec<f64>,
    k: [Vec<f64>; 6],
    stage: Vec<f64>,
    low: Vec<f64>,
    high: Vec<f64>,
    /// `k[0]` holds f(t, y) at the coming step's start.
    first_known: bool,
    /// Components from here on are dormant (module docs).
    dormant_from: usize,
}

impl Rkf45 {
    /// An integrator for states of `len` components.
    pub fn new(params: Rkf45Params, len: usize) -> BeltResult<Self> {
        params.validate()?;
        let v = || vec![0.0; len];
        Ok(Rkf45 {
            params,
            stats: Rkf45Stats {
                smallest_step: f64::INFINITY,
                ..Default::default()
            },
            last_error_norm: 0.0,
            h: params.initial_step,
            scales: vec![1.0; len],
            k: [v(), v(), v(), v(), v(), v()],
            stage: v(),
            low: v(),
            high: v(),
            first_known: false,
            dormant_from: len,
        })
    }

    /// The first-stage buffer, for a caller that has f(t, y) at the start of the coming
    /// step: it must fill the slice with exactly that derivative (the state and time that
    /// the next [`Rkf45::step`] starts from), and the step then does not evaluate it again.
    pub fn known_first_stage(&mut self) -> &mut [f64] {
        self.first_known = true;
        &mut self.k[0]
    }

    /// Components `start..` are dormant: left out of the error norm's mean while they are
    /// zero at both ends of a step with zero error (module docs). Default: none.
    pub fn set_dormant_from(&mut self, start: usize) {
        self.dormant_from = start.min(self.scales.len());
    }

    /// The step the next call will try first, s (0 before the first step when automatic).
    pub fn next_step(&self) -> f64 {
        self.h
    }

    /// Per-component multipliers of the absolute tolerance (atolᵢ = atol·scaleᵢ), for states
    /// that mix units (positions, angles, speeds); all 1 by default. Each must be finite and
    /// > 0, one per component.
    pub fn set_absolute_scales(&mut self, scales: &[f64]) -> BeltResult<()> {
        if scales.len() != self.scales.len() {
            return Err(BeltError::Usage(format!(
                "RKF45 absolute-tolerance scales: {} given for a state of {} components",
                scales.len(),
                self.scales.len()
            )));
        }
        if let Some((i, v)) = scales
            .iter()
            .enumerate()
            .find(|(_, v)| !(v.is_finite() && **v > 0.0))
        {
            return Err(BeltError::invalid(
                format!("rkf45.absolute_scales[{i}]"),
                v,
                "must be finite and > 0",
            ));
        }
        self.scales.copy_from_slice(scales);
        Ok(())
    }

    /// Error norm of a difference `e` for states `y` and `y_new` (module docs).
    fn norm(&self, e: &[f64], y: &[f64], y_new: &[f64]) -> f64 {
        let (rt, at) = (
            self.params.relative_tolerance,
            self.params.absolute_tolerance,
        );
        let mut s = 0.0;
        let mut n = 0usize;
        let len = e.len();
        let (y, y_new, scales) = (&y[..len], &y_new[..len], &self.scales[..len]);
        for i in 0..len {
            let (a, b) = (y[i], y_new[i]);
            if i >= self.dormant_from && e[i] == 0.0 && a == 0.0 && b == 0.0 {
                continue;
            }
            let q = e[i] / (at * scales[i] + rt * a.abs().max(b.abs()));
            s += q * q;
            n += 1;
        }
        (s / n.max(1) as f64).sqrt()
    }

    /// Hairer's starting step (Solving ODEs I, II.4): from the sizes of y, f(y) and an
    /// estimate of the second derivative.
    fn starting_step<F>(&mut self, t: f64, y: &[f64], f: &mut F) -> f64
    where
        F: FnMut(f64, &[f64], &mut [f64]),
    {
        let n = y.len();
        f(t, y, &mut self.k[0]);
        self.stats.evaluations += 1;
        let zeros = vec![0.0; n];
        let d0 = self.norm(y, y, y);
        let d1 = self.norm(&self.k[0], y, y);
        let h0 = if d0 < 1e-5 || d1 < 1e-5 {
            1e-6
        } else {
            0.01 * d0 / d1
        };
        let h0 = h0.min(self.params.max_step);
        for i in 0..n {
            self.stage[i] = y[i] + h0 * self.k[0][i];
        }
        f(t + h0, &self.stage, &mut self.k[1]);
        self.stats.evaluations += 1;
        for i in 0..n {
            self.low[i] = (self.k[1][i] - self.k[0][i]) / h0;
        }
        let d2 = self.norm(&self.low, y, &zeros);
        let h1 = if d1.max(d2) <= 1e-15 {
            (h0 * 1e-3).max(1e-6)
        } else {
            (0.01 / d1.max(d2)).powf(0.2)
        };
        (100.0 * h0).min(h1).min(self.params.max_step)
    }

    /// Take one accepted step from (`t`, `y`), no further than `t_end`; retries with smaller
    /// steps on rejection. Updates `t` and `y` and returns the step taken, s.
    pub fn step<F>(
        &mut self,
        t: &mut f64,
        y: &mut [f64],
        t_end: f64,
        f: &mut F,
    ) -> Result<f64, StepError>
    where
        F: FnMut(f64, &[f64], &mut [f64]),
    {
        let n = y.len();
        if self.h <= 0.0 {
            // Evaluates k₀ = f(t, y) on the way.
            self.h = self.starting_step(*t, y, f);
            self.first_known = true;
        }
        if !self.first_known {
            f(*t, y, &mut self.k[0]);
            self.stats.evaluations += 1;
            self.first_known = true;
        }
        let min_step = if self.params.min_step > 0.0 {
            self.params.min_step
        } else {
            64.0 * f64::EPSILON * t.abs().max(t_end.abs()).max(f64::MIN_POSITIVE)
        };
        let mut rejected_here = false;
        loop {
            let remaining = t_end - *t;
            let mut h = self.h.min(self.params.max_step);
            let last = h >= remaining;
            if last {
                h = remaining;
            }
            if h < min_step && !last {
                return Err(StepError::StepTooSmall {
                    time: *t,
                    step: h,
                    min_step,
                    error_norm: self.last_error_norm,
                    relative_tolerance: self.params.relative_tolerance,
                    absolute_tolerance: self.params.absolute_tolerance,
                });
            }
            self.stages(*t, y, h, f, 1);
            self.stats.evaluations += 5;
            let k: [&[f64]; 6] = std::array::from_fn(|s| &self.k[s][..n]);
            combine(&mut self.low, y, h, B4, k);
            combine(&mut self.high, y, h, B5, k);
            // Whether all are finite in one pass without an early exit (vectorised), then
            // the first that is not, only when one is not.
            let finite = |i: usize| self.low[i].is_finite() && self.high[i].is_finite();
            let all_finite = (self.low.iter().zip(&self.high))
                .fold(true, |ok, (lo, hi)| ok & lo.is_finite() & hi.is_finite());
            let bad = if all_finite {
                None
            } else {
                (0..n).find(|&i| !finite(i))
            };
            if let Some(index) = bad {
                // A non-finite trial may be an overshoot of an unstable step: shrink first,
                // fail only when the step cannot shrink further.
                if h * self.params.max_shrink < min_step {
                    return Err(StepError::NonFinite {
                        time: *t,
                        step: h,
                        index,
                    });
                }
                self.h = h * self.params.max_shrink;
                self.stats.rejected += 1;
                rejected_here = true;
                self.last_error_norm = f64::INFINITY;
                continue;
            }
            // The error estimate is the same for both propagation choices.
            for (e, (hi, lo)) in self.stage.iter_mut().zip(self.high.iter().zip(&self.low)) {
                *e = hi - lo;
            }
            let err = self.norm(&self.stage, y, &self.low);
            self.last_error_norm = err;
            let factor = if err == 0.0 {
                self.params.max_growth
            } else {
                (self.params.safety * err.powf(-0.2))
                    .clamp(self.params.max_shrink, self.params.max_growth)
            };
            if err <= 1.0 {
                let kept = if self.params.local_extrapolation {
                    &self.high
                } else {
                    &self.low
                };
                y.copy_from_slice(kept);
                *t = if last { t_end } else { *t + h };
                self.first_known = false;
                self.stats.accepted += 1;
                self.stats.smallest_step = self.stats.smallest_step.min(h);
                self.stats.largest_step = self.stats.largest_step.max(h);
                // A shortened last step says nothing about the step the error allows beyond
                // itself: it keeps the unshortened step, and may raise it to h·factor but
                // never grow it by its own factor. (Growing it by the factor compounded
                // over a run of shortened steps, RKF45 landing on a recording grid finer
                // than its step: on a creep drive recorded every 0.1 of the stable step
                // the next step reached 10²⁷² s in 700 steps, then overflowed, and the
                // next call refused the infinite initial step.)
                let base = if last { self.h.max(h) } else { h };
                self.h = if rejected_here {
                    base * factor.min(1.0)
                } else if last && factor > 1.0 {
                    self.h.max(h * factor)
                } else {
                    base * factor
                };
                return Ok(h);
            }
            self.stats.rejected += 1;
            rejected_here = true;
            self.h = h * factor.min(1.0);
        }
    }

    /// Integrate from (`t`, `y`) to `t_end` (≥ t).
    pub fn advance_to<F>(
        &mut self,
        t: &mut f64,
        y: &mut [f64],
        t_end: f64,
        f: &mut F,
    ) -> Result<(), StepError>
    where
        F: FnMut(f64, &[f64], &mut [f64]),
    {
        while *t < t_end {
            self.step(t, y, t_end, f)?;
        }
        Ok(())
    }

    /// The Fehlberg stage derivatives k_from…k₅ of a step of size `h` from (`t`, `y`), into
    /// `self.k` (one evaluation of `f` each; k₀ = f(t, y) when `from` is 0).
    fn stages<F>(&mut self, t: f64, y: &[f64], h: f64, f: &mut F, from: usize)
    where
        F: FnMut(f64, &[f64], &mut [f64]),
    {
        for s in from..6 {
            let (stage, k) = (&mut self.stage, &self.k);
            match s {
                0 => combine(stage, y, h, [], []),
                1 => combine(stage, y, h, [A[1][0]], [&k[0]]),
                2 => combine(stage, y, h, [A[2][0], A[2][1]], [&k[0], &k[1]]),
                3 => combine(
                    stage,
                    y,
                    h,
                    [A[3][0], A[3][1], A[3][2]],
                    [&k[0], &k[1], &k[2]],
                ),
                4 => combine(
                    stage,
                    y,
                    h,
                    [A[4][0], A[4][1], A[4][2], A[4][3]],
                    [&k[0], &k[1], &k[2], &k[3]],
                ),
                _ => combine(
                    stage,
                    y,
                    h,
                    [A[5][0], A[5][1], A[5][2], A[5][3], A[5][4]],
                    [&k[0], &k[1], &k[2], &k[3], &k[4]],
                ),
            }
            let (ks, _) = self.k.split_at_mut(s + 1);
            f(t + C[s] * h, &self.stage, &mut ks[s]);
        }
    }

    /// The local error estimate ŷ − y of one trial step of size `h` from (`t`, `y`) without
    /// moving: (4th-order solution, 5th-order solution). For tests of the estimate.
    pub fn trial<F>(&mut self, t: f64, y: &[f64], h: f64, f: &mut F) -> (Vec<f64>, Vec<f64>)
    where
        F: FnMut(f64, &[f64], &mut [f64]),
    {
        let n = y.len();
        self.stages(t, y, h, f, 0);
        self.first_known = false;
        let mut lo = y.to_vec();
        let mut hi = y.to_vec();
        for i in 0..n {
            for s in 0..6 {
                lo[i] += h * B4[s] * self.k[s][i];
                hi[i] += h * B5[s] * self.k[s][i];
            }
        }
        (lo, hi)
    }
}
