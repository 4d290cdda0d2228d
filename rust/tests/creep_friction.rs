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
use beltrs::record::Channels;
use beltrs::scene::{
    BeltParams, DriveSpec, Formulation, FrictionModel, IntegratorKind, PulleyContact, PulleySpec,
    Scene, Table,
};
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

// ------------------------------------------------------------------ creep under RKF45

/// A small rigid-body drive (R = 0.05 m, centres 0.3 m apart, EA = 2e4 N, 0.1 kg/m, 60
/// bodies, 1 % short, no gravity) with creep friction on both pulleys: a torque rising to
/// `torque` N·m over 2 ms on "a", a viscous resistance on "b".
fn creep_drive(integrator: IntegratorKind, torque: f64, dv: f64) -> Scene {
    let law = CreepFriction {
        static_coefficient: 0.5,
        kinetic_coefficient: 0.4,
        transition_speed: dv,
        creep_limit: 1e-4,
    };
    let pulley = |name: &str, x: f64, drive: DriveSpec| PulleySpec {
        name: name.into(),
        center: [x, 0.0],
        radius: 0.05,
        mass: 1.0,
        inertia: Some(1e-3),
        contact_stiffness: 1e7,
        friction: FrictionModel::Creep(law),
        drive: Some(drive),
        ..Default::default()
    };
    let path = 2.0 * 0.3 + std::f64::consts::TAU * 0.05;
    let mut scene = Scene {
        belt: BeltParams {
            formulation: Formulation::RigidBody,
            axial_stiffness: 2e4,
            mass_per_length: 0.1,
            bending_stiffness: 1e-4,
            damping_ratio: 0.1,
            length: Some(path / 1.01),
            elements: Some(60),
            ..Default::default()
        },
        pulleys: vec![
            pulley(
                "a",
                0.0,
                DriveSpec {
                    torque: Table {
                        x: vec![0.0, 2e-3],
                        y: vec![0.0, torque],
                    },
                    ..Default::default()
                },
            ),
            pulley(
                "b",
                0.3,
                DriveSpec {
                    viscous: 0.05,
                    ..Default::default()
                },
            ),
        ],
        gravity: 0.0,
        ..Default::default()
    };
    scene.solver.integrator = integrator;
    scene
}

/// Checks on the creep memory of a simulation: only points on a pulley carry creep, and
/// never beyond ±Δmax. Returns (pairs with creep, pairs held at ±Δmax).
fn memory_census(sim: &Simulation) -> (usize, usize) {
    let stride = sim.model.pulleys.len();
    let (mut live, mut held) = (0, 0);
    for (k, &d) in sim.state.creep.iter().enumerate() {
        if d == 0.0 {
            continue;
        }
        let (i, j) = (k / stride, k % stride);
        let FrictionModel::Creep(law) = sim.model.pulleys[j].friction else {
            panic!("creep at pulley {j} without creep friction");
        };
        assert!(d.abs() <= law.creep_limit, "point {i}, pulley {j}: Δ = {d}");
        let r = (sim.state.position[i] - sim.state.pulley_center(&sim.model, j)).norm();
        assert!(
            r < sim.model.pulleys[j].radius,
            "point {i}, pulley {j} at r = {r}"
        );
        live += 1;
        held += usize::from(d.abs() == law.creep_limit);
    }
    (live, held)
}

#[test]
fn rkf45_integrates_the_creep_memory_and_resumes_bit_for_bit() {
    let scene = creep_drive(IntegratorKind::Rkf45, 0.4, 1e-2);
    let mut a = Simulation::new(&scene).unwrap();
    assert_eq!(a.state.creep.len(), 2 * a.model.nodes);
    a.advance_to(2e-3, u64::MAX).unwrap();
    // Stop within a stretch (a step count, not a time).
    a.advance_to(4e-3, 40).unwrap();
    let (live, _) = memory_census(&a);
    assert!(live > 5, "only {live} contacts carry creep");
    let dir = std::env::temp_dir().join(format!("beltrs-creeprk-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("creep.ck");
    checkpoint::save(&a, &path).unwrap();
    let mut b = checkpoint::load(&path).unwrap();
    assert_eq!(b.state, a.state);
    for sim in [&mut a, &mut b] {
        sim.begin_recording(Channels::default(), 5, usize::MAX);
        assert!(sim.advance_to(6e-3, u64::MAX).unwrap());
        sim.end_recording().unwrap();
    }
    assert_eq!(a.recording, b.recording);
    assert_eq!(a.state, b.state);
    for (x, y) in a.state.creep.iter().zip(&b.state.creep) {
        assert_eq!(x.to_bits(), y.to_bits());
    }
    let (live, _) = memory_census(&a);
    assert!(live > 5, "{live} live");
    assert!(a.state.accepted_steps > 100 && a.state.rejected_steps > 0);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn rkf45_and_central_differences_agree_with_creep_friction() {
    // Relaxed, then 6 ms with the torque ramped over 2 ms. With Δv = 10 mm/s the law's
    // damping (up to 1.5·µs·N/Δv ≈ 4700 N·s/m on bodies of 1.6 g) is resolved by central
    // differences at a tenth of their stable step and below, so both integrators solve
    // the same ODE and central differences converge to RKF45 as their step falls
    // (measured: 7.7·10⁻⁴, 8.4·10⁻⁵, 1.68·10⁻⁵, 8.4·10⁻⁶ and 4.2·10⁻⁶ of the pulley
    // speeds at 0.5, 0.1, 0.02, 0.01 and 0.005 of the stable step: first order, to the
    // RKF45 answer, which moves by 3·10⁻⁸ at tolerances of 10⁻¹⁰; with the bodies resting
    // on their ends (`belt::rigid::contact`) and the drums taking the contact's moment and
    // the friction's with the bodies' arms (session 13; 8.4·10⁻⁴, 8.4·10⁻⁵ and 1.69·10⁻⁵
    // without), whose turning on the drum is the fastest mode, 3k/m: at half the stable
    // step central differences resolve it least; 9·10⁻⁴, 1.1·10⁻⁴ and 2.3·10⁻⁵ with the
    // earlier contact at the mass centres; a tolerance of about twice that). Each run
    // relaxes on its own step, so the relaxed states must not depend on it: the drums'
    // contact moment given in the relaxation, where they are frictionless, turned them by
    // 0.013 rad at 0.5 of the stable step and 2·10⁻⁵ at 0.02, and the gap then stayed at
    // 5·10⁻⁵ whatever the step (session 12's 5.9·10⁻⁵). An unrelaxed start is no test:
    // the belt, 1 % short, bounces on the pulleys, and each separation resets a contact's
    // memory.
    let end = 6e-3;
    let run = |integrator, fraction: f64| {
        let mut scene = creep_drive(integrator, 0.4, 1e-2);
        scene.solver.time_step_fraction = fraction;
        let mut sim = Simulation::new(&scene).unwrap();
        assert!(sim.stabilise(&Default::default()).unwrap().converged);
        sim.advance_to(end, u64::MAX).unwrap();
        sim.state.pulley_omega.clone()
    };
    let rk = run(IntegratorKind::Rkf45, 0.5);
    assert!(rk[0] > 0.5 && rk[1] > 0.5, "{rk:?}");
    let gap = |w: &[f64]| {
        (0..2)
            .map(|j| (w[j] - rk[j]).abs() / rk[j])
            .fold(0.0, f64::max)
    };
    let gaps: Vec<f64> = [0.5, 0.1, 0.02]
        .iter()
        .map(|&f| gap(&run(IntegratorKind::CentralDifference, f)))
        .collect();
    assert!(gaps[2] < gaps[1] && gaps[1] < gaps[0], "{gaps:?}");
    assert!(gaps[0] < 8e-3 && gaps[2] < 5e-5, "{gaps:?}");
}

/// The contact of `one_contact` as an ODE: the point (0.01 kg, N = 100 N, the pulley at
/// rest) pulled along +x by `load(t)` N; state [x, vx, Δ]. The kernel applies the law as
/// it is (no step) and gives dΔ/dt.
fn block(load: &dyn Fn(f64) -> f64, t: f64, y: &[f64], dy: &mut [f64]) {
    let other = V2::new(load(t), 0.0);
    let (friction, rates) = one_contact(y[1], other, None, y[2]);
    dy[0] = y[1];
    // The friction force is along t = (−1, 0).
    dy[1] = (other.x - friction) / 0.01;
    dy[2] = rates.first().map_or(0.0, |r| r.1);
}

/// The smooth step from `a` at `t0` to `b` at `t1`.
fn ramp(t: f64, t0: f64, a: f64, t1: f64, b: f64) -> f64 {
    beltrs::contact::nonlinear::cubic_step(t, t0, a, t1, b)
}

#[test]
fn under_rkf45_the_memory_is_the_creep_spring_the_limit_and_the_unwinding() {
    use beltrs::integrate::rkf45::{Rkf45, Rkf45Params};
    let (n, mu_s, mu_k, limit) = (100.0, 0.5, 0.4, 1e-4);
    // Load to half of µs·N over 20 ms and hold; at T1 to 1.2·µs·N over 10 ms (breakaway,
    // sliding); at T2 = T1 + 12 ms reverse to −½µs·N within 0.1 ms and hold until T3.
    // Below Δv the law is rate-dependent: a loaded contact creeps on at speeds of order Δv
    // until the creep part alone carries the load, over times of order Δmax/Δv = 0.1 s.
    const T1: f64 = 0.3;
    const T2: f64 = T1 + 0.012;
    const T3: f64 = T2 + 0.6;
    let load = |t: f64| {
        if t < T1 {
            ramp(t, 0.0, 0.0, 0.02, 0.5 * mu_s * n)
        } else if t < T2 {
            ramp(t, T1, 0.5 * mu_s * n, T1 + 0.01, 1.2 * mu_s * n)
        } else {
            ramp(t, T2, 1.2 * mu_s * n, T2 + 1e-4, -0.5 * mu_s * n)
        }
    };
    let mut f = |t: f64, y: &[f64], dy: &mut [f64]| block(&load, t, y, dy);
    let mut rk = Rkf45::new(
        Rkf45Params {
            relative_tolerance: 1e-8,
            absolute_tolerance: 1e-11,
            ..Default::default()
        },
        3,
    )
    .unwrap();
    let (mut t, mut y) = (0.0, [0.0, 0.0, 0.0]);
    // Step as the engine does (integrate::adaptive): after each accepted step Δ is put back
    // within ±Δmax (the stages may carry it past the limit; µ₁ is flat there).
    let mut advance = |rk: &mut Rkf45, t: &mut f64, y: &mut [f64; 3], to: f64, turn: &mut f64| {
        while *t < to {
            rk.step(t, y, to, &mut f).unwrap();
            y[2] = y[2].clamp(-limit, limit);
            *turn = turn.max(y[0]);
        }
    };
    let mut turn = f64::NEG_INFINITY;
    // 1. A creep spring: the memory is the displacement (the same rates, bit for bit), and
    //    at rest the creep part alone carries the load, µ₁(Δ)·N = F: Δ = Δmax/2.
    advance(&mut rk, &mut t, &mut y, T1, &mut turn);
    assert_eq!(y[2].to_bits(), y[0].to_bits());
    let settled = (y[2] - 0.5 * limit).abs();
    assert!(settled < 1e-3 * limit, "Δ = {}, off by {settled}", y[2]);
    // 2. Breakaway: the memory holds at Δmax while the point slides at µk·N.
    advance(&mut rk, &mut t, &mut y, T2 - 1e-3, &mut turn);
    let v0 = y[1];
    advance(&mut rk, &mut t, &mut y, T2, &mut turn);
    let accel = (y[1] - v0) / 1e-3;
    let want = (1.2 * mu_s - mu_k) * n / 0.01;
    assert!((accel - want).abs() < 1e-9 * want, "{accel} vs {want}");
    assert_eq!(y[2], limit);
    // 3. Reversed: the memory unwinds from Δmax at once (not from the slid distance), so
    //    the point comes back 1.5·Δmax from its turning point to rest at Δ = −Δmax/2.
    turn = y[0];
    advance(&mut rk, &mut t, &mut y, T3, &mut turn);
    let back = turn - y[0];
    assert!((y[2] + 0.5 * limit).abs() < 1e-3 * limit, "Δ = {}", y[2]);
    assert!(
        (back - 1.5 * limit).abs() < 1e-3 * limit,
        "came back {back}"
    );
}

// ------------------------------------------- angular momentum of the belt and its drums

#[test]
fn the_pulley_takes_the_creep_frictions_moment_with_each_contacts_arm() {
    // Two rigid bodies on a pulley of radius 1 (pulley at rest, sliding at µk·N): their
    // friction acts at their mass centres, whose arms about the centre are 0.9 and 1.1 m
    // (a body resting on the drum and one landing). The pulley's torque is the moment the
    // bodies receive, not the friction radius times the sum; a wrap joint's slide changes
    // the lever (the surface speed) and not the arm.
    let mut contacts = PulleyContacts::default();
    for (n, arm, lever) in [(V2::new(0.0, 1.0), 0.9, 0.9), (V2::new(1.0, 0.0), 1.1, 1.3)] {
        contacts.node.push(contacts.node.len());
        contacts.normal.push(n);
        contacts.normal_force.push(100.0);
        contacts.penetration.push(1e-6);
        contacts.arm.push(arm);
        contacts.lever.push(lever);
    }
    let pulley = CreepPulley {
        radius: 1.0,
        inertia: 1.0,
        omega: 0.0,
        center_velocity: V2::zeros(),
    };
    let v = [V2::new(0.05, 0.0), V2::new(0.0, -0.03)];
    let run = |contacts: &PulleyContacts| {
        let mut force = vec![V2::zeros(); 2];
        let out = pulley_creep_friction(
            &LAW,
            contacts,
            &pulley,
            &v,
            &[0.01, 0.01],
            None,
            &[0.0, 0.0],
            MemoryColumn {
                stride: 1,
                column: 0,
            },
            &mut force,
            &mut Vec::new(),
            None,
        );
        (out, force)
    };
    let (out, force) = run(&contacts);
    // Both slide at µk·N = 40 N against their motion along t = Ẑ × n.
    let f = [
        force[0].dot(&V2::new(-1.0, 0.0)),
        force[1].dot(&V2::new(0.0, 1.0)),
    ];
    assert_eq!(f, [40.0, 40.0]);
    assert_eq!(out.tangential, -80.0);
    assert_eq!(out.torque, -(0.9 * 40.0 + 1.1 * 40.0));
    // Without arms (nodes): the radius for each.
    contacts.arm.clear();
    contacts.lever.clear();
    assert_eq!(run(&contacts).0.torque, -80.0);
}

/// Angular momentum about the origin of the belt's bodies (translation and spin) and the
/// pulleys' rotation (their centres are fixed), kg·m²/s.
fn angular_momentum(sim: &Simulation) -> f64 {
    let (m, s) = (&sim.model, &sim.state);
    let pulleys: f64 = (0..m.pulleys.len())
        .map(|j| m.pulleys[j].inertia * s.pulley_omega[j])
        .sum();
    let bodies: f64 = (0..m.nodes)
        .map(|i| {
            let (x, v) = (s.position[i], s.velocity[i]);
            s.node_mass[i] * (x.x * v.y - x.y * v.x) + m.body_inertia[i] * s.body_spin[i]
        })
        .sum();
    pulleys + bodies
}

/// The drive of [`creep_drive`] with `friction` on both pulleys and `pulley_contact`,
/// undriven and without bearing drag, relaxed, its pulley "a" then set turning at 20
/// rad/s under the belt at rest: friction takes the belt along and it drags "b" up to
/// speed. Central
/// differences for `steps` steps; after each, the change of the angular momentum about
/// the origin less the moment of the only external forces (the bearings' reactions −F_j
/// at the pulleys' fixed centres c_j, F_j the belt's force on pulley j from the step's
/// evaluation). Returns the largest running imbalance over the run, over the initial
/// angular momentum.
///
/// Central differences keep angular momentum exactly, to rounding, under forces that do
/// (v(t + Δt/2) = v(t − Δt/2) + Δt·F(t)/m and x(t + Δt) = x(t) + Δt·v(t + Δt/2), so that
/// x(t + Δt) × v(t + Δt/2) = x(t) × v(t + Δt/2)): Σ m·x(t) × v(t − Δt/2) + I·ω(t − Δt/2)
/// changes in each step by exactly Δt times the moment of the forces of the evaluation at
/// x(t).
fn momentum_imbalance(friction: FrictionModel, pulley_contact: PulleyContact) -> f64 {
    let mut scene = creep_drive(IntegratorKind::CentralDifference, 0.0, 1e-2);
    scene.belt.pulley_contact = pulley_contact;
    for p in &mut scene.pulleys {
        p.drive = None;
        p.friction = friction;
    }
    let mut sim = Simulation::new(&scene).unwrap();
    assert!(sim.stabilise(&Default::default()).unwrap().converged);
    sim.state.pulley_omega[0] = 20.0;
    let channels = Channels {
        tension: false,
        node_position: false,
        node_velocity: false,
        ..Default::default()
    };
    sim.begin_recording(channels, 1, usize::MAX);
    let (dt, np) = (sim.model.dt, sim.model.pulleys.len());
    let centers: Vec<V2> = (0..np)
        .map(|j| sim.state.pulley_center(&sim.model, j))
        .collect();
    let l0 = angular_momentum(&sim);
    let (mut external, mut worst) = (0.0, 0.0_f64);
    for k in 0..20_000 {
        sim.advance(1).unwrap();
        let row = &sim.recording.pulley_force[2 * np * k..2 * np * (k + 1)];
        for (j, c) in centers.iter().enumerate() {
            let on_pulley = V2::new(row[2 * j], row[2 * j + 1]);
            // The bearing's reaction −F_j at c_j.
            external -= dt * (c.x * on_pulley.y - c.y * on_pulley.x);
        }
        worst = worst.max((angular_momentum(&sim) - l0 - external).abs());
    }
    // The belt has come up to speed: "b" turns.
    assert!(
        sim.state.pulley_omega[1] > 2.0,
        "{:?}",
        sim.state.pulley_omega
    );
    worst / l0
}

#[test]
fn belt_and_free_drums_keep_their_angular_momentum_under_creep_friction() {
    // Exactly, to rounding (measured 9.5e-15 with nodal contact, 3.7e-15 with wrap joints,
    // over 20 000 steps): the drums take the bodies' contact moment (l/2)(N_a − N_b)
    // (`Scratch::contact_torque`) and the creep friction's moment with the arms the
    // bodies receive it at (`PulleyContacts::arm`). Without the contact moment (main
    // before) the imbalance reached 0.13 of the initial angular momentum (nodal; 0.051
    // with wrap joints); with it but the friction radius for the friction's moment,
    // 2.6e-4 (nodal). A bound of 1e-10: rounding, with room.
    for contact in [PulleyContact::Nodes, PulleyContact::Wrap] {
        let imbalance = momentum_imbalance(FrictionModel::Creep(LAW), contact);
        assert!(imbalance < 1e-10, "{contact:?}: {imbalance:e}");
    }
}

#[test]
fn belt_and_free_drums_keep_their_angular_momentum_under_stick_force_friction() {
    // Exactly, to rounding (measured 8.8e-15 with nodal contact, 4.7e-15 with wrap joints,
    // over 20 000 steps): the drums take the contact moment, and the stick-force solve
    // gives each body's friction its own arm, in the drum's torque and in the coupling
    // (the drum's surface accelerates at lever·α under a body; `friction::mod`,
    // `release_slipping_arms`). With the friction radius ρ for all (main before) the
    // imbalance reached 3.1e-4 of the initial angular momentum (nodal; 3.3e-4 with wrap
    // joints); without the contact moment, 0.13 (nodal) and 0.052 (wrap joints). A bound
    // of 1e-10: rounding, with room.
    let friction = FrictionModel::StickForce {
        static_coefficient: 0.5,
        kinetic_coefficient: 0.4,
    };
    for contact in [PulleyContact::Nodes, PulleyContact::Wrap] {
        let imbalance = momentum_imbalance(friction, contact);
        assert!(imbalance < 1e-10, "{contact:?}: {imbalance:e}");
    }
}
