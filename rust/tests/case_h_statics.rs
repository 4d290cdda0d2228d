//! Case H statics (reference-cases.md): both relaxation methods reach the same equilibrium.
use crate::common;

use beltrs::scene::FrictionModel;
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

/// Thesis §6.3 / fig. 6.6 (reference case H check 4): stabilising with friction on locks
/// in lower tensions around the pulleys, because the belt on the arcs sticks while the
/// takeup is still pulling the strands tight. The result is a frictional equilibrium: at
/// rest, every node in balance, and every contact inside its friction cone.
#[test]
fn stabilising_with_friction_locks_in_lower_tensions() {
    let mut frictionless = Simulation::new(&common::case_h(89)).unwrap();
    frictionless
        .stabilise(&StabiliseOptions::default())
        .unwrap();
    let reference = frictionless.tensions().to_vec();

    let mut scene = common::case_h(89);
    for p in &mut scene.pulleys {
        p.friction = FrictionModel::StickForce {
            static_coefficient: 0.3,
            kinetic_coefficient: 0.25,
        };
    }
    let mut sim = Simulation::new(&scene).unwrap();
    let rep = sim
        .stabilise(&StabiliseOptions {
            friction: true,
            ..Default::default()
        })
        .unwrap();
    assert!(rep.converged, "{rep:?}");
    let tension = sim.tensions().to_vec();
    // Every node in contact with a pulley sticks: at rest, no contact may need more than
    // µs·N (the friction solve reports how many slip when the belt is held still).
    assert_eq!(sim.slipping_contacts(), 0);
    // The strands between the pulleys carry the same tensions as without friction only
    // where no friction acts; on the arcs the tension drops below both tangent values.
    // Elements on the takeup arc: both end nodes below the pulley centre.
    let centre = sim.state.pulley_center(&sim.model, 1);
    let n = sim.model.nodes;
    let arc: Vec<usize> = (0..n)
        .filter(|&e| {
            let (a, b) = (sim.state.position[e], sim.state.position[(e + 1) % n]);
            a.y < centre.y && b.y < centre.y
        })
        .collect();
    assert!(arc.len() >= 4, "{arc:?}");
    let min_over = |t: &[f64]| arc.iter().map(|&e| t[e]).fold(f64::INFINITY, f64::min);
    let max_over = |t: &[f64]| arc.iter().map(|&e| t[e]).fold(0.0, f64::max);
    let (lower_ref, lower) = (min_over(&reference), min_over(&tension));
    assert!(
        lower < 0.8 * lower_ref,
        "arc minimum {lower} N vs frictionless {lower_ref} N"
    );
    // Frictionless arc tension is uniform to within the chord-polygon steps (< 2 %).
    let lower_ref_max = max_over(&reference);
    assert!(
        lower_ref_max < 1.02 * lower_ref,
        "{lower_ref_max} {lower_ref}"
    );
    // Equilibrium of the takeup still holds: the belt carries (counterweight + pulley)·g
    // in its two strands, whatever friction locked in on the arcs.
    let w = (30_000.0 + 600.0) * 9.81;
    let f = sim.takeup_force(1);
    assert!((f - w).abs() < 1e-6 * w, "{f} vs {w}");
}

/// Axial and contact damping do not change the equilibrium, and the relaxation must not
/// apply them on its fictitious masses (where an explicit damper can be unstable: before
/// the fix a 20 % damping ratio diverged within 1000 relaxation steps).
#[test]
fn damping_does_not_change_or_upset_the_relaxation() {
    let mut plain = Simulation::new(&common::case_h(89)).unwrap();
    plain.stabilise(&StabiliseOptions::default()).unwrap();
    let mut scene = common::case_h(89);
    scene.belt.damping_ratio = 0.2;
    for p in &mut scene.pulleys {
        p.contact_damping = Some(1e5);
    }
    let mut damped = Simulation::new(&scene).unwrap();
    let rep = damped.stabilise(&StabiliseOptions::default()).unwrap();
    assert!(rep.converged, "{rep:?}");
    let (a, b) = (plain.state.takeup_travel[1], damped.state.takeup_travel[1]);
    // Both relax to 1e-7 of the largest tension: the takeups agree to 1e-6 relative.
    assert!((a - b).abs() < 1e-6 * a, "{a} vs {b}");
}
