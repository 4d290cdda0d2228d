//! Kernel tests of the design placement (`design.rs`).

use super::*;
use crate::scene::PulleySpec;

/// Two pulleys of radius 0.5 m, 4 m apart (counter-clockwise wraps), no gravity.
fn two_pulleys() -> Scene {
    let pulley = |x: f64| PulleySpec {
        center: [x, 0.0],
        radius: 0.5,
        contact_stiffness: 1e8,
        ..Default::default()
    };
    Scene {
        pulleys: vec![pulley(0.0), pulley(4.0)],
        gravity: 0.0,
        ..Default::default()
    }
}

#[test]
fn corners_give_the_pulleys_own_path() {
    // The pulleys' path starts on pulley 0 where the top span arrives (0, 0.5), goes
    // round it counter-clockwise; the same loop as four 90° corners of radius 0.5.
    let scene = two_pulleys();
    let by_pulleys = BeltPath::from_pulleys(&scene.pulleys).unwrap();
    let corners = [
        [-0.5, 0.5, 0.5],
        [-0.5, -0.5, 0.5],
        [4.5, -0.5, 0.5],
        [4.5, 0.5, 0.5],
    ];
    let by_corners = path_from_corners(&scene, &corners).unwrap();
    assert!((by_corners.length - by_pulleys.length).abs() < 1e-12);
    for k in 0..200 {
        let s = by_pulleys.length * k as f64 / 200.0;
        assert!(
            (by_corners.point(s) - by_pulleys.point(s)).norm() < 1e-12,
            "s = {s}"
        );
        let t = tangent(&by_corners, s);
        let d = by_corners.point(s + 1e-7) - by_corners.point(s - 1e-7);
        assert!((t - d / d.norm()).norm() < 1e-6, "s = {s}");
    }
}

/// Each element's tension from its chord, N.
fn tensions(d: &DesignPlacement, ea: f64) -> Vec<f64> {
    (0..d.nodes)
        .map(|e| {
            let chord = (d.positions[(e + 1) % d.nodes] - d.positions[e]).norm();
            ea * (chord / d.rest_length - 1.0)
        })
        .collect()
}

#[test]
fn placement_stretches_every_element_to_its_design_tension() {
    // After the drum nodes sink by N/k, every chord is l0·(1 + T/EA): uniform 20 kN to
    // 10 mN (on the spans, the wraps and where the belt runs onto them), and a tension
    // rising 20 → 30 kN half way round and back to within 0.5 N at each element's middle
    // (the table's slope is 1.8 N/mm; on a drum the chord's middle lies inside the arc).
    let mut scene = two_pulleys();
    scene.belt.axial_stiffness = 1e6;
    scene.belt.elements = Some(120);
    let path = BeltPath::from_pulleys(&scene.pulleys).unwrap();
    let ea = scene.belt.axial_stiffness;
    let uniform = InitialState {
        tension: vec![20e3],
        ..Default::default()
    };
    let d = place(&scene, &uniform, &path).unwrap();
    assert_eq!(d.nodes, 120);
    for (e, t) in tensions(&d, ea).into_iter().enumerate() {
        assert!((t - 20e3).abs() < 1e-2, "element {e}: {t}");
    }
    let rising = InitialState {
        tension: vec![20e3, 30e3],
        distance: vec![0.0, 0.5 * path.length],
        ..Default::default()
    };
    let d = place(&scene, &rising, &path).unwrap();
    for (e, t) in tensions(&d, ea).into_iter().enumerate() {
        let middle = 0.5 * (d.positions[e] + d.positions[(e + 1) % d.nodes]);
        let s = crate::loads::project_on_path(&path, middle).0;
        let expect = rising.tension_at(s, path.length);
        assert!((t - expect).abs() < 0.5, "element {e}: {t} vs {expect}");
    }
    assert!(d.motion.velocity.iter().all(|v| v.norm() == 0.0));
}

#[test]
fn a_running_start_moves_nodes_and_pulleys_with_the_belt() {
    let scene = two_pulleys();
    let path = BeltPath::from_pulleys(&scene.pulleys).unwrap();
    let init = InitialState {
        tension: vec![1e3],
        speed: -3.0,
        ..Default::default()
    };
    let d = place(&scene, &init, &path).unwrap();
    for v in &d.motion.velocity {
        assert!((v.norm() - 3.0).abs() < 1e-6);
    }
    // against node order round counter-clockwise wraps: clockwise, ω = −v/r
    for w in &d.motion.pulley_omega {
        assert!((w + 6.0).abs() < 1e-9, "{w}");
    }
}
