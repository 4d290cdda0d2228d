//! Case H statics against the exact continuum answers (reference-cases.md).
use crate::common;

use beltrs::simulation::{Relaxation, StabiliseOptions};
use beltrs::Simulation;

#[test]
fn case_h_static_tensions_and_takeup() {
    let mut sim = Simulation::new(&common::case_h(89)).unwrap();
    let t0 = std::time::Instant::now();
    let rep = sim.stabilise(&StabiliseOptions::default()).unwrap();
    let wall = t0.elapsed();
    let t = sim.tensions().to_vec();
    let tmax = t.iter().cloned().fold(f64::MIN, f64::max);
    let tmin = t.iter().cloned().fold(f64::MAX, f64::min);
    eprintln!(
        "{rep:?} wall {wall:?} dt {} limit {} ({})",
        sim.model.dt, sim.model.dt_limit, sim.model.dt_cause
    );
    eprintln!(
        "travel {} tmin {tmin} tmax {tmax}",
        sim.state.takeup_travel[1]
    );
    let mut sim2 = Simulation::new(&common::case_h(89)).unwrap();
    let rep2 = sim2
        .stabilise(&StabiliseOptions {
            method: Relaxation::KineticEnergy,
            ..Default::default()
        })
        .unwrap();
    eprintln!("KE {rep2:?} travel {}", sim2.state.takeup_travel[1]);
    assert!(rep.converged);
}
