//! Bulk material loads and DIN 22101 running resistance at idlers.
use beltrs::contact::IdlerContact;
use beltrs::friction::running_resistance;
use beltrs::loads::{self, MassArrays};
use beltrs::model::{Model, Stage};
use beltrs::scene::{DriveSpec, IdlerSpec, LoadSpec, PulleySpec, Scene, Table, TakeupSpec};
use beltrs::Simulation;
use nalgebra::Vector2;

type V2 = Vector2<f64>;

const RADIUS: f64 = 0.4;
const LENGTH: f64 = 20.0;

/// A horizontal 20 m conveyor: head pulley at the origin, tail at (20, 0) on a horizontal
/// gravity takeup, the belt counter-clockwise (carry strand on top, running towards the
/// head), carry idlers every 1 m, material from near the tail to the head's top tangent.
fn conveyor(mass_per_length: f64, resistance: f64, torque: f64) -> Scene {
    let mut s = Scene::default();
    s.belt.axial_stiffness = 2e7;
    s.belt.mass_per_length = 20.0;
    s.belt.damping_ratio = 0.05;
    s.belt.elements = Some(220);
    s.pulleys.push(PulleySpec {
        name: "head".into(),
        center: [0.0, 0.0],
        radius: RADIUS,
        mass: 500.0,
        contact_stiffness: 1e8,
        friction: beltrs::scene::FrictionModel::StickForce {
            static_coefficient: 0.4,
            kinetic_coefficient: 0.35,
        },
        drive: (torque != 0.0).then(|| DriveSpec {
            torque: Table {
                x: vec![0.0, 0.5],
                y: vec![0.0, torque],
            },
            ..Default::default()
        }),
        ..Default::default()
    });
    s.pulleys.push(PulleySpec {
        name: "tail".into(),
        center: [LENGTH, 0.0],
        radius: RADIUS,
        mass: 500.0,
        contact_stiffness: 1e8,
        takeup: Some(TakeupSpec {
            counterweight: 500.0,
            direction: [1.0, 0.0],
            ..Default::default()
        }),
        ..Default::default()
    });
    let r = 0.0635;
    for k in 1..20 {
        for y in [RADIUS - r, -RADIUS - r] {
            s.idlers.push(IdlerSpec {
                center: [k as f64, y],
                radius: r,
                resistance,
                rotating_mass: 8.0,
                ..Default::default()
            });
        }
    }
    s.loads.push(LoadSpec {
        mass_per_length,
        start: [LENGTH - 0.5, RADIUS],
        end: [0.0, RADIUS],
    });
    s
}

/// Belt material on the nodes: their masses less the belt's, kg.
fn material(sim: &Simulation) -> f64 {
    sim.state
        .node_mass
        .iter()
        .zip(&sim.model.mass)
        .map(|(m, b)| m - b)
        .sum()
}

fn zone_length(sim: &Simulation) -> f64 {
    loads::zone_lengths(
        &sim.model.loads,
        &sim.state.load_edges,
        sim.model.load_belt(),
    )[0]
}

#[test]
fn stages_compile_only_when_used() {
    let with = Model::compile(&conveyor(50.0, 0.02, 0.0)).unwrap();
    assert_eq!(with.stages[0], Stage::Loads);
    assert!(with.has_stage(Stage::RunningResistance));
    let mut scene = conveyor(50.0, 0.0, 0.0);
    scene.loads.clear();
    let without = Model::compile(&scene).unwrap();
    assert!(!without.has_stage(Stage::Loads));
    assert!(!without.has_stage(Stage::RunningResistance));
}

/// One element along x from node 0 to node 1 touching an idler below it at its middle.
fn contact() -> IdlerContact {
    IdlerContact {
        active: true,
        element: 0,
        gamma: 0.5,
        normal: V2::new(0.0, 1.0),
        normal_force: 1000.0,
        penetration: 1e-5,
        ..Default::default()
    }
}

#[test]
fn resistance_holds_a_belt_at_rest_below_its_limit_and_slides_at_it_above() {
    // perp(normal) for the normal +y is −x, the tangent of the kernel.
    let limit = 0.02 * (1000.0 + 8.0 * 9.81);
    let mass = [10.0, 10.0];
    let dt = 1e-4;
    let v = [V2::zeros(); 2];
    // Below the limit: a net pull of 0.9 limit along +x is held, the nodes stay at rest.
    let mut force = [V2::new(0.45 * limit, 0.0), V2::new(0.45 * limit, 0.0)];
    let (f, sliding) = running_resistance(&contact(), limit, &v, &mass, dt, &mut force);
    assert!(!sliding);
    assert!((f.abs() - 0.9 * limit).abs() < 1e-12 * limit, "{f}");
    let total = force[0] + force[1];
    assert!(total.x.abs() < 1e-12 * limit, "net force {total}");
    // Above the limit: it slides and the resistance is exactly the limit, opposing.
    let mut force = [V2::new(0.75 * limit, 0.0), V2::new(0.75 * limit, 0.0)];
    let (f, sliding) = running_resistance(&contact(), limit, &v, &mass, dt, &mut force);
    assert!(sliding);
    assert_eq!(f.abs(), limit);
    let total = force[0] + force[1];
    assert!(
        (total.x - 0.5 * limit).abs() < 1e-12 * limit,
        "net force {total}"
    );
    // A moving belt with no other force: the resistance opposes the motion at the limit
    // (the stick force that would stop it in one step is far larger).
    let v = [V2::new(1.0, 0.0); 2];
    let mut force = [V2::zeros(); 2];
    let (_, sliding) = running_resistance(&contact(), limit, &v, &mass, dt, &mut force);
    assert!(sliding);
    assert!(((force[0] + force[1]).x + limit).abs() < 1e-12 * limit);
}

#[test]
fn a_drive_below_the_total_resistance_does_not_move_the_belt() {
    // Total resistance on the 38 idlers of the empty conveyor: f·(belt weight on idlers +
    // 38 rolls' weight) ≈ 0.1·(20·9.81·38 + 38·8·9.81) ≈ 1040 N, i.e. 420 N·m at the head.
    // 200 N·m stretches the belt and then is held: every node ends at rest.
    let mut scene = conveyor(0.0, 0.1, 200.0);
    scene.loads.clear();
    let mut sim = Simulation::new(&scene).unwrap();
    sim.stabilise(&Default::default()).unwrap();
    let dt = sim.model.dt;
    sim.step((3.0 / dt) as u64).unwrap();
    let fastest = sim
        .state
        .velocity
        .iter()
        .map(|v| v.norm())
        .fold(0.0, f64::max);
    // Without resistance the same torque accelerates the ~1.8 t of belt and pulleys at
    // ~0.3 m/s^2, ~1 m/s after 3 s; held, only damped elastic ringing remains.
    assert!(fastest < 2e-3, "fastest node {fastest} m/s");
    scene.idlers.iter_mut().for_each(|d| d.resistance = 0.0);
    let mut free = Simulation::new(&scene).unwrap();
    free.stabilise(&Default::default()).unwrap();
    free.step((3.0 / dt) as u64).unwrap();
    let head = free.state.pulley_omega[0].abs() * RADIUS;
    assert!(head > 0.3, "without resistance the belt runs at {head} m/s");
}

#[test]
fn material_on_the_nodes_equals_the_zone_while_the_belt_moves() {
    let m_l = 50.0;
    let mut sim = Simulation::new(&conveyor(m_l, 0.02, 1500.0)).unwrap();
    let z0 = sim.state.load_edges[0];
    // The zone runs from the loading point to the head's top tangent point: about 19.5 m.
    assert!(
        (zone_length(&sim) - 19.5).abs() < 0.05,
        "{}",
        zone_length(&sim)
    );
    let dt = sim.model.dt;
    for _ in 0..20 {
        sim.step((0.1 / dt) as u64).unwrap();
        let on_nodes = material(&sim);
        let zone = m_l * zone_length(&sim);
        // Rounding: sums of a few hundred masses of ~5 kg.
        assert!(
            (on_nodes - zone).abs() < 1e-9 * zone,
            "{on_nodes} vs {zone}"
        );
        let full = loads::node_masses(
            &sim.model.mass,
            &sim.model.loads,
            &sim.state.load_edges,
            sim.model.load_belt(),
        );
        // The incremental update equals a full recomputation bit for bit.
        assert_eq!(full, sim.state.node_mass);
    }
    // The belt has moved: the edges are elsewhere on the belt.
    let z1 = sim.state.load_edges[0];
    assert!((z1.start - z0.start).abs() > 0.5, "{z0:?} {z1:?}");
    assert!((z1.end - z0.end).abs() > 0.5, "{z0:?} {z1:?}");
}

/// The node masses of `model`'s belt with its loads, as placed.
fn placed_masses(model: &Model) -> Vec<f64> {
    let edges = loads::initial_edges(&model.loads, &model.initial_positions, model.load_belt());
    loads::node_masses(&model.mass, &model.loads, &edges, model.load_belt())
}

/// Move `model`'s loaded belt 0.3 element along itself (node i towards node i+1's place)
/// with velocities `v` (and, for rigid bodies, `bodies`) through `loads::update`: the node
/// masses before and after, and the integrator's masses and their inverses after.
fn move_loaded_belt(
    model: &Model,
    v: &mut [V2],
    bodies: Option<loads::Bodies<'_>>,
) -> (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>) {
    let belt = model.load_belt();
    let x0 = &model.initial_positions;
    let mut edges = loads::initial_edges(&model.loads, x0, belt);
    let before = placed_masses(model);
    let mut node_mass = before.clone();
    let mut mass = node_mass.clone();
    let mut inv_mass: Vec<f64> = mass.iter().map(|m| 1.0 / m).collect();
    let n = model.nodes;
    let x1: Vec<V2> = (0..n)
        .map(|i| x0[i] + (x0[(i + 1) % n] - x0[i]) * 0.3)
        .collect();
    loads::update(
        &model.loads,
        &model.mass,
        belt,
        &x1,
        v,
        &mut edges,
        &mut MassArrays {
            node_mass: &mut node_mass,
            inertia: Some((&mut mass, &mut inv_mass)),
            bodies,
        },
    );
    (before, node_mass, mass, inv_mass)
}

#[test]
fn a_node_gaining_material_keeps_its_momentum_and_one_losing_it_its_velocity() {
    let model = Model::compile(&conveyor(80.0, 0.0, 0.0)).unwrap();
    // Velocities that differ per node.
    let n = model.nodes;
    let v0: Vec<V2> = (0..n)
        .map(|i| V2::new(1.0 + 0.01 * i as f64, -0.5))
        .collect();
    let mut v = v0.clone();
    let (before, node_mass, mass, inv_mass) = move_loaded_belt(&model, &mut v, None);
    let (mut grew, mut shrank) = (0, 0);
    for i in 0..n {
        if node_mass[i] > before[i] {
            grew += 1;
            let p0 = v0[i] * before[i];
            let p1 = v[i] * node_mass[i];
            assert!(
                (p1 - p0).norm() < 1e-13 * p0.norm(),
                "node {i}: {p0} -> {p1}"
            );
        } else {
            if node_mass[i] < before[i] {
                shrank += 1;
            }
            assert_eq!(v[i], v0[i], "node {i}");
        }
        assert_eq!(mass[i], node_mass[i]);
        assert_eq!(inv_mass[i], 1.0 / node_mass[i]);
    }
    assert!(grew >= 1 && shrank >= 1, "grew {grew}, shrank {shrank}");
}

#[test]
fn a_rigid_body_gaining_material_keeps_its_momenta_and_turns_with_its_inertia() {
    let mut scene = conveyor(80.0, 0.0, 0.0);
    scene.belt.formulation = beltrs::scene::Formulation::RigidBody;
    let model = Model::compile(&scene).unwrap();
    assert!(model.is_rigid() && model.has_stage(Stage::Loads));
    let node_mass = placed_masses(&model);
    // The physical inertia at the start: m·l²/12 of each body with its material.
    let mut inertia = beltrs::integrate::Inertia::physical(&model, &node_mass).body_inertia;
    for i in 0..model.nodes {
        let l = model.rest_length[i];
        let expected = node_mass[i] * l * l / 12.0;
        assert!(
            (inertia[i] - expected).abs() <= 1e-12 * expected,
            "body {i}"
        );
    }
    let n = model.nodes;
    let mut v = vec![V2::new(1.0, -0.5); n];
    let spin0: Vec<f64> = (0..n).map(|i| 0.1 + 0.01 * i as f64).collect();
    let mut spin = spin0.clone();
    let inertia0 = inertia.clone();
    let bodies = loads::Bodies {
        belt_inertia: &model.body_inertia,
        inertia: &mut inertia,
        spin: &mut spin,
    };
    let (before, node_mass, _, _) = move_loaded_belt(&model, &mut v, Some(bodies));
    let (mut grew, mut shrank) = (0, 0);
    for i in 0..n {
        let l = model.rest_length[i];
        let expected = node_mass[i] * l * l / 12.0;
        assert!(
            (inertia[i] - expected).abs() <= 1e-12 * expected,
            "body {i}"
        );
        if node_mass[i] > before[i] {
            grew += 1;
            let (h0, h1) = (inertia0[i] * spin0[i], inertia[i] * spin[i]);
            assert!((h1 - h0).abs() < 1e-13 * h0.abs(), "body {i}: {h0} -> {h1}");
        } else {
            shrank += usize::from(node_mass[i] < before[i]);
            assert_eq!(spin[i], spin0[i], "body {i}");
        }
    }
    assert!(grew >= 1 && shrank >= 1, "grew {grew}, shrank {shrank}");
}
