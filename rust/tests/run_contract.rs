//! The run contract in time: `run(duration)` ends at the start time plus `duration`
//! exactly (whole steps, then one shortened central-difference step) and samples there.
use beltrs::record::Channels;
use beltrs::scene::{BeltParams, DriveSpec, PulleySpec, Scene, Table};
use beltrs::Simulation;

const INERTIA: f64 = 4.0; // kg·m²
const DAMPING: f64 = 0.2; // N·m·s/rad: b/I = 0.05 1/s
const OMEGA0: f64 = 20.0; // rad/s

/// A free pulley (no belt contact) spinning down on its bearings, ω = ω0·e^(−b·t/I), so
/// its angle is θ(t) = ω0·(I/b)·(1 − e^(−b·t/I)).
fn spinning() -> Simulation {
    spinning_with(DAMPING, None)
}

/// The free pulley with bearing damping `damping` and, if given, a drive of constant
/// torque (N·m).
fn spinning_with(damping: f64, torque: Option<f64>) -> Simulation {
    let pulley = |center: [f64; 2]| PulleySpec {
        center,
        radius: 0.5,
        inertia: Some(INERTIA),
        ..Default::default()
    };
    let scene = Scene {
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
                drive: torque.map(|t| DriveSpec {
                    torque: Table::constant(t),
                    ..Default::default()
                }),
                ..pulley([5.0, 0.0])
            },
        ],
        gravity: 0.0,
        ..Default::default()
    };
    let mut sim = Simulation::new(&scene).unwrap();
    let rate = damping / INERTIA;
    sim.state.pulley_omega[1] = OMEGA0 * (0.5 * rate * sim.model.dt).exp();
    sim
}

fn exact_angle(t: f64) -> f64 {
    let rate = DAMPING / INERTIA;
    OMEGA0 / rate * (1.0 - (-rate * t).exp())
}

#[test]
fn a_run_ends_exactly_at_its_duration_and_samples_there() {
    let mut sim = spinning();
    let dt = sim.model.dt;
    // 2000.5 steps: whole steps, then a half step.
    let duration = 2000.5 * dt;
    let rec = sim.run(duration, 100.0 * dt, Channels::default()).unwrap();
    let last = *rec.time.last().unwrap();
    assert_eq!(last.to_bits(), duration.to_bits());
    assert_eq!(sim.state.time.to_bits(), duration.to_bits());
    // 0, 100, ..., 2000 steps on the grid, then the end.
    assert_eq!(sim.recording.len(), 22);
    // The angle at the end: a shortened step taken as a whole one would be off by about
    // ω0·Δt/2; the scheme's own error is far below 1 % of ω0·Δt here (b·t/I ≪ 1).
    let angle = sim.state.pulley_angle[1];
    let error = (angle - exact_angle(duration)).abs();
    assert!(
        error < 0.01 * OMEGA0 * dt,
        "angle error {error:e} rad, ω0·Δt = {:e}",
        OMEGA0 * dt
    );
    // The recorded speed at the end is ω(t) at the end time.
    let speed = *sim.recording.pulley_speed.last().unwrap();
    let exact = OMEGA0 * (-DAMPING / INERTIA * duration).exp();
    assert!((speed / exact - 1.0).abs() < 1e-6, "{speed} vs {exact}");
}

#[test]
fn a_run_continues_after_a_shortened_step_as_one_run_would() {
    let mut split = spinning();
    let dt = split.model.dt;
    split
        .run(700.25 * dt, 50.0 * dt, Channels::default())
        .unwrap();
    split
        .run(1300.5 * dt, 50.0 * dt, Channels::default())
        .unwrap();
    let mut whole = spinning();
    whole
        .run(2000.75 * dt, 50.0 * dt, Channels::default())
        .unwrap();
    let (a, b) = (split.state.pulley_angle[1], whole.state.pulley_angle[1]);
    assert!((a - b).abs() < 0.01 * OMEGA0 * dt, "{a} vs {b}");
    assert!((a - exact_angle(2000.75 * dt)).abs() < 0.01 * OMEGA0 * dt);
}

#[test]
fn a_duration_on_the_step_grid_takes_whole_steps_only() {
    let mut sim = spinning();
    let dt = sim.model.dt;
    sim.run(1000.0 * dt, 10.0 * dt, Channels::default())
        .unwrap();
    assert_eq!(sim.state.step, 1000);
    assert_eq!(sim.recording.len(), 101);
}

#[test]
fn shortened_steps_keep_a_constant_torque_spin_up_exact() {
    // A constant torque on a free pulley: ω = T·t/I, θ = T·t²/(2I). Central differences
    // are exact for it (linear ω at the half steps, midpoint rule for θ), and so must be a
    // run split at instants off the step grid: the shortened step and the return to
    // half-step speeds add no error. Without the return, the recorded end speed would be
    // off by (T/I)·(Δt − r)/2 and the next run's angle by that times its duration.
    let torque = 3.0;
    let mut sim = spinning_with(0.0, Some(torque));
    sim.state.pulley_omega[1] = -0.5 * torque / INERTIA * sim.model.dt;
    let dt = sim.model.dt;
    let alpha = torque / INERTIA;
    let mut end = 0.0;
    for duration in [700.25 * dt, 1300.5 * dt, 33.9 * dt] {
        sim.run(duration, 50.0 * dt, Channels::default()).unwrap();
        end += duration;
        let speed = *sim.recording.pulley_speed.last().unwrap();
        assert!(
            (speed - alpha * end).abs() < 1e-9 * alpha * end,
            "{speed} vs {}",
            alpha * end
        );
    }
    let angle = sim.state.pulley_angle[1];
    let exact = 0.5 * alpha * end * end;
    assert!((angle - exact).abs() < 1e-9 * exact, "{angle} vs {exact}");
}
