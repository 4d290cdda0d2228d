//! The rigid-body belt's wrap joints (`belt.pulley_contact = "wrap"`,
//! `belt::rigid::wrap_joint`) on a running loop: the strand drawn at the string's speed.
use beltrs::scene::{BeltParams, Formulation, InitialState, PulleyContact, PulleySpec, Scene};
use beltrs::Simulation;

/// Two drums of radius 0.4 m, 4 m apart, no gravity, frictionless; a rigid-body belt of
/// 52 bodies (0.2 m: a = 0.5 rad, case G's bodies on case G's drums), EA = 10 MN,
/// 10 kg/m, running at 2 m/s under 20 kN from its design state.
fn running_loop(contact: PulleyContact, damping_ratio: f64) -> Scene {
    let pulley = |name: &str, x: f64| PulleySpec {
        name: name.into(),
        center: [x, 0.0],
        radius: 0.4,
        mass: 100.0,
        inertia: Some(10.0),
        contact_damping_ratio: Some(damping_ratio),
        ..Default::default()
    };
    Scene {
        belt: BeltParams {
            formulation: Formulation::RigidBody,
            axial_stiffness: 1e7,
            mass_per_length: 10.0,
            damping_ratio,
            elements: Some(52),
            pulley_contact: contact,
            ..Default::default()
        },
        pulleys: vec![pulley("a", 0.0), pulley("b", 4.0)],
        gravity: 0.0,
        initial: Some(InitialState {
            tension: vec![2e4],
            speed: 2.0,
            ..Default::default()
        }),
        recording: beltrs::scene::RecordingParams {
            stabilise: false,
            ..Default::default()
        },
        ..Default::default()
    }
}

/// Tension of the joint nearest the top span's middle, every `interval` s for `duration` s
/// after `settle` s.
fn mid_span_tension(scene: &Scene, settle: f64, duration: f64, interval: f64) -> Vec<f64> {
    let mut sim = Simulation::new(scene).unwrap();
    sim.advance_to(settle, u64::MAX).unwrap();
    let mut out = Vec::new();
    let samples = (duration / interval).round() as usize;
    for k in 1..=samples {
        sim.advance_to(settle + k as f64 * interval, u64::MAX)
            .unwrap();
        let target = nalgebra::Vector2::new(2.0, 0.4);
        let e = (0..sim.model.nodes)
            .min_by(|&i, &j| {
                let di = (sim.state.position[i] - target).norm();
                let dj = (sim.state.position[j] - target).norm();
                di.total_cmp(&dj)
            })
            .unwrap();
        out.push(sim.tensions()[e]);
    }
    out
}

fn rms_about_mean(v: &[f64]) -> f64 {
    let m = v.iter().sum::<f64>() / v.len() as f64;
    (v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / v.len() as f64).sqrt()
}

#[test]
fn wrap_joints_take_the_chordal_ripple_off_a_running_loop() {
    // A string running round frictionless drums keeps one tension (the exact answer: no
    // ripple). The bodies' polygon draws each strand at R_e·ω·cos θ (θ from −a/2 to a/2
    // at v/l = 10 Hz) and rings it; the wrap joints draw it at R·ω. Measured on this loop
    // (mid-span joint, 1 s after 2 s from the design state): plain joints 903.3 N rms, wrap
    // joints 494.9 N rms (0.55 of it). What is left: the fades at both ends of each bend
    // (`wrap_joint::FADE`) and, not measured apart, the couples ∓x′·T that the bend's term
    // puts on the strand's last body (docs/kubas.md, "Wrap joints"). Asserted: below 0.65 of the plain
    // joints' (a tenth of the plain ripple over the measured figure; the run is
    // deterministic, the margin is for other platforms' rounding of a ringing loop).
    let rms = |contact| {
        let t = mid_span_tension(&running_loop(contact, 0.2), 2.0, 1.0, 1e-3);
        rms_about_mean(&t)
    };
    let (plain, wrap) = (rms(PulleyContact::Nodes), rms(PulleyContact::Wrap));
    assert!(
        plain > 500.0,
        "the chordal ripple this test is about: {plain} N rms"
    );
    assert!(
        wrap < 0.65 * plain,
        "wrap joints {wrap} N rms against plain {plain} N rms"
    );
}

#[test]
fn an_undamped_loop_with_wrap_joints_keeps_its_energy() {
    // Undamped and frictionless, 0.2 s: the wrap joints are their energy's gradient (the
    // kernel tests check it by finite differences), so they add no drift. What drifts is
    // the bodies' contact on the drums, whose forces act along the body's normal and are
    // not its energy's gradient (`belt::rigid::contact`). Measured: worst drift 37.2 J of
    // 671 J with plain joints, 14.0 J of 672 J with wrap joints (their fades of 1 % with a
    // C² step; 18.4 J with the former 4 % C¹ fades, whose x″ jumps at the fades' ends).
    let drift = |contact| {
        let mut sim = Simulation::new(&running_loop(contact, 0.0)).unwrap();
        let e0 = sim.current_energies().total();
        let mut worst: f64 = 0.0;
        for k in 1..=100 {
            sim.advance_to(k as f64 * 2e-3, u64::MAX).unwrap();
            worst = worst.max((sim.current_energies().total() - e0).abs());
        }
        (worst, e0)
    };
    let (plain, e_plain) = drift(PulleyContact::Nodes);
    let (wrap, e_wrap) = drift(PulleyContact::Wrap);
    println!("wrap {wrap} J of {e_wrap}, plain {plain} J of {e_plain}");
    assert!(e_plain > 500.0 && e_wrap > 500.0, "{e_plain} {e_wrap}");
    assert!(
        wrap < plain && wrap < 0.03 * e_wrap,
        "wrap {wrap} J of {e_wrap}, plain {plain} J"
    );
}

#[test]
fn the_design_start_places_the_wrap_joints_offsets() {
    // The design placement stands each boundary joint's body off by x along the drum
    // (`design_rigid::stand_off`), its chord lengthened by x·(t_C·t_B) in the walk: at
    // t = 0 every joint carries the design tension as with plain joints. Without it the
    // boundary joints carried c_x·x on top (on case G at rest: −111 kN … +181 kN against
    // 50 kN). Measured here: worst joint 0.99 % off 20 kN with plain joints and with wrap
    // joints alike (design_rigid's transition error at the tangent points).
    let worst = |contact| {
        let mut sim = Simulation::new(&running_loop(contact, 0.2)).unwrap();
        sim.tensions()
            .iter()
            .map(|t| (t / 2e4 - 1.0).abs())
            .fold(0.0, f64::max)
    };
    let (plain, wrap) = (worst(PulleyContact::Nodes), worst(PulleyContact::Wrap));
    println!("plain {plain}, wrap {wrap}");
    assert!(
        wrap < 0.02 && wrap < plain + 1e-3,
        "wrap {wrap}, plain {plain}"
    );
}
