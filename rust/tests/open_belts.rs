//! Open belts (`belt.start`, `belt.end`): the path and placement, elements and recording,
//! anchors, pulls and hanging masses, checkpoints.

use crate::common::case_h;
use beltrs::checkpoint;
use beltrs::model::{EndModel, Model};
use beltrs::record::Channels;
use beltrs::scene::{BeltEndSpec, EndHold, PulleySpec, Scene, Wrap};
use beltrs::{Simulation, StabiliseOptions};
use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// A belt over one pulley (R = 0.5 m at the origin, clockwise wrap `theta` symmetric about
/// the top), its straight ends `span` m long, gravity off.
pub fn capstan(theta: f64, span: f64, start: EndHold, end: EndHold) -> Scene {
    let r = 0.5;
    let a0 = std::f64::consts::FRAC_PI_2 + 0.5 * theta;
    let a1 = a0 - theta;
    let p = |a: f64| V2::new(a.cos(), a.sin()) * r;
    let d = |a: f64| V2::new(a.sin(), -a.cos());
    let s = p(a0) - d(a0) * span;
    let e = p(a1) + d(a1) * span;
    let end_spec = |at: V2, hold: EndHold| BeltEndSpec {
        point: Some([at.x, at.y]),
        hold,
        force: (hold == EndHold::Force).then_some(1000.0),
        force_rate: None,
        mass: (hold == EndHold::Mass).then_some(100.0),
    };
    let mut scene = Scene {
        gravity: 0.0,
        ..Scene::default()
    };
    scene.belt.axial_stiffness = 1e6;
    scene.belt.mass_per_length = 1.0;
    scene.belt.damping_ratio = 0.1;
    scene.belt.start = Some(end_spec(s, start));
    scene.belt.end = Some(end_spec(e, end));
    scene.pulleys.push(PulleySpec {
        center: [0.0, 0.0],
        radius: r,
        mass: 10.0,
        wrap: Wrap::Clockwise,
        contact_stiffness: 1e8,
        ..PulleySpec::default()
    });
    scene
}

#[test]
fn placement_runs_from_start_to_end_with_equal_chords() {
    for theta in [0.5 * std::f64::consts::PI, std::f64::consts::PI, 4.0] {
        let scene = capstan(theta, 1.0, EndHold::Anchor, EndHold::Force);
        let m = Model::compile(&scene).unwrap();
        let x = &m.initial_positions;
        let n = m.nodes;
        assert_eq!(m.elements, n - 1);
        let s = scene.belt.start.as_ref().unwrap().at();
        let e = scene.belt.end.as_ref().unwrap().at();
        assert!((x[0] - V2::new(s[0], s[1])).norm() < 1e-12);
        assert!((x[n - 1] - V2::new(e[0], e[1])).norm() < 1e-9);
        let chord = (x[1] - x[0]).norm();
        for i in 0..n - 1 {
            let c = (x[i + 1] - x[i]).norm();
            assert!(
                (c - chord).abs() < 1e-9 * chord,
                "chord {i}: {c} vs {chord}"
            );
        }
        let wrap = m.path.wrap_angles[0];
        assert!((wrap - theta).abs() < 1e-12, "wrap {wrap} vs {theta}");
        assert!((m.path.length - (2.0 + 0.5 * theta)).abs() < 1e-12);
        // The last entry is no element.
        assert_eq!(m.axial_stiffness[n - 1], 0.0);
        assert_eq!(m.mass[0], 0.5 * m.mass[1]);
        assert!(matches!(m.ends.unwrap().start, EndModel::Anchor(_)));
        let f = m.ends.unwrap().end.pull(0.0);
        assert!(matches!(m.ends.unwrap().end, EndModel::Force { .. }));
        // Pulled along the span, away from the pulley.
        assert!((f.norm() - 1000.0).abs() < 1e-9);
        assert!(f.dot(&(x[n - 1] - x[n - 2])) > 0.0);
    }
    // A closed loop is as it was.
    let m = Model::compile(&case_h(89)).unwrap();
    assert_eq!((m.nodes, m.elements), (89, 89));
    assert!(m.ends.is_none());
    assert!(!m.stages.iter().any(|s| s.name().starts_with("end_")));
}

#[test]
fn a_frictionless_belt_pulled_at_one_end_carries_the_pull_everywhere() {
    let scene = capstan(std::f64::consts::PI, 1.0, EndHold::Anchor, EndHold::Force);
    let mut sim = Simulation::new(&scene).unwrap();
    let names: Vec<_> = sim.model.stages.iter().map(|s| s.name()).collect();
    assert_eq!(names.first(), Some(&"axial_damped"));
    assert!(names.contains(&"end_pulls") && names.last() == Some(&"end_anchors"));
    let anchor = sim.state.position[0];
    let report = sim.stabilise(&StabiliseOptions::default()).unwrap();
    assert!(report.converged, "{report:?}");
    assert_eq!(sim.state.position[0], anchor, "the anchor does not move");
    let t = sim.tensions().to_vec();
    assert_eq!(t.len(), sim.model.elements);
    // The pulled span carries the pull. Along a frictionless wrap every chord carries one
    // tension; where a span meets the wrap the node balances the span against the first
    // chord at an angle up to half the chord's angle a, so the chords carry up to
    // T/cos(a/2) (the chord polygon's O(a²) error, 3.4 % at the default 30°) and the
    // anchored span, whose junction node sits where the fixed belt length puts it, within
    // that of the pull.
    // Half the angle a chord of the stretched element (strain 0.1 %, 1 % allowed) spans.
    let half = (1.01 * sim.model.rest_length[0] / (2.0 * 0.5)).asin();
    let bound = 1.0 / half.cos() - 1.0;
    assert!((t[t.len() - 1] - 1000.0).abs() < 1e-6 * 1000.0, "{t:?}");
    for (e, &te) in t.iter().enumerate() {
        assert!(
            te >= 1000.0 * (1.0 - 1e-9),
            "element {e}: {te} N; all {t:?}"
        );
        assert!(
            te <= 1000.0 * (1.0 + bound),
            "element {e}: {te} N; all {t:?}"
        );
    }
    // Dynamics: recording n − 1 elements, the anchor stays put.
    sim.begin_recording(Channels::default(), 10, usize::MAX);
    sim.advance(200).unwrap();
    sim.end_recording().unwrap();
    let r = &sim.recording;
    assert_eq!(r.elements, sim.model.elements);
    assert_eq!(r.tension.len(), r.len() * sim.model.elements);
    assert_eq!(sim.state.position[0], anchor);
}

#[test]
fn a_hanging_mass_is_held_by_its_weight() {
    // Vertical ends, both hanging masses of 100 kg: the belt balances at T = m·g.
    let mut scene = capstan(std::f64::consts::PI, 1.0, EndHold::Mass, EndHold::Mass);
    scene.gravity = 9.81;
    let mut sim = Simulation::new(&scene).unwrap();
    let report = sim.stabilise(&StabiliseOptions::default()).unwrap();
    assert!(report.converged, "{report:?}");
    let t = sim.tensions().to_vec();
    // Tension at the bottom of each span: the mass plus half an end element.
    let m_end = sim.model.mass[0];
    assert!(
        (t[0] - m_end * 9.81).abs() < 1e-6 * t[0],
        "{} vs {}",
        t[0],
        m_end * 9.81
    );
}

#[test]
fn open_belts_resume_from_a_checkpoint_bit_for_bit() {
    let scene = capstan(std::f64::consts::PI, 1.0, EndHold::Anchor, EndHold::Force);
    let mut a = Simulation::new(&scene).unwrap();
    a.step(300).unwrap();
    let dir = std::env::temp_dir().join(format!("beltrs-open-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("open.ck");
    checkpoint::save(&a, &path).unwrap();
    let mut b = checkpoint::load(&path).unwrap();
    a.step(300).unwrap();
    b.step(300).unwrap();
    assert_eq!(a.state, b.state);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_ends_are_refused_by_name() {
    let base = capstan(std::f64::consts::PI, 1.0, EndHold::Anchor, EndHold::Force);
    let check = |scene: &Scene, field: &str, words: &str| {
        let err = Model::compile(scene).unwrap_err().to_string();
        assert!(err.contains(field) && err.contains(words), "{err}");
    };
    let mut s = base.clone();
    s.belt.end = None;
    check(&s, "belt.end", "both ends");
    let mut s = base.clone();
    s.belt.start.as_mut().unwrap().point = None;
    check(&s, "belt.start.point", "required");
    let mut s = base.clone();
    s.belt.end.as_mut().unwrap().force = None;
    check(
        &s,
        "belt.end.force",
        "required with belt.end.hold = \"force\"",
    );
    let mut s = base.clone();
    s.belt.start.as_mut().unwrap().mass = Some(3.0);
    check(&s, "belt.start.mass", "no effect");
    let mut s = base.clone();
    s.belt.start.as_mut().unwrap().point = Some([0.1, 0.1]);
    check(&s, "belt.start.point", "inside pulleys[0]");
    let mut s = base.clone();
    s.idlers.push(Default::default());
    check(&s, "idlers", "open belt");
}

/// `capstan` with the rigid-body belt.
fn rigid(theta: f64, span: f64, start: EndHold, end: EndHold) -> Scene {
    let mut scene = capstan(theta, span, start, end);
    scene.belt.formulation = beltrs::scene::Formulation::RigidBody;
    scene
}

#[test]
fn an_open_rigid_chain_has_its_end_points_and_the_belt_s_compliance() {
    use beltrs::state::Rigid;
    for theta in [0.5 * std::f64::consts::PI, std::f64::consts::PI, 4.0] {
        let scene = rigid(theta, 1.0, EndHold::Anchor, EndHold::Force);
        let m = Model::compile(&scene).unwrap();
        let (x, n) = (&m.initial_positions, m.nodes);
        // Bodies as the node belt counts its elements, plus the two end points.
        // The default bodies span at most half the node belt's default element angle.
        let bodies = n - 2;
        let node = Model::compile(&capstan(theta, 1.0, EndHold::Anchor, EndHold::Force)).unwrap();
        assert!(
            bodies >= 2 * node.elements - 2,
            "{bodies} bodies, {} elements",
            node.elements
        );
        assert!(m.rest_length[1] <= 0.5 * std::f64::consts::FRAC_PI_6 * 0.5 * (1.0 + 1e-12));
        assert_eq!(m.elements, n - 1);
        let s = scene.belt.start.as_ref().unwrap().at();
        let e = scene.belt.end.as_ref().unwrap().at();
        assert!((x[0] - V2::new(s[0], s[1])).norm() < 1e-12);
        assert!((x[n - 1] - V2::new(e[0], e[1])).norm() < 1e-9);
        // Equal chords between the mass centres, half of one from the end points, and a
        // chord within the chord polygon's a²/24 (< 0.3 %) of the body length.
        let l = m.rest_length[1];
        let (r, total) = (0.5, scene.belt.length.unwrap_or(m.path.length));
        assert!((l - total / bodies as f64).abs() < 1e-15 * total);
        let c = (x[2] - x[1]).norm();
        assert!((c / l - 1.0).abs() < 3e-3, "chord {c} vs body {l}");
        assert!(((x[1] - x[0]).norm() - 0.5 * c).abs() < 1e-9 * l);
        assert!(((x[n - 1] - x[n - 2]).norm() - 0.5 * c).abs() < 1e-9 * l);
        for i in 1..n - 2 {
            assert!(((x[i + 1] - x[i]).norm() - c).abs() < 1e-9 * l, "body {i}");
        }
        // Mass centres on the pulley sit on its rim (where contact acts).
        let on = (1..n - 1)
            .filter(|&i| (x[i].norm() - r).abs() < 1e-9)
            .count();
        assert!(on >= 2, "{on} mass centres on the rim");
        // The chain's compliance is the belt's, L/EA: N − 1 joints of c_x = EA/l and two
        // end joints of 2·c_x; its unstretched length N·l; its bodies carry ρL.
        let compliance: f64 = m.axial_stiffness[..m.elements]
            .iter()
            .map(|k| 1.0 / k)
            .sum();
        let ea = scene.belt.axial_stiffness;
        assert!(
            (compliance * ea / total - 1.0).abs() < 1e-12,
            "{compliance}"
        );
        assert_eq!(m.axial_stiffness[0], 2.0 * m.axial_stiffness[1]);
        assert_eq!(m.axial_damping[n - 2], 2.0 * m.axial_damping[1]);
        assert_eq!(m.axial_stiffness[n - 1], 0.0);
        assert_eq!(
            (m.bending_stiffness[0], m.bending_stiffness[n - 2]),
            (0.0, 0.0)
        );
        let rest: f64 = m.element_rest_length().iter().sum();
        assert!((rest / total - 1.0).abs() < 1e-12);
        let body_mass: f64 = m.mass[1..n - 1].iter().sum();
        let rho = scene.belt.mass_per_length;
        assert!((body_mass / (rho * total) - 1.0).abs() < 1e-12);
        assert_eq!(m.mass[0], 0.5 * m.mass[1]);
        // The end points are points: no rotation in the layout.
        assert!(!m.dofs.rigid.contains(&Rigid::Body(0)));
        assert!(!m.dofs.rigid.contains(&Rigid::Body(n - 1)));
        assert!(m.dofs.rigid.contains(&Rigid::Body(1)));
        assert!(m.dt > 0.0 && m.dt.is_finite());
    }
}

#[test]
fn an_open_rigid_chain_pulled_at_one_end_carries_the_pull() {
    let scene = rigid(std::f64::consts::PI, 1.0, EndHold::Anchor, EndHold::Force);
    let mut sim = Simulation::new(&scene).unwrap();
    let names: Vec<_> = sim.model.stages.iter().map(|s| s.name()).collect();
    assert_eq!(names.first(), Some(&"rigid_chain"));
    assert!(names.contains(&"end_pulls") && names.last() == Some(&"end_anchors"));
    let anchor = sim.state.position[0];
    let report = sim.stabilise(&StabiliseOptions::default()).unwrap();
    assert!(report.converged, "{report:?}");
    assert_eq!(sim.state.position[0], anchor, "the anchor does not move");
    let t = sim.tensions().to_vec();
    assert_eq!(t.len(), sim.model.elements);
    // The pulled end joint carries the pull, and so does every span joint; on the
    // frictionless wrap the joints sit outside the rim (contact at the mass centres) and
    // carry up to T/cos(a/2) of the tangent polygon, a the body angle.
    let a = sim.model.rest_length[1] / 0.5;
    let bound = 1.0 / (0.5 * a).cos() - 1.0;
    assert!((t[t.len() - 1] - 1000.0).abs() < 1e-6 * 1000.0, "{t:?}");
    assert!((t[0] - 1000.0).abs() < bound * 1000.0, "{t:?}");
    for (e, &te) in t.iter().enumerate() {
        assert!(
            (te - 1000.0).abs() <= bound * 1000.0,
            "joint {e}: {te} N; all {t:?}"
        );
    }
    sim.begin_recording(Channels::default(), 10, usize::MAX);
    sim.advance(200).unwrap();
    sim.end_recording().unwrap();
    let r = &sim.recording;
    assert_eq!(r.elements, sim.model.elements);
    assert_eq!(r.tension.len(), r.len() * sim.model.elements);
    assert_eq!(sim.state.position[0], anchor);
}

#[test]
fn an_open_rigid_chain_hangs_its_masses_by_their_weight() {
    let mut scene = rigid(std::f64::consts::PI, 1.0, EndHold::Mass, EndHold::Mass);
    scene.gravity = 9.81;
    let mut sim = Simulation::new(&scene).unwrap();
    let report = sim.stabilise(&StabiliseOptions::default()).unwrap();
    assert!(report.converged, "{report:?}");
    let t = sim.tensions().to_vec();
    // The end joint holds its point: the hanging mass and half a body.
    let m_end = sim.model.mass[0];
    assert!((m_end - (100.0 + 0.5 * sim.model.mass[1])).abs() < 1e-12);
    for te in [t[0], t[t.len() - 1]] {
        assert!(
            (te - m_end * 9.81).abs() < 1e-6 * te,
            "{te} vs {}",
            m_end * 9.81
        );
    }
    // Each body above adds its weight (the spans hang straight down).
    let w = sim.model.mass[1] * 9.81;
    assert!(
        (t[1] - t[0] - w).abs() < 1e-6 * t[1],
        "{} {}",
        t[1] - t[0],
        w
    );
}

#[test]
fn open_rigid_chain_forces_are_minus_the_energy_gradient() {
    // Undamped, frictionless, a constant pull (its potential −F·x is counted): the stage
    // forces are −∂E/∂x at the end points and the bodies. The sheave has Kubas's contact
    // (at the mass centres, a potential force): the linear penalty's contact of bodies
    // resting on their ends acts along the bodies' normals, not along its energy's
    // gradient (`belt::rigid::contact`; measured 1.3 % off at a body here).
    let mut scene = rigid(std::f64::consts::PI, 1.0, EndHold::Anchor, EndHold::Force);
    scene.belt.damping_ratio = 0.0;
    scene.belt.bending_stiffness = 50.0;
    scene.pulleys[0].contact_stiffness = PulleySpec::default().contact_stiffness;
    scene.pulleys[0].nonlinear_contact = Some(beltrs::contact::nonlinear::NonlinearContact {
        damping: 0.0,
        ..Default::default()
    });
    let mut sim = Simulation::new(&scene).unwrap();
    sim.step(500).unwrap();
    let energy = |sim: &mut Simulation| {
        let e = sim.current_energies();
        e.strain + e.bending + e.contact + e.gravity
    };
    let forces = sim.forces().to_vec();
    let n = sim.model.nodes;
    let h = 1e-8;
    for i in [1, 2, n / 2, n - 2, n - 1] {
        for axis in 0..2 {
            let x0 = sim.state.position[i][axis];
            sim.state.position[i][axis] = x0 + h;
            let ep = energy(&mut sim);
            sim.state.position[i][axis] = x0 - h;
            let em = energy(&mut sim);
            sim.state.position[i][axis] = x0;
            let numeric = -(ep - em) / (2.0 * h);
            let f = forces[i][axis];
            assert!(
                (numeric - f).abs() < 2e-3 * f.abs().max(1.0),
                "point {i} axis {axis}: force {f}, −dE/dx {numeric}"
            );
        }
    }
}

#[test]
fn open_rigid_chains_resume_from_a_checkpoint_bit_for_bit() {
    let scene = rigid(std::f64::consts::PI, 1.0, EndHold::Mass, EndHold::Force);
    let mut a = Simulation::new(&scene).unwrap();
    a.step(300).unwrap();
    let dir = std::env::temp_dir().join(format!("beltrs-open-rigid-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("open.ck");
    checkpoint::save(&a, &path).unwrap();
    let mut b = checkpoint::load(&path).unwrap();
    a.step(300).unwrap();
    b.step(300).unwrap();
    assert_eq!(a.state, b.state);
    let _ = std::fs::remove_dir_all(&dir);
}
