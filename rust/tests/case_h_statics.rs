//! Case H statics (reference-cases.md): both relaxation methods reach the same equilibrium.
use crate::common;

use beltrs::simulation::{Relaxation, StabiliseOptions};
use beltrs::Simulation;

#[test]
fn fire_and_kinetic_damping_reach_the_same_equilibrium() {
    let mut fire = Simulation::new(&common::case_h(89)).unwrap();
    let rep_fire = fire.stabilise(&StabiliseOptions::default()).unwrap();
    let mut kinetic = Simulation::new(&common::case_h(89)).unwrap();
    let rep_kinetic = kinetic
        .stabilise(&StabiliseOptions {
            method: Relaxation::KineticEnergy,
            ..Default::default()
        })
        .unwrap();
    assert!(
        rep_fire.converged && rep_kinetic.converged,
        "{rep_fire:?} {rep_kinetic:?}"
    );
    let (a, b) = (fire.state.takeup_travel[1], kinetic.state.takeup_travel[1]);
    // Both stop at a residual of 1e-7 of the largest tension; the takeup agrees to 1e-6.
    assert!((a - b).abs() < 1e-6 * a, "{a} vs {b}");
    // Reference displacement 3.128 m within 8 % at 89 elements (issue), overshooting the
    // exact continuum 3.1410 m because the chord polygon frees belt length.
    let exact_continuum = 3.140_955; // beltrs.analytic.two_pulley_takeup_statics()
    assert!(
        (a - 3.128).abs() < 0.08 * 3.128 && a > exact_continuum,
        "{a}"
    );
    // FIRE is the faster relaxation.
    assert!(
        rep_fire.steps * 10 < rep_kinetic.steps,
        "{rep_fire:?} {rep_kinetic:?}"
    );
    // Truly at rest: every velocity is zero on return.
    assert!(fire.state.velocity.iter().all(|v| v.norm() == 0.0));
}
