//! Adaptive Runge–Kutta–Fehlberg 4(5): the embedded error estimate against the true local
//! error on ODEs with known solutions, tolerance proportionality, step control and errors.
use beltrs::integrate::rkf45::{Rkf45, Rkf45Params, StepError};
use beltrs::BeltError;

fn decay(_t: f64, y: &[f64], dy: &mut [f64]) {
    dy[0] = -y[0];
}

fn oscillator(_t: f64, y: &[f64], dy: &mut [f64]) {
    dy[0] = y[1];
    dy[1] = -y[0];
}

/// (true local error of the propagated 4th-order solution, embedded estimate) for one step
/// of size h from y0, with `exact` the solution after h.
fn local_errors<F: FnMut(f64, &[f64], &mut [f64])>(
    y0: &[f64],
    h: f64,
    exact: &[f64],
    f: &mut F,
) -> (f64, f64) {
    let mut rk = Rkf45::new(Rkf45Params::default(), y0.len()).unwrap();
    let (lo, hi) = rk.trial(0.0, y0, h, f);
    let true_err = lo
        .iter()
        .zip(exact)
        .map(|(a, b)| (a - b).powi(2))
        .sum::<f64>()
        .sqrt();
    let est = lo
        .iter()
        .zip(&hi)
        .map(|(a, b)| (a - b).powi(2))
        .sum::<f64>()
        .sqrt();
    (true_err, est)
}

#[test]
fn error_estimate_matches_true_local_error_on_decay() {
    let mut prev: Option<(f64, f64)> = None;
    for k in 0..5 {
        let h = 0.2 / 2f64.powi(k);
        let (e, est) = local_errors(&[1.0], h, &[(-h).exp()], &mut decay);
        // The estimate is the leading h⁵ term of the local error of the 4th-order solution,
        // so their ratio is 1 + c·h + O(h²), with c the ratio of the h⁶ to the h⁵ error
        // coefficient: |c| < 1 for a problem whose derivatives are all of size 1 (measured
        // c ≈ −0.7 here). A wrong estimate would not tend to 1.
        assert!(
            (est / e - 1.0).abs() < h,
            "h = {h}: true {e:e}, estimate {est:e}"
        );
        if let Some((pe, pest)) = prev {
            // Both are O(h⁵): halving h divides them by 2⁵ = 32 (order within ±0.15).
            let order = (pe / e).log2();
            let order_est = (pest / est).log2();
            assert!((order - 5.0).abs() < 0.15, "h = {h}: order {order}");
            assert!(
                (order_est - 5.0).abs() < 0.15,
                "h = {h}: estimate order {order_est}"
            );
        }
        prev = Some((e, est));
    }
}

#[test]
fn error_estimate_matches_true_local_error_on_oscillator() {
    let mut prev: Option<f64> = None;
    for k in 0..5 {
        let h = 0.25 / 2f64.powi(k);
        let (e, est) = local_errors(&[1.0, 0.0], h, &[h.cos(), -h.sin()], &mut oscillator);
        assert!(
            (est / e - 1.0).abs() < h,
            "h = {h}: true {e:e}, estimate {est:e}"
        );
        if let Some(pe) = prev {
            let order = (pe / e).log2();
            assert!((order - 5.0).abs() < 0.15, "h = {h}: order {order}");
        }
        prev = Some(e);
    }
}

/// Global error after 10 periods of the oscillator at tolerance `tol`, with the counters.
fn oscillator_run(tol: f64, extrapolate: bool) -> (f64, Rkf45) {
    let p = Rkf45Params {
        relative_tolerance: tol,
        absolute_tolerance: tol,
        local_extrapolation: extrapolate,
        ..Default::default()
    };
    let mut rk = Rkf45::new(p, 2).unwrap();
    let mut y = [1.0, 0.0];
    let mut t = 0.0;
    let t_end = 20.0 * std::f64::consts::PI;
    rk.advance_to(&mut t, &mut y, t_end, &mut oscillator)
        .unwrap();
    assert_eq!(t, t_end, "lands exactly on the end time");
    ((y[0] - 1.0).hypot(y[1]), rk)
}

#[test]
fn global_error_scales_with_tolerance() {
    // A 4th-order method whose local error per step is held at tol has a global error
    // ∝ tol^(4/5) at fixed work per unit time (error per unit step ∝ h⁴ ∝ tol^(4/5)).
    // Measured over a decade ladder: the slope of log(error) against log(tol) must lie in
    // [0.7, 1.05]. Each accepted step's error norm is ≤ 1, i.e. a Euclidean local error
    // ≤ √2·(atol + rtol·|y|) ≤ 2√2·tol for |y| ≤ 1, and the oscillator's flow is an isometry,
    // so local errors add at most linearly: the global error stays below steps·2√2·tol.
    let tols = [1e-4, 1e-6, 1e-8, 1e-10];
    let runs: Vec<(f64, Rkf45)> = tols.iter().map(|&t| oscillator_run(t, false)).collect();
    for (k, (err, rk)) in runs.iter().enumerate() {
        let steps = rk.stats.accepted as f64;
        assert!(
            *err < steps * 2.0 * 2f64.sqrt() * tols[k],
            "tol {}: error {err:e} after {steps} steps",
            tols[k]
        );
        // The first stage once per step (the starting-step rule evaluates it with one probe),
        // five more per attempt.
        let (acc, rej) = (rk.stats.accepted, rk.stats.rejected);
        assert_eq!(rk.stats.evaluations, 2 + (acc - 1) + 5 * (acc + rej));
        if k > 0 {
            let slope = (runs[k - 1].0 / err).log10() / 2.0;
            assert!(
                (0.7..=1.05).contains(&slope),
                "tol {}: slope {slope}",
                tols[k]
            );
            // More accuracy costs more steps, by about tol^(−1/5) per decade: 100^(1/5) ≈ 2.5.
            let ratio = steps / runs[k - 1].1.stats.accepted as f64;
            assert!(
                (2.0..=3.2).contains(&ratio),
                "tol {}: step ratio {ratio}",
                tols[k]
            );
        }
    }
    // Local extrapolation is more accurate at the same tolerance.
    let (e5, _) = oscillator_run(1e-6, true);
    assert!(e5 < runs[1].0, "5th order {e5:e} vs 4th {:e}", runs[1].0);
}

#[test]
fn step_control_rejects_and_recovers() {
    // A derivative that jumps from −y to −1000·y at t = 1: steps are cut there (rejections)
    // and the solution stays within tolerance of exp(−1)·exp(−1000(t − 1)).
    let mut f = |t: f64, y: &[f64], dy: &mut [f64]| {
        dy[0] = if t < 1.0 { -y[0] } else { -1000.0 * y[0] };
    };
    let p = Rkf45Params {
        relative_tolerance: 1e-8,
        absolute_tolerance: 1e-12,
        ..Default::default()
    };
    let mut rk = Rkf45::new(p, 1).unwrap();
    let (mut t, mut y) = (0.0, [1.0]);
    rk.advance_to(&mut t, &mut y, 1.01, &mut f).unwrap();
    let exact = (-1.0f64).exp() * (-10.0f64).exp();
    assert!(
        (y[0] - exact).abs() < 1e-6 * exact + 1e-11,
        "{} vs {exact}",
        y[0]
    );
    assert!(rk.stats.rejected > 0, "{:?}", rk.stats);
    assert!(
        rk.stats.smallest_step < 1e-3 && rk.stats.largest_step > 0.05,
        "{:?}",
        rk.stats
    );
    // The step grows back by at most max_growth per step.
    let mut rk = Rkf45::new(
        Rkf45Params {
            initial_step: 1e-6,
            ..Default::default()
        },
        1,
    )
    .unwrap();
    let (mut t, mut y) = (0.0, [1.0]);
    let mut last = 1e-6;
    for _ in 0..10 {
        let h = rk.step(&mut t, &mut y, 10.0, &mut decay).unwrap();
        assert!(h <= 5.0 * last * (1.0 + 1e-12), "{h} after {last}");
        last = h;
    }
}

#[test]
fn shortened_steps_do_not_compound_the_next_step() {
    // Landing on a grid much finer than the step the error allows (a recording every 10⁻⁴
    // s on the oscillator, which allows steps of about 0.05 s at 10⁻⁸): every step is
    // shortened to the grid. The next step is the one the error allows, not grown by the
    // growth factor of each shortened step in turn: compounded, ×5 a step (the first
    // shortened step read 5× the allowed step, 0.40 s), it overflows after about 440
    // steps, and a new integrator refuses the infinite initial step.
    let p = Rkf45Params {
        relative_tolerance: 1e-8,
        absolute_tolerance: 1e-12,
        ..Default::default()
    };
    let mut rk = Rkf45::new(p, 2).unwrap();
    let (mut t, mut y) = (0.0, [1.0, 0.0]);
    let mut f = oscillator;
    // The step the error allows, from a free run.
    for _ in 0..20 {
        rk.step(&mut t, &mut y, 10.0, &mut f).unwrap();
    }
    let allowed = rk.next_step();
    assert!(allowed > 1e-2 && allowed < 1.0, "{allowed}");
    for k in 1..=2000 {
        let to = t + 1e-4;
        rk.step(&mut t, &mut y, to, &mut f).unwrap();
        assert_eq!(t, to);
        let next = rk.next_step();
        assert!(
            next.is_finite() && next < 2.0 * allowed,
            "step {k}: {next} s"
        );
    }
    // Still on the solution, and a new integrator takes the step over.
    assert!((y[0] - t.cos()).abs() < 1e-6 && (y[1] + t.sin()).abs() < 1e-6);
    let again = Rkf45::new(
        Rkf45Params {
            initial_step: rk.next_step(),
            ..p
        },
        2,
    );
    assert!(again.is_ok());
}

#[test]
fn minimum_step_error_names_time_and_step() {
    // y' = y² from y(0) = 1 blows up at t = 1.
    let mut f = |_t: f64, y: &[f64], dy: &mut [f64]| dy[0] = y[0] * y[0];
    let mut rk = Rkf45::new(
        Rkf45Params {
            min_step: 1e-9,
            ..Default::default()
        },
        1,
    )
    .unwrap();
    let (mut t, mut y) = (0.0, [1.0]);
    let err = rk.advance_to(&mut t, &mut y, 2.0, &mut f).unwrap_err();
    match &err {
        StepError::StepTooSmall {
            time,
            step,
            min_step,
            ..
        } => {
            assert!(*time > 0.99 && *time < 1.0, "time {time}");
            assert!(*step < *min_step);
        }
        other => panic!("unexpected {other:?}"),
    }
    let msg = err.to_string();
    assert!(
        msg.contains("at t = 0.99") && msg.contains("below the minimum 1e-9"),
        "{msg}"
    );
    let belt: BeltError = err.into();
    assert!(belt.to_string().contains("RKF45 step"));
}

#[test]
fn parameters_are_validated_by_name() {
    let e = Rkf45::new(
        Rkf45Params {
            relative_tolerance: 0.0,
            ..Default::default()
        },
        3,
    )
    .unwrap_err();
    assert!(e.to_string().contains("rkf45.relative_tolerance"), "{e}");
    let e = Rkf45::new(
        Rkf45Params {
            safety: 1.5,
            ..Default::default()
        },
        3,
    )
    .unwrap_err();
    assert!(e.to_string().contains("rkf45.safety"), "{e}");
    let e = Rkf45::new(
        Rkf45Params {
            min_step: 1.0,
            max_step: 0.1,
            ..Default::default()
        },
        3,
    )
    .unwrap_err();
    assert!(e.to_string().contains("rkf45.min_step"), "{e}");
}

#[test]
fn a_rejected_attempt_reuses_the_first_stage() {
    // The derivative jump of `step_control_rejects_and_recovers`: rejections happen, and
    // each costs five evaluations, not six (k₀ = f(t, y) does not change with the step).
    let mut calls = 0u64;
    let mut f = |t: f64, y: &[f64], dy: &mut [f64]| {
        calls += 1;
        dy[0] = if t < 1.0 { -y[0] } else { -1000.0 * y[0] };
    };
    let mut rk = Rkf45::new(Rkf45Params::default(), 1).unwrap();
    let (mut t, mut y) = (0.0, [1.0]);
    rk.advance_to(&mut t, &mut y, 1.01, &mut f).unwrap();
    let (acc, rej) = (rk.stats.accepted, rk.stats.rejected);
    assert!(rej > 0);
    assert_eq!(calls, rk.stats.evaluations);
    assert_eq!(calls, 2 + (acc - 1) + 5 * (acc + rej));
}

#[test]
fn a_known_first_stage_replaces_its_evaluation() {
    // Handing over f(t, y) gives the same steps to the last bit, one evaluation fewer per
    // step.
    let run = |hand_over: bool| {
        let mut rk = Rkf45::new(Rkf45Params::default(), 2).unwrap();
        let (mut t, mut y) = (0.0, [1.0, 0.0]);
        let mut calls = 0u64;
        let mut f = |t: f64, y: &[f64], dy: &mut [f64]| {
            calls += 1;
            oscillator(t, y, dy)
        };
        for _ in 0..50 {
            if hand_over && rk.next_step() > 0.0 {
                oscillator(t, &y, rk.known_first_stage());
            }
            rk.step(&mut t, &mut y, 100.0, &mut f).unwrap();
        }
        (t, y, calls)
    };
    let (t0, y0, c0) = run(false);
    let (t1, y1, c1) = run(true);
    assert_eq!(t0.to_bits(), t1.to_bits());
    assert_eq!(y0.map(f64::to_bits), y1.map(f64::to_bits));
    assert_eq!(c0 - c1, 49, "{c0} vs {c1}");
}

#[test]
fn dormant_components_leave_the_norm_alone_until_they_wake() {
    // The oscillator with 98 extra components that stay zero (a memory of contacts that
    // never touch): dormant, they change nothing, step for step; counted, they dilute the
    // RMS norm by √(2/100) and the steps grow.
    let run = |dormant: bool, wake: bool| {
        let mut rk = Rkf45::new(Rkf45Params::default(), 100).unwrap();
        if dormant {
            rk.set_dormant_from(2);
        }
        let mut y = vec![0.0; 100];
        y[0] = 1.0;
        let mut t = 0.0;
        let mut f = |t: f64, y: &[f64], dy: &mut [f64]| {
            oscillator(t, y, dy);
            dy[2..].fill(0.0);
            if wake && t > 5.0 {
                // One memory component wakes: it follows cos t from t = 5.
                dy[2] = y[1];
            }
        };
        rk.advance_to(&mut t, &mut y, 10.0, &mut f).unwrap();
        (y, rk.stats)
    };
    let plain = oscillator_stats(10.0);
    let (y, st) = run(true, false);
    assert_eq!(st.accepted, plain.1.accepted);
    assert_eq!(st.rejected, plain.1.rejected);
    assert_eq!(y[0].to_bits(), plain.0[0].to_bits());
    let (_, diluted) = run(false, false);
    assert!(
        diluted.accepted < st.accepted,
        "{} vs {}",
        diluted.accepted,
        st.accepted
    );
    // Awake, the component is counted and its error sets steps like any other: the run
    // differs from the one where it sleeps, and it integrates ∫₅ᵗ −sin = cos t − cos 5 with
    // the oscillator's accuracy.
    let (yw, sw) = run(true, true);
    assert!(sw.accepted != st.accepted || yw[0] != y[0]);
    let exact = (10.0f64).cos() - (5.0f64).cos();
    assert!((yw[2] - exact).abs() < 1e-5, "{} vs {exact}", yw[2]);
}

/// The plain oscillator to `t_end` at the default settings: (y, stats).
fn oscillator_stats(t_end: f64) -> ([f64; 2], beltrs::integrate::rkf45::Rkf45Stats) {
    let mut rk = Rkf45::new(Rkf45Params::default(), 2).unwrap();
    let (mut t, mut y) = (0.0, [1.0, 0.0]);
    rk.advance_to(&mut t, &mut y, t_end, &mut oscillator)
        .unwrap();
    (y, rk.stats)
}
