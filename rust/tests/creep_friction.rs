//! Creep friction (Kubas eq. 12–19) as an engine friction model: the per-pulley kernel with
//! and without the stick limit, the memory in the state, and an exact resume from a
//! checkpoint.

use crate::common::case_h;
use beltrs::checkpoint;
use beltrs::contact::PulleyContacts;
use beltrs::friction::creep::{
    pulley_creep_friction, CreepFriction, CreepPulley, MemoryColumn, DEFAULT_CREEP_LIMIT,
    DEFAULT_TRANSITION_SPEED,
};
use beltrs::model::Model;
use beltrs::scene::{DriveSpec, FrictionModel, Scene, Table};
use beltrs::Simulation;
use nalgebra::Vector2;

type V2 = Vector2<f64>;

const LAW: CreepFriction = CreepFriction {
    static_coefficient: 0.5,
    kinetic_coefficient: 0.4,
    transition_speed: 1e-3,
    creep_limit: 1e-4,
};

/// One belt point touching a pulley of radius 1 at the top (normal +y, tangent −x),
/// moving along x at `vx` with the pulley at rest.
fn one_contact(vx: f64, other: V2, dt: Option<f64>, creep: f64) -> (f64, Vec<(usize, f64)>) {
    let mut contacts = PulleyContacts::default();
    contacts.node.push(0);
    contacts.normal.push(V2::new(0.0, 1.0));
    contacts.normal_force.push(100.0);
    contacts.penetration.push(1e-6);
    let pulley = CreepPulley {
        radius: 1.0,
        inertia: f64::INFINITY,
        omega: 0.0,
        center_velocity: V2::zeros(),
    };
    let mut force = vec![other];
    let mut rates = Vec::new();
    let memory = [creep];
    pulley_creep_friction(
        &LAW,
        &contacts,
        &pulley,
        &[V2::new(vx, 0.0)],
        &[0.01],
        dt,
        &memory,
        MemoryColumn {
            stride: 1,
            column: 0,
        },
        &mut force,
        &mut rates,
        None,
    );
    // The friction force along the tangent t = (−1, 0).
    (-(force[0].x - other.x), rates)
}

#[test]
fn the_kernel_applies_the_law_as_it_is_without_a_step() {
    // Tangent t = Ẑ × n = (−1, 0): a point moving along +x has t·v = −vx, so the pulley
    // surface moves at +vx relative to it along t.
    for (vx, creep) in [
        (0.05, 0.0),
        (-0.05, 3e-5),
        (2e-4, 5e-5),
        (-4e-4, -2e-4),
        (0.0, 7e-5),
    ] {
        let (f, rates) = one_contact(vx, V2::zeros(), None, creep);
        let speed = vx;
        assert_eq!(
            f,
            LAW.coefficient(creep, speed) * 100.0,
            "vx {vx}, Δ {creep}"
        );
        assert_eq!(rates, vec![(0, LAW.creep_rate(creep, speed))]);
    }
    // Sliding: µk·N along the relative speed; in the creep range the spring of Δ.
    assert_eq!(one_contact(0.05, V2::zeros(), None, 0.0).0, 40.0);
    assert_eq!(one_contact(0.0, V2::zeros(), None, 1e-4).0, 50.0);
}

#[test]
fn the_stick_limit_never_reverses_the_relative_speed() {
    // A small step: µk·N changes the point's speed by 40·1e-6/0.01 = 4 mm/s < 50 mm/s:
    // the law as it is.
    let (f, _) = one_contact(0.05, V2::zeros(), Some(1e-6), 0.0);
    assert_eq!(f, 40.0);
    // A step long enough to stop it: the stick force m·v/Δt instead (0.01·0.05/1e-3).
    let (f, rates) = one_contact(0.05, V2::zeros(), Some(1e-3), 0.0);
    assert!((f - 0.5).abs() < 1e-12, "{f}");
    assert_eq!(rates.len(), 1, "the memory still advances");
    // The other forces on the point counted: with 30 N pushing it along t (the way the
    // surface moves relative to it) the stick force is 0.5 − 30 N, within µs·N.
    let (f, _) = one_contact(0.05, V2::new(-30.0, 0.0), Some(1e-3), 0.0);
    assert!((f - (0.5 - 30.0)).abs() < 1e-12, "{f}");
    // Beyond µs·N the point slides with µk·N in the stick force's direction.
    let (f, _) = one_contact(0.05, V2::new(-80.0, 0.0), Some(1e-3), 0.0);
    assert_eq!(f, -40.0);
    // Quasi-static (an infinite step): the stick force, and no memory rates.
    let (f, rates) = one_contact(0.05, V2::new(-30.0, 0.0), Some(f64::INFINITY), 0.0);
    assert_eq!(f, -30.0);
    assert!(rates.is_empty());
}

#[test]
fn defaults_and_scene_rules() {
    assert_eq!(DEFAULT_TRANSITION_SPEED, 1e-3);
    assert_eq!(DEFAULT_CREEP_LIMIT, 1e-4);
    let mut scene = case_h(89);
    scene.pulleys[0].friction = FrictionModel::Creep(CreepFriction {
        transition_speed: -1.0,
        ..LAW
    });
    let err = Model::compile(&scene).unwrap_err().to_string();
    assert!(
        err.contains("pulleys[0].friction.transition_speed") && err.contains("> 0"),
        "{err}"
    );
    scene.pulleys[0].friction = FrictionModel::Creep(CreepFriction {
        kinetic_coefficient: 0.6,
        ..LAW
    });
    let err = Model::compile(&scene).unwrap_err().to_string();
    assert!(err.contains("pulleys[0].friction.kinetic"), "{err}");
}

/// Case H with creep friction on both pulleys and a drive torque that makes the belt
/// creep and slip.
fn creep_scene() -> Scene {
    let mut s = case_h(89);
    s.belt.damping_ratio = 0.02;
    for p in &mut s.pulleys {
        p.friction = FrictionModel::Creep(CreepFriction {
            static_coefficient: 0.3,
            kinetic_coefficient: 0.25,
            transition_speed: 1e-3,
            creep_limit: 1e-3,
        });
    }
    s.pulleys[0].drive = Some(DriveSpec {
        torque: Table {
            x: vec![0.0, 0.2, 10.0],
            y: vec![0.0, 4e5, 4e5],
        },
        ..Default::default()
    });
    s
}

#[test]
fn the_memory_lives_in_the_state_and_resumes_bit_for_bit() {
    let scene = creep_scene();
    let mut a = Simulation::new(&scene).unwrap();
    assert_eq!(a.state.creep.len(), a.model.nodes * 2);
    assert!(a.model.stages.iter().any(|s| s.name() == "pulley_friction"));
    a.step(600).unwrap();
    let held = a.state.creep.iter().filter(|d| **d != 0.0).count();
    assert!(held > 5, "only {held} contacts carry creep");
    // Only points on a pulley carry creep.
    for (k, &d) in a.state.creep.iter().enumerate() {
        let (i, j) = (k / 2, k % 2);
        if d != 0.0 {
            let c = a.state.pulley_center(&a.model, j);
            let r = (a.state.position[i] - c).norm();
            assert!(
                r < a.model.pulleys[j].radius + 1e-3,
                "point {i}, pulley {j}"
            );
        }
    }
    let dir = std::env::temp_dir().join(format!("beltrs-creep-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("creep.ck");
    checkpoint::save(&a, &path).unwrap();
    let mut b = checkpoint::load(&path).unwrap();
    assert_eq!(b.state, a.state);
    a.step(700).unwrap();
    b.step(700).unwrap();
    for (x, y) in a.state.creep.iter().zip(&b.state.creep) {
        assert_eq!(x.to_bits(), y.to_bits());
    }
    for (x, y) in a.state.position.iter().zip(&b.state.position) {
        assert_eq!(x.x.to_bits(), y.x.to_bits());
        assert_eq!(x.y.to_bits(), y.y.to_bits());
    }
    assert_eq!(a.state, b.state);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn switching_creep_friction_on_and_off_sizes_the_memory() {
    let mut scene = case_h(89);
    let mut sim = Simulation::new(&scene).unwrap();
    assert!(sim.state.creep.is_empty());
    scene.pulleys[1].friction = FrictionModel::Creep(LAW);
    sim.set_scene(&scene).unwrap();
    assert_eq!(sim.state.creep.len(), sim.model.nodes * 2);
    scene.pulleys[1].friction = FrictionModel::None;
    sim.set_scene(&scene).unwrap();
    assert!(sim.state.creep.is_empty());
}
