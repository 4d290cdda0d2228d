//! Case K with Kubas's creep friction: what the adaptive RKF45 costs in steady running, at
//! each creep transition speed Δv (docs/kubas.md, "Case K with creep friction").
//!
//! `cargo run --release --example case_k_rkf45 -- [settle s] [measure s] [chunks] [Δv m/s]...`
//! (defaults 0.4, 1e-4, 10, then 1e-5 1e-4 1e-3 1e-2 5e-2).
//!
//! Case K (`presets::case_k`) with creep friction (µs 1.05, µk 1.0, Δmax 10⁻⁴ m, Δv the
//! paper's 10⁻⁵ m/s) is relaxed and run to steady running under central differences (the
//! creep law with its stick limit, which costs no step) for `settle` seconds, with the
//! torque ramp of 0.3 s. Its state then starts an RKF45 run of the same scene at each Δv
//! (default tolerances, rtol 10⁻⁸, atol 10⁻¹¹) for `measure` seconds in `chunks` equal
//! pieces. Printed per Δv: accepted and rejected steps, the mean step over the whole
//! measure and the smallest and largest chunk mean, derivative evaluations, wall time and
//! wall time per simulated second. The central-difference velocities lag half a step
//! (about 4·10⁻⁷ s); the first chunk absorbs that small start transient, so the chunks'
//! spread is reported and the median chunk is the steady figure.

use beltrs::friction::creep::CreepFriction;
use beltrs::scene::{FrictionModel, IntegratorKind, Scene};
use beltrs::Simulation;
use std::time::Instant;

fn with_creep(dv: f64, integrator: IntegratorKind) -> Scene {
    let mut scene = beltrs::presets::case_k(0.3, 0.00344);
    for p in &mut scene.pulleys {
        p.friction = FrictionModel::Creep(CreepFriction {
            transition_speed: dv,
            ..Default::default()
        });
    }
    scene.solver.integrator = integrator;
    scene
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .map(|a| a.parse::<f64>())
        .collect::<Result<_, _>>()?;
    let settle = args.first().copied().unwrap_or(0.4);
    let measure = args.get(1).copied().unwrap_or(1e-4);
    let chunks = args.get(2).copied().unwrap_or(10.0).max(1.0) as usize;
    let dvs: Vec<f64> = if args.len() > 3 {
        args[3..].to_vec()
    } else {
        vec![1e-5, 1e-4, 1e-3, 1e-2, 5e-2]
    };
    let mut cd = Simulation::new(&with_creep(1e-5, IntegratorKind::CentralDifference))?;
    let report = cd.stabilise(&Default::default())?;
    assert!(report.converged, "{report:?}");
    let t0 = Instant::now();
    cd.advance_to(settle, u64::MAX)?;
    println!(
        "case K, creep friction, central differences to {settle} s (dv 1e-5 m/s, step {:.3e} s): {:.1} s wall; drive {:.4}, driven {:.4} rad/s",
        cd.model.dt,
        t0.elapsed().as_secs_f64(),
        cd.state.pulley_omega[0],
        cd.state.pulley_omega[1]
    );
    println!("then RKF45 (rtol 1e-8, atol 1e-11) for {measure} s in {chunks} chunks:");
    println!("  dv (m/s) | accepted | rejected | mean step (s) | chunk means (s): min, median, max | evaluations | wall (s) | wall per simulated s");
    for dv in dvs {
        let mut rk = Simulation::new(&with_creep(dv, IntegratorKind::Rkf45))?;
        rk.state = cd.state.clone();
        rk.state.adaptive_step = 0.0;
        rk.state.accepted_steps = 0;
        rk.state.rejected_steps = 0;
        let start = rk.state.time;
        let piece = measure / chunks as f64;
        let mut means = Vec::with_capacity(chunks);
        let t0 = Instant::now();
        for k in 1..=chunks {
            let before = rk.state.accepted_steps;
            rk.advance_to(start + piece * k as f64, u64::MAX)?;
            means.push(piece / (rk.state.accepted_steps - before).max(1) as f64);
        }
        let wall = t0.elapsed().as_secs_f64();
        means.sort_by(f64::total_cmp);
        let (acc, rej) = (rk.state.accepted_steps, rk.state.rejected_steps);
        println!(
            "  {dv:8.0e} | {acc:8} | {rej:8} | {:.2e} | {:.2e}, {:.2e}, {:.2e} | {:11} | {wall:8.2} | {:.3e}",
            measure / acc as f64,
            means[0],
            means[chunks / 2],
            means[chunks - 1],
            6 * acc + 5 * rej,
            wall / measure
        );
    }
    Ok(())
}
