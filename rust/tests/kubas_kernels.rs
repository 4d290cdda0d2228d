//! Kernel checks of Kubas's (2014) model: nonlinear damped contact (eq. 4–11), creep-rate
//! friction (eq. 12–19), the rigid-body SDEs (eq. 20–23) and the pulley resistance (eq. 24).
use beltrs::belt::rigid::link_inertia;
use beltrs::belt::rigid::sdes::{chain_loads, joint, joint_energy, LinkState, SdeParams};
use beltrs::contact::nonlinear::{circle_gap, cubic_step, cubic_step_slope, NonlinearContact};
use beltrs::drives::resistance::{friction_torque_on_pulley, pulley_acceleration, SpeedResistance};
use beltrs::friction::creep::{CreepFriction, CreepMemory};
use beltrs::BeltError;
use nalgebra::Vector2;

type V2 = Vector2<f64>;

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

// ---------------------------------------------------------------- contact (eq. 4–11)

#[test]
fn contact_force_curve_matches_eq9() {
    let c = NonlinearContact::default();
    let (c1, c2, b, pm) = (3.0256e9, 6.5e5, 300.0, 1e-3);
    for &p in &[1e-6, 1e-5, 1.5e-4, 5e-4, 1e-3, 2e-3] {
        let elastic = c1 * p * p + c2 * p;
        // At rest the force is the elastic part, to rounding.
        assert!(
            close(c.normal_force(p, 0.0), elastic, 1e-12 * elastic),
            "p = {p}"
        );
        // Approaching at 0.01 m/s adds δ(p)·b·ṗ with δ from eq. 11 written out here.
        let d = (p / pm).min(1.0);
        let delta = d * d * (3.0 - 2.0 * d);
        let expected = elastic + delta * b * 0.01;
        assert!(
            close(c.normal_force(p, 0.01), expected, 1e-12 * expected),
            "p = {p}"
        );
    }
    // Case K's quadratic term dominates above p = c₂/c₁ ≈ 0.215 mm.
    let p = c2 / c1;
    assert!(close(c.elastic_force(p), 2.0 * c2 * p, 1e-9 * c2 * p));
    // The inverse used to place bodies at a given load.
    for &n in &[0.0, 1.0, 163.0, 1e4] {
        let p = c.penetration_for(n);
        assert!(close(c.elastic_force(p), n, 1e-9 * n.max(1.0)), "N = {n}");
    }
    let linear = NonlinearContact {
        quadratic_stiffness: 0.0,
        linear_stiffness: 5e6,
        ..c
    };
    assert_eq!(linear.penetration_for(50.0), 1e-5);
}

#[test]
fn damping_ramp_is_c1_with_zero_slope_at_both_ends() {
    let c = NonlinearContact::default();
    let pm = c.damping_depth;
    assert_eq!(c.damping_ramp(0.0), 0.0);
    assert_eq!(c.damping_ramp(-1.0), 0.0);
    assert_eq!(c.damping_ramp(pm), 1.0);
    assert_eq!(c.damping_ramp(3.0 * pm), 1.0);
    assert!(close(c.damping_ramp(0.5 * pm), 0.5, 1e-15));
    // Continuity: approaching each end from inside, δ tends to its outside value like ε².
    for &eps in &[1e-3, 1e-5, 1e-7] {
        let e = eps * pm;
        assert!(
            c.damping_ramp(e) <= 3.0 * eps * eps + 1e-300,
            "δ(ε) = {}",
            c.damping_ramp(e)
        );
        assert!(
            1.0 - c.damping_ramp(pm - e) <= 3.0 * eps * eps,
            "δ(p_max − ε)"
        );
        // Slope tends to zero at both ends (C¹ joins with the constant pieces).
        assert!(c.damping_ramp_slope(e) <= 6.0 * eps / pm);
        assert!(c.damping_ramp_slope(pm - e) <= 6.0 * eps / pm);
    }
    // The analytic slope matches central differences everywhere inside; largest 1.5/p_max.
    let h = 1e-9 * pm;
    let mut largest: f64 = 0.0;
    for k in 1..200 {
        let p = pm * k as f64 / 200.0;
        let fd = (c.damping_ramp(p + h) - c.damping_ramp(p - h)) / (2.0 * h);
        let s = c.damping_ramp_slope(p);
        assert!(close(fd, s, 1e-5 / pm), "p = {p}: {fd} vs {s}");
        largest = largest.max(s);
    }
    assert!(close(largest, 1.5 / pm, 1e-12 / pm));
    // The generic eq. 10 with other end values.
    assert_eq!(cubic_step(-2.0, -1.0, 3.0, 1.0, 5.0), 3.0);
    assert_eq!(cubic_step(0.0, -1.0, 3.0, 1.0, 5.0), 4.0);
    assert_eq!(cubic_step_slope(0.0, -1.0, 3.0, 1.0, 5.0), 1.5);
}

#[test]
fn contact_never_pulls_and_is_silent_when_separated() {
    let c = NonlinearContact::default();
    for &p in &[-1e-2, -1e-6, 0.0] {
        for &pd in &[-10.0, 0.0, 10.0] {
            assert_eq!(c.normal_force(p, pd), 0.0, "p = {p}, ṗ = {pd}");
        }
    }
    // A body leaving fast: eq. 9 alone would be negative, the law clamps it to zero.
    let p = 2e-3;
    let raw = c.elastic_force(p) + c.damping * -100.0;
    assert!(raw < 0.0);
    assert_eq!(c.normal_force(p, -100.0), 0.0);
    for i in 0..100 {
        let p = 3e-3 * i as f64 / 100.0;
        for j in 0..41 {
            let pd = -20.0 + j as f64;
            assert!(c.normal_force(p, pd) >= 0.0);
        }
    }
}

#[test]
fn circle_gap_follows_eq4_to_7() {
    // Mass centre 2 mm inside a 0.1 m pulley at 30°, moving inwards at 0.5 m/s and along.
    let a = 30f64.to_radians();
    let n = V2::new(a.cos(), a.sin());
    let t = V2::new(-a.sin(), a.cos());
    let centre = V2::new(0.3, -0.2);
    let x = centre + n * 0.098;
    let v = -n * 0.5 + t * 3.0;
    let g = circle_gap(x, v, centre, V2::zeros(), 0.1).unwrap();
    assert!((g.normal - n).norm() < 1e-15);
    assert!(close(g.penetration, 0.002, 1e-15));
    assert!(close(g.penetration_rate, 0.5, 1e-14));
    // A moving pulley centre counts relative velocity.
    let g2 = circle_gap(x, v, centre, -n * 0.5, 0.1).unwrap();
    assert!(close(g2.penetration_rate, 0.0, 1e-14));
    assert!(circle_gap(centre, v, centre, V2::zeros(), 0.1).is_none());
}

#[test]
fn contact_validation_names_the_field() {
    let bad = NonlinearContact {
        damping_depth: 0.0,
        ..Default::default()
    };
    let e = bad.validate("pulleys[1].contact").unwrap_err();
    assert!(
        e.to_string().contains("pulleys[1].contact.damping_depth"),
        "{e}"
    );
    let none = NonlinearContact {
        quadratic_stiffness: 0.0,
        linear_stiffness: 0.0,
        ..Default::default()
    };
    assert!(none.validate("c").is_err());
    assert!(NonlinearContact::default().validate("c").is_ok());
}

// ---------------------------------------------------------------- creep friction (eq. 12–19)

#[test]
fn creep_friction_limits_and_transitions() {
    let f = CreepFriction::default();
    let (ms, mk, dv, dm) = (1.05, 1.0, 1e-5, 1e-4);
    // Fully developed sliding above 1.5Δv: µk, whatever the creep.
    for &v in &[1.5 * dv, 2.0 * dv, 1.0, 100.0] {
        for &d in &[0.0, 0.5 * dm, 10.0 * dm] {
            assert_eq!(f.magnitude(d, v), mk);
            assert_eq!(f.coefficient(d, v), mk);
            assert_eq!(f.coefficient(-d, -v), -mk);
        }
    }
    // At Δv the coefficient is µs from both sides (figure 6c meets eq. 13 there).
    for &d in &[0.0, 0.3 * dm, dm] {
        assert_eq!(f.magnitude(d, dv), ms);
        let below = f.magnitude(d, dv * (1.0 - 1e-9));
        assert!(close(below, ms, 1e-8), "Δ = {d}: {below}");
    }
    // Halfway down the µs → µk ramp.
    assert!(close(f.magnitude(0.0, 1.25 * dv), 0.5 * (ms + mk), 1e-15));
    // At rest the creep part alone: 0 without creep, µs at Δmax and beyond, half at Δmax/2.
    assert_eq!(f.coefficient(0.0, 0.0), 0.0);
    assert_eq!(f.coefficient(dm, 0.0), ms);
    assert_eq!(f.coefficient(5.0 * dm, 0.0), ms);
    assert!(close(f.coefficient(0.5 * dm, 0.0), 0.5 * ms, 1e-15));
    // Creep beyond Δmax: µs throughout the creep range of speeds.
    for k in 0..10 {
        let v = dv * k as f64 / 10.0;
        assert!(close(f.magnitude(2.0 * dm, v), ms, 1e-15));
    }
    // β and µ₁ of figure 6a/6b.
    assert_eq!(f.speed_share(0.0), 0.0);
    assert_eq!(f.speed_share(dv), 1.0);
    assert!(close(f.speed_share(-0.5 * dv), 0.5, 1e-15));
    assert!(close(f.creep_part(-0.5 * dm), 0.5 * ms, 1e-15));
}

#[test]
fn creep_friction_is_monotone() {
    let f = CreepFriction::default();
    let (dv, dm) = (f.transition_speed, f.creep_limit);
    // In |Δ| at any speed below Δv; in |v| on [0, Δv]; non-increasing in |v| above Δv.
    for j in 0..20 {
        let v = dv * j as f64 / 20.0;
        let mut prev = -1.0;
        for i in 0..=60 {
            let m = f.magnitude(2.0 * dm * i as f64 / 60.0, v);
            assert!(m >= prev - 1e-15, "v = {v}, i = {i}");
            prev = m;
        }
    }
    for i in 0..=10 {
        let d = 1.5 * dm * i as f64 / 10.0;
        let mut prev = -1.0;
        for j in 0..=100 {
            let m = f.magnitude(d, dv * j as f64 / 100.0);
            assert!(m >= prev - 1e-15, "Δ = {d}, j = {j}");
            prev = m;
        }
        let mut prev = f64::INFINITY;
        for j in 0..=100 {
            let m = f.magnitude(d, dv * (1.0 + j as f64 / 50.0));
            assert!(m <= prev + 1e-15, "Δ = {d}, j = {j}");
            prev = m;
        }
    }
    // Bounded by µs and never negative.
    for i in -30..=30 {
        for j in -30..=30 {
            let m = f.magnitude(dm * i as f64 / 10.0, dv * j as f64 / 10.0);
            assert!((0.0..=f.static_coefficient).contains(&m));
        }
    }
}

#[test]
fn creep_friction_is_odd_and_continuous() {
    let f = CreepFriction::default();
    let (dv, dm) = (f.transition_speed, f.creep_limit);
    let n = 400;
    let grid = |k: i32, scale: f64| scale * k as f64 / (n as f64 / 4.0);
    let mut largest_jump: f64 = 0.0;
    for i in -n / 2..=n / 2 {
        for j in -n / 2..=n / 2 {
            let (d, v) = (grid(i, dm), grid(j, dv));
            let m = f.coefficient(d, v);
            // Odd symmetry, exactly.
            assert_eq!(f.coefficient(-d, -v), -m, "Δ = {d}, v = {v}");
            // Magnitude equals eq. 13 whenever creep and speed agree in sign.
            if d * v >= 0.0 {
                assert!(close(m.abs(), f.magnitude(d, v), 1e-15));
            }
            if j > -n / 2 {
                largest_jump = largest_jump.max((m - f.coefficient(d, grid(j - 1, dv))).abs());
            }
            if i > -n / 2 {
                largest_jump = largest_jump.max((m - f.coefficient(grid(i - 1, dm), v)).abs());
            }
        }
    }
    // One grid step is 1/100 of Δv or Δmax; the steepest ramps rise 1.5·2µs per unit of the
    // scaled variable (the two signs across v = 0), so a continuous law moves < 0.04 per step.
    assert!(largest_jump < 0.04, "largest jump {largest_jump}");
}

#[test]
fn creep_memory_holds_at_the_limit_and_round_trips() {
    let f = CreepFriction::default();
    let dm = f.creep_limit;
    assert_eq!(f.creep_rate(0.5 * dm, 0.3), 0.3);
    assert_eq!(f.creep_rate(dm, 0.3), 0.0);
    assert_eq!(f.creep_rate(dm, -0.3), -0.3);
    assert_eq!(f.creep_rate(-2.0 * dm, -0.3), 0.0);
    assert_eq!(f.creep_rate(-2.0 * dm, 0.3), 0.3);
    let mut m = CreepMemory::new(3, 2);
    m.set(2, 1, 4e-5);
    m.set(0, 0, -1e-5);
    let saved = m.as_slice().to_vec();
    let mut back = CreepMemory::new(3, 2);
    back.restore(&saved).unwrap();
    assert_eq!(back, m);
    assert_eq!(back.get(2, 1), 4e-5);
    back.release(2, 1);
    assert_eq!(back.get(2, 1), 0.0);
    assert!(matches!(
        back.restore(&saved[..3]),
        Err(BeltError::Usage(_))
    ));
    let bad = CreepFriction {
        static_coefficient: 0.9,
        ..Default::default()
    };
    let e = bad.validate("pulleys[0].friction").unwrap_err();
    assert!(
        e.to_string()
            .contains("pulleys[0].friction.static_coefficient"),
        "{e}"
    );
}

// ---------------------------------------------------------------- rigid-body SDEs (eq. 20–23)

fn wavy_chain(n: usize, closed: bool) -> Vec<LinkState> {
    (0..n)
        .map(|i| {
            let s = i as f64;
            let a = if closed {
                std::f64::consts::TAU * s / n as f64
            } else {
                0.3 * s
            };
            let r = 0.05 * (1.0 + 0.05 * (3.0 * s).sin());
            LinkState {
                position: V2::new(r * a.cos() + 0.002 * (5.0 * s).cos(), r * a.sin()),
                angle: a
                    + std::f64::consts::FRAC_PI_2
                    + 0.2 * (7.0 * s).sin()
                    + 4.0 * std::f64::consts::TAU * (s > 3.0) as i32 as f64,
                velocity: V2::zeros(),
                angular_velocity: 0.0,
                length: 0.02 + 0.003 * (2.0 * s).cos(),
            }
        })
        .collect()
}

fn chain_energy(links: &[LinkState], p: &SdeParams, closed: bool) -> f64 {
    let n = links.len();
    let joints = if closed { n } else { n - 1 };
    (0..joints)
        .map(|e| joint_energy(&links[e], &links[(e + 1) % n], p))
        .sum()
}

#[test]
fn sde_forces_are_minus_gradient_of_spring_potential() {
    let p = SdeParams {
        translational_stiffness: 1.9e7,
        translational_damping: 20.5,
        torsional_stiffness: 0.026,
        torsional_damping: 0.0,
    };
    for closed in [false, true] {
        let links = wavy_chain(9, closed);
        let n = links.len();
        let mut f = vec![V2::zeros(); n];
        let mut tq = vec![0.0; n];
        let mut tension = vec![0.0; n];
        chain_loads(&links, &p, closed, &mut f, &mut tq, &mut tension);
        let scale = f.iter().map(|v| v.norm()).fold(0.0, f64::max);
        let tscale = tq.iter().map(|v| v.abs()).fold(0.0, f64::max);
        for i in 0..n {
            for c in 0..3 {
                let h = if c < 2 { 1e-9 } else { 1e-7 };
                let mut lp = links.clone();
                let mut lm = links.clone();
                match c {
                    0 => {
                        lp[i].position.x += h;
                        lm[i].position.x -= h;
                    }
                    1 => {
                        lp[i].position.y += h;
                        lm[i].position.y -= h;
                    }
                    _ => {
                        lp[i].angle += h;
                        lm[i].angle -= h;
                    }
                }
                let g =
                    -(chain_energy(&lp, &p, closed) - chain_energy(&lm, &p, closed)) / (2.0 * h);
                let (got, s) = if c < 2 {
                    (f[i][c], scale)
                } else {
                    (tq[i], tscale)
                };
                // Central differences of a quadratic-in-d potential: truncation error is
                // O(h²·curvature) and rounding ~ε·E/h; 1e-6 of the largest load covers both.
                assert!(
                    close(got, g, 1e-6 * s),
                    "closed {closed}, body {i}, coord {c}: {got} vs {g}"
                );
            }
        }
        // Tension of an SDE at rest is c_tra·|d| (eq. 20).
        let j = joint(&links[0], &links[1], &p);
        assert!(close(
            j.tension,
            p.translational_stiffness * j.elongation,
            1e-9 * j.tension
        ));
    }
}

#[test]
fn sde_damping_is_objective_and_dissipative() {
    let p = SdeParams {
        translational_stiffness: 0.0,
        translational_damping: 20.5,
        torsional_stiffness: 0.0,
        torsional_damping: 1e-3,
    };
    let mut links = wavy_chain(8, true);
    // A rigid motion of the whole belt (translation plus spin about a point) is not a
    // deformation: the dampers must be silent.
    let (u, w, o) = (V2::new(0.7, -0.2), 25.0, V2::new(0.01, 0.02));
    for l in links.iter_mut() {
        let r = l.position - o;
        l.velocity = u + V2::new(-w * r.y, w * r.x);
        l.angular_velocity = w;
    }
    let n = links.len();
    let (mut f, mut tq, mut t) = (vec![V2::zeros(); n], vec![0.0; n], vec![0.0; n]);
    chain_loads(&links, &p, true, &mut f, &mut tq, &mut t);
    for i in 0..n {
        assert!(
            f[i].norm() < 1e-12 && tq[i].abs() < 1e-14,
            "body {i}: {} {}",
            f[i],
            tq[i]
        );
    }
    // Any other motion: the dampers take power out, never put it in.
    for seed in 0..20 {
        for (i, l) in links.iter_mut().enumerate() {
            let s = (seed * 31 + i * 7) as f64;
            l.velocity = V2::new((1.3 * s).sin(), (2.1 * s).cos());
            l.angular_velocity = 30.0 * (0.7 * s).sin();
        }
        let (mut f, mut tq, mut t) = (vec![V2::zeros(); n], vec![0.0; n], vec![0.0; n]);
        chain_loads(&links, &p, true, &mut f, &mut tq, &mut t);
        let power: f64 = (0..n)
            .map(|i| f[i].dot(&links[i].velocity) + tq[i] * links[i].angular_velocity)
            .sum();
        assert!(power <= 1e-12, "seed {seed}: power {power}");
    }
}

#[test]
fn sde_loads_balance_forces_and_moments() {
    let p = SdeParams {
        translational_stiffness: 1.52e5,
        translational_damping: 20.5,
        torsional_stiffness: 0.026,
        torsional_damping: 1e-4,
    };
    let mut links = wavy_chain(7, false);
    for (i, l) in links.iter_mut().enumerate() {
        l.velocity = V2::new((i as f64).sin(), 0.3);
        l.angular_velocity = (3 * i) as f64;
    }
    let n = links.len();
    let (mut f, mut tq, mut t) = (vec![V2::zeros(); n], vec![0.0; n], vec![0.0; n]);
    chain_loads(&links, &p, false, &mut f, &mut tq, &mut t);
    let sum: V2 = f.iter().sum();
    let moment: f64 = (0..n)
        .map(|i| links[i].position.x * f[i].y - links[i].position.y * f[i].x + tq[i])
        .sum();
    let scale = f.iter().map(|v| v.norm()).fold(0.0, f64::max);
    assert!(sum.norm() < 1e-12 * scale);
    assert!(moment.abs() < 1e-12 * scale);
    // A straight chain with gap g between ends: tension c·g, pure axial force.
    let a = LinkState {
        position: V2::zeros(),
        angle: 0.0,
        velocity: V2::zeros(),
        angular_velocity: 0.0,
        length: 0.008,
    };
    let b = LinkState {
        position: V2::new(0.0085, 0.0),
        ..a
    };
    let j = joint(&a, &b, &p);
    assert!(close(j.tension, 1.52e5 * 0.0005, 1e-9));
    assert!(close(j.force_on_right.x, -1.52e5 * 0.0005, 1e-9) && j.force_on_right.y == 0.0);
    assert!(j.torque_on_left.abs() < 1e-15 && j.torque_on_right.abs() < 1e-15);
    assert!(close(
        link_inertia(7.68e-4, 0.008),
        7.68e-4 * 6.4e-5 / 12.0,
        1e-20
    ));
}

// ---------------------------------------------------------------- pulley (eq. 24)

#[test]
fn resistance_torque_and_pulley_equation() {
    // Case K: 15 N·m at 4 rev/s.
    let w = 8.0 * std::f64::consts::PI;
    let r = SpeedResistance::viscous_reaching(15.0, w).unwrap();
    assert!(close(r.torque(w), -15.0, 1e-12));
    assert!(close(r.torque(-0.5 * w), 7.5, 1e-12));
    assert_eq!(r.torque(0.0), 0.0);
    // A constant part opposes motion, smoothly: zero at rest, full beyond ω_ε.
    let c = SpeedResistance {
        constant: 2.0,
        viscous: 0.1,
        smoothing_speed: 0.01,
    };
    c.validate("pulleys[1].resistance").unwrap();
    assert!(close(c.torque(1.0), -2.1, 1e-12));
    assert!(close(c.torque(-1.0), 2.1, 1e-12));
    assert_eq!(c.torque(0.0), 0.0);
    let step = 1e-9;
    assert!(
        (c.torque(step) - c.torque(-step)).abs() < 1e-6,
        "continuous through zero"
    );
    for k in -100..=100 {
        let om = 0.02 * k as f64 / 100.0;
        assert!(c.torque(om) * om <= 0.0);
    }
    let e = SpeedResistance {
        constant: 1.0,
        viscous: 0.0,
        smoothing_speed: 0.0,
    }
    .validate("pulleys[1].resistance")
    .unwrap_err();
    assert!(
        e.to_string()
            .contains("pulleys[1].resistance.smoothing_speed"),
        "{e}"
    );
    assert!(SpeedResistance::viscous_reaching(15.0, 0.0).is_err());
    // Friction dragging a body counter-clockwise at (r, 0) brakes the pulley.
    let tq = friction_torque_on_pulley(V2::new(0.027, 0.0), V2::new(0.0, 100.0));
    assert!(close(tq, -2.7, 1e-12));
    assert!(close(
        pulley_acceleration(2.4e-4, 15.0, tq),
        (15.0 - 2.7) / 2.4e-4,
        1e-9
    ));
}
