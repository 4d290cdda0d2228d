//! Kernel tests of the viscoelastic (Zener) belt element, `belt::node::zener`: the arm's
//! exact step against the closed forms of the standard linear solid (complex stiffness and
//! loss factor at a frequency, relaxation under a held strain, energy dissipated per cycle).

use beltrs::belt::node::zener::{advance, Zener};
use std::f64::consts::PI;

/// Drive one element (relaxed stiffness `k`, arm `z`) with l(t) = A sin ωt at `steps` steps
/// per period for `periods` periods; returns the last period's (in-phase, out-of-phase)
/// Fourier components of the total force k·l + σ over A (N/m), and the work done on the
/// element over that period, J.
fn drive(
    k: f64,
    z: Zener,
    amplitude: f64,
    omega: f64,
    steps: usize,
    periods: usize,
) -> (f64, f64, f64) {
    let dt = 2.0 * PI / omega / steps as f64;
    let (mut sigma, mut l_old) = (0.0, 0.0);
    let (mut c, mut s, mut work) = (0.0, 0.0, 0.0);
    let mut f_old = 0.0;
    for n in 1..=steps * periods {
        let t = n as f64 * dt;
        let l = amplitude * (omega * t).sin();
        sigma = advance(sigma, z.ratio * k, z.time, l - l_old, dt);
        let f = k * l + sigma;
        if n > steps * (periods - 1) {
            c += f * (omega * t).sin();
            s += f * (omega * t).cos();
            // Trapezoidal ∮ f dl.
            work += 0.5 * (f + f_old) * (l - l_old);
        }
        (f_old, l_old) = (f, l);
    }
    let scale = 2.0 / steps as f64 / amplitude;
    (c * scale, s * scale, work)
}

#[test]
fn from_loss_factor_puts_the_peak_at_the_frequency() {
    // tan δ(ω) = rωτ/(1 + (1 + r)ω²τ²) peaks at ω₀τ = 1/√(1 + r) with r/(2√(1 + r)).
    for (eta, f) in [(0.05, 2.0), (0.1, 5.0), (0.3, 10.0)] {
        let z = Zener::from_loss_factor(eta, f);
        let w0 = 2.0 * PI * f;
        assert!(
            (z.loss_factor(w0) - eta).abs() < 1e-12 * eta.max(1.0),
            "{eta} {f}"
        );
        assert!(z.loss_factor(w0 * 1.01) < eta && z.loss_factor(w0 / 1.01) < eta);
        assert!((z.ratio / (2.0 * (1.0 + z.ratio).sqrt()) - eta).abs() < 1e-12);
    }
}

#[test]
fn complex_stiffness_at_a_frequency_matches_the_closed_form() {
    // The exact step is exact for a length linear over each step; a sine at 2000 steps per
    // period differs from its chords by O((ωΔt)²) = 1e-5, so 1e-4 of the storage stiffness.
    let k = 3.0e7;
    let z = Zener::from_loss_factor(0.1, 5.0);
    for f in [1.0, 5.0, 20.0] {
        let w = 2.0 * PI * f;
        let (storage, loss) = z.complex_modulus(w);
        // Settled after 40 relaxation times at the lowest frequency (40 periods).
        let (c, s, _) = drive(k, z, 1e-3, w, 2000, 40);
        assert!(
            (c / k - storage).abs() < 1e-4 * storage,
            "f {f}: storage {} against {storage}",
            c / k
        );
        assert!(
            (s / k - loss).abs() < 1e-4 * storage,
            "f {f}: loss {} against {loss}",
            s / k
        );
        assert!(((s / c) - z.loss_factor(w)).abs() < 2e-4, "f {f}: tan δ");
    }
}

#[test]
fn a_held_strain_relaxes_to_the_static_stiffness() {
    // A step of length Δl in one (vanishing) step loads the arm to k₁Δl; held, the arm
    // relaxes as e^(−t/τ) exactly, whatever the step (the exponential update is exact for a
    // constant length), and the element's force falls from (1 + r)kΔl to kΔl.
    let k = 1.0e6;
    let z = Zener::from_loss_factor(0.2, 3.0);
    let dl = 2e-3;
    let k1 = z.ratio * k;
    let mut sigma = advance(0.0, k1, z.time, dl, 0.0);
    assert_eq!(sigma, k1 * dl);
    for dt in [1e-6, z.time * 0.3, z.time * 5.0] {
        let mut s = sigma;
        let mut t = 0.0;
        for _ in 0..20 {
            s = advance(s, k1, z.time, 0.0, dt);
            t += dt;
            let exact = k1 * dl * (-t / z.time).exp();
            assert!(
                (s - exact).abs() <= 1e-12 * k1 * dl,
                "dt {dt}: {s} against {exact}"
            );
        }
    }
    // Unconditionally stable: a step far beyond τ leaves the arm relaxed, never overshoots.
    sigma = advance(sigma, k1, z.time, 0.0, 1e3 * z.time);
    assert!(sigma.abs() < 1e-300_f64.max(1e-12 * k1 * dl));
}

#[test]
fn energy_dissipated_per_cycle_is_pi_loss_stiffness_amplitude_squared() {
    // ∮ F dl over one steady cycle of l = A sin ωt is π·k''·A², k'' = k·r·ωτ/(1 + ω²τ²).
    let k = 2.0e7;
    let z = Zener::from_loss_factor(0.15, 4.0);
    let a = 5e-4;
    for f in [1.5, 4.0, 12.0] {
        let w = 2.0 * PI * f;
        let (_, loss) = z.complex_modulus(w);
        let exact = PI * k * loss * a * a;
        let (_, _, work) = drive(k, z, a, w, 4000, 40);
        assert!(
            (work - exact).abs() < 1e-4 * exact,
            "f {f}: {work} J against {exact} J"
        );
    }
}
