//! Scenes and helpers shared by the integration tests: case H, the drive test rigs (a free
//! pulley inertia, a two-pulley loop with friction), and the small helpers their tests
//! all use.
#![allow(dead_code)]

use beltrs::record::Channels;
use beltrs::scene::{BeltParams, DriveSpec, FrictionModel, PulleySpec, Scene, SolverParams};
use beltrs::{Simulation, StabiliseOptions, StartCurve, StartShape};
use std::f64::consts::PI;

/// Case H (reference-cases.md): Hustrulid's two-pulley vertical loop with a gravity takeup.
pub fn case_h(elements: usize) -> Scene {
    beltrs::presets::case_h(elements)
}

/// |got − want| ≤ tol, with a readable panic message.
pub fn close(what: &str, got: f64, want: f64, tol: f64) {
    assert!(
        (got - want).abs() <= tol,
        "{what}: got {got:e}, want {want:e} (diff {:e}, allowed {tol:e})",
        (got - want).abs()
    );
}

/// Record only the small per-pulley arrays (no tensions, positions or velocities).
pub const PER_PULLEY_ONLY: Channels = Channels {
    tension: false,
    node_position: false,
    node_velocity: false,
    energy: false,
    contact_forces: false,
};

/// The scene relaxed to static equilibrium (drives off): the belt at rest on its pulleys,
/// without the ringing that the placement on the path would start.
pub fn relaxed(scene: &Scene) -> Simulation {
    let mut sim = Simulation::new(scene).unwrap();
    let report = sim.stabilise(&StabiliseOptions::default()).unwrap();
    assert!(report.converged);
    sim
}

/// A free rigid inertia driven by `drive`: a 10 m two-pulley loop without gravity (belt
/// EA = 1 MN, 10 kg/m, `elements` elements; both pulleys of `radius` (m) and `inertia`
/// (kg·m²), contact 1e7 N/m) whose pulley 0 does not touch the belt (contact stiffness
/// 0), so that it turns alone; time step `dt` (s).
pub fn free_pulley(drive: DriveSpec, radius: f64, inertia: f64, elements: usize, dt: f64) -> Scene {
    let pulley = |center: [f64; 2]| PulleySpec {
        center,
        radius,
        inertia: Some(inertia),
        contact_stiffness: 1e7,
        ..Default::default()
    };
    Scene {
        belt: BeltParams {
            axial_stiffness: 1e6,
            mass_per_length: 10.0,
            elements: Some(elements),
            ..Default::default()
        },
        pulleys: vec![
            PulleySpec {
                contact_stiffness: 0.0,
                drive: Some(drive),
                ..pulley([0.0, 0.0])
            },
            pulley([10.0, 0.0]),
        ],
        gravity: 0.0,
        solver: SolverParams {
            time_step: Some(dt),
            ..Default::default()
        },
        ..Default::default()
    }
}

/// Radius of the pulleys of [`belt_loop`], m.
pub const LOOP_RADIUS: f64 = 1.0;
/// Inertia of the pulleys of [`belt_loop`], kg·m².
pub const LOOP_INERTIA: f64 = 50.0;
/// Belt mass per length of [`belt_loop`], kg/m.
pub const LOOP_RHO: f64 = 10.0;
/// Distance between the pulley centres of [`belt_loop`], m.
pub const LOOP_SPAN: f64 = 10.0;
/// Belt axial stiffness of [`belt_loop`], N.
pub const LOOP_EA: f64 = 1e6;

/// A horizontal 10 m two-pulley loop without gravity: pulleys of 1 m radius, 100 kg and
/// 50 kg·m², contact 1e7 N/m, with belt friction `friction` (pulley 0, pulley 1); 240
/// elements (6.3° each on the wraps, so the polygon's chordal speed ripple is 0.15 %),
/// EA = 1 MN, 10 kg/m, the belt 0.5 % shorter than its path (about 5 kN of pretension).
/// Pulley 0 carries `drive`.
pub fn belt_loop(drive: DriveSpec, friction: [FrictionModel; 2]) -> Scene {
    let path = 2.0 * LOOP_SPAN + 2.0 * PI * LOOP_RADIUS;
    let pulley = |center: [f64; 2], friction: FrictionModel| PulleySpec {
        center,
        radius: LOOP_RADIUS,
        mass: 100.0,
        inertia: Some(LOOP_INERTIA),
        contact_stiffness: 1e7,
        friction,
        ..Default::default()
    };
    let [f0, f1] = friction;
    Scene {
        belt: BeltParams {
            axial_stiffness: LOOP_EA,
            mass_per_length: LOOP_RHO,
            length: Some(path * 0.995),
            elements: Some(240),
            ..Default::default()
        },
        pulleys: vec![
            PulleySpec {
                drive: Some(drive),
                ..pulley([0.0, 0.0], f0)
            },
            pulley([LOOP_SPAN, 0.0], f1),
        ],
        gravity: 0.0,
        ..Default::default()
    }
}

/// Belt friction µs = µk = 0.5 (stick-force).
pub fn grip() -> FrictionModel {
    FrictionModel::StickForce {
        static_coefficient: 0.5,
        kinetic_coefficient: 0.5,
    }
}

/// An ideal speed-controlled drive starting the belt of [`belt_loop`] to 2 m/s over 1 s
/// from t = 0.1 s with the ramp `shape`, within `max_torque` (N·m).
pub fn start_drive(shape: StartShape, max_torque: f64) -> DriveSpec {
    DriveSpec {
        start_curve: Some(StartCurve {
            shape,
            speed: 2.0,
            ramp: 1.0,
            start: 0.1,
            ..Default::default()
        }),
        max_torque,
        ..Default::default()
    }
}
