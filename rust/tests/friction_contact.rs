//! Contact and stick-force friction kernels against hand-derived physics.
//!
//! Conventions (see `contact.rs` / `friction.rs`): the outward normal n points from the body
//! centre to the belt, the tangent is t = (−n.y, n.x) (counter-clockwise), the node receives
//! −f·t and the body +f·t and torque R·f, and the relative tangential speed of a pulley
//! contact is v_n = t·(v_i − v_centre) − R·ω.
//!
//! Every expected value below is computed here from the physics (penalty law, lever rule,
//! one explicit step of Newton's law), not by calling the kernels' own helpers.
use beltrs::contact::{
    idler_contact, pulley_contact, segment_distance, update_window, IdlerBody, IdlerContact,
    PulleyBody, PulleyContacts,
};
use beltrs::friction::{
    idler_stick_friction, pulley_stick_friction, FrictionIdler, FrictionPulley, Prescribed,
    StickScratch,
};
use beltrs::state::ContactWindow;
use nalgebra::Vector2;

type V2 = Vector2<f64>;

/// Counter-clockwise tangent for an outward normal, written out independently of the crate.
fn tangent(n: V2) -> V2 {
    V2::new(-n.y, n.x)
}

fn unit(angle: f64) -> V2 {
    V2::new(angle.cos(), angle.sin())
}

/// Small deterministic generator (xorshift64*), so the "random-ish" inputs are reproducible.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let bits = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11;
        lo + (hi - lo) * (bits as f64 / (1u64 << 53) as f64)
    }
    fn vec(&mut self, half: f64) -> V2 {
        V2::new(self.uniform(-half, half), self.uniform(-half, half))
    }
}

/// |a − b| ≤ tol·scale, with a readable panic message.
fn assert_close(what: &str, got: f64, want: f64, tol: f64, scale: f64) {
    assert!(
        (got - want).abs() <= tol * scale,
        "{what}: got {got:e}, want {want:e} (diff {:e}, allowed {:e})",
        (got - want).abs(),
        tol * scale
    );
}

fn assert_close_v(what: &str, got: V2, want: V2, tol: f64, scale: f64) {
    assert_close(&format!("{what}.x"), got.x, want.x, tol, scale);
    assert_close(&format!("{what}.y"), got.y, want.y, tol, scale);
}

// ---------------------------------------------------------------------------------------
// 1. Pulley contact force law
// ---------------------------------------------------------------------------------------

/// A 16-node ring (radius 1, centre (1.25, −0.2)) that dips into a pulley of radius 0.5 at
/// (0.4, −0.15). By construction 3 nodes (angles 157.5°, 180°, 202.5°) are inside the
/// pulley, 2 more (135°, 225°) lie between R and R + margin, and the rest are beyond.
fn dipping_ring() -> (Vec<V2>, PulleyBody) {
    let n = 16;
    let x = (0..n)
        .map(|i| V2::new(1.25, -0.2) + unit(std::f64::consts::TAU * i as f64 / n as f64))
        .collect();
    let body = PulleyBody {
        center: V2::new(0.4, -0.15),
        center_velocity: V2::zeros(),
        radius: 0.5,
        stiffness: 2.0e6,
        damping: 0.0,
        margin: 0.3,
    };
    (x, body)
}

/// Indices of the window as a sorted list.
fn window_nodes(w: &ContactWindow, n: usize) -> Vec<usize> {
    let mut v: Vec<usize> = (0..w.len).map(|k| (w.first + k) % n).collect();
    v.sort_unstable();
    v
}

#[test]
fn pulley_contact_is_linear_penalty_along_outward_normal() {
    let (x, body) = dipping_ring();
    let n = x.len();
    let v = vec![V2::zeros(); n];

    // Brute force: who is within R (contact) and within R + margin (window).
    let dist: Vec<f64> = x.iter().map(|p| (p - body.center).norm()).collect();
    let inside: Vec<usize> = (0..n).filter(|&i| dist[i] < body.radius).collect();
    let near: Vec<usize> = (0..n)
        .filter(|&i| dist[i] < body.radius + body.margin)
        .collect();
    // Guard the construction: otherwise the test would check nothing interesting.
    assert_eq!(inside, vec![7, 8, 9]);
    assert_eq!(near, vec![6, 7, 8, 9, 10]);

    // From an empty window (full scan) and from a window overlapping the run at one end.
    for start in [
        ContactWindow::default(),
        ContactWindow { first: 10, len: 1 },
        ContactWindow { first: 4, len: 4 },
    ] {
        let mut w = start;
        update_window(&mut w, &x, &body, false);
        assert_eq!(window_nodes(&w, n), near, "window from {start:?}");

        // Pre-load the force array: the kernel must add, not overwrite.
        let before: Vec<V2> = (0..n).map(|i| V2::new(i as f64, -3.0 * i as f64)).collect();
        let mut force = before.clone();
        let mut out = PulleyContacts::default();
        let on_pulley = pulley_contact(&w, &x, &v, &body, &mut force, &mut out);

        let mut got_nodes = out.node.clone();
        got_nodes.sort_unstable();
        assert_eq!(got_nodes, inside);

        // Force scale k·R = 1e6 N; the kernel evaluates the same closed form with a
        // different operation order, so agreement is at rounding level (~1e-16 relative).
        // 1e-12·k·R leaves ample room for that and still catches any wrong factor or sign.
        let scale = body.stiffness * body.radius;
        let mut sum = V2::zeros();
        for i in 0..n {
            let added = force[i] - before[i];
            let rel = x[i] - body.center;
            let a = rel.norm();
            let want = if a < body.radius {
                rel / a * (body.stiffness * (body.radius - a))
            } else {
                V2::zeros()
            };
            assert_close_v(&format!("force on node {i}"), added, want, 1e-12, scale);
            sum += want;
        }
        // Newton's third law: the pulley receives minus the sum of the node forces.
        assert_close_v("force on pulley", on_pulley, -sum, 1e-12, scale);

        // The recorded contacts describe the same law.
        for k in 0..out.len() {
            let i = out.node[k];
            let rel = x[i] - body.center;
            let a = rel.norm();
            assert_close_v("normal", out.normal[k], rel / a, 1e-14, 1.0);
            assert_close(
                "penetration",
                out.penetration[k],
                body.radius - a,
                1e-14,
                1.0,
            );
            assert_close(
                "normal force",
                out.normal_force[k],
                body.stiffness * (body.radius - a),
                1e-12,
                scale,
            );
        }
    }
}

#[test]
fn pulley_contact_is_zero_at_and_beyond_the_radius() {
    // Node 0 exactly on the surface (0.5 is exact in binary, so a² == R² exactly), node 1
    // a hair outside, node 2 a hair inside. Only node 2 may be pushed.
    let body = PulleyBody {
        center: V2::zeros(),
        center_velocity: V2::zeros(),
        radius: 0.5,
        stiffness: 1.0e7,
        damping: 0.0,
        margin: 0.1,
    };
    let x = vec![
        V2::new(0.5, 0.0),
        V2::new(0.0, 0.5 * (1.0 + 1e-12)),
        V2::new(-0.5 * (1.0 - 1e-6), 0.0),
        V2::new(5.0, 5.0),
    ];
    let v = vec![V2::zeros(); x.len()];
    let mut w = ContactWindow::default();
    update_window(&mut w, &x, &body, false);
    assert_eq!(window_nodes(&w, x.len()), vec![0, 1, 2]);
    let mut force = vec![V2::zeros(); x.len()];
    let mut out = PulleyContacts::default();
    let on_pulley = pulley_contact(&w, &x, &v, &body, &mut force, &mut out);
    assert_eq!(force[0], V2::zeros(), "a == R must give exactly zero");
    assert_eq!(force[1], V2::zeros(), "a > R must give exactly zero");
    assert_eq!(force[3], V2::zeros());
    assert_eq!(out.node, vec![2]);
    // Depth 0.5e-6 m, k = 1e7 N/m → 5 N along −x. Rounding in the depth is ~1e-16 m, i.e.
    // ~1e-9 N, so 1e-8 N absolute is a safe bound that still detects any real error.
    assert_close_v("node 2", force[2], V2::new(-5.0, 0.0), 1e-8, 1.0);
    assert_close_v("pulley", on_pulley, V2::new(5.0, 0.0), 1e-8, 1.0);
}

#[test]
fn pulley_contact_damping_acts_on_approach_speed_and_never_pulls() {
    let (x, mut body) = dipping_ring();
    body.damping = 2.0e5;
    body.center_velocity = V2::new(0.3, -1.1); // moving centre (takeup-like)
    let n = x.len();

    // Normal velocity relative to the centre, as a multiple of k·depth/c:
    // node 7 approaches (force > k·depth), node 8 recedes slowly (0 < force < k·depth),
    // node 9 recedes fast (k·depth + c·approach < 0 → exactly 0, not a pull).
    // Each node also gets a tangential component, which must not matter.
    let factor = [(7usize, -0.5), (8, 0.5), (9, 3.0)];
    let mut v = vec![V2::new(7.0, 7.0); n];
    for &(i, s) in &factor {
        let rel = x[i] - body.center;
        let a = rel.norm();
        let nrm = rel / a;
        let depth = body.radius - a;
        let outward_speed = s * body.stiffness * depth / body.damping;
        v[i] = body.center_velocity + nrm * outward_speed + tangent(nrm) * 2.5;
    }
    let mut w = ContactWindow::default();
    update_window(&mut w, &x, &body, false);
    let mut force = vec![V2::zeros(); n];
    let mut out = PulleyContacts::default();
    let on_pulley = pulley_contact(&w, &x, &v, &body, &mut force, &mut out);
    assert_eq!(out.len(), 3);

    // Same rounding argument as the undamped test: 1e-12 of the k·R force scale.
    let scale = body.stiffness * body.radius;
    let mut sum = V2::zeros();
    for &(i, s) in &factor {
        let rel = x[i] - body.center;
        let a = rel.norm();
        let nrm = rel / a;
        let elastic = body.stiffness * (body.radius - a);
        let approach = -(v[i] - body.center_velocity).dot(&nrm);
        let want = (elastic + body.damping * approach).max(0.0);
        match s {
            s if s < 0.0 => assert!(want > elastic),
            s if s < 1.0 => assert!(want > 0.0 && want < elastic),
            _ => assert_eq!(want, 0.0),
        }
        assert_close_v(&format!("node {i}"), force[i], nrm * want, 1e-12, scale);
        // Never a pulling force: the normal component is ≥ 0 on every node.
        assert!(
            force[i].dot(&nrm) >= 0.0,
            "node {i} is pulled onto the pulley"
        );
        sum += nrm * want;
    }
    // Receding fast: exactly zero force (max(…, 0) must clip, not leave a pull).
    assert_eq!(force[9], V2::zeros());
    let k9 = out.node.iter().position(|&i| i == 9).unwrap();
    assert_eq!(out.normal_force[k9], 0.0);
    assert_close_v("pulley", on_pulley, -sum, 1e-12, scale);
}

// ---------------------------------------------------------------------------------------
// 2. Idler contact
// ---------------------------------------------------------------------------------------

/// A closed belt loop: carry run y = 0 from x = 0 to 9 (nodes 0–9, element e joins x = e and
/// x = e + 1), return run y = −4 back to x = 0 (nodes 10–19), closing element 19 vertical.
/// Mapped by a rigid motion (rotation `theta`, translation `shift`).
fn loop_belt(theta: f64, shift: V2) -> Vec<V2> {
    let rot = nalgebra::Rotation2::new(theta);
    let carry = (0..10).map(|i| V2::new(i as f64, 0.0));
    let ret = (0..10).map(|i| V2::new(9.0 - i as f64, -4.0));
    carry.chain(ret).map(|p| rot * p + shift).collect()
}

#[test]
fn idler_contact_uses_lever_rule_at_the_foot_of_the_perpendicular() {
    // In the unrotated frame the idler centre is at (2.3, −0.4) with R = 0.5: the nearest
    // element is 2 (x ∈ [2, 3]), the foot of the perpendicular is at γ = 0.3, distance 0.4,
    // outward normal +y, penetration 0.1. A rigid motion of the whole scene must not change
    // γ, the distance or the force magnitude, and must rotate the normal.
    for (theta, shift) in [
        (0.0, V2::zeros()),
        (0.7, V2::new(-3.0, 11.0)),
        (-2.4, V2::new(100.0, -50.0)),
    ] {
        let rot = nalgebra::Rotation2::new(theta);
        let x = loop_belt(theta, shift);
        let n = x.len();
        let v = vec![V2::zeros(); n];
        let body = IdlerBody {
            center: rot * V2::new(2.3, -0.4) + shift,
            radius: 0.5,
            stiffness: 3.0e5,
            damping: 0.0,
        };
        // Start 3 elements ahead (5) and 3 behind (19, the closing element, wraps round).
        for start in [5usize, 19] {
            let before: Vec<V2> = (0..n).map(|i| V2::new(0.5 * i as f64, 1.0)).collect();
            let mut force = before.clone();
            let mut element = start;
            let c = idler_contact(&mut element, &x, &v, &body, &mut force);
            assert_eq!(element, 2, "tracked element from {start} (theta {theta})");
            assert!(c.active);
            assert_eq!(c.element, 2);
            // γ and the distance come from coordinates of size ≤ ~100 after the rigid
            // motion, so rounding is ~1e-14 absolute; 1e-12 is safe and still tight.
            assert_close("gamma", c.gamma, 0.3, 1e-12, 1.0);
            assert_close("penetration", c.penetration, 0.1, 1e-12, 1.0);
            let normal = rot * V2::new(0.0, 1.0);
            assert_close_v("normal", c.normal, normal, 1e-12, 1.0);
            let fmag = body.stiffness * 0.1; // k (R − dist) = 3e4 N
            assert_close("normal force", c.normal_force, fmag, 1e-12, body.stiffness);
            for i in 0..n {
                let added = force[i] - before[i];
                let want = match i {
                    2 => normal * (fmag * 0.7),
                    3 => normal * (fmag * 0.3),
                    _ => V2::zeros(),
                };
                // Force error = k·(position rounding) ≈ 3e5·1e-14; 1e-12·k is ample.
                assert_close_v(&format!("node {i}"), added, want, 1e-12, body.stiffness);
            }
        }
        // Not touching (distance 0.6 > R): no force, but the element is still tracked.
        let far = IdlerBody {
            center: rot * V2::new(2.3, -0.6) + shift,
            ..body
        };
        let mut force = vec![V2::zeros(); n];
        let mut element = 5;
        let c = idler_contact(&mut element, &x, &v, &far, &mut force);
        assert!(!c.active);
        assert_eq!(element, 2);
        assert!(force.iter().all(|f| *f == V2::zeros()));
    }
}

#[test]
fn idler_contact_damping_uses_contact_point_velocity() {
    // Same geometry (unrotated). Contact point velocity (1 − γ)v_2 + γ v_3; approach speed
    // −v_c·n with n = +y. With γ = 0.35, v_2 = (4, −2) and v_3 = (−1, 1): v_c =
    // (2.25, −0.95), approach 0.95 m/s → f = k·0.1 + c·0.95. (The roll sits 0.35 m into
    // element 2 so that element 1, 0.53 m away, does not touch it.) Reversing the velocities with a large damping
    // gives a negative sum, which must be clipped to zero.
    let x = loop_belt(0.0, V2::zeros());
    let n = x.len();
    let mut v = vec![V2::zeros(); n];
    v[2] = V2::new(4.0, -2.0);
    v[3] = V2::new(-1.0, 1.0);
    let body = IdlerBody {
        center: V2::new(2.35, -0.4),
        radius: 0.5,
        stiffness: 3.0e5,
        damping: 1.0e4,
    };
    let mut force = vec![V2::zeros(); n];
    let mut element = 2;
    let c = idler_contact(&mut element, &x, &v, &body, &mut force);
    let want = 3.0e5 * 0.1 + 1.0e4 * 0.95;
    // Rounding ~1e-16 relative on a 4e4 N force; 1e-10 relative is a safe bound.
    assert_close("normal force", c.normal_force, want, 1e-10, want);
    assert_close_v("node 2", force[2], V2::new(0.0, 0.65 * want), 1e-10, want);
    assert_close_v("node 3", force[3], V2::new(0.0, 0.35 * want), 1e-10, want);

    v[2] = -v[2];
    v[3] = -v[3];
    let mut force = vec![V2::zeros(); n];
    let body = IdlerBody {
        damping: 1.0e5,
        ..body
    }; // 3e4 − 0.95e5 < 0
    let c = idler_contact(&mut element, &x, &v, &body, &mut force);
    assert!(c.active);
    assert_eq!(c.normal_force, 0.0);
    assert!(
        force.iter().all(|f| *f == V2::zeros()),
        "idler pulls the belt"
    );
}

#[test]
fn segment_distance_matches_rigid_construction() {
    // Foot of the perpendicular built by construction: p + γ d + h d⊥/|d|.
    let mut rng = Rng(0x1234_5678_9abc_def1);
    for _ in 0..50 {
        let p = rng.vec(10.0);
        let d = rng.vec(3.0);
        let gamma = rng.uniform(0.0, 1.0);
        let h = rng.uniform(-2.0, 2.0);
        let c = p + d * gamma + tangent(d.normalize()) * h;
        let (dist, g, closest) = segment_distance(c, p, p + d);
        // Coordinates ≤ ~15, |d| ≥ ~0.01 in practice: rounding well below 1e-9.
        assert_close("gamma", g, gamma, 1e-9, 1.0);
        assert_close("dist", dist, h.abs(), 1e-9, 1.0);
        assert_close_v("closest", closest, p + d * gamma, 1e-9, 1.0);
    }
}

// ---------------------------------------------------------------------------------------
// 3–6. Pulley stick-force friction
// ---------------------------------------------------------------------------------------

/// One contact at `node` with outward normal `normal` and normal force `nf`.
fn one_contact(node: usize, normal: V2, nf: f64) -> PulleyContacts {
    let mut c = PulleyContacts::default();
    c.node.push(node);
    c.normal.push(normal);
    c.normal_force.push(nf);
    c.penetration.push(0.0);
    c
}

/// Explicit update of the nodes and the pulley with the forces after friction, then the
/// relative tangential speed of contact k: t·(v' − v_p) − R ω'. Returns (v_n', scale) where
/// scale bounds the magnitudes of the terms that were added, for relative tolerances.
#[allow(clippy::too_many_arguments)]
fn relative_speed_after(
    contacts: &PulleyContacts,
    k: usize,
    pulley: &FrictionPulley,
    v: &[V2],
    mass: &[f64],
    dt: f64,
    force_after: &[V2],
    torque_out: f64,
) -> (f64, f64) {
    let i = contacts.node[k];
    let t = tangent(contacts.normal[k]);
    let v_new = v[i] + force_after[i] * (dt / mass[i]);
    let omega_new = pulley.omega + dt * (torque_out + pulley.applied_torque) / pulley.inertia;
    let vn_new = t.dot(&(v_new - pulley.center_velocity)) - pulley.radius * omega_new;
    let scale = t.dot(&(v[i] - pulley.center_velocity)).abs()
        + (pulley.radius * pulley.omega).abs()
        + dt * force_after[i].norm() / mass[i]
        + pulley.radius * dt * (torque_out.abs() + pulley.applied_torque.abs()) / pulley.inertia;
    (vn_new, scale)
}

/// Single-node stick force from the zero-relative-speed condition, derived directly:
/// v_n + Δt(t·F − f)/m − RΔt(T + R f)/I = 0
///   ⇒ f = (v_n/Δt + t·F/m − R T/I) / (1/m + R²/I).
/// (Algebraically equal to the kernel's form, but evaluated differently.)
fn single_stick_force(vn: f64, tf: f64, m: f64, p: &FrictionPulley, dt: f64) -> f64 {
    let r = p.radius;
    (vn / dt + tf / m - r * p.applied_torque / p.inertia) / (1.0 / m + r * r / p.inertia)
}

/// Random-ish single-node friction case. The node sits at index 2 of 4.
struct SingleCase {
    pulley: FrictionPulley,
    normal: V2,
    v: Vec<V2>,
    mass: Vec<f64>,
    ext: V2,
    dt: f64,
}

fn single_case(rng: &mut Rng, moving_centre: bool) -> SingleCase {
    let pulley = FrictionPulley {
        radius: rng.uniform(0.2, 2.0),
        inertia: rng.uniform(0.05, 50.0),
        omega: rng.uniform(-20.0, 20.0),
        center_velocity: if moving_centre {
            rng.vec(2.0)
        } else {
            V2::zeros()
        },
        applied_torque: rng.uniform(-500.0, 500.0),
        mu_static: 1e9,
        mu_kinetic: 0.3,
        prescribed: None,
    };
    let normal = unit(rng.uniform(0.0, std::f64::consts::TAU));
    let v = (0..4).map(|_| rng.vec(5.0)).collect();
    let mass = (0..4).map(|_| rng.uniform(0.5, 20.0)).collect();
    SingleCase {
        pulley,
        normal,
        v,
        mass,
        ext: rng.vec(1000.0),
        dt: rng.uniform(1e-5, 1e-3),
    }
}

#[test]
fn stick_force_brings_single_node_to_surface_speed() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for trial in 0..40 {
        let c = single_case(&mut rng, trial % 2 == 1);
        let contacts = one_contact(2, c.normal, 1.0e3);
        let mut force = vec![V2::new(11.0, -7.0); 4];
        force[2] = c.ext;
        let mut scratch = StickScratch::default();
        let out = pulley_stick_friction(
            &contacts,
            &c.pulley,
            &c.v,
            &c.mass,
            c.dt,
            &mut force,
            &mut scratch,
        );
        assert_eq!(out.slipping, 0, "trial {trial}: µs·N = 1e12 must hold");
        let (vn_new, scale) = relative_speed_after(
            &contacts, 0, &c.pulley, &c.v, &c.mass, c.dt, &force, out.torque,
        );
        // The residual is a sum of a few terms of size ≤ `scale`, each carrying ~1e-16
        // relative rounding; 1e-9 of the scale is far above that and far below any error
        // in the stick force (a 1e-9 relative error in f already shows).
        assert!(
            vn_new.abs() <= 1e-9 * scale,
            "trial {trial}: relative speed after step {vn_new:e} (scale {scale:e})"
        );
        // Friction is purely tangential, the other nodes are untouched, and the outcome
        // reports f·t, f and R f consistently.
        let t = tangent(c.normal);
        let f = out.tangential;
        let fscale = f.abs() + c.ext.norm();
        assert_close_v("node force", force[2], c.ext - t * f, 1e-12, fscale);
        assert_close_v("pulley force", out.force, t * f, 1e-12, fscale);
        assert_close("torque", out.torque, c.pulley.radius * f, 1e-12, fscale);
        for i in [0, 1, 3] {
            assert_eq!(force[i], V2::new(11.0, -7.0));
        }
        // And it equals the independently derived single-node stick force.
        let vn = t.dot(&(c.v[2] - c.pulley.center_velocity)) - c.pulley.radius * c.pulley.omega;
        let want = single_stick_force(vn, t.dot(&c.ext), c.mass[2], &c.pulley, c.dt);
        let terms = c.mass[2] * (vn / c.dt).abs() + t.dot(&c.ext).abs() + want.abs();
        assert_close("stick force", f, want, 1e-10, terms);
    }
}

/// Five contacts on an arc of a pulley, nodes 1, 2, 3, 5 and 6 of `n` (the others not in
/// contact), random normal loads; then the `n` nodes' masses, velocities and forces before
/// friction.
#[allow(clippy::type_complexity)]
fn five_on_an_arc(rng: &mut Rng, n: usize) -> (PulleyContacts, Vec<f64>, Vec<V2>, Vec<V2>) {
    let mut contacts = PulleyContacts::default();
    let a0 = rng.uniform(0.0, std::f64::consts::TAU);
    for (k, i) in [1usize, 2, 3, 5, 6].into_iter().enumerate() {
        contacts.node.push(i);
        contacts.normal.push(unit(a0 + 0.4 * k as f64));
        contacts.normal_force.push(rng.uniform(100.0, 2000.0));
        contacts.penetration.push(1e-3);
    }
    let mass = (0..n).map(|_| rng.uniform(0.2, 15.0)).collect();
    let v = (0..n).map(|_| rng.vec(4.0)).collect();
    let before = (0..n).map(|_| rng.vec(800.0)).collect();
    (contacts, mass, v, before)
}

#[test]
fn stick_force_brings_all_sticking_nodes_to_surface_speed() {
    let mut rng = Rng(0xdead_beef_cafe_f00d);
    for trial in 0..20 {
        let n = 9;
        let pulley = FrictionPulley {
            radius: rng.uniform(0.3, 1.5),
            inertia: rng.uniform(0.1, 30.0),
            omega: rng.uniform(-10.0, 10.0),
            center_velocity: if trial % 2 == 1 {
                rng.vec(1.5)
            } else {
                V2::zeros()
            },
            applied_torque: rng.uniform(-300.0, 300.0),
            mu_static: 1e9,
            mu_kinetic: 0.3,
            prescribed: None,
        };
        let dt = rng.uniform(1e-5, 5e-4);
        // Five contacts on an arc, with nodes 0, 4, 8 not in contact (must be untouched).
        let (contacts, mass, v, before) = five_on_an_arc(&mut rng, n);
        let mut force = before.clone();
        let mut scratch = StickScratch::default();
        let out =
            pulley_stick_friction(&contacts, &pulley, &v, &mass, dt, &mut force, &mut scratch);
        assert_eq!(out.slipping, 0);
        for k in 0..contacts.len() {
            let (vn_new, scale) =
                relative_speed_after(&contacts, k, &pulley, &v, &mass, dt, &force, out.torque);
            // Same rounding argument as the single-node test.
            assert!(
                vn_new.abs() <= 1e-9 * scale,
                "trial {trial} contact {k}: relative speed after {vn_new:e} (scale {scale:e})"
            );
        }
        for i in [0, 4, 7, 8] {
            assert_eq!(force[i], before[i], "node {i} is not in contact");
        }
        // Pulley torque and resultant are the sums of the contact forces.
        let mut sum_f = 0.0;
        let mut sum_fv = V2::zeros();
        for (k, &i) in contacts.node.iter().enumerate() {
            let t = tangent(contacts.normal[k]);
            let f = -(force[i] - before[i]).dot(&t);
            sum_f += f;
            sum_fv += t * f;
        }
        let fscale: f64 = scratch.force.iter().map(|f| f.abs()).sum::<f64>() + 1.0;
        assert_close("torque", out.torque, pulley.radius * sum_f, 1e-12, fscale);
        assert_close_v("resultant", out.force, sum_fv, 1e-12, fscale);
    }
}

#[test]
fn nodes_left_sticking_after_a_slip_still_reach_surface_speed() {
    // Three contacts; contact 1 has a tiny normal force so it must slip, the others have
    // µs·N = 1e12 and stick. After the slip loop re-solves, the sticking nodes must reach
    // the surface speed *including* the slipping node's kinetic torque.
    let mut rng = Rng(0x0123_4567_89ab_cdef);
    for trial in 0..20 {
        let pulley = FrictionPulley {
            radius: rng.uniform(0.3, 1.5),
            inertia: rng.uniform(0.5, 30.0),
            omega: rng.uniform(-10.0, 10.0),
            center_velocity: rng.vec(1.0),
            applied_torque: rng.uniform(-300.0, 300.0),
            mu_static: 0.5,
            mu_kinetic: 0.35,
            prescribed: None,
        };
        let dt = 1e-4;
        let mut contacts = PulleyContacts::default();
        for (k, nf) in [(0usize, 2e12), (1, 1.0), (2, 2e12)] {
            contacts.node.push(k);
            contacts.normal.push(unit(1.0 + 0.5 * k as f64));
            contacts.normal_force.push(nf);
            contacts.penetration.push(1e-3);
        }
        let mass = vec![
            rng.uniform(1.0, 5.0),
            rng.uniform(1.0, 5.0),
            rng.uniform(1.0, 5.0),
        ];
        let v: Vec<V2> = (0..3).map(|_| rng.vec(4.0)).collect();
        let before: Vec<V2> = (0..3).map(|_| rng.vec(500.0)).collect();
        let mut force = before.clone();
        let mut scratch = StickScratch::default();
        let out =
            pulley_stick_friction(&contacts, &pulley, &v, &mass, dt, &mut force, &mut scratch);
        assert_eq!(out.slipping, 1, "trial {trial}");
        // Contact 1 carries µk·N in the direction of its stick force (all-stick solution,
        // derived here: α = (T + R Σ(m v_n/Δt + t·F)) / (I + R² Σm), f_k = … − m_k R α).
        let r = pulley.radius;
        let free: Vec<f64> = (0..3)
            .map(|k| {
                let t = tangent(contacts.normal[k]);
                let vn = t.dot(&(v[k] - pulley.center_velocity)) - r * pulley.omega;
                mass[k] * vn / dt + t.dot(&before[k])
            })
            .collect();
        let alpha = (pulley.applied_torque + r * free.iter().sum::<f64>())
            / (pulley.inertia + r * r * mass.iter().sum::<f64>());
        let f1_stick = free[1] - mass[1] * r * alpha;
        assert!(
            f1_stick.abs() > 0.5,
            "construction: contact 1 must exceed µs·N"
        );
        assert_eq!(scratch.force[1], 0.35 * 1.0 * f1_stick.signum());
        for k in [0, 2] {
            let (vn_new, scale) =
                relative_speed_after(&contacts, k, &pulley, &v, &mass, dt, &force, out.torque);
            assert!(
                vn_new.abs() <= 1e-9 * scale,
                "trial {trial} contact {k}: relative speed after {vn_new:e} (scale {scale:e})"
            );
        }
    }
}

#[test]
fn slip_starts_exactly_when_stick_force_exceeds_static_limit() {
    let mut rng = Rng(0x5151_5151_a5a5_a5a5);
    let mut signs = [0usize; 2];
    for trial in 0..40 {
        let mut c = single_case(&mut rng, trial % 3 == 0);
        c.pulley.mu_static = 0.45;
        c.pulley.mu_kinetic = 0.3;
        let t = tangent(c.normal);
        let r = c.pulley.radius;
        let m = c.mass[2];
        let vn = t.dot(&(c.v[2] - c.pulley.center_velocity)) - r * c.pulley.omega;
        let tf = t.dot(&c.ext);
        let f_req = single_stick_force(vn, tf, m, &c.pulley, c.dt);
        // The kernel forms f = free − m R α from terms of size ≤ `terms`; its rounding is
        // ~1e-16·terms. Skip draws with strong cancellation, where that rounding could
        // approach the ±1e-9 margin (it must stay ≥ 1e4 times smaller).
        let free = m * vn / c.dt + tf;
        let terms = free.abs() + (free - f_req).abs();
        if terms * 1e-16 * 1e4 > 1e-9 * f_req.abs() {
            continue;
        }
        signs[(f_req > 0.0) as usize] += 1;

        for (margin, slips) in [(1.0 + 1e-9, false), (1.0 - 1e-9, true)] {
            let nf = f_req.abs() * margin / c.pulley.mu_static;
            let contacts = one_contact(2, c.normal, nf);
            let mut force = vec![V2::zeros(); 4];
            force[2] = c.ext;
            let mut scratch = StickScratch::default();
            let out = pulley_stick_friction(
                &contacts,
                &c.pulley,
                &c.v,
                &c.mass,
                c.dt,
                &mut force,
                &mut scratch,
            );
            if slips {
                assert_eq!(out.slipping, 1, "trial {trial}: µs·N = f_req(1 − 1e-9)");
                // Same operands, same operations as the law µk·N·sign(f): bitwise equal.
                let fk = c.pulley.mu_kinetic * nf * f_req.signum();
                assert_eq!(out.tangential, fk, "trial {trial}");
                assert_eq!(scratch.force[0], fk);
                assert_close_v("node force", force[2], c.ext - t * fk, 1e-12, terms);
            } else {
                assert_eq!(out.slipping, 0, "trial {trial}: µs·N = f_req(1 + 1e-9)");
                // Two evaluations of the same quantity by different algebra: agreement to
                // ~1e-16·terms; 1e-12·terms is safe and far tighter than the 1e-9 margin.
                assert_close("stick force", out.tangential, f_req, 1e-12, terms);
            }
        }
    }
    assert!(
        signs[0] >= 5 && signs[1] >= 5,
        "both slip directions exercised: {signs:?}"
    );
}

#[test]
fn kinetic_friction_never_reverses_relative_motion() {
    // Single slipping node. With no other tangential load (F = 0, T = 0) the relative speed
    // after the step must keep its sign and shrink. With loads, the same holds relative to
    // the frictionless prediction v_n + Δt t·F/m − RΔt T/I: friction moves the relative
    // speed towards zero but never past it.
    let mut rng = Rng(0x7777_1111_3333_9999);
    let mut slipped = 0;
    for trial in 0..60 {
        let mut c = single_case(&mut rng, trial % 2 == 0);
        let loaded = trial % 3 != 0;
        if !loaded {
            c.ext = V2::zeros();
            c.pulley.applied_torque = 0.0;
        }
        c.pulley.mu_static = 0.4;
        c.pulley.mu_kinetic = if trial % 4 == 0 { 0.4 } else { 0.25 };
        let t = tangent(c.normal);
        let r = c.pulley.radius;
        let m = c.mass[2];
        let vn = t.dot(&(c.v[2] - c.pulley.center_velocity)) - r * c.pulley.omega;
        let f_req = single_stick_force(vn, t.dot(&c.ext), m, &c.pulley, c.dt);
        // Normal force between 5 % and 90 % of what sticking would need: always a slip.
        let nf = f_req.abs() * rng.uniform(0.05, 0.9) / c.pulley.mu_static;
        let contacts = one_contact(2, c.normal, nf);
        let mut force = vec![V2::zeros(); 4];
        force[2] = c.ext;
        let mut scratch = StickScratch::default();
        let out = pulley_stick_friction(
            &contacts,
            &c.pulley,
            &c.v,
            &c.mass,
            c.dt,
            &mut force,
            &mut scratch,
        );
        assert_eq!(out.slipping, 1, "trial {trial}");
        slipped += 1;
        let (vn_new, _) = relative_speed_after(
            &contacts, 0, &c.pulley, &c.v, &c.mass, c.dt, &force, out.torque,
        );
        let reference = if loaded {
            vn + c.dt * t.dot(&c.ext) / m - r * c.dt * c.pulley.applied_torque / c.pulley.inertia
        } else {
            vn
        };
        assert!(
            vn_new * reference >= 0.0,
            "trial {trial}: friction reversed the slip: before {reference:e}, after {vn_new:e}"
        );
        assert!(
            vn_new.abs() < reference.abs(),
            "trial {trial}: friction did not reduce the slip: {reference:e} → {vn_new:e}"
        );
    }
    assert_eq!(slipped, 60);
}

/// Two contacts on a light pulley. Flagging every violator of the all-stick solve at once
/// (α assumes both stick) gives both µk·N, the pulley no net friction torque, and drags
/// contact 1 — which had zero relative speed — ahead of the surface *by its own friction*
/// (v_n' = +0.08 m/s with friction on the node along +t: negative dissipation). With
/// contact 0 slipping alone, contact 1 needs only |f| = 72.7 N < µs·N = 100 N and sticks.
/// The slip loop therefore releases only the worst violator per pass.
#[test]
fn multi_contact_slip_never_reverses_relative_motion() {
    let pulley = FrictionPulley {
        radius: 1.0,
        inertia: 0.1,
        omega: 0.0,
        center_velocity: V2::zeros(),
        applied_torque: 0.0,
        mu_static: 0.5,
        mu_kinetic: 0.4,
        prescribed: None,
    };
    let dt = 1e-3;
    let mut contacts = PulleyContacts::default();
    for k in 0..2 {
        contacts.node.push(k);
        contacts.normal.push(unit(1.0 + 0.3 * k as f64));
        contacts.normal_force.push(200.0);
        contacts.penetration.push(1e-3);
    }
    let mass = vec![1.0, 1.0];
    // Contact 0 slides forward at 1 m/s, contact 1 moves with the surface.
    let v = vec![tangent(contacts.normal[0]), V2::zeros()];
    let mut force = vec![V2::zeros(); 2];
    let mut scratch = StickScratch::default();
    let out = pulley_stick_friction(&contacts, &pulley, &v, &mass, dt, &mut force, &mut scratch);
    let (vn1, _) = relative_speed_after(&contacts, 1, &pulley, &v, &mass, dt, &force, out.torque);
    // Friction may not make a contact slide in the direction the belt is pushed.
    assert!(
        scratch.force[1] * vn1 >= -1e-12,
        "contact 1: friction {} N, relative speed after {vn1} m/s, slipping {}",
        scratch.force[1],
        out.slipping
    );
}

// ---------------------------------------------------------------------------------------
// 7. Idler stick friction
// ---------------------------------------------------------------------------------------

#[test]
fn idler_stick_force_brings_contact_point_to_roll_speed() {
    let mut rng = Rng(0xabcd_ef01_2345_6789);
    let n = 6;
    for trial in 0..40 {
        // Element 5 wraps round to node 0 on some trials.
        let e = if trial % 4 == 0 { n - 1 } else { 2 };
        let j = (e + 1) % n;
        let contact = IdlerContact {
            active: true,
            element: e,
            gamma: if trial % 5 == 0 {
                [0.0, 1.0][trial % 2]
            } else {
                rng.uniform(0.0, 1.0)
            },
            normal: unit(rng.uniform(0.0, std::f64::consts::TAU)),
            normal_force: 500.0,
            penetration: 1e-3,
            ..Default::default()
        };
        let idler = FrictionIdler {
            radius: rng.uniform(0.05, 0.3),
            inertia: rng.uniform(0.01, 2.0),
            omega: rng.uniform(-50.0, 50.0),
            mu_static: 1e9,
            mu_kinetic: 0.3,
        };
        let dt = rng.uniform(1e-5, 1e-3);
        let mass: Vec<f64> = (0..n).map(|_| rng.uniform(0.2, 10.0)).collect();
        let v: Vec<V2> = (0..n).map(|_| rng.vec(5.0)).collect();
        let before: Vec<V2> = (0..n).map(|_| rng.vec(300.0)).collect();
        let mut force = before.clone();
        let (f, slipping) = idler_stick_friction(&contact, &idler, &v, &mass, dt, &mut force);
        assert!(!slipping);
        let g = contact.gamma;
        let t = tangent(contact.normal);
        // Lever rule: −(1 − γ) f t on the first node, −γ f t on the second, nothing else.
        let fscale = f.abs() + 300.0;
        assert_close_v(
            "first node",
            force[e] - before[e],
            -t * (f * (1.0 - g)),
            1e-12,
            fscale,
        );
        assert_close_v(
            "second node",
            force[j] - before[j],
            -t * (f * g),
            1e-12,
            fscale,
        );
        for i in (0..n).filter(|&i| i != e && i != j) {
            assert_eq!(force[i], before[i]);
        }
        // One explicit step of both nodes and the roll (torque R f, no other torque).
        let vi = v[e] + force[e] * (dt / mass[e]);
        let vj = v[j] + force[j] * (dt / mass[j]);
        let omega = idler.omega + dt * idler.radius * f / idler.inertia;
        let vn_new = (vi * (1.0 - g) + vj * g).dot(&t) - idler.radius * omega;
        let scale = v[e].norm()
            + v[j].norm()
            + (idler.radius * idler.omega).abs()
            + dt * (force[e].norm() / mass[e] + force[j].norm() / mass[j])
            + dt * idler.radius * idler.radius * f.abs() / idler.inertia;
        // Same rounding argument as the pulley: a few terms ≤ scale at ~1e-16 each.
        assert!(
            vn_new.abs() <= 1e-9 * scale,
            "trial {trial}: relative speed after {vn_new:e} (scale {scale:e}, γ {g})"
        );

        // The same contact with a small normal force slips with exactly µk·N·sign(f).
        let weak = IdlerContact {
            normal_force: 0.5 * f.abs() / 0.45,
            ..contact
        };
        let slip_idler = FrictionIdler {
            mu_static: 0.45,
            ..idler
        };
        let mut force = before.clone();
        let (fs, slipping) = idler_stick_friction(&weak, &slip_idler, &v, &mass, dt, &mut force);
        assert!(slipping, "trial {trial}");
        assert_eq!(fs, 0.3 * weak.normal_force * f.signum());
    }
}

/// A pulley of radius 1 m at the origin, at rest (the contact-window tests).
fn unit_pulley() -> PulleyBody {
    PulleyBody {
        center: V2::zeros(),
        center_velocity: V2::zeros(),
        radius: 1.0,
        stiffness: 1.0e7,
        damping: 0.0,
        margin: 0.05,
    }
}

/// A window whose run of nodes leaves the pulley is re-found in the same call: the belt
/// that touches elsewhere in that step is not missed for one step.
#[test]
fn emptied_window_rescans_in_the_same_step() {
    let body = unit_pulley();
    let n = 40;
    let far = |i: usize| V2::new(10.0 + i as f64, 10.0);
    let mut x: Vec<V2> = (0..n).map(far).collect();
    for (k, i) in (5..9).enumerate() {
        x[i] = V2::new(-0.3 + 0.2 * k as f64, -0.99);
    }
    let mut w = ContactWindow::default();
    update_window(&mut w, &x, &body, false);
    assert_eq!(window_nodes(&w, n), vec![5, 6, 7, 8]);
    // Nodes 5..9 lift clear; nodes 20..23 now dip into the pulley.
    for i in 5..9 {
        x[i] = far(i);
    }
    for (k, i) in (20..23).enumerate() {
        x[i] = V2::new(-0.1 + 0.1 * k as f64, 0.99);
    }
    update_window(&mut w, &x, &body, false);
    assert_eq!(window_nodes(&w, n), vec![20, 21, 22]);
    let v = vec![V2::zeros(); n];
    let mut force = vec![V2::zeros(); n];
    let mut out = PulleyContacts::default();
    pulley_contact(&w, &x, &v, &body, &mut force, &mut out);
    assert_eq!(out.node, vec![20, 21, 22]);
}

/// A brake solved with the friction: holding, the pulley stops this step and the belt
/// sticks to it (the brake takes the belt's and the drive's torque); beyond its capacity it
/// slides at the capacity and the nodes see a free pulley with that known torque.
#[test]
fn braked_pulley_holds_the_belt_or_slides_at_capacity() {
    let dt = 1e-3;
    let mass = vec![2.0, 2.0];
    let mut contacts = PulleyContacts::default();
    for (k, angle) in [0.3f64, 0.9].into_iter().enumerate() {
        contacts.node.push(k);
        contacts.normal.push(unit(angle));
        contacts.normal_force.push(1000.0);
        contacts.penetration.push(1e-4);
    }
    // Both nodes pulled along +t by 200 N (well inside µs·N = 500 N), pulley turning.
    let pulley = FrictionPulley {
        radius: 0.5,
        inertia: 3.0,
        omega: 0.2,
        center_velocity: V2::zeros(),
        applied_torque: 40.0,
        mu_static: 0.5,
        mu_kinetic: 0.4,
        prescribed: Some(Prescribed::at_rest(1.0e4)),
    };
    let v: Vec<V2> = (0..2)
        .map(|k| tangent(contacts.normal[k]) * (pulley.radius * pulley.omega))
        .collect();
    let pushed = |k: usize| tangent(contacts.normal[k]) * 200.0;
    let mut force = vec![pushed(0), pushed(1)];
    let mut scratch = StickScratch::default();
    let out = pulley_stick_friction(&contacts, &pulley, &v, &mass, dt, &mut force, &mut scratch);
    let brake = out
        .held_torque
        .expect("a braked pulley reports its brake torque");
    // Holding: the pulley stops this step, I·(0 − ω)/Δt = T + R·Σf + B.
    let total = pulley.applied_torque + out.torque + brake;
    assert_close(
        "pulley stops",
        pulley.omega + dt * total / pulley.inertia,
        0.0,
        1e-12,
        1.0,
    );
    assert_eq!(out.slipping, 0);
    // ... and every node stops with it (zero relative speed on a stopped pulley).
    for (k, f) in force.iter().enumerate() {
        let v_new = v[k] + f * (dt / mass[k]);
        assert_close("node stops", v_new.norm(), 0.0, 1e-12, 1.0);
    }

    // The same with a weak brake: it slides at its capacity, opposing the motion.
    let weak = FrictionPulley {
        prescribed: Some(Prescribed::at_rest(5.0)),
        ..pulley
    };
    let mut force = vec![pushed(0), pushed(1)];
    let out = pulley_stick_friction(&contacts, &weak, &v, &mass, dt, &mut force, &mut scratch);
    assert_eq!(out.held_torque, Some(-5.0));
    // Sticking nodes reach the surface speed of the pulley under T + B + R·Σf.
    let omega_new = weak.omega + dt * (weak.applied_torque - 5.0 + out.torque) / weak.inertia;
    for (k, f) in force.iter().enumerate() {
        let t = tangent(contacts.normal[k]);
        let v_new = v[k] + f * (dt / mass[k]);
        assert_close(
            "sticks to the sliding pulley",
            t.dot(&v_new),
            weak.radius * omega_new,
            1e-9,
            1.0,
        );
    }
}

/// Belt reaching a pulley at a second place (a slack loop folding back) is not in the
/// window of the first run; the periodic full scan widens the window to take it in.
#[test]
fn full_scan_catches_a_second_run_of_belt() {
    let body = unit_pulley();
    let n = 40;
    let mut x: Vec<V2> = (0..n).map(|i| V2::new(10.0 + i as f64, 10.0)).collect();
    for (k, i) in (5..8).enumerate() {
        x[i] = V2::new(-0.1 + 0.1 * k as f64, -0.99);
    }
    let mut w = ContactWindow::default();
    update_window(&mut w, &x, &body, false);
    assert_eq!(window_nodes(&w, n), vec![5, 6, 7]);
    // Nodes 30 and 31 fold back onto the top of the pulley while 5..8 stay.
    x[30] = V2::new(-0.05, 0.99);
    x[31] = V2::new(0.05, 0.99);
    update_window(&mut w, &x, &body, false);
    assert_eq!(
        window_nodes(&w, n),
        vec![5, 6, 7],
        "tracking alone misses them"
    );
    update_window(&mut w, &x, &body, true);
    let nodes = window_nodes(&w, n);
    assert!(
        nodes.contains(&30) && nodes.contains(&31) && nodes.contains(&5),
        "{nodes:?}"
    );
    let v = vec![V2::zeros(); n];
    let mut force = vec![V2::zeros(); n];
    let mut out = PulleyContacts::default();
    pulley_contact(&w, &x, &v, &body, &mut force, &mut out);
    let mut touching = out.node.clone();
    touching.sort();
    assert_eq!(touching, vec![5, 6, 7, 30, 31]);
}

/// The one-at-a-time slip loop of thesis figure 4.9, written out plainly (O(n_c²)): the
/// reference for the linear-time solve. Returns (tangential force per contact, slipping).
fn one_at_a_time(
    free: &[f64],
    mass: &[f64],
    normal: &[f64],
    pulley: &FrictionPulley,
    known_torque: f64,
) -> (Vec<f64>, usize) {
    let n = free.len();
    let r = pulley.radius;
    let mut sticking = vec![true; n];
    let mut force = vec![0.0; n];
    let mut torque = known_torque;
    let mut slipping = 0;
    loop {
        let (mut a, mut m) = (0.0, 0.0);
        for k in 0..n {
            if sticking[k] {
                a += free[k];
                m += mass[k];
            }
        }
        let alpha = (torque + r * a) / (pulley.inertia + r * r * m);
        let mut worst: Option<(usize, f64)> = None;
        for k in 0..n {
            if !sticking[k] {
                continue;
            }
            force[k] = free[k] - mass[k] * r * alpha;
            let excess = force[k].abs() - pulley.mu_static * normal[k];
            if excess > 0.0 && worst.is_none_or(|(_, e)| excess > e) {
                worst = Some((k, excess));
            }
        }
        let Some((k, _)) = worst else { break };
        force[k] = pulley.mu_kinetic * normal[k] * force[k].signum();
        sticking[k] = false;
        torque += r * force[k];
        slipping += 1;
    }
    (force, slipping)
}

/// Issue 11: the linear-time slip loop gives the one-at-a-time rule's forces, node by node,
/// on random pulleys with slip on one side, on both sides, and with cascades (a light
/// pulley whose acceleration moves a lot with each release), equal node masses.
#[test]
fn slip_loop_matches_one_at_a_time_rule() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut cases = [0usize; 3];
    for trial in 0..3000 {
        let nc = 1 + (rng.uniform(0.0, 60.0) as usize);
        let radius = rng.uniform(0.05, 2.0);
        let inertia = 10f64.powf(rng.uniform(-4.0, 3.0));
        let mu_kinetic = rng.uniform(0.1, 0.6);
        let mu_static = mu_kinetic * rng.uniform(1.0, 1.3);
        let pulley = FrictionPulley {
            radius,
            inertia,
            omega: rng.uniform(-5.0, 5.0),
            center_velocity: V2::zeros(),
            applied_torque: rng.uniform(-50.0, 50.0),
            mu_static,
            mu_kinetic,
            prescribed: None,
        };
        let m_node = rng.uniform(0.01, 1.0);
        let dt = 1e-4;
        // Nodes on the upper half of the pulley, in contact.
        let mut contacts = PulleyContacts::default();
        let mut x = Vec::new();
        let mut v = Vec::new();
        let mut force = Vec::new();
        let bias = rng.uniform(-1.0, 1.0);
        for k in 0..nc {
            let a = std::f64::consts::PI * (k as f64 + 0.5) / nc as f64;
            let n = unit(a);
            contacts.node.push(k);
            contacts.normal.push(n);
            contacts.normal_force.push(rng.uniform(0.0, 100.0));
            contacts.penetration.push(1e-6);
            x.push(n * radius);
            // Relative speeds around the pulley's surface speed, biased to one side or
            // spread over both.
            let vt = radius * pulley.omega + 1e-3 * (bias + rng.uniform(-1.0, 1.0));
            v.push(tangent(n) * vt + n * rng.uniform(-0.1, 0.1));
            force.push(rng.vec(20.0));
        }
        let mass = vec![m_node; nc];
        let free: Vec<f64> = (0..nc)
            .map(|k| {
                let t = tangent(contacts.normal[k]);
                let vn = t.dot(&v[k]) - radius * pulley.omega;
                mass[k] * vn / dt + t.dot(&force[k])
            })
            .collect();
        let (want, want_slipping) = one_at_a_time(
            &free,
            &mass,
            &contacts.normal_force,
            &pulley,
            pulley.applied_torque,
        );
        let signs = want
            .iter()
            .zip(&contacts.normal_force)
            .filter(|(f, n)| f.abs() >= mu_kinetic * **n * (1.0 - 1e-12) && **n > 0.0)
            .fold((false, false), |(p, q), (f, _)| {
                (p || *f > 0.0, q || *f < 0.0)
            });
        cases[usize::from(signs.0) + usize::from(signs.1)] += 1;
        let mut got_force = force.clone();
        let mut scratch = StickScratch::default();
        let out = pulley_stick_friction(
            &contacts,
            &pulley,
            &v,
            &mass,
            dt,
            &mut got_force,
            &mut scratch,
        );
        assert_eq!(out.slipping, want_slipping, "trial {trial}: slipping nodes");
        // Same set and the same kinetic forces; the sticking forces differ only by the
        // rounding of α (sums in another order), far below 1e-9 of the force scale.
        let scale = free.iter().map(|f| f.abs()).fold(1.0, f64::max);
        for k in 0..nc {
            assert_close("friction force", scratch.force[k], want[k], 1e-9, scale);
        }
    }
    // The random cases cover no slip, one-sided and two-sided slip.
    assert!(cases.iter().all(|&c| c > 50), "case mix {cases:?}");
}

// ---------------------------------------------------------------------------------------
// Coulomb's kinetic state and the slip front (docs/wrap-contact.md, "Session 10: the
// drums' stick–slip")
// ---------------------------------------------------------------------------------------

/// Contacts at `nodes` on a pulley held at its speed (α = 0, so each contact's stick force
/// is its own m·v_n/Δt + t·F, here t·F = `stick[k]` with v_n = 0), each with normal force
/// `nf`, µs = 0.5, µk = 0.4, and the points in `sliding` remembered as sliding. Returns the
/// friction force of each contact and the remembered points after the step.
fn held_step(
    nodes: &[usize],
    n: usize,
    stick: &[f64],
    sliding: &[usize],
    dt: f64,
) -> (Vec<f64>, Vec<usize>) {
    let nf = 1000.0;
    let mut contacts = PulleyContacts::default();
    for (k, &i) in nodes.iter().enumerate() {
        let a = 0.3 * k as f64;
        contacts.node.push(i);
        contacts.normal.push(unit(a));
        contacts.normal_force.push(nf);
        contacts.penetration.push(0.0);
    }
    let pulley = FrictionPulley {
        radius: 0.5,
        inertia: 10.0,
        omega: 2.0,
        center_velocity: V2::zeros(),
        applied_torque: 0.0,
        mu_static: 0.5,
        mu_kinetic: 0.4,
        prescribed: Some(Prescribed::within(2.0, f64::INFINITY)),
    };
    // Every point moves with the surface: v = R ω t.
    let mut v = vec![V2::zeros(); n];
    let mut force = vec![V2::zeros(); n];
    for (k, &i) in nodes.iter().enumerate() {
        let t = tangent(contacts.normal[k]);
        v[i] = t * (pulley.radius * pulley.omega);
        force[i] = t * stick[k];
    }
    let mass = vec![2.0; n];
    let mut scratch = StickScratch::default();
    scratch.sliding = sliding.to_vec();
    pulley_stick_friction(&contacts, &pulley, &v, &mass, dt, &mut force, &mut scratch);
    (scratch.force.clone(), scratch.sliding.clone())
}

#[test]
fn a_sliding_contact_keeps_the_kinetic_limit_until_it_can_stop() {
    // µk·N = 400 N < 450 N < µs·N = 500 N: held at rest, slides on once sliding.
    let dt = 1e-4;
    let (f, after) = held_step(&[3], 8, &[450.0], &[], dt);
    assert_eq!(
        (f[0], after.as_slice()),
        (450.0, &[][..]),
        "at rest: held within µs·N"
    );
    let (f, after) = held_step(&[3], 8, &[450.0], &[3], dt);
    assert_eq!(
        (f[0], after.as_slice()),
        (400.0, &[3][..]),
        "sliding: µk·N, still sliding"
    );
    let (f, after) = held_step(&[3], 8, &[-450.0], &[3], dt);
    assert_eq!(
        (f[0], after.as_slice()),
        (-400.0, &[3][..]),
        "either direction"
    );
    // Below µk·N kinetic friction stops it within the step: it sticks and is forgotten.
    let (f, after) = held_step(&[3], 8, &[390.0], &[3], dt);
    assert_eq!((f[0], after.as_slice()), (390.0, &[][..]));
    // Beyond µs·N a contact at rest breaks away and is remembered.
    let (f, after) = held_step(&[3], 8, &[510.0], &[], dt);
    assert_eq!((f[0], after.as_slice()), (400.0, &[3][..]));
    // Quasi-static friction (infinite step) has no motion to remember: µs·N throughout.
    let (f, after) = held_step(&[3], 8, &[450.0], &[3], f64::INFINITY);
    assert_eq!((f[0], after.as_slice()), (450.0, &[][..]));
}

#[test]
fn the_slip_front_advances_at_the_kinetic_limit() {
    let dt = 1e-4;
    // Points 1, 2, 3 on the pulley, 3 sliding: 2 is at the slip front (µk·N), 1 is not.
    let (f, after) = held_step(&[1, 2, 3], 8, &[450.0, 450.0, 450.0], &[3], dt);
    assert_eq!(f, vec![450.0, 400.0, 400.0]);
    assert_eq!(after, vec![2, 3]);
    // The same from the other side, and a point sliding the other way counts too.
    let (f, _) = held_step(&[1, 2, 3], 8, &[450.0, 450.0, -450.0], &[1], dt);
    assert_eq!(f, vec![400.0, 400.0, -450.0]);
    // Neighbours in the list that are not neighbours on the belt (a gap) are not.
    let (f, _) = held_step(&[1, 3], 8, &[450.0, 450.0], &[3], dt);
    assert_eq!(f, vec![450.0, 400.0]);
    // A closed belt: the last point and point 0 are neighbours.
    let (f, after) = held_step(&[7, 0], 8, &[450.0, 450.0], &[0], dt);
    assert_eq!(f, vec![400.0, 400.0]);
    assert_eq!(after, vec![0, 7]);
    // Nothing remembered: every contact at rest holds up to µs·N.
    let (f, after) = held_step(&[1, 2, 3], 8, &[450.0, 499.0, 450.0], &[], dt);
    assert_eq!(f, vec![450.0, 499.0, 450.0]);
    assert!(after.is_empty());
}

#[test]
fn bodies_with_their_own_arms_stick_at_their_lever_and_turn_the_pulley_with_their_arms() {
    // Rigid bodies (`PulleyContacts::arm`, `lever`): a sticking body reaches the surface
    // speed lever_k·ω' at the end of the step, a slipping one carries µk·N, and the pulley
    // takes Σ arm_k·f_k, the moment the bodies receive. Random arms 0.8-1.2 R, levers the
    // arm ± a wrap joint's slide, limits low enough that some contacts slip.
    let mut rng = Rng(0x5eed_a4a5_0123_4567);
    let mut slipped = 0;
    for trial in 0..40 {
        let n = 8;
        let r = rng.uniform(0.3, 1.5);
        let pulley = FrictionPulley {
            radius: r,
            inertia: rng.uniform(0.1, 30.0),
            omega: rng.uniform(-10.0, 10.0),
            center_velocity: V2::zeros(),
            applied_torque: rng.uniform(-300.0, 300.0),
            mu_static: if trial % 2 == 0 { 1e9 } else { 0.5 },
            mu_kinetic: 0.4,
            prescribed: None,
        };
        let dt = rng.uniform(1e-5, 5e-4);
        let (mut contacts, mass, v, before) = five_on_an_arc(&mut rng, n);
        for _ in 0..contacts.len() {
            let arm = r * rng.uniform(0.8, 1.2);
            contacts.arm.push(arm);
            contacts.lever.push(arm + r * rng.uniform(-0.05, 0.05));
        }
        let mut force = before.clone();
        let mut scratch = StickScratch::default();
        let out =
            pulley_stick_friction(&contacts, &pulley, &v, &mass, dt, &mut force, &mut scratch);
        slipped += out.slipping;
        let omega_new = pulley.omega + dt * (out.torque + pulley.applied_torque) / pulley.inertia;
        let (mut moment, mut scale) = (0.0, 1.0);
        let mut slipping = 0;
        for (k, &i) in contacts.node.iter().enumerate() {
            let t = tangent(contacts.normal[k]);
            let f = -(force[i] - before[i]).dot(&t);
            moment += contacts.arm[k] * f;
            scale += (contacts.arm[k] * f).abs();
            let kinetic = pulley.mu_kinetic * contacts.normal_force[k];
            if (f.abs() - kinetic).abs() <= 1e-12 * kinetic {
                slipping += 1;
                continue;
            }
            assert!(f.abs() <= pulley.mu_static * contacts.normal_force[k]);
            let v_new = v[i] + force[i] * (dt / mass[i]);
            let vn_new = t.dot(&v_new) - contacts.lever[k] * omega_new;
            let vscale = t.dot(&v[i]).abs()
                + (contacts.lever[k] * pulley.omega).abs()
                + dt * force[i].norm() / mass[i]
                + contacts.lever[k].abs() * (omega_new - pulley.omega).abs();
            assert!(
                vn_new.abs() <= 1e-9 * vscale,
                "trial {trial} contact {k}: relative speed after {vn_new:e} (scale {vscale:e})"
            );
        }
        assert_eq!(slipping, out.slipping, "trial {trial}");
        assert_close("torque", out.torque, moment, 1e-12, scale);
    }
    // It can fail: the slip branch was exercised.
    assert!(slipped > 0);
}
