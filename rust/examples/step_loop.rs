//! Steps the benchmark scenes without Python, for profiling the force evaluation and the
//! integration (e.g. `valgrind --tool=callgrind`, whose instruction counts are
//! reproducible). Prints ns per node-step (best and median of five repeats).
//!
//! ```sh
//! cargo build --release --example step_loop
//! target/release/examples/step_loop loop 10000 2000      # frictionless loop, 1e4 nodes
//! target/release/examples/step_loop case_h 89 20000      # case H with friction
//! valgrind --tool=callgrind target/release/examples/step_loop loop 10000 200
//! STEP_LOOP_COMPARE=1 target/release/examples/step_loop loop 10000 1000  # fused vs not
//! ```
//!
//! Environment: `STEP_LOOP_UNFUSED` times the step without the fusion of each integration
//! with the next axial pass (profiling on, which turns it off), `STEP_LOOP_COMPARE` also
//! alternates five fused and five unfused repeats in the same process, `STEP_LOOP_PROFILE`
//! prints the per-stage profile of one more run.
//!
//! Scenes: `loop` is the frictionless loop of `benches/numpy_ref.py` (the 1 km conveyor of
//! `benches/bench_scenes.conveyor` without idlers, friction or drive: EA 60 MN, 25 kg/m,
//! pulleys of radius 0.4 m, tail takeup of 4000 kg), `idlers` the same with carry and
//! return idlers (benchmark 1), `case_h` case H with friction µs 0.3, µk 0.25 (after a
//! frictionless relaxation to 1e-7).

use beltrs::scene::{BeltParams, FrictionModel, IdlerSpec, PulleySpec, Scene, TakeupSpec};
use beltrs::{Simulation, StabiliseOptions};
use std::time::Instant;

mod common;

fn conveyor(length: f64, nodes: usize, idlers: bool) -> Scene {
    let radius = 0.4;
    let r_idler = 0.0635;
    let pulley = |name: &str, center: [f64; 2]| PulleySpec {
        name: name.into(),
        center,
        radius,
        mass: 1000.0,
        inertia: Some(1000.0 * radius * radius),
        contact_stiffness: 1e8,
        ..Default::default()
    };
    let mut tail = pulley("tail", [length, 0.0]);
    tail.takeup = Some(TakeupSpec {
        counterweight: 4000.0,
        direction: [1.0, 0.0],
        ..Default::default()
    });
    let stations = |spacing: f64| -> Vec<f64> {
        let count = ((length - 2.0 * radius) / spacing).floor() as usize;
        let first = 0.5 * (length - (count as f64 - 1.0) * spacing);
        (0..count).map(|k| first + k as f64 * spacing).collect()
    };
    let mut rolls = Vec::new();
    if idlers {
        for x in stations(1.5) {
            rolls.push(IdlerSpec {
                center: [x, radius - r_idler],
                ..Default::default()
            });
        }
        for x in stations(3.0) {
            rolls.push(IdlerSpec {
                center: [x, -radius - r_idler],
                ..Default::default()
            });
        }
    }
    Scene {
        belt: BeltParams {
            axial_stiffness: 60e6,
            mass_per_length: 25.0,
            elements: Some(nodes),
            ..Default::default()
        },
        pulleys: vec![pulley("head", [0.0, 0.0]), tail],
        idlers: rolls,
        ..Default::default()
    }
}

fn case_h(elements: usize) -> Scene {
    let friction = FrictionModel::StickForce {
        static_coefficient: 0.3,
        kinetic_coefficient: 0.25,
    };
    let mut scene = beltrs::presets::case_h(elements);
    for p in &mut scene.pulleys {
        p.friction = friction;
    }
    scene
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let which = args.get(1).map_or("loop", String::as_str);
    let nodes: usize = args.get(2).map_or(10_000, |s| s.parse().expect("nodes"));
    let steps: u64 = args.get(3).map_or(2000, |s| s.parse().expect("steps"));
    let scene = match which {
        "loop" => conveyor(nodes as f64 * 0.1, nodes, false),
        "idlers" => conveyor(nodes as f64 * 0.1, nodes, true),
        "case_h" => case_h(nodes),
        other => panic!("unknown scene {other}: loop, idlers or case_h"),
    };
    let mut sim = Simulation::new(&scene).expect("scene compiles");
    if which == "case_h" {
        let mut without = scene.clone();
        for p in &mut without.pulleys {
            p.friction = FrictionModel::None;
        }
        sim.set_scene(&without).expect("same scene");
        sim.stabilise(&StabiliseOptions::default())
            .expect("relaxes");
        sim.set_scene(&scene).expect("same scene");
    }
    // Profiling times each stage on its own, so it turns the fusion of the integration
    // with the next axial pass off: STEP_LOOP_UNFUSED measures the step without it.
    if std::env::var_os("STEP_LOOP_UNFUSED").is_some() {
        sim.set_profiling(true);
    }
    sim.step(10).expect("warm-up");
    // STEP_LOOP_COMPARE: five fused and five unfused repeats alternating in this process
    // (the same core), for the ratio of the two.
    if std::env::var_os("STEP_LOOP_COMPARE").is_some() {
        let mut times = [Vec::new(), Vec::new()];
        for _ in 0..5 {
            for (unfused, t) in times.iter_mut().enumerate() {
                sim.set_profiling(unfused == 1);
                let t0 = Instant::now();
                sim.step(steps).expect("steps");
                t.push(t0.elapsed().as_secs_f64() / (nodes as f64 * steps as f64) * 1e9);
            }
        }
        sim.set_profiling(false);
        for t in &mut times {
            t.sort_by(f64::total_cmp);
        }
        println!(
            "fused {:.2} ns per node-step median ({:.2} best), unfused {:.2} ({:.2})",
            times[0][2], times[0][0], times[1][2], times[1][0]
        );
    }
    // Five timed repeats: the shared machine makes single timings noisy; the fastest is the
    // steadier figure.
    let mut walls: Vec<f64> = (0..5)
        .map(|_| {
            let t0 = Instant::now();
            sim.step(steps).expect("steps");
            t0.elapsed().as_secs_f64()
        })
        .collect();
    walls.sort_by(f64::total_cmp);
    // Fingerprint of the final state, bit for bit: a change that claims to leave the
    // arithmetic unchanged must leave it unchanged.
    let fingerprint = common::fingerprint(common::node_values(&sim));
    let node_steps = nodes as f64 * steps as f64;
    if std::env::var_os("STEP_LOOP_PROFILE").is_some() {
        common::print_stage_profile(&mut sim, steps, node_steps, "node-step");
    }
    println!(
        "{which} {nodes} nodes, {steps} steps x 5, stages {:?}: {:.2} ns per node-step best, {:.2} median ({:.3e} node-steps/s best); state fingerprint {fingerprint:016x}",
        sim.model.stages.iter().map(|s| s.name()).collect::<Vec<_>>(),
        walls[0] / node_steps * 1e9,
        walls[2] / node_steps * 1e9,
        node_steps / walls[0]
    );
}
