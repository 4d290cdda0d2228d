//! Steps a simulation loaded from a checkpoint without Python, for the cost of the
//! rigid-body belt's step against the node belt's (`benches/rigid_cost.py --checkpoints DIR`
//! writes the scenes' checkpoints; docs/developer/performance.md, "The rigid-body belt's
//! step"). Prints ns per element-step (best and median of five repeats) and a fingerprint
//! of the final state (positions, velocities, body angles and spins, pulley speeds, creep
//! memory), bit for bit.
//!
//! ```sh
//! cargo build --release --example rigid_loop
//! target/release/examples/rigid_loop /tmp/conveyor_rigid.ckpt 2000
//! target/release/examples/rigid_loop /tmp/case_k_rigid.ckpt 200 rkf45   # RKF45 instead
//! valgrind --tool=callgrind --dump-instr=no target/release/examples/rigid_loop /tmp/c.ckpt 200 cd 1
//! ```
//!
//! Arguments: checkpoint path, steps per repeat (default 2000), integrator (`cd`, the
//! checkpoint's own, default; or `rkf45` with the default tolerances: `steps` model steps of
//! time per repeat), repeats (default 5). `RIGID_LOOP_PROFILE` prints the per-stage profile
//! of one more repeat (central differences).

use beltrs::scene::IntegratorKind;
use std::path::Path;
use std::time::Instant;

mod common;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let path = args
        .get(1)
        .expect("usage: rigid_loop CHECKPOINT [steps] [cd|rkf45] [repeats]");
    let steps: u64 = args.get(2).map_or(2000, |s| s.parse().expect("steps"));
    let integrator = args.get(3).map_or("cd", String::as_str);
    let repeats: usize = args.get(4).map_or(5, |s| s.parse().expect("repeats"));
    let mut sim = beltrs::checkpoint::load(Path::new(path)).expect("checkpoint loads");
    if integrator == "rkf45" {
        // The same scene and state under RKF45 (a running simulation may not change its
        // integrator): a new simulation given the checkpoint's state, its own step counters.
        let mut scene = sim.model.scene.clone();
        scene.solver.integrator = IntegratorKind::Rkf45;
        let mut rk = beltrs::Simulation::new(&scene).expect("the scene under RKF45");
        rk.state = sim.state.clone();
        rk.state.adaptive_step = 0.0;
        rk.state.accepted_steps = 0;
        rk.state.rejected_steps = 0;
        sim = rk;
    } else {
        assert_eq!(integrator, "cd", "integrator: cd or rkf45");
    }
    let elements = sim.model.elements as f64;
    let evaluations =
        |sim: &beltrs::Simulation| sim.state.accepted_steps + sim.state.rejected_steps;
    let mut walls = Vec::new();
    let mut per_step = Vec::new();
    let mut attempts = 0;
    for _ in 0..repeats {
        let (t0, step0, acc0) = (Instant::now(), sim.state.step, evaluations(&sim));
        sim.step(steps).expect("steps");
        let wall = t0.elapsed().as_secs_f64();
        walls.push(wall);
        // Steps the integrator took: the model's steps (central differences), or RKF45's
        // accepted and rejected attempts.
        let taken = if integrator == "rkf45" {
            evaluations(&sim) - acc0
        } else {
            sim.state.step - step0
        };
        attempts += taken;
        per_step.push(wall / (elements * taken.max(1) as f64) * 1e9);
    }
    walls.sort_by(f64::total_cmp);
    per_step.sort_by(f64::total_cmp);
    let fingerprint = common::fingerprint(
        common::node_values(&sim)
            .chain(sim.state.body_angle.iter().copied())
            .chain(sim.state.body_spin.iter().copied())
            .chain(sim.state.pulley_omega.iter().copied())
            .chain(sim.state.creep.iter().copied()),
    );
    if std::env::var_os("RIGID_LOOP_PROFILE").is_some() {
        common::print_stage_profile(&mut sim, steps, elements * steps as f64, "element-step");
    }
    let m = repeats / 2;
    println!(
        "{path} ({:?}, {} elements, {integrator}): {steps} steps x {repeats} ({attempts} steps taken): {:.2} ns per element-step best, {:.2} median ({:.3e} element-steps/s best, per {} step); wall {:.3} s median; state fingerprint {fingerprint:016x}",
        sim.model.scene.belt.formulation,
        sim.model.elements,
        per_step[0],
        per_step[m],
        1e9 / per_step[0],
        if integrator == "rkf45" { "attempted RKF45" } else { "model" },
        walls[m],
    );
}
