//! The rigid-body belt (Kubas 2014, Guo & Wang 2020) in the engine, Kubas's nonlinear
//! contact, and the adaptive RKF45 integrator on the whole state.
use beltrs::checkpoint;
use beltrs::contact::nonlinear::NonlinearContact;
use beltrs::record::Channels;
use beltrs::scene::{
    BeltParams, DriveSpec, Formulation, FrictionModel, IntegratorKind, PulleySpec, Scene, Table,
};
use beltrs::{BeltError, Simulation};

/// A small two-pulley drive: R = 0.05 m, centres 0.3 m apart, EA = 2e4 N, 0.1 kg/m, 60
/// elements/bodies, the belt 1 % shorter than its path, no gravity.
fn drive_scene(formulation: Formulation) -> Scene {
    let pulley = |name: &str, x: f64| PulleySpec {
        name: name.into(),
        center: [x, 0.0],
        radius: 0.05,
        mass: 1.0,
        inertia: Some(1e-3),
        contact_stiffness: 1e7,
        ..Default::default()
    };
    let path = 2.0 * 0.3 + std::f64::consts::TAU * 0.05;
    Scene {
        belt: BeltParams {
            formulation,
            axial_stiffness: 2e4,
            mass_per_length: 0.1,
            bending_stiffness: 1e-4,
            damping_ratio: 0.1,
            length: Some(path / 1.01),
            elements: Some(60),
            ..Default::default()
        },
        pulleys: vec![pulley("a", 0.0), pulley("b", 0.3)],
        gravity: 0.0,
        ..Default::default()
    }
}

/// Kubas's nonlinear contact (case K's stiffnesses) with damping `b` on every pulley.
fn kubas_contact(scene: &mut Scene, b: f64) {
    for p in &mut scene.pulleys {
        p.contact_stiffness = PulleySpec::default().contact_stiffness;
        p.nonlinear_contact = Some(NonlinearContact {
            damping: b,
            ..Default::default()
        });
    }
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len() as f64
}

/// Mean static tension (relaxed, frictionless) of `drive_scene` with `n` elements, and
/// the continuum's: EA·(path/L − 1) less the path the contact sinks into the pulleys.
fn static_tension(f: Formulation, n: usize) -> (f64, f64, f64) {
    let mut scene = drive_scene(f);
    scene.belt.elements = Some(n);
    let mut sim = Simulation::new(&scene).unwrap();
    let report = sim.stabilise(&Default::default()).unwrap();
    assert!(report.converged, "{f:?}: {report:?}");
    let t = sim.tensions().to_vec();
    let m = mean(&t);
    let spread = t.iter().map(|x| (x - m).abs()).fold(0.0, f64::max);
    let (ea, l, r, k) = (2e4, scene.belt.length.unwrap(), 0.05, 1e7);
    let path = 2.0 * 0.3 + std::f64::consts::TAU * r;
    // Each point on an arc carries N = T·(l/R) and sinks N/k into its pulley.
    let sink = m * (l / n as f64) / r / k;
    let continuum = ea * ((path - std::f64::consts::TAU * sink) / l - 1.0);
    (m, spread, continuum)
}

#[test]
fn rigid_and_node_belts_relax_to_the_continuum_tension_at_second_order() {
    // Frictionless and weightless: one tension everywhere (joints on the arcs included).
    // On an arc the node belt is the inscribed polygon of its nodes (shorter than the arc
    // by θ²/24 per element of arc angle θ): its static tension is low, converging to the
    // continuum's EA·strain at second order in θ. The rigid bodies rest on the pulleys
    // with their ends, their mass centres at ρ = (l/2)·cot(θ/2) (`belt::rigid::contact`),
    // where their polygon holds exactly the arc's length: no θ² term of that kind is
    // left. Measured (60, 120 bodies): node −14 %, −3.4 % (order 2.03); rigid +0.48 %,
    // +0.095 % (order 2.35; with the contact at the mass centres on the rim the rigid
    // error was the circumscribed polygon's θ²/12, about twice the node belt's).
    let mut errors = Vec::new();
    for f in [Formulation::NodeKelvinVoigt, Formulation::RigidBody] {
        let mut e = Vec::new();
        for n in [60, 120] {
            let (t, spread, continuum) = static_tension(f, n);
            assert!(spread < 5e-3 * t, "{f:?}, {n}: spread {spread} of {t}");
            e.push((t - continuum) / continuum);
        }
        let order = (e[0] / e[1]).log2();
        if f == Formulation::NodeKelvinVoigt {
            assert!(
                (order - 2.0).abs() < 0.3,
                "{f:?}: errors {e:?}, order {order}"
            );
        } else {
            // At least second order, and far below the node belt's error.
            assert!(order > 1.8, "{f:?}: errors {e:?}, order {order}");
        }
        errors.push(e);
    }
    assert!(errors[0][0] < 0.0, "{errors:?}");
    for k in 0..2 {
        assert!(errors[1][k].abs() < 0.1 * errors[0][k].abs(), "{errors:?}");
    }
}

#[test]
fn rigid_stage_forces_are_minus_the_energy_gradient() {
    // Every spring of the rigid chain and of Kubas's contact is conservative without its
    // damping: the forces the stages apply must be −∂E/∂x of the energies the recorder
    // reports (strain, bending, contact), here by central differences on body positions.
    let mut scene = drive_scene(Formulation::RigidBody);
    scene.belt.damping_ratio = 0.0;
    kubas_contact(&mut scene, 0.0);
    let mut sim = Simulation::new(&scene).unwrap();
    // Move into a general state: a few steps of free motion.
    sim.step(200).unwrap();
    let energy = |sim: &mut Simulation| {
        let e = sim.current_energies();
        e.strain + e.bending + e.contact
    };
    let forces = sim.forces().to_vec();
    let h = 1e-8;
    let mut checked = 0;
    for i in (0..sim.model.nodes).step_by(7) {
        for axis in 0..2 {
            let x0 = sim.state.position[i][axis];
            sim.state.position[i][axis] = x0 + h;
            let ep = energy(&mut sim);
            sim.state.position[i][axis] = x0 - h;
            let em = energy(&mut sim);
            sim.state.position[i][axis] = x0;
            let numeric = -(ep - em) / (2.0 * h);
            let f = forces[i][axis];
            let scale = f.abs().max(1.0);
            assert!(
                (numeric - f).abs() < 2e-3 * scale,
                "body {i} axis {axis}: force {f}, −dE/dx {numeric}"
            );
            checked += 1;
        }
    }
    assert!(checked > 10);
}

#[test]
fn rkf45_matches_central_differences_and_conserves_energy() {
    // Undamped, frictionless: the belt starts on the path (mass centres on the rims) and
    // sinks into Kubas's contact, oscillating. RKF45 at its default tolerances keeps the
    // energy; central differences agree with it.
    let mut scene = drive_scene(Formulation::RigidBody);
    scene.belt.damping_ratio = 0.0;
    kubas_contact(&mut scene, 0.0);
    let end = 2e-3;
    let mut rk_scene = scene.clone();
    rk_scene.solver.integrator = IntegratorKind::Rkf45;
    let mut rk = Simulation::new(&rk_scene).unwrap();
    let e0 = rk.current_energies().total();
    rk.advance_to(end, u64::MAX).unwrap();
    assert_eq!(rk.state.time, end);
    assert!(rk.state.accepted_steps > 10, "{}", rk.state.accepted_steps);
    let e1 = rk.current_energies().total();
    assert!(e0 > 0.0);
    // Measured 8·10⁻⁷ at the default rtol = 10⁻⁸ (1.8·10⁻⁴ at 10⁻⁶).
    assert!((e1 - e0).abs() < 1e-5 * e0, "energy {e0} → {e1}");
    // Central differences converge to it at second order: the run is dominated by the
    // high-frequency ringing of a belt released unbalanced (undamped), so the largest
    // joint-tension difference is the measure (234 N at 0.5 of the stable step).
    let tr = rk.tensions().to_vec();
    let difference = |fraction: f64| {
        let mut sc = scene.clone();
        sc.solver.time_step_fraction = fraction;
        let mut c = Simulation::new(&sc).unwrap();
        c.advance_to(end, u64::MAX).unwrap();
        let tc = c.tensions().to_vec();
        tc.iter()
            .zip(&tr)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    };
    let (coarse, fine) = (difference(0.1), difference(0.02));
    assert!(fine < 0.02 * mean(&tr), "{fine} of {}", mean(&tr));
    assert!(coarse / fine > 8.0, "{coarse} → {fine}");
}

#[test]
fn rkf45_resumes_from_a_checkpoint_bit_for_bit() {
    let mut scene = drive_scene(Formulation::RigidBody);
    scene.solver.integrator = IntegratorKind::Rkf45;
    scene.pulleys[0].drive = Some(DriveSpec {
        torque: Table {
            x: vec![0.0, 1e-3],
            y: vec![0.0, 0.5],
        },
        ..Default::default()
    });
    let dir = std::env::temp_dir().join(format!("beltrs-rk-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("rk.ck");
    let mut a = Simulation::new(&scene).unwrap();
    a.advance_to(1e-3, u64::MAX).unwrap();
    // Stop in the middle of a stretch (a step count, not a time).
    a.advance_to(2e-3, 37).unwrap();
    checkpoint::save(&a, &path).unwrap();
    let mut b = checkpoint::load(&path).unwrap();
    assert_eq!(b.state, a.state);
    assert!(a.state.adaptive_step > 0.0);
    for sim in [&mut a, &mut b] {
        sim.begin_recording(Channels::default(), 5, usize::MAX);
        assert!(sim.advance_to(3e-3, u64::MAX).unwrap());
        sim.end_recording().unwrap();
    }
    assert!(a.state.rejected_steps + a.state.accepted_steps > 50);
    assert!(a.state.drive_work != 0.0);
    assert_eq!(a.recording, b.recording);
    assert_eq!(a.state, b.state);
    // The recording lands on its time grid: every 5 model steps of time.
    let unit = 5.0 * a.model.dt;
    for (k, t) in a
        .recording
        .time
        .iter()
        .enumerate()
        .take(a.recording.len() - 1)
    {
        let want = a.recording.time[0] + k as f64 * unit;
        assert!((t - want).abs() < 1e-12, "sample {k} at {t}, grid {want}");
    }
    assert_eq!(*a.recording.time.last().unwrap(), 3e-3);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn rkf45_refuses_fixed_step_effects_naming_the_field() {
    let mut scene = drive_scene(Formulation::RigidBody);
    scene.solver.integrator = IntegratorKind::Rkf45;
    scene.pulleys[1].friction = FrictionModel::StickForce {
        static_coefficient: 0.5,
        kinetic_coefficient: 0.4,
    };
    let Err(BeltError::InvalidParameter { field, rule, .. }) = Simulation::new(&scene) else {
        panic!("stick-force friction under RKF45 must be refused");
    };
    assert_eq!(field, "pulleys[1].friction.model");
    assert!(rule.contains("creep"), "{rule}");
    scene.pulleys[1].friction = FrictionModel::None;
    scene.solver.relative_tolerance = 0.0;
    let Err(BeltError::InvalidParameter { field, .. }) = Simulation::new(&scene) else {
        panic!("rtol 0 must be refused");
    };
    assert_eq!(field, "solver.relative_tolerance");
}

#[test]
fn nonlinear_contact_refuses_the_linear_laws_settings() {
    let mut scene = drive_scene(Formulation::NodeKelvinVoigt);
    scene.pulleys[0].nonlinear_contact = Some(NonlinearContact::default());
    // drive_scene sets a linear stiffness of 1e7: it would be silently unused.
    let Err(BeltError::InvalidParameter { field, .. }) = Simulation::new(&scene) else {
        panic!("a linear stiffness beside the nonlinear law must be refused");
    };
    assert_eq!(field, "pulleys[0].contact_stiffness");
    scene.pulleys[0].contact_stiffness = PulleySpec::default().contact_stiffness;
    scene.pulleys[0].contact_damping_ratio = Some(0.1);
    let Err(BeltError::InvalidParameter { field, .. }) = Simulation::new(&scene) else {
        panic!("a linear damping ratio beside the nonlinear law must be refused");
    };
    assert_eq!(field, "pulleys[0].contact_damping_ratio");
    scene.pulleys[0].contact_damping_ratio = None;
    // Works with the node belt too.
    let mut sim = Simulation::new(&scene).unwrap();
    assert!(sim.stabilise(&Default::default()).unwrap().converged);
    scene.belt.formulation = Formulation::RigidBody;
    scene.belt.tension_only = true;
    let Err(BeltError::InvalidParameter { field, .. }) = Simulation::new(&scene) else {
        panic!("tension_only with rigid bodies must be refused");
    };
    assert_eq!(field, "belt.tension_only");
}
