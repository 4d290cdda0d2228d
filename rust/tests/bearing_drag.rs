//! Bearing drag −b·ω (drives/bearing.rs): the exponential spin-down of a free pulley.
use beltrs::scene::{BeltParams, PulleySpec, Scene};
use beltrs::{Simulation, Stage};

const INERTIA: f64 = 4.0; // kg·m²
const DAMPING: f64 = 2.0; // N·m·s/rad: b/I = 0.5 1/s

/// A belt loop round two pulleys without gravity, at rest and unstrained. Pulley 1 does not
/// touch the belt (contact stiffness 0): it turns on its bearings alone.
fn free_pulley(damping: f64) -> Scene {
    let pulley = |center: [f64; 2]| PulleySpec {
        center,
        radius: 0.5,
        inertia: Some(INERTIA),
        ..Default::default()
    };
    Scene {
        belt: BeltParams {
            axial_stiffness: 1e6,
            mass_per_length: 10.0,
            elements: Some(100),
            ..Default::default()
        },
        pulleys: vec![
            pulley([0.0, 0.0]),
            PulleySpec {
                contact_stiffness: 0.0,
                bearing_damping: damping,
                ..pulley([5.0, 0.0])
            },
        ],
        gravity: 0.0,
        ..Default::default()
    }
}

#[test]
fn a_free_pulley_spins_down_exponentially() {
    let mut sim = Simulation::new(&free_pulley(DAMPING)).unwrap();
    assert!(sim.model.has_stage(Stage::BearingDrag));
    let dt = sim.model.dt;
    let (omega0, rate) = (10.0, DAMPING / INERTIA);
    // Central differences keep ω at the half step: start from ω(−Δt/2) on the exact curve.
    sim.state.pulley_omega[1] = omega0 * (0.5 * rate * dt).exp();
    sim.state.pulley_omega[0] = 3.0;
    let steps = (2.0 / dt).round() as u64;
    sim.step(steps).unwrap();
    let t_half = sim.state.time - 0.5 * dt;
    let exact = omega0 * (-rate * t_half).exp();
    let error = sim.state.pulley_omega[1] / exact - 1.0;
    // Explicit drag decays by (1 − h) per step, h = b·Δt/I, against e^(−h): the log error
    // per step is h²/2 + O(h³), so after N steps it is N·h²/2 = (b·t/I)·h/2. Allow twice.
    let h = rate * dt;
    let bound = rate * t_half * h;
    assert!(error.abs() < bound, "relative error {error:e} > {bound:e}");
    // ω(2 s) = ω0·e^(−1): the pulley lost 63 % of its speed.
    assert!((sim.state.pulley_omega[1] / omega0 - (-1.0f64).exp()).abs() < 1e-3);
    // The other pulley has no drag and no belt force: it keeps its speed exactly.
    assert_eq!(sim.state.pulley_omega[0], 3.0);
}

#[test]
fn no_bearing_damping_compiles_no_stage() {
    let sim = Simulation::new(&free_pulley(0.0)).unwrap();
    assert!(!sim.model.has_stage(Stage::BearingDrag));
    let names: Vec<_> = sim.model.stages.iter().map(|s| s.name()).collect();
    assert!(!names.contains(&"bearing_drag"), "{names:?}");
}

#[test]
fn a_huge_bearing_damping_bounds_the_stable_step() {
    // b·Δt/I must stay below 1 (a drag never reverses the spin): with b = 1e9 the bearing,
    // not the belt, sets the step.
    let sim = Simulation::new(&free_pulley(1e9)).unwrap();
    assert!(sim.model.dt_limit <= INERTIA / 1e9);
    assert!(
        sim.model.dt_cause.contains("bearing damping"),
        "{}",
        sim.model.dt_cause
    );
}
