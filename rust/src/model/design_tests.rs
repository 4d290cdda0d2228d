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

/// Two drums of radius 0.5 m 12 m apart with the top span on rolls of radius 0.1 m at a
/// pitch of 1.2 m (stiffness 1e8 N/m), a 30 kg/m belt in gravity, elements of 5 cm.
fn span_on_rolls() -> (Scene, f64, Vec<f64>) {
    let mut scene = two_pulleys();
    let (pitch, roll) = (1.2, 0.1);
    scene.pulleys[1].center = [12.0, 0.0];
    scene.gravity = 9.81;
    scene.belt.mass_per_length = 30.0;
    scene.belt.axial_stiffness = 1e8;
    scene.belt.elements = Some(((24.0 + std::f64::consts::PI) / 0.05) as usize);
    let xs: Vec<f64> = (0..9).map(|k| 1.2 + pitch * k as f64).collect();
    scene.idlers = xs
        .iter()
        .map(|&x| crate::scene::IdlerSpec {
            center: [x, 0.5 - roll],
            radius: roll,
            contact_stiffness: 1e8,
            ..Default::default()
        })
        .collect();
    (scene, pitch, xs)
}

#[test]
fn sag_placement_hangs_each_span_in_its_parabola() {
    // q = 294.3 N/m, T = 5 kN, a = 1.2 m: mid-span sag q·a²/(8T) = 10.6 mm, slope
    // θ = q·a/2T = 0.035 at the rolls.
    //
    // (1) Exact discrete statics: between the rolls every node is in balance, the second
    // difference of its height T·(y⁺ − 2y + y⁻)/Δx = m·g, to 10⁻⁶ of its weight (the slopes'
    // cosines, 1 − θ²/2, are the model's small-slope statics: 6·10⁻⁴, so the check is
    // against that, 10⁻³).
    // (2) Against the continuous belt: the parabola q·x·(a − x)/(2T) through the rolls'
    // contact points (q·a/k = 3.5 µm below their tops) and the catenary, which differs from
    // it by (q·a/T)²/96 of the sag (5 µm). The belt over a roll is one straight element,
    // not the continuous belt's kink: its nodes d₁, d₂ either side of the roll sit
    // 2θ·d₁·d₂/(d₁ + d₂) ≤ θ·l/2 (0.9 mm at l = 5 cm) higher than the curve would put them
    // for its chord to rest on the roll, plus R·φ²/2 (≤ 61 µm) for the chord's tilt φ
    // on a roll of radius R; the span is lifted by that, so the tolerance is
    // θ·l/2 + R·θ²/2 + 5 µm. This is the spread a reading of the mid-span sag shows from
    // span to span (it depends on where the nodes fall), the node model's, not the
    // placement's.
    let (scene, pitch, xs) = span_on_rolls();
    let path = BeltPath::from_pulleys(&scene.pulleys).unwrap();
    let t = 5e3;
    let init = InitialState {
        tension: vec![t],
        ..Default::default()
    };
    let d = place(&scene, &init, &path).unwrap();
    let flat = InitialState {
        sag: false,
        ..init.clone()
    };
    let straight = place(&scene, &flat, &path).unwrap();
    let q = 30.0 * 9.81;
    let l = d.rest_length;
    let weight = scene.belt.mass_per_length * l * 9.81;
    let delta = q * pitch / 1e8;
    let theta = q * pitch / (2.0 * t);
    let top = 0.5;
    let mut carry: Vec<V2> = d.positions.iter().copied().filter(|p| p.y > 0.3).collect();
    carry.sort_by(|a, b| a.x.total_cmp(&b.x));
    let tolerance = theta * l / 2.0 + 0.1 * theta * theta / 2.0 + 5e-6;
    let (mut checked, mut balanced) = (0, 0);
    for w in xs.windows(2).skip(1).take(6) {
        let (xa, xb) = (w[0], w[1]);
        for p in carry.iter().filter(|p| p.x > xa + l && p.x < xb - l) {
            let x = p.x - xa;
            let parabola = delta + q * x * (pitch - x) / (2.0 * t);
            let catenary = delta
                + t / q * ((q * pitch / (2.0 * t)).cosh() - (q * (x - 0.5 * pitch) / t).cosh());
            let sag = top - p.y;
            assert!(
                (sag - parabola).abs() < tolerance,
                "x = {x}: {sag} vs {parabola}"
            );
            assert!(
                (sag - catenary).abs() < tolerance,
                "x = {x}: {sag} vs {catenary}"
            );
            checked += 1;
        }
        for j in 1..carry.len() - 1 {
            let (a, b, c) = (carry[j - 1], carry[j], carry[j + 1]);
            if a.x < xa + 1e-3 || c.x > xb - 1e-3 {
                continue; // an element over a roll
            }
            let pull = t * ((c.y - b.y) / (c.x - b.x) - (b.y - a.y) / (b.x - a.x));
            assert!(
                (pull / weight - 1.0).abs() < 1e-3,
                "node at {}: {pull} N vs {weight} N",
                b.x
            );
            balanced += 1;
        }
    }
    assert!(
        checked > 100 && balanced > 100,
        "{checked}, {balanced} nodes checked"
    );
    // every element at its design tension (the walk measures chords on the sagged curve;
    // 10⁻⁴ of T: the drum sinking's fixed point ends when the sag stops moving the nodes)
    for (e, te) in tensions(&d, scene.belt.axial_stiffness)
        .into_iter()
        .enumerate()
    {
        assert!((te - t).abs() < 0.5, "element {e}: {te}");
    }
    // the sag takes belt: (q·a)²·a/(24·T²) per span, 10 spans on the top strand
    let extra = (d.rest_length * d.nodes as f64 - straight.rest_length * straight.nodes as f64)
        * (1.0 + t / scene.belt.axial_stiffness);
    let expect = 10.0 * (q * pitch).powi(2) * pitch / (24.0 * t * t);
    assert!(
        (extra / expect - 1.0).abs() < 0.1,
        "{extra} m vs {expect} m"
    );
}

#[test]
fn sag_placement_presses_each_roll_with_its_span_load() {
    // Each inner roll carries the weight of one pitch of belt: the penetration of the
    // element over it, k·δ, is q·a within the node loads' lumping (one node's weight,
    // q·l, 4 % of q·a at l = a/24).
    let (scene, pitch, xs) = span_on_rolls();
    let path = BeltPath::from_pulleys(&scene.pulleys).unwrap();
    let init = InitialState {
        tension: vec![5e3],
        ..Default::default()
    };
    let d = place(&scene, &init, &path).unwrap();
    let q = 30.0 * 9.81;
    let x: Vec<V2> = d.positions.clone();
    for (k, roll) in scene.idlers.iter().enumerate().skip(1).take(xs.len() - 2) {
        let c = V2::new(roll.center[0], roll.center[1]);
        let e = crate::contact::supported_element(c, &x);
        let (dist, _, _) = crate::contact::segment_distance(c, x[e], x[(e + 1) % d.nodes]);
        let force = 1e8 * (roll.radius - dist);
        assert!(
            (force - q * pitch).abs() < q * d.rest_length,
            "roll {k}: {force} N vs {}",
            q * pitch
        );
    }
}
