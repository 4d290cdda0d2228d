//! Wrap contact kernels (`beltrs::contact::wrap`, `pulley_wrap_contact`) against geometry
//! worked out here: the length of a string wrapped round a circle, its gradient by finite
//! differences, no moment about the centre, continuity as a node lands on or lifts off the
//! circle, and a belt lying on its path round a drum in equilibrium with the same forces
//! wherever its nodes are along the path (no kick as a node crosses a tangent point).
use beltrs::contact::wrap::{wrap, ElementLaw};
use beltrs::contact::{pulley_wrap_contact, update_window, PulleyBody, PulleyContacts};
use beltrs::state::ContactWindow;
use nalgebra::Vector2;

type V2 = Vector2<f64>;

fn unit(angle: f64) -> V2 {
    V2::new(angle.cos(), angle.sin())
}

fn cross(a: V2, b: V2) -> f64 {
    a.x * b.y - a.y * b.x
}

const R: f64 = 0.4;

/// Length of a string from `p` to `q` wrapped counter-clockwise round the circle of radius
/// R at the origin, both points outside: the two tangent lengths and the arc between the
/// tangent points, written from the textbook construction (angle of each point less the
/// half-angle acos(R/ρ) its tangent subtends).
fn string_length(p: V2, q: V2) -> f64 {
    let (rp, rq) = (p.norm(), q.norm());
    let between = (cross(p, q))
        .atan2(p.dot(&q))
        .rem_euclid(std::f64::consts::TAU);
    let arc = between - (R / rp).acos() - (R / rq).acos();
    (rp * rp - R * R).sqrt() + (rq * rq - R * R).sqrt() + R * arc
}

#[test]
fn clear_segment_is_not_wrapped() {
    let c = V2::zeros();
    assert!(wrap(V2::new(-1.0, 0.5), V2::new(1.0, 0.5), c, R).is_none());
    // Tangent exactly: not cutting (distance = R).
    assert!(wrap(V2::new(-1.0, R), V2::new(1.0, R), c, R).is_none());
}

#[test]
fn wrapped_length_is_the_string_length() {
    let c = V2::zeros();
    // Both outside, the segment cutting the circle: tangents and arc.
    for (p, q) in [
        (V2::new(0.3, -0.5), V2::new(0.3, 0.5)),
        (V2::new(0.5, -0.1), V2::new(0.2, 0.45)),
        (V2::new(0.42, -0.2), V2::new(0.38, 0.2)),
    ] {
        let g = wrap(p, q, c, R).expect("cuts the circle");
        assert_eq!(g.sense, 1.0);
        let expect = string_length(p, q);
        assert!(
            (g.length - expect).abs() < 1e-13,
            "{} vs {expect}",
            g.length
        );
        assert!(g.length > (q - p).norm());
        // The straight parts are tangents: perpendicular to the normal at their ends.
        let tp = c + g.normal_p * R;
        assert!((p - tp).dot(&g.normal_p).abs() < 1e-13);
        assert!(((p - tp).norm() - g.tangent_p).abs() < 1e-13);
    }
    // Both on the circle (just inside): the arc r·φ.
    let (a, b) = (0.1, 0.6);
    let g = wrap(
        unit(a) * (R * (1.0 - 1e-12)),
        unit(b) * (R * (1.0 - 1e-12)),
        c,
        R,
    )
    .unwrap();
    assert!((g.length - R * (b - a)).abs() < 1e-12);
    assert!((g.angle - (b - a)).abs() < 1e-12);
    assert!((g.share_q - 0.5).abs() < 1e-12);
    // Clockwise the other way round.
    let g = wrap(
        unit(b) * (R * (1.0 - 1e-12)),
        unit(a) * (R * (1.0 - 1e-12)),
        c,
        R,
    )
    .unwrap();
    assert_eq!(g.sense, -1.0);
    assert!((g.length - R * (b - a)).abs() < 1e-12);
}

#[test]
fn gradient_matches_finite_differences_and_has_no_moment() {
    let c = V2::new(1.5, -0.7);
    let h = 1e-7;
    let cases = [
        (V2::new(0.3, -0.5), V2::new(0.3, 0.5)),   // both outside
        (unit(-0.3) * 0.39, V2::new(0.25, 0.5)),   // first inside
        (V2::new(0.45, -0.3), unit(0.4) * 0.398),  // second inside
        (unit(0.2) * 0.399, unit(0.6) * 0.3995),   // both inside
        (V2::new(-0.3, 0.5), V2::new(-0.3, -0.5)), // the other side (also counter-clockwise)
        (V2::new(0.3, 0.5), V2::new(0.3, -0.5)),   // clockwise
    ];
    for (p0, q0) in cases {
        let (p, q) = (p0 + c, q0 + c);
        let g = wrap(p, q, c, R).expect("wraps");
        let len = |p: V2, q: V2| wrap(p, q, c, R).unwrap().length;
        for (k, e) in [V2::new(1.0, 0.0), V2::new(0.0, 1.0)]
            .into_iter()
            .enumerate()
        {
            let dp = (len(p + e * h, q) - len(p - e * h, q)) / (2.0 * h);
            let dq = (len(p, q + e * h) - len(p, q - e * h)) / (2.0 * h);
            assert!(
                (dp - g.grad_p[k]).abs() < 1e-6,
                "dL/dp[{k}] {dp} vs {}",
                g.grad_p[k]
            );
            assert!(
                (dq - g.grad_q[k]).abs() < 1e-6,
                "dL/dq[{k}] {dq} vs {}",
                g.grad_q[k]
            );
        }
        // Turning both nodes about the centre leaves the length: no moment on the pulley.
        let moment = cross(p - c, g.grad_p) + cross(q - c, g.grad_q);
        assert!(moment.abs() < 1e-12, "moment {moment}");
        assert!((0.0..=1.0).contains(&g.share_q));
    }
}

#[test]
fn continuous_as_a_node_lands_and_as_the_segment_starts_to_cut() {
    let c = V2::zeros();
    // The first node crossing the circle radially: length, gradient, normal continuous.
    let q = V2::new(0.3, 0.5);
    let at = |rho: f64| wrap(unit(-0.2) * rho, q, c, R).unwrap();
    let (a, b) = (at(R * (1.0 - 1e-10)), at(R * (1.0 + 1e-10)));
    assert!((a.length - b.length).abs() < 1e-9);
    assert!((a.grad_p - b.grad_p).norm() < 1e-4);
    assert!((a.normal_p - b.normal_p).norm() < 1e-4);
    // A segment moved onto the circle: from clear (the chord) to cutting, the length grows
    // from the chord's, with no jump.
    let (p, q) = (V2::new(-0.5, 0.0), V2::new(0.5, 0.0));
    let chord = 1.0;
    for y in [R + 1e-9, R - 1e-9, R - 1e-6] {
        let len = wrap(p + V2::new(0.0, y), q + V2::new(0.0, y), c, R).map_or(chord, |g| g.length);
        assert!(len >= chord - 1e-15 && len - chord < 1e-5, "y {y}: {len}");
    }
}

/// A belt lying on its path round a drum of radius R at the origin: in along y = −R
/// (moving +x), half way round counter-clockwise, out along y = +R (moving −x). Point at
/// path parameter s (m).
fn on_path(s: f64, a: f64) -> V2 {
    let arc = std::f64::consts::PI * R;
    if s < a {
        V2::new(-a + s, -R)
    } else if s < a + arc {
        unit(-std::f64::consts::FRAC_PI_2 + (s - a) / R) * R
    } else {
        V2::new(-(s - a - arc), R)
    }
}

/// The axial pass's chord forces (elastic, tension-only), as `belt::node` applies them.
fn chord_forces(x: &[V2], k: f64, l0: f64) -> Vec<V2> {
    let mut f = vec![V2::zeros(); x.len()];
    for e in 0..x.len() - 1 {
        let d = x[e + 1] - x[e];
        let l = d.norm();
        let t = (k * (l - l0)).max(0.0);
        f[e] += d * (t / l);
        f[e + 1] -= d * (t / l);
    }
    f
}

#[test]
fn belt_on_its_path_is_in_equilibrium_wherever_its_nodes_are() {
    // 30° elements (l = R·π/6) at tension T, as the default mesh on a drum.
    let (l, a) = (R * std::f64::consts::PI / 6.0, 1.2);
    let (k, t) = (8e7 / l, 40e3);
    let l0 = l - t / k;
    let stiff = vec![k; 64];
    let zero = vec![0.0; 64];
    let rest = vec![l0; 64];
    let law = ElementLaw {
        stiffness: &stiff,
        damping: &zero,
        rest_length: &rest,
        damped: false,
        tension_only: true,
        arm: &[],
    };
    let body = PulleyBody {
        center: V2::zeros(),
        center_velocity: V2::zeros(),
        radius: R,
        stiffness: 1e8,
        damping: 0.0,
        margin: l,
    };
    let total = 2.0 * a + std::f64::consts::PI * R;
    let nodes = ((total - l) / l) as usize;
    // Shift the belt along its path through one element length in small steps: a node
    // crosses each tangent point on the way.
    for step in 0..=40 {
        let s0 = 0.5 * l + l * step as f64 / 40.0;
        let x: Vec<V2> = (0..nodes).map(|i| on_path(s0 + l * i as f64, a)).collect();
        let v = vec![V2::zeros(); nodes];
        let mut force = chord_forces(&x, k, l0);
        let mut window = ContactWindow::default();
        update_window(&mut window, &x, &body, false);
        let mut tension = vec![0.0; nodes];
        let mut out = PulleyContacts::default();
        let on = pulley_wrap_contact(
            &window,
            &x,
            &v,
            &body,
            &law,
            &mut force,
            &mut tension,
            &mut out,
            None,
        );
        // Every interior node in equilibrium, except for the radial cap (wrap::apply_wrap):
        // a strand node within 4T/k of a tangent point is pulled in as a penalty spring
        // would push, not along the exact tangent line, an error of at most T²/(k·r)
        // (40 N here, 1e-3·T); every other node to rounding.
        let cap = t * t / (body.stiffness * R);
        for (i, f) in force.iter().enumerate().take(nodes - 1).skip(1) {
            let near_tangent = x[i].x.abs() < 4.0 * t / body.stiffness && x[i].x <= 0.0;
            let bound = if near_tangent { 1.01 * cap } else { 1e-3 };
            assert!(f.norm() < bound, "step {step}, node {i}: {f:?}");
        }
        // The pulley holds both strands: T along each, pointing away from it (less the cap).
        let expect = V2::new(-2.0 * t, 0.0);
        assert!(
            (on - expect).norm() < 1e-6 * t + 2.0 * cap,
            "step {step}: {on:?}"
        );
        // The friction solve sees T·π of normal load (the capstan's ∫T dφ), whatever the
        // phase of the nodes, on nodes next to or on the arc.
        let load: f64 = out.normal_force.iter().sum();
        assert!(
            (load - t * std::f64::consts::PI).abs() < 1e-6 * t,
            "step {step}: {load}"
        );
        // Every element's tension is T (the wrapped ones measured along the path).
        for e in window.first..window.first + window.len - 1 {
            if tension[e] != 0.0 {
                assert!(
                    (tension[e] - t).abs() < 1e-6 * t,
                    "element {e}: {}",
                    tension[e]
                );
            }
        }
    }
}
