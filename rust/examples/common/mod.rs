//! What the timing examples (`step_loop`, `rigid_loop`) share: the state's fingerprint and
//! the per-stage profile of one more timed repeat.

use std::time::Instant;

use beltrs::Simulation;

/// Fingerprint of a run of values, bit for bit: a change that claims to leave the
/// arithmetic unchanged must leave it unchanged (FNV-like fold of the values' bits).
pub fn fingerprint(values: impl Iterator<Item = f64>) -> u64 {
    values.fold(0u64, |h, c| {
        (h ^ c.to_bits())
            .rotate_left(5)
            .wrapping_mul(0x100_0000_01b3)
    })
}

/// The node belt's state as values for [`fingerprint`]: positions, then velocities (x, y).
pub fn node_values(sim: &Simulation) -> impl Iterator<Item = f64> + '_ {
    sim.state
        .position
        .iter()
        .chain(&sim.state.velocity)
        .flat_map(|p| [p.x, p.y])
}

/// Steps `sim` `steps` more with the stage profiler on and prints each stage's time and
/// what lies outside the stages, in ns per `unit` (e.g. "node-step"): the wall divided by
/// `count` (points × steps).
pub fn print_stage_profile(sim: &mut Simulation, steps: u64, count: f64, unit: &str) {
    sim.set_profiling(true);
    let t0 = Instant::now();
    sim.step(steps).expect("steps");
    let wall = t0.elapsed().as_secs_f64();
    let profile = sim.profile.clone().unwrap_or_default();
    let scale = 1e9 / count;
    for (stage, t) in sim.model.stages.iter().zip(&profile) {
        println!("  {:>18}: {:.2} ns per {unit}", stage.name(), t * scale);
    }
    let staged: f64 = profile.iter().sum();
    println!(
        "  {:>18}: {:.2} ns per {unit}",
        "outside stages",
        (wall - staged) * scale
    );
}
