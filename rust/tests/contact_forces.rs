//! The opt-in recording of contact forces per belt point (issue 11): the per-point normal
//! and friction forces add up to the per-pulley sums, for both formulations, both friction
//! models and both pulley contacts; the angle is the point's about the pulley centre;
//! switching the channel on changes nothing in the motion.

use beltrs::friction::creep::CreepFriction;
use beltrs::presets::case_k;
use beltrs::record::{Channels, Recording};
use beltrs::scene::{Formulation, FrictionModel, PulleyContact, Scene};
use beltrs::Simulation;

const WITH_CONTACTS: Channels = Channels {
    tension: true,
    node_position: true,
    node_velocity: false,
    energy: false,
    contact_forces: true,
};

/// Case K with the drive torque on within 1 ms, so that both pulleys carry friction
/// within a few hundred steps.
fn drive(formulation: Formulation, friction: Option<FrictionModel>) -> Scene {
    let mut scene = case_k(1e-3, 0.00344);
    scene.belt.formulation = formulation;
    if let Some(f) = friction {
        for p in &mut scene.pulleys {
            p.friction = f;
        }
    }
    scene
}

fn record(scene: &Scene, channels: Channels, steps: u64) -> Recording {
    let mut sim = Simulation::new(scene).unwrap();
    sim.begin_recording(channels, 50, usize::MAX);
    sim.advance(steps).unwrap();
    sim.end_recording().unwrap();
    sim.recording.take()
}

/// The per-point arrays of one recording add up to its per-pulley sums, hold zeros (and NaN
/// angles) off the pulleys, and the angles are those of the recorded positions. Returns
/// the number of (instant, pulley, point) contacts and the largest |friction_force|.
fn check_sums(r: &Recording) -> (usize, f64) {
    let (p, n) = (r.pulleys, r.nodes);
    assert_eq!(r.contact_normal.len(), r.len() * p * n);
    let (mut touching, mut friction) = (0, 0.0_f64);
    for t in 0..r.len() {
        for j in 0..p {
            let row = (t * p + j) * n..(t * p + j + 1) * n;
            let normal: f64 = r.contact_normal[row.clone()].iter().sum();
            let tangential: f64 = r.contact_friction[row].iter().sum();
            let total = r.normal_force[t * p + j];
            assert!((normal - total).abs() <= 1e-12 * total.abs().max(1.0));
            let ft = r.friction_force[t * p + j];
            assert!(
                (tangential - ft).abs() <= 1e-12 * ft.abs().max(1.0),
                "{tangential} {ft}"
            );
            friction = friction.max(ft.abs());
            let at = 2 * (t * p + j);
            let c = [r.pulley_position[at], r.pulley_position[at + 1]];
            let mut count = 0;
            for i in 0..n {
                let k = (t * p + j) * n + i;
                let angle = r.contact_angle[k];
                if angle.is_nan() {
                    assert_eq!(r.contact_normal[k], 0.0);
                    assert_eq!(r.contact_friction[k], 0.0);
                    continue;
                }
                count += 1;
                assert!(r.contact_normal[k] >= 0.0);
                let x = &r.node_position[2 * (t * n + i)..2 * (t * n + i) + 2];
                let expect = (x[1] - c[1]).atan2(x[0] - c[0]);
                assert_eq!(angle.to_bits(), expect.to_bits());
            }
            assert_eq!(count as f64, r.contact_nodes[t * p + j]);
            touching += count;
        }
    }
    (touching, friction)
}

#[test]
fn per_point_forces_add_up_to_the_pulley_sums_for_both_formulations() {
    let creep = FrictionModel::Creep(CreepFriction {
        transition_speed: 1e-3,
        ..CreepFriction::default()
    });
    for formulation in [Formulation::RigidBody, Formulation::NodeKelvinVoigt] {
        for friction in [None, Some(creep)] {
            let r = record(&drive(formulation, friction), WITH_CONTACTS, 600);
            let (touching, largest) = check_sums(&r);
            assert!(touching > 0, "{formulation:?}: no contacts recorded");
            // The drive torque is on: friction acts (not a vacuous sum of zeros).
            assert!(
                largest > 1.0,
                "{formulation:?} {friction:?}: friction {largest}"
            );
        }
    }
}

#[test]
fn per_point_forces_add_up_with_wrap_contact() {
    let mut scene = drive(Formulation::NodeKelvinVoigt, None);
    scene.belt.pulley_contact = PulleyContact::Wrap;
    for p in &mut scene.pulleys {
        p.nonlinear_contact = None; // Kubas's law is nodal only
    }
    let r = record(&scene, WITH_CONTACTS, 600);
    let (touching, largest) = check_sums(&r);
    assert!(touching > 0 && largest > 1.0);
}

#[test]
fn recording_contact_forces_changes_nothing_else() {
    let scene = drive(Formulation::RigidBody, None);
    let on = record(&scene, WITH_CONTACTS, 400);
    let off = record(
        &scene,
        Channels {
            contact_forces: false,
            ..WITH_CONTACTS
        },
        400,
    );
    assert!(off.contact_normal.is_empty() && off.contact_angle.is_empty());
    assert_eq!(
        on.bytes_per_sample(),
        off.bytes_per_sample() + 8 * 3 * 2 * on.nodes
    );
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&on.tension), bits(&off.tension));
    assert_eq!(bits(&on.pulley_speed), bits(&off.pulley_speed));
    assert_eq!(bits(&on.friction_force), bits(&off.friction_force));
}
