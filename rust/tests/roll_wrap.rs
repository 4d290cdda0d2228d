//! Wrap contact on idler rolls (`beltrs::contact::roll_wrap`): the node forces are minus the
//! gradient of the energy (finite differences), the roll takes the resultant, the forces are
//! continuous as a chain slides over the roll (a node landing on it, an element starting to
//! touch), and a belt lying on its continuous path over a roll (two straight runs tangent to
//! the roll) presses it with the same force whatever the phase of its nodes: the segment
//! contact's chordal action (nodes lifted above the path when the roll is under an element's
//! middle) is gone.
use beltrs::contact::roll_wrap::idler_wrap_contact;
use beltrs::contact::wrap::{wrap, ElementLaw};
use beltrs::contact::{idler_contact, IdlerBody};
use nalgebra::Vector2;

type V2 = Vector2<f64>;

const R: f64 = 0.0635;
const L0: f64 = 0.2;
const K: f64 = 4.0e8; // EA/l, N/m
const KC: f64 = 1.0e8; // roll contact stiffness, N/m

fn roll() -> IdlerBody {
    IdlerBody {
        center: V2::new(0.0, -R),
        radius: R,
        stiffness: KC,
        damping: 0.0,
    }
}

struct Chain {
    stiffness: Vec<f64>,
    damping: Vec<f64>,
    rest: Vec<f64>,
}

impl Chain {
    fn new(n: usize, rest: f64) -> Chain {
        Chain {
            stiffness: vec![K; n],
            damping: vec![0.0; n],
            rest: vec![rest; n],
        }
    }
    fn law(&self) -> ElementLaw<'_> {
        ElementLaw {
            stiffness: &self.stiffness,
            damping: &self.damping,
            rest_length: &self.rest,
            damped: false,
            tension_only: true,
            arm: &[],
        }
    }
}

/// The forces of an open run of nodes `x` (a closed loop in the kernels' indexing, its
/// closing element slack: rest length far above its chord) over the roll: the axial pass's
/// chord forces, then the roll's wrap contact. Returns (node forces, contact).
fn forces(x: &[V2], chain: &Chain) -> (Vec<V2>, beltrs::contact::IdlerContact) {
    let n = x.len();
    let v = vec![V2::zeros(); n];
    let law = chain.law();
    let mut f = vec![V2::zeros(); n];
    let mut tension = vec![0.0; n];
    for e in 0..n {
        let j = (e + 1) % n;
        let d = x[j] - x[e];
        let l = d.norm();
        let t = law.tension(e, l, 0.0);
        tension[e] = t;
        f[e] += d * (t / l);
        f[j] -= d * (t / l);
    }
    let mut claimed = vec![0u64; n];
    let mut element = n / 2;
    let c = idler_wrap_contact(
        &mut element,
        x,
        &v,
        &roll(),
        &law,
        &mut claimed,
        1,
        &mut f,
        &mut tension,
        None,
    );
    (f, c)
}

/// Energy of the same run: the elements at their wrapped length where the roll wraps them
/// (the contact's elements: the tracked one and its neighbours), at their chord elsewhere,
/// plus the penalty of nodes inside the roll.
fn energy(x: &[V2], chain: &Chain) -> f64 {
    let n = x.len();
    let law = chain.law();
    let b = roll();
    let mut e = 0.0;
    for k in 0..n {
        let (p, q) = (x[k], x[(k + 1) % n]);
        let l = match wrap(p, q, b.center, b.radius) {
            Some(g) if k > 0 && k + 1 < n => g.length,
            _ => (q - p).norm(),
        };
        e += law.energy(k, l);
    }
    for p in x {
        let depth = b.radius - (p - b.center).norm();
        if depth > 0.0 {
            e += 0.5 * KC * depth * depth;
        }
    }
    e
}

/// Nodes at spacing `h` of path length along the path that rises at `slope` to the roll,
/// follows it and falls at `slope` beyond (the continuous belt over a roll: a slope change
/// of 2·slope, rounded by the roll), the first node at path length `s0` from the first
/// tangent point (negative: before it).
fn on_path(s0: f64, h: f64, nodes: usize, slope: f64) -> Vec<V2> {
    let a = slope.atan();
    let c = roll().center;
    let left = c + V2::new(-a.sin(), a.cos()) * R;
    let right = c + V2::new(a.sin(), a.cos()) * R;
    let arc = 2.0 * a * R;
    let point = |s: f64| {
        if s <= 0.0 {
            left + V2::new(a.cos(), a.sin()) * s
        } else if s >= arc {
            right + V2::new(a.cos(), -a.sin()) * (s - arc)
        } else {
            let phi = a - s / R; // from the vertical, clockwise
            c + V2::new(-phi.sin(), phi.cos()) * R
        }
    };
    (0..nodes).map(|k| point(s0 + h * k as f64)).collect()
}

#[test]
fn node_forces_are_minus_the_energy_gradient() {
    let chain = Chain::new(6, L0 * 0.999);
    // Six nodes over the roll: one element cutting the roll, one node pressed into it.
    let mut x = on_path(-0.45, L0, 5, 0.02);
    x.push(V2::new(0.0, -2.0)); // the closing elements: slack
    let mut chain = chain;
    chain.rest[4] = 10.0;
    chain.rest[5] = 10.0;
    // One node pressed 5 µm into the roll.
    let i = (0..5)
        .min_by(|&a, &b| x[a].x.abs().total_cmp(&x[b].x.abs()))
        .unwrap();
    let c = roll().center;
    x[i] = c + (x[i] - c).normalize() * (R - 5e-6);
    let (f, contact) = forces(&x, &chain);
    assert!(contact.active);
    let h = 1e-9;
    for k in 0..5 {
        for (axis, unit) in [(0, V2::new(1.0, 0.0)), (1, V2::new(0.0, 1.0))] {
            let (mut a, mut b) = (x.clone(), x.clone());
            a[k] += unit * h;
            b[k] -= unit * h;
            let grad = (energy(&a, &chain) - energy(&b, &chain)) / (2.0 * h);
            let tol = 1e-5 * f[k].norm().max(1.0) + 1e-3;
            assert!(
                (f[k][axis] + grad).abs() < tol,
                "node {k} axis {axis}: {} vs {}",
                f[k][axis],
                -grad
            );
        }
    }
}

#[test]
fn roll_takes_the_resultant_through_its_centre() {
    let mut chain = Chain::new(6, L0 * 0.999);
    chain.rest[4] = 10.0;
    chain.rest[5] = 10.0;
    // (Not with a node within a few mm of a tangent point: there the radial pull on it is
    // capped at the contact stiffness times its height, `contact::wrap::capped`, and the
    // roll takes the difference, as a penalty spring would, until the node settles.)
    for x0 in [-0.45, -0.41, -0.37, -0.33, -0.4 + 0.01 * R] {
        let mut x = on_path(x0, L0, 5, 0.02);
        x.push(V2::new(0.0, -2.0));
        let (f, c) = forces(&x, &chain);
        // Internal forces cancel: the net force on the nodes is the roll's push.
        let net: V2 = f.iter().sum();
        assert!(c.active);
        assert!(
            (net - c.normal * c.normal_force).norm() < 1e-6 * c.normal_force,
            "{net:?} vs {:?}",
            c.normal * c.normal_force
        );
        // It pushes out of the roll, near the vertical, and about 2·T·slope.
        let t = K * (L0 - L0 * 0.999);
        assert!(c.normal.y > 0.99, "{:?}", c.normal);
        let expect = 2.0 * t * 0.02_f64.atan().sin();
        assert!(
            (c.normal_force - expect).abs() < 0.01 * expect,
            "x0 {x0}: {} vs {expect}",
            c.normal_force
        );
        assert!(c.gamma >= 0.0 && c.gamma <= 1.0);
    }
}

#[test]
fn the_roll_load_is_the_same_at_every_phase_of_the_nodes() {
    // The belt on its continuous path over the roll, its nodes shifted along it through one
    // element: the wrap contact sees the same load (to the nodes' penalty on the short arc),
    // the segment contact does not (a straight element under tension over the roll lifts its
    // nodes off the path, so nodes laid on the path press the roll's chord into it).
    let slope: f64 = 0.0175; // a carry roll: half the slope change q·a/T = 0.035
    let mut chain = Chain::new(8, L0 * 0.9995);
    chain.rest[6] = 10.0;
    chain.rest[7] = 10.0;
    let t = K * (L0 - L0 * 0.9995);
    let expect = 2.0 * t * slope.atan().sin();
    let (mut wrap_lo, mut wrap_hi) = (f64::INFINITY, 0.0_f64);
    let (mut seg_lo, mut seg_hi) = (f64::INFINITY, 0.0_f64);
    for k in 0..40 {
        let mut x = on_path(-0.65 + L0 * k as f64 / 40.0, L0, 7, slope);
        x.push(V2::new(0.0, -2.0));
        let (_, c) = forces(&x, &chain);
        wrap_lo = wrap_lo.min(c.normal_force);
        wrap_hi = wrap_hi.max(c.normal_force);
        let v = vec![V2::zeros(); x.len()];
        let mut f = vec![V2::zeros(); x.len()];
        let mut element = 3;
        let s = idler_contact(&mut element, &x, &v, &roll(), &mut f);
        seg_lo = seg_lo.min(if s.active { s.normal_force } else { 0.0 });
        seg_hi = seg_hi.max(s.normal_force);
    }
    assert!(
        (wrap_lo - expect).abs() < 0.01 * expect,
        "{wrap_lo} vs {expect}"
    );
    assert!(
        (wrap_hi - expect).abs() < 0.01 * expect,
        "{wrap_hi} vs {expect}"
    );
    // The segment contact: every chord next to the roll dips into it (the path is convex
    // there), by up to θ·l/8 when the roll is under an element's middle: the load swings by
    // tens of kN at 1e8 N/m.
    assert!(seg_hi - seg_lo > 10.0 * expect, "{seg_lo} .. {seg_hi}");
}

#[test]
fn forces_are_continuous_as_the_chain_slides_over_the_roll() {
    // The belt sliding along its path over the roll in steps of 10 µm: no force jumps as an
    // element starts to touch, a node lands on the roll or leaves it (a jump would be of
    // order T·slope, ~1.4 kN here).
    let slope: f64 = 0.0175;
    let mut chain = Chain::new(8, L0 * 0.9995);
    chain.rest[6] = 10.0;
    chain.rest[7] = 10.0;
    let mut last: Option<Vec<V2>> = None;
    let step = 1e-5;
    let mut worst = 0.0_f64;
    for k in 0..(2.0 * L0 / step) as usize {
        let mut x = on_path(-0.65 + step * k as f64, L0, 7, slope);
        x.push(V2::new(0.0, -2.0));
        let (f, _) = forces(&x, &chain);
        if let Some(prev) = &last {
            for i in 0..7 {
                worst = worst.max((f[i] - prev[i]).norm());
            }
        }
        last = Some(f);
    }
    assert!(
        worst < 50.0,
        "largest change of a node force over a 10 µm slide: {worst} N"
    );
}

/// The closed chain's element tensions on its nodes plus each node's weight `weight` (N,
/// acting in −y): the axial pass of the chain runs below.
fn weighed_chain_forces(x: &[V2], law: &ElementLaw, weight: f64) -> Vec<V2> {
    let n = x.len();
    let mut f = vec![V2::new(0.0, -weight); n];
    for e in 0..n {
        let j = (e + 1) % n;
        let d = x[j] - x[e];
        let len = d.norm();
        let te = law.tension(e, len, 0.0);
        f[e] += d * (te / len);
        f[j] -= d * (te / len);
    }
    f
}

/// A chain of 20 kg nodes (0.2 m elements, 100 kg/m of belt and load) at 12 kN runs at
/// `speed` m/s under gravity over five rolls of radius `radius` 1.2 m apart (their tops at
/// 0, a turn of q·a/T ≈ 0.1 over each), its two ends driven along at that speed at the
/// height of the tops 3.6 m either side of the middle roll at 2 m/s (longer above 2 m/s,
/// so that the chain still covers the rolls at the end). Returns the middle roll's normal
/// force every step over 0.4 s (four elements passing it at 2 m/s) after 0.3 s of settling
/// (nodes damped towards the belt's speed for the first 0.25 s). `damped`: the rolls'
/// contact damping (half critical on one node), else none.
fn run_over(radius: f64, speed: f64, damped: bool) -> Vec<f64> {
    let (l, mass, g, pitch) = (0.2, 20.0, 9.81, 1.2);
    let extra = ((speed - 2.0).max(0.0) * 0.7 / l).ceil() as usize;
    let n: usize = 37 + 2 * extra;
    const DT: f64 = 2e-5;
    // EA/l = 4e8 n/m, stretched 3e-5 m: 12 kN.
    let mut chain = Chain::new(n, l - 3e-5);
    chain.rest[n - 1] = 1e3; // the closing element, slack
    let law = chain.law();
    let bodies: Vec<IdlerBody> = (-2..=2)
        .map(|k| IdlerBody {
            center: V2::new(k as f64 * pitch, -radius),
            radius,
            stiffness: KC,
            // half critical on one node, as the builder's rolls
            damping: if damped { (KC * mass).sqrt() } else { 0.0 },
        })
        .collect();
    // Nodes on the parabolas between the tops, node n/2 this far before the middle roll.
    let start = -0.05;
    let sag = |x: f64| {
        let u = (x + 3.0 * pitch).rem_euclid(pitch);
        -mass / l * g * u * (pitch - u) / (2.0 * 12e3)
    };
    let mut x: Vec<V2> = (0..n)
        .map(|i| {
            let xi = start + (i as f64 - (n / 2) as f64) * l;
            V2::new(xi, sag(xi))
        })
        .collect();
    let ends = (x[0], x[n - 1]);
    let mut v = vec![V2::new(speed, 0.0); n];
    let mut claimed = vec![0u64; n];
    let mut element: Vec<usize> = bodies
        .iter()
        .map(|b| {
            (0..n - 1)
                .min_by(|&i, &j| {
                    (x[i] - b.center)
                        .norm()
                        .total_cmp(&(x[j] - b.center).norm())
                })
                .unwrap()
        })
        .collect();
    let mut tension = vec![0.0; n];
    let (settle, measure) = ((0.3 / DT) as usize, (0.4 / DT) as usize);
    let mut load = Vec::with_capacity(measure);
    for step in 0..settle + measure {
        let t = step as f64 * DT;
        let mut f = weighed_chain_forces(&x, &law, mass * g);
        for (k, body) in bodies.iter().enumerate() {
            let c = idler_wrap_contact(
                &mut element[k],
                &x,
                &v,
                body,
                &law,
                &mut claimed,
                step as u64 + 1,
                &mut f,
                &mut tension,
                None,
            );
            if k == 2 && step >= settle {
                load.push(c.normal_force);
            }
        }
        let damp = if t < 0.25 {
            0.2 * (4e8 * mass).sqrt()
        } else {
            0.0
        };
        for i in 1..n - 1 {
            let a = (f[i] - (v[i] - V2::new(speed, 0.0)) * damp) / mass;
            v[i] += a * DT;
            x[i] += v[i] * DT;
        }
        let shift = V2::new(speed * (t + DT), 0.0);
        x[0] = ends.0 + shift;
        x[n - 1] = ends.1 + shift;
    }
    load
}

#[test]
fn a_node_crossing_the_spread_arc_keeps_the_roll_loaded() {
    // A lumped node on a roll's own arc gets no pull towards it from the element's path
    // tension (the path's gradient there is its tangent): held by gravity alone it leaves
    // the roll when v² > g·R (0.41 m at 2 m/s against a 0.0665 m roll), flies over it and
    // the roll unloads as each node passes. Over the spread circle (`wrap_radius`: three
    // element lengths, 0.6 m here, above 0.41 m) it stays on. Measured over 0.4 s: the bare
    // roll's load falls to 0 (flight) at every passing (mean 1172 N), the spread circle's
    // never below 668 N (mean 1174 N). Both swing with the nodes' phase by about ±40 %
    // in this short chain (its 10 Hz sway, rung by the start and undamped, is at the
    // passing frequency): the bound is 0.4 of the mean, and flight would read 0.
    let bare = run_over(0.0665, 2.0, true);
    let spread = run_over(
        beltrs::contact::roll_wrap::wrap_radius(0.0665, 0.2, 2.0, 9.81),
        2.0,
        true,
    );
    let mean = |s: &[f64]| s.iter().sum::<f64>() / s.len() as f64;
    let min = |s: &[f64]| s.iter().cloned().fold(f64::INFINITY, f64::min);
    println!(
        "bare: mean {:.1} min {:.1} N; spread: mean {:.1} min {:.1} N",
        mean(&bare),
        min(&bare),
        mean(&spread),
        min(&spread)
    );
    assert_eq!(
        min(&bare),
        0.0,
        "the bare roll unloads: the node flies over its arc"
    );
    assert!(
        min(&spread) > 0.4 * mean(&spread),
        "{} {}",
        min(&spread),
        mean(&spread)
    );
}

/// Five nodes 0.2 m apart along the top of a wrap circle of radius `radius` (m), the chain
/// stretched to 12 kN, running along it at `speed` (m/s): nodes 0 and 4 driven round the
/// circle, nodes 1–3 free (20 kg each, gravity, the wrap contact with the builders' damping
/// on the middle elements). Returns the middle node's largest height above the circle (m)
/// over `time` s.
fn node_on_circle(radius: f64, speed: f64, time: f64) -> f64 {
    const N: usize = 5;
    const DT: f64 = 2e-6;
    let (l, mass, g) = (0.2, 20.0, 9.81);
    let mut chain = Chain::new(N, l - 3e-5);
    chain.rest[N - 1] = 1e3; // the closing element, slack
    let law = chain.law();
    let body = IdlerBody {
        center: V2::new(0.0, -radius),
        radius,
        stiffness: KC,
        damping: (KC * mass).sqrt(),
    };
    let at = |phi: f64| body.center + V2::new(phi.sin(), phi.cos()) * radius;
    let dphi = l / radius;
    let omega = speed / radius;
    let mut x: Vec<V2> = (0..N).map(|i| at((i as f64 - 2.0) * dphi)).collect();
    let mut v: Vec<V2> = (0..N)
        .map(|i| {
            let phi = (i as f64 - 2.0) * dphi;
            V2::new(phi.cos(), -phi.sin()) * speed
        })
        .collect();
    let mut claimed = vec![0u64; N];
    let mut element = 1;
    let mut tension = vec![0.0; N];
    let mut highest: f64 = 0.0;
    let steps = (time / DT) as usize;
    for step in 0..steps {
        let t = (step + 1) as f64 * DT;
        let mut f = weighed_chain_forces(&x, &law, mass * g);
        idler_wrap_contact(
            &mut element,
            &x,
            &v,
            &body,
            &law,
            &mut claimed,
            step as u64 + 1,
            &mut f,
            &mut tension,
            None,
        );
        for i in 1..N - 1 {
            v[i] += f[i] / mass * DT;
            x[i] += v[i] * DT;
        }
        for (i, phi0) in [(0, -2.0 * dphi), (N - 1, 2.0 * dphi)] {
            x[i] = at(phi0 + omega * t);
        }
        highest = highest.max((x[2] - body.center).norm() - radius);
    }
    highest
}

#[test]
fn at_conveyor_speed_the_node_stays_on_the_speed_aware_circle() {
    // A lumped node on the wrap circle gets no pull towards it from the path tension (the
    // path's gradient there is the circle's tangent): gravity alone must give it v²/R_w.
    // At 5 m/s over session 9's circle of three element lengths (0.6 m, v²/R_w = 41.7 m/s²)
    // it leaves the circle: 1.2 mm in 0.02 s (free, ½·(v²/R_w − g)·t² = 6 mm; its
    // neighbours, held by the chords of the outer elements the contact does not track,
    // hold it back). Over the speed-aware circle (`wrap_radius`: k·v²/g, 3.57 m,
    // v²/R_w = g/k = 7.0 m/s²) gravity presses it on with (1 − 1/k) of its weight: it never
    // rises above the circle (measured 0; 0.1 mm allowed, the old circle's flight 12×).
    use beltrs::contact::roll_wrap::{wrap_radius, ARC_SPREAD, FLIGHT_MARGIN};
    let (v, g, l) = (5.0, 9.81, 0.2);
    let old = 0.0665f64.max(ARC_SPREAD * l);
    let new = wrap_radius(0.0665, l, v, g);
    assert_eq!(new, FLIGHT_MARGIN * v * v / g);
    let before = node_on_circle(old, v, 0.02);
    let after = node_on_circle(new, v, 0.02);
    println!("middle node's largest height above the circle: R_w {old:.3} m {before:e} m; R_w {new:.3} m {after:e} m");
    assert!(before > 5e-4, "over 3·l the node flies at 5 m/s: {before}");
    assert!(after < 1e-4, "{after}");
}

#[test]
fn the_wrap_radius_law() {
    use beltrs::contact::roll_wrap::{wrap_radius, ARC_SPREAD, ARC_SPREAD_MAX, FLIGHT_MARGIN};
    // The builders' 0.0665 m rolls, 0.2094 m elements: up to 2 m/s (and at 1.5 m/s on
    // 0.15 m elements) the circle is session 9's 3·l; above, k·v²/g.
    let (r, g) = (0.0665, 9.81);
    for v in [0.0, 1.0, 2.0] {
        assert_eq!(wrap_radius(r, 0.2094, v, g), 3.0 * 0.2094);
        assert_eq!(wrap_radius(r, 0.2, v, g), ARC_SPREAD * 0.2);
    }
    assert_eq!(wrap_radius(r, 0.15, 1.5, g), ARC_SPREAD * 0.15);
    for v in [3.0, 4.0, 5.0] {
        assert_eq!(wrap_radius(r, 0.2094, v, g), FLIGHT_MARGIN * v * v / g);
    }
    // Above about 5.4 m/s the arc would outgrow the four nodes the contact tracks.
    for v in [6.0, 8.0] {
        assert_eq!(wrap_radius(r, 0.2094, v, g), ARC_SPREAD_MAX * 0.2094);
    }
    // A big roll keeps its own radius; no gravity, no flight term (nothing holds a node
    // on any circle); a speed is a speed whatever its sign.
    assert_eq!(wrap_radius(3.0, 0.2, 4.0, g), 3.0);
    assert_eq!(wrap_radius(r, 0.2, 6.0, 0.0), ARC_SPREAD * 0.2);
    assert_eq!(wrap_radius(r, 0.2, -4.0, g), wrap_radius(r, 0.2, 4.0, g));
}

/// A node `p` approaching a roll along its sagged chain at `speed`, the element beyond it
/// wrapped over the roll to `q`: the element before `p` flatter than the wrapped piece by
/// the node's kink 2α, `p` moving along their bisector (its locus in steady running), the
/// chain at 12 kN, every other node at rest. Returns (the damping's force on `p`: its force
/// with the roll's contact damping `c` less that without, the approach across the piece's
/// line, the speed along it).
fn steady_approach(alpha: f64, speed: f64, c: f64) -> (V2, f64, f64) {
    let (l, t) = (0.2, 12e3);
    let beta: f64 = 0.05; // the piece's slope where it meets the roll
    let rot = |a: V2, th: f64| {
        V2::new(
            a.x * th.cos() - a.y * th.sin(),
            a.x * th.sin() + a.y * th.cos(),
        )
    };
    let centre = V2::new(0.0, -R);
    let d = V2::new(beta.cos(), beta.sin());
    let p = centre + V2::new(-beta.sin(), beta.cos()) * R - d * 0.1;
    let d2 = V2::new(beta.cos(), -beta.sin());
    let q = centre + V2::new(beta.sin(), beta.cos()) * R + d2 * 0.1;
    let e = rot(d, -2.0 * alpha);
    let x = vec![
        p - e * (2.0 * l),
        p - e * l,
        p,
        q,
        q + d2 * l,
        q + d2 * (2.0 * l),
    ];
    let n = x.len();
    let mut v = vec![V2::zeros(); n];
    v[2] = rot(d, -alpha) * speed;
    let mut chain = Chain::new(n, l);
    for k in 0..n {
        let len = match k {
            2 => wrap(x[2], x[3], centre, R).unwrap().length,
            _ => (x[(k + 1) % n] - x[k]).norm(),
        };
        chain.rest[k] = len - t / K;
    }
    chain.rest[n - 1] = 1e3; // the closing element, slack
    let law = chain.law();
    let run = |damping: f64| {
        let body = IdlerBody {
            center: centre,
            radius: R,
            stiffness: KC,
            damping,
        };
        let mut f = vec![V2::zeros(); n];
        let mut tension = vec![0.0; n];
        let mut claimed = vec![0u64; n];
        let mut element = 2;
        idler_wrap_contact(
            &mut element,
            &x,
            &v,
            &body,
            &law,
            &mut claimed,
            1,
            &mut f,
            &mut tension,
            None,
        );
        assert!((tension[2] - t).abs() < 1e-6 * t, "{}", tension[2]);
        f[2]
    };
    (run(c) - run(0.0), speed * alpha.sin(), speed * alpha.cos())
}

#[test]
fn the_tangent_line_damping_on_a_node_running_along_its_chain() {
    // A 20 kg node kinked by its weight (m·g = 2·α·T) approaching a roll along its locus
    // crosses the wrapped piece's line at v·sin α though the belt does not approach the
    // roll. With the roll's damping c (half critical, 44.7e3 N·s/m) the damper's steady
    // force would be c·v·α, in the node's weights c·v/(2T) (T = 12 kN): 0.93 at 0.5 m/s,
    // 3.7 at 2, 9.3 at 5, 14.9 at 8 m/s. Limited (`tangent_damping`) it is c·v·α while
    // that stays below η·m·g and η·m·g above, whatever the speed.
    use beltrs::contact::roll_wrap::{tangent_damping, TANGENT_DAMPING_WEIGHTS};
    let (c, t) = ((KC * 20.0).sqrt(), 12e3);
    let weight = 20.0 * 9.81;
    let alpha = weight / (2.0 * t);
    for speed in [0.5, 2.0, 5.0, 8.0] {
        let (f, approach, along) = steady_approach(alpha, speed, c);
        let expected = tangent_damping(c, t, along) * approach;
        assert!(
            (f.norm() - expected).abs() < 1e-9 * expected,
            "{speed} m/s: {} against {expected}",
            f.norm()
        );
        let free = c * approach; // the roll's damping as it is
        println!(
            "{speed} m/s: steady force {:.1} N = {:.3} node weights (unlimited {:.1} N)",
            f.norm(),
            f.norm() / weight,
            free
        );
        if c * speed / (2.0 * t) <= TANGENT_DAMPING_WEIGHTS {
            assert!((f.norm() - free).abs() < 1e-9 * free, "below the limit: c");
        } else {
            // η·m·g, within cos α (the speed along the piece) and sin α/α: 1e-4 here
            assert!(
                (f.norm() / weight - TANGENT_DAMPING_WEIGHTS).abs()
                    < 1e-4 * TANGENT_DAMPING_WEIGHTS,
                "{}",
                f.norm() / weight
            );
        }
    }
    // At rest (a real approach, the belt stopped) or without tension: the roll's damping.
    assert_eq!(tangent_damping(c, t, 0.0), c);
    assert_eq!(tangent_damping(c, 0.0, 5.0), c);
    assert_eq!(tangent_damping(c, t, -5.0), tangent_damping(c, t, 5.0));
    assert_eq!(
        tangent_damping(c, t, 5.0),
        2.0 * TANGENT_DAMPING_WEIGHTS * t / 5.0
    );
}
