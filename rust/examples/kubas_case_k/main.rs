//! Case K (Kubas 2014, section 4) with the rigid-body belt, both readings of c_tra.
//!
//! `cargo run --release --example kubas_case_k [-- t_end [tolerance [csv_prefix]]]`
//!
//! For each reading: settle the preload, run to `t_end` (default 1 s), and print the span
//! tensions T₁ (tight, bottom) and T₂ (slack, top), the pulley speeds and the slip averaged
//! over the last 40 % of the run, against M/r, twice the preload and creep theory.
mod drive;

use beltrs::integrate::rkf45::{Rkf45, Rkf45Params};
use drive::{run, settle, CaseK, CtraReading, System};
use std::io::Write;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let t_end: f64 = args
        .get(1)
        .map(|s| s.parse().expect("t_end, s"))
        .unwrap_or(1.0);
    let tol: f64 = args
        .get(2)
        .map(|s| s.parse().expect("tolerance"))
        .unwrap_or(1e-5);
    let csv = args.get(3).cloned();
    let readings: Vec<CtraReading> = match std::env::var("KUBAS_READING").as_deref() {
        Ok("element") => vec![CtraReading::PerElement],
        Ok("strain") => vec![CtraReading::PerUnitStrain],
        _ => vec![CtraReading::PerUnitStrain, CtraReading::PerElement],
    };
    for reading in readings {
        let mut case = CaseK::paper(reading);
        case.tolerance = tol;
        if let Ok(dv) = std::env::var("KUBAS_DV") {
            case.friction.transition_speed = dv.parse().expect("KUBAS_DV, m/s");
        }
        if let Ok(r) = std::env::var("KUBAS_RAMP") {
            case.ramp_time = r.parse().expect("KUBAS_RAMP, s");
        }
        println!(
            "Δv = {:e} m/s, ramp {} s, tolerance {tol:e}",
            case.friction.transition_speed, case.ramp_time
        );
        let wall = Instant::now();
        let settled = settle(case).unwrap_or_else(|e| panic!("settling failed: {e}"));
        let t_settle = wall.elapsed().as_secs_f64();
        let l = settled.length;
        let ea = case.axial_rigidity(l);
        println!(
            "== c_tra read {:?}: SDE stiffness {:.4e} N/m, EA {:.4e} N",
            reading,
            case.sde_stiffness(l),
            ea
        );
        println!(
            "   body length {:.5} mm (belt {:.4} m unstretched), preload {:.1} N after {} settling passes ({:.1} s wall)",
            l * 1e3,
            l * case.bodies as f64,
            settled.preload,
            settled.passes,
            t_settle
        );
        let mut sys = System::new(case, l);
        let mut y = settled.state.clone();
        let params = Rkf45Params {
            relative_tolerance: tol,
            absolute_tolerance: tol,
            ..Default::default()
        };
        let mut rk = Rkf45::new(params, y.len()).unwrap();
        rk.set_absolute_scales(&sys.scales()).unwrap();
        let mut t = 0.0;
        let mut samples = Vec::new();
        let wall = Instant::now();
        let res = run(&mut sys, &mut rk, &mut t, &mut y, t_end, 1e-3, &mut samples);
        let secs = wall.elapsed().as_secs_f64();
        if let Err(e) = res {
            println!("   run stopped at t = {t:.5} s: {e}");
        }
        let st = rk.stats;
        println!(
            "   {:.3} s simulated in {:.1} s wall: {} steps accepted, {} rejected, {} evaluations, step {:.2e}..{:.2e} s",
            t, secs, st.accepted, st.rejected, st.evaluations, st.smallest_step, st.largest_step
        );
        if let Some(prefix) = &csv {
            let name = format!(
                "{prefix}_{}.csv",
                if reading == CtraReading::PerElement {
                    "element"
                } else {
                    "strain"
                }
            );
            let mut f = std::fs::File::create(&name).unwrap();
            writeln!(
                f,
                "t,theta1,theta2,omega1,omega2,tight,slack,mean,sde0,contacts1,contacts2,creeping"
            )
            .unwrap();
            for s in &samples {
                writeln!(
                    f,
                    "{},{},{},{},{},{},{},{},{},{},{},{}",
                    s.time,
                    s.theta[0],
                    s.theta[1],
                    s.omega[0],
                    s.omega[1],
                    s.tight,
                    s.slack,
                    s.mean,
                    s.sde0,
                    s.contacts[0],
                    s.contacts[1],
                    s.creeping
                )
                .unwrap();
            }
            println!("   samples written to {name}");
        }
        let t0 = 0.6 * t;
        let w: Vec<_> = samples.iter().filter(|s| s.time >= t0).collect();
        if w.len() < 2 {
            continue;
        }
        let mean = |f: &dyn Fn(&drive::Sample) -> f64| {
            w.iter().map(|s| f(s)).sum::<f64>() / w.len() as f64
        };
        let std = |f: &dyn Fn(&drive::Sample) -> f64| {
            let m = mean(f);
            (w.iter().map(|s| (f(s) - m).powi(2)).sum::<f64>() / w.len() as f64).sqrt()
        };
        let (t1, t2) = (mean(&|s| s.tight), mean(&|s| s.slack));
        let (a, b) = (w[0], w[w.len() - 1]);
        let w1 = (b.theta[0] - a.theta[0]) / (b.time - a.time);
        let w2 = (b.theta[1] - a.theta[1]) / (b.time - a.time);
        let slip = 1.0 - w2 / w1;
        let target = case.drive_torque / case.radius;
        println!("   window {:.3}..{:.3} s:", a.time, b.time);
        println!(
            "   T1 {:.1} N (±{:.1}), T2 {:.1} N (±{:.1})",
            t1,
            std(&|s| s.tight),
            t2,
            std(&|s| s.slack)
        );
        println!(
            "   T1 - T2 {:.1} N against M/r = {:.1} N: {:+.2} %",
            t1 - t2,
            target,
            100.0 * (t1 - t2 - target) / target
        );
        println!(
            "   T1 + T2 {:.1} N against 2 x preload {:.1} N: {:+.2} %; mean SDE tension {:.1} N",
            t1 + t2,
            2.0 * settled.preload,
            100.0 * (t1 + t2 - 2.0 * settled.preload) / (2.0 * settled.preload),
            mean(&|s| s.mean)
        );
        println!(
            "   drive {:.3} rad/s, driven {:.3} rad/s (8π = {:.3}), slip {:.3} %",
            w1,
            w2,
            8.0 * std::f64::consts::PI,
            100.0 * slip
        );
        println!(
            "   creep theory (T1 - T2)/(EA + T1) = {:.3} %",
            100.0 * (t1 - t2) / (ea + t1)
        );
        println!(
            "   bodies on pulleys {:.1} / {:.1}, within Δv of sticking {:.1}",
            mean(&|s| s.contacts[0] as f64),
            mean(&|s| s.contacts[1] as f64),
            mean(&|s| s.creeping as f64)
        );
    }
}
