//! Speed-controlled drives: the starting curves (Guo & Wang 2020 §4) and a drive that makes
//! its pulley follow one within a torque limit (docs/drives.md).
use beltrs::checkpoint;
use beltrs::record::Channels;
use beltrs::scene::{
    BeltParams, BrakeSpec, DriveSpec, FrictionModel, PulleySpec, Scene, Table, Wrap,
};
use beltrs::{BeltError, Simulation, StabiliseOptions, Stage, StartCurve, StartShape};
use std::f64::consts::PI;

/// Record only the small per-pulley arrays (no tensions, positions or velocities).
const PER_PULLEY_ONLY: Channels = Channels {
    tension: false,
    node_position: false,
    node_velocity: false,
    energy: false,
    contact_forces: false,
};

// ---------------------------------------------------------------------------------------
// 1. The curves
// ---------------------------------------------------------------------------------------

fn curve(shape: StartShape, speed: f64, ramp: f64) -> StartCurve {
    StartCurve {
        shape,
        speed,
        ramp,
        ..Default::default()
    }
}

/// |a − b| ≤ tol, with a readable panic message.
fn close(what: &str, got: f64, want: f64, tol: f64) {
    assert!(
        (got - want).abs() <= tol,
        "{what}: got {got:e}, want {want:e} (diff {:e}, allowed {tol:e})",
        (got - want).abs()
    );
}

/// Values at τ = ¼, ½, ¾ worked out by hand from each formula (v₀ = 2 m/s, T = 10 s).
#[test]
fn curves_take_their_published_values() {
    let v0 = 2.0;
    let s2 = std::f64::consts::FRAC_1_SQRT_2;
    let cases = [
        // Harrison: v0/2 (1 − cos πτ): (1 − √½)/2·2, 1, (1 + √½)/2·2.
        (StartShape::Harrison, [1.0 - s2, 1.0, 1.0 + s2]),
        // Nordell: 2v0τ² = 0.25, 1; v0(−1 + 3 − 9/8) = 1.75.
        (StartShape::Nordell, [0.25, 1.0, 1.75]),
        // Cubic: v0(3τ² − 2τ³) = 2(3/16 − 1/32) = 0.3125, 1, 2(27/16 − 27/32) = 1.6875.
        (StartShape::Cubic, [0.3125, 1.0, 1.6875]),
        (StartShape::Linear, [0.5, 1.0, 1.5]),
    ];
    for (shape, want) in cases {
        let c = curve(shape, v0, 10.0);
        for (k, tau) in [0.25, 0.5, 0.75].into_iter().enumerate() {
            // The formulas in a few operations: agreement to a few ulps of v0.
            close(
                &format!("{shape:?} v({tau}T)"),
                c.speed_at(tau * 10.0),
                want[k],
                4.0 * f64::EPSILON * v0,
            );
        }
        assert_eq!(c.speed_at(0.0), 0.0, "{shape:?} starts at rest");
        assert_eq!(c.speed_at(-1.0), 0.0, "{shape:?} at rest before the start");
        assert_eq!(c.speed_at(10.0), v0, "{shape:?}: v(T) = v0 exactly");
        assert_eq!(c.speed_at(25.0), v0, "{shape:?} holds v0 after the ramp");
        assert_eq!(c.acceleration_at(25.0), 0.0);
        // Just before T the speed is v0 to within the slope times the distance.
        let eps = 1e-9;
        close(
            &format!("{shape:?} v(T−)"),
            c.speed_at(10.0 - eps),
            v0,
            (v0 / 10.0) * eps + 1e-14,
        );
    }
    // Peak accelerations: Harrison π/2·v0/T at τ = ½, Nordell 2v0/T, cubic 1.5v0/T, linear v0/T.
    for (shape, peak) in [
        (StartShape::Harrison, PI / 2.0 * 0.2),
        (StartShape::Nordell, 0.4),
        (StartShape::Cubic, 0.3),
        (StartShape::Linear, 0.2),
    ] {
        close(
            &format!("{shape:?} a(T/2)"),
            curve(shape, v0, 10.0).acceleration_at(5.0),
            peak,
            1e-15,
        );
    }
}

/// The acceleration is the derivative of the speed (checked against a central difference
/// at many points), and both are continuous inside the ramp; Nordell's acceleration is
/// continuous at τ = ½ and zero at τ = 1 (the paper's printed form is neither).
#[test]
fn accelerations_are_the_derivatives_and_nordell_is_continuous() {
    for shape in StartShape::ALL {
        let c = curve(shape, -3.0, 4.0);
        for k in 1..400 {
            let t = 4.0 * k as f64 / 400.0;
            let h = 1e-5;
            let fd = (c.speed_at(t + h) - c.speed_at(t - h)) / (2.0 * h);
            // Central difference error h²/6·|v'''| ≤ 1e-10·(π³/2·3/4³ ≈ 0.73) plus
            // rounding 2·ε·|v|/(2h) ≈ 7e-11; the Nordell kink in v'' at ½ adds
            // h·|Δv''|/2 ≤ 1e-5·(8·3/16)/2 < 1e-5.
            close(
                &format!("{shape:?} dv/dt at {t}"),
                c.acceleration_at(t),
                fd,
                1e-5,
            );
        }
    }
    let c = curve(StartShape::Nordell, 1.0, 1.0);
    let (below, above) = (c.evaluate(0.5 - 1e-12), c.evaluate(0.5 + 1e-12));
    close("Nordell v at ½", below.0, above.0, 1e-11);
    close("Nordell a at ½", below.1, above.1, 1e-11);
    close(
        "Nordell a at ½ is the peak 2v0/T",
        c.acceleration_at(0.5),
        2.0,
        0.0,
    );
    close(
        "Nordell a(T−) → 0",
        c.acceleration_at(1.0 - 1e-9),
        0.0,
        1e-8,
    );
    close("Nordell v(T−) → v0", c.speed_at(1.0 - 1e-9), 1.0, 1e-15);
}

/// Start delay and pre-start: at rest before `start`, a run-up over `creep_ramp` to the
/// creep speed, a hold until start + prestart, then the main ramp from the creep speed.
#[test]
fn prestart_sections() {
    let c = StartCurve {
        shape: StartShape::Cubic,
        speed: 2.0,
        ramp: 10.0,
        start: 1.0,
        prestart: 3.0,
        ..Default::default()
    };
    // Defaults: creep speed 10 % of the speed, run-up over half the pre-start.
    assert_eq!(c.creep_speed_or_default(), 0.2);
    assert_eq!(c.creep_ramp_or_default(), 1.5);
    assert_eq!(c.evaluate(0.5), (0.0, 0.0));
    assert_eq!(c.speed_at(1.0), 0.0);
    // Run-up: cubic at τ = ½ of 1.5 s is half the creep speed, acceleration 1.5·0.2/1.5.
    close("run-up midpoint", c.speed_at(1.75), 0.1, 1e-16);
    close(
        "run-up peak acceleration",
        c.acceleration_at(1.75),
        0.2,
        1e-16,
    );
    // Hold.
    assert_eq!(c.evaluate(2.5), (0.2, 0.0));
    assert_eq!(c.evaluate(3.999), (0.2, 0.0));
    // Main ramp from 0.2 to 2 over [4, 14].
    assert_eq!(c.speed_at(4.0), 0.2);
    close(
        "main ramp midpoint",
        c.speed_at(9.0),
        0.2 + 1.8 * 0.5,
        1e-15,
    );
    close(
        "main ramp peak",
        c.acceleration_at(9.0),
        1.5 * 1.8 / 10.0,
        1e-16,
    );
    assert_eq!(c.end(), 14.0);
    assert_eq!(c.evaluate(14.0), (2.0, 0.0));
    // Continuous at each section boundary.
    for t in [1.0, 2.5, 4.0, 14.0] {
        close(
            &format!("continuity at {t}"),
            c.speed_at(t - 1e-9),
            c.speed_at(t + 1e-9),
            1e-9,
        );
    }
    // Creep ramp equal to the pre-start: no hold section; explicit creep speed.
    let d = StartCurve {
        creep_speed: Some(0.5),
        creep_ramp: Some(3.0),
        ..c.clone()
    };
    close("no hold", d.speed_at(3.999_999), 0.5, 1e-9);
    assert_eq!(d.speed_at(4.0), 0.5);
}

#[test]
fn bad_curves_name_the_field_and_value() {
    let good = StartCurve {
        speed: 2.0,
        ramp: 10.0,
        prestart: 3.0,
        ..Default::default()
    };
    good.validate("c").unwrap();
    let cases: Vec<(StartCurve, &str, &str)> = vec![
        (
            StartCurve {
                speed: f64::NAN,
                ..good.clone()
            },
            "c.speed",
            "finite",
        ),
        (
            StartCurve {
                speed: 0.0,
                ..good.clone()
            },
            "c.speed",
            "non-zero",
        ),
        (
            StartCurve {
                ramp: -1.0,
                ..good.clone()
            },
            "c.ramp",
            "> 0",
        ),
        (
            StartCurve {
                ramp: 0.0,
                ..good.clone()
            },
            "c.ramp",
            "> 0",
        ),
        (
            StartCurve {
                start: f64::INFINITY,
                ..good.clone()
            },
            "c.start",
            "finite",
        ),
        (
            StartCurve {
                prestart: -1.0,
                ..good.clone()
            },
            "c.prestart",
            "≥ 0",
        ),
        (
            StartCurve {
                creep_speed: Some(2.5),
                ..good.clone()
            },
            "c.creep_speed",
            "between 0 and speed",
        ),
        (
            StartCurve {
                creep_speed: Some(-0.1),
                ..good.clone()
            },
            "c.creep_speed",
            "same sign",
        ),
        (
            StartCurve {
                creep_speed: Some(f64::NAN),
                ..good.clone()
            },
            "c.creep_speed",
            "finite",
        ),
        (
            StartCurve {
                creep_ramp: Some(4.0),
                ..good.clone()
            },
            "c.creep_ramp",
            "≤ prestart",
        ),
        (
            StartCurve {
                creep_ramp: Some(0.0),
                ..good.clone()
            },
            "c.creep_ramp",
            "> 0",
        ),
        (
            StartCurve {
                prestart: 0.0,
                creep_ramp: Some(1.0),
                ..good.clone()
            },
            "c.creep_ramp",
            "no effect without a pre-start",
        ),
    ];
    for (c, field, rule) in cases {
        match c.validate("c") {
            Err(BeltError::InvalidParameter {
                field: f, rule: r, ..
            }) => {
                assert_eq!(f, field);
                assert!(r.contains(rule), "{field}: rule {r:?} lacks {rule:?}");
            }
            other => panic!("{field}: expected an error, got {other:?}"),
        }
    }
}

// ---------------------------------------------------------------------------------------
// 2. The drive
// ---------------------------------------------------------------------------------------

const RADIUS: f64 = 1.0;
const INERTIA: f64 = 50.0;

/// A horizontal 10 m two-pulley loop without gravity: pulleys of 1 m radius, 240 elements
/// (6.3° each on the wraps, so the polygon's chordal speed ripple is 0.15 %), EA = 1 MN,
/// 10 kg/m, the belt 0.5 % shorter than its path (about 5 kN of pretension). The drive
/// pulley (0) has friction µ = 0.5; the other is frictionless (the belt slides round it).
/// The drive starts the belt to 2 m/s over 1 s from t = 0.1 s.
fn loop_scene(shape: StartShape, max_torque: f64) -> Scene {
    let path = 2.0 * 10.0 + 2.0 * PI * RADIUS;
    let pulley = |center: [f64; 2]| PulleySpec {
        center,
        radius: RADIUS,
        mass: 100.0,
        inertia: Some(INERTIA),
        contact_stiffness: 1e7,
        ..Default::default()
    };
    Scene {
        belt: BeltParams {
            axial_stiffness: 1e6,
            mass_per_length: 10.0,
            length: Some(path * 0.995),
            elements: Some(240),
            ..Default::default()
        },
        pulleys: vec![
            PulleySpec {
                friction: FrictionModel::StickForce {
                    static_coefficient: 0.5,
                    kinetic_coefficient: 0.5,
                },
                drive: Some(DriveSpec {
                    start_curve: Some(StartCurve {
                        shape,
                        speed: 2.0,
                        ramp: 1.0,
                        start: 0.1,
                        ..Default::default()
                    }),
                    max_torque,
                    ..Default::default()
                }),
                ..pulley([0.0, 0.0])
            },
            pulley([10.0, 0.0]),
        ],
        gravity: 0.0,
        ..Default::default()
    }
}

/// The scene relaxed to static equilibrium (drives off): the belt at rest on its pulleys,
/// without the ringing that the placement on the path would start.
fn relaxed(scene: &Scene) -> Simulation {
    let mut sim = Simulation::new(scene).unwrap();
    let report = sim.stabilise(&StabiliseOptions::default()).unwrap();
    assert!(report.converged);
    sim
}

fn the_curve(sim: &Simulation, j: usize) -> StartCurve {
    sim.model.pulleys[j]
        .drive
        .as_ref()
        .and_then(|d| d.start_curve.clone())
        .unwrap()
}

/// Within the torque limit the pulley follows the curve exactly (ω(t + Δt/2) is the
/// curve's speed there over the radius, bit for bit), and the drive torque is what the
/// pulley and the belt need: drive + belt friction torque = I·Δω/Δt each step, and
/// I·a(t)/r − belt torque against the curve's analytic acceleration.
#[test]
fn drive_follows_the_curve_and_supplies_inertia_plus_belt_torque() {
    for shape in StartShape::ALL {
        let mut sim = relaxed(&loop_scene(shape, f64::INFINITY));
        assert!(sim.model.has_stage(Stage::SpeedDrives));
        assert!(!sim.model.has_stage(Stage::Brakes));
        let c = the_curve(&sim, 0);
        let dt = sim.model.dt;
        let steps = (1.3 / dt) as u64;
        sim.begin_recording(PER_PULLEY_ONLY, 1, usize::MAX);
        let mut peak_belt = 0.0f64;
        for _ in 0..steps {
            let t = sim.state.time;
            sim.advance(1).unwrap();
            assert_eq!(
                sim.state.pulley_omega[0],
                c.speed_at(t + 0.5 * dt) / RADIUS,
                "{shape:?}: pulley off its curve at t = {t}"
            );
        }
        let r = &sim.recording;
        let p = 2;
        let (mut peak, mut worst_exact, mut worst_analytic) = (0.0f64, 0.0f64, 0.0f64);
        for k in 0..r.time.len() {
            let t = r.time[k];
            let drive = r.drive_torque[k * p];
            let belt = r.friction_torque[k * p];
            let dw = (c.speed_at(t + 0.5 * dt) - c.speed_at(t - 0.5 * dt)) / RADIUS;
            worst_exact = worst_exact.max((drive + belt - INERTIA * dw / dt).abs());
            let analytic = INERTIA * c.acceleration_at(t) / RADIUS - belt;
            // Linear has acceleration steps at its ends: a(t) is one-sided there.
            if shape != StartShape::Linear || (t - 0.1).abs() > dt && (t - 1.1).abs() > dt {
                worst_analytic = worst_analytic.max((drive - analytic).abs());
            }
            peak = peak.max(drive.abs());
            peak_belt = peak_belt.max(belt.abs());
        }
        // Sum of three torques in the friction solve: rounding of a few ulps of the peak.
        assert!(
            worst_exact <= 1e-9 * peak,
            "{shape:?}: {worst_exact} of {peak}"
        );
        // (v(t+Δt/2) − v(t−Δt/2))/Δt = a(t) + O(Δt²·a''/24); next to the ends of the
        // Harrison, cubic and Nordell ramps a' jumps, giving up to Δt·|Δa'|/8 (|a'| ≤ π²
        // v0/T² ≈ 20 m/s³): I/r·Δt·20/8 = 50·Δt·2.5 ≈ 0.02 N·m at Δt ≈ 1.6e-4 s.
        assert!(
            worst_analytic <= INERTIA / RADIUS * dt * 20.0 / 8.0 + 1e-9 * peak,
            "{shape:?}: drive torque off I·a/r − belt torque by {worst_analytic} N·m"
        );
        // The belt takes most of the torque (its mass is ~262 kg against the pulley's
        // 50 kg equivalent), so the check above is not about the pulley alone.
        assert!(
            peak_belt > 0.3 * peak,
            "{shape:?}: belt torque {peak_belt} of {peak}"
        );
        println!("{shape:?}: peak drive torque {peak:.1} N·m, belt {peak_belt:.1} N·m, exact balance {worst_exact:.2e}, analytic {worst_analytic:.2e}");
    }
}

/// With a motor limit below the torque the curve needs, the drive sits at the limit and the
/// pulley falls behind; after the ramp it catches up and holds the final speed again.
#[test]
fn low_torque_limit_lags_then_catches_up() {
    // The curve needs r·(m_belt + I/r²)·π/2·v0/T ≈ 980 N·m at its peak.
    let limit = 500.0;
    let mut sim = relaxed(&loop_scene(StartShape::Harrison, limit));
    let c = the_curve(&sim, 0);
    let dt = sim.model.dt;
    sim.begin_recording(PER_PULLEY_ONLY, 1, usize::MAX);
    let steps = (3.0 / dt) as u64;
    let (mut at_limit, mut max_lag, mut last_lag) = (0u64, 0.0f64, 0.0);
    let (mut late, mut late_held, mut late_speed) = (0u64, 0u64, 0.0);
    for _ in 0..steps {
        let t = sim.state.time;
        sim.advance(1).unwrap();
        let target = c.speed_at(t + 0.5 * dt) / RADIUS;
        let lag = target - sim.state.pulley_omega[0];
        if lag > 1e-2 * target {
            last_lag = t;
        }
        if t > 2.5 {
            late += 1;
            late_held += u64::from(sim.state.pulley_omega[0] == target);
            late_speed += sim.state.pulley_omega[0];
        }
        max_lag = max_lag.max(lag);
        // Behind the curve, never ahead of it, while the belt is being accelerated (later
        // the belt's elastic rebound may push the pulley past the final speed by more than
        // the motor can brake).
        if t < c.end() {
            assert!(lag >= -1e-12, "ahead of the curve by {lag} rad/s at {t}");
        }
    }
    let r = &sim.recording;
    for k in 0..r.time.len() {
        let drive = r.drive_torque[2 * k];
        // Never above the limit (the limit is exact: it is the value supplied).
        assert!(drive.abs() <= limit, "{drive} N·m at {}", r.time[k]);
        if drive == limit {
            at_limit += 1;
        }
    }
    assert!(at_limit > 100, "at the limit for {at_limit} steps only");
    assert!(max_lag > 0.1, "lagged by {max_lag} rad/s only");
    // Caught up soon after the ramp (measured: at 1.45 s; no lag beyond 1 % after 2 s).
    // On the final speed the
    // drive holds the pulley exactly most of the time; the polygon ripple of the nodal
    // belt (a zero-mean torque at the node passing frequency, docs/drives.md) can exceed
    // the limit for single steps, so neither "always" nor a bound on the count is exact.
    assert!(
        last_lag > c.end() && last_lag < 2.0,
        "lagging until {last_lag} s"
    );
    let held = late_held as f64 / late as f64;
    let mean = late_speed / late as f64;
    assert!(
        held > 0.5,
        "held on the curve {:.1} % of the last 0.5 s",
        100.0 * held
    );
    close("mean final speed", mean, 2.0 / RADIUS, 1e-3 * 2.0 / RADIUS);
    println!("limit {limit} N·m: {at_limit} steps at the limit, max lag {max_lag:.3} rad/s, lag < 1 % from {last_lag:.3} s, held {:.1} % of the last 0.5 s", 100.0 * held);
}

/// A speed-controlled pulley without friction (or with friction switched off, or no belt
/// contacts) is solved by the stage itself: the torque is I·Δω/Δt exactly, and with a
/// limit the pulley accelerates at limit/I.
#[test]
fn frictionless_pulley_is_held_by_the_stage() {
    let mut scene = loop_scene(StartShape::Cubic, f64::INFINITY);
    scene.pulleys[0].friction = FrictionModel::None;
    scene.pulleys[0].drive.as_mut().unwrap().viscous = 3.0;
    let mut sim = Simulation::new(&scene).unwrap();
    assert!(!sim.model.has_stage(Stage::PulleyFriction));
    let c = the_curve(&sim, 0);
    let dt = sim.model.dt;
    sim.begin_recording(Channels::default(), 1, usize::MAX);
    let steps = (1.2 / dt) as u64;
    for _ in 0..steps {
        let t = sim.state.time;
        sim.advance(1).unwrap();
        assert_eq!(sim.state.pulley_omega[0], c.speed_at(t + 0.5 * dt) / RADIUS);
    }
    let r = &sim.recording;
    let mut peak = 0.0f64;
    for k in 0..r.time.len() {
        let t = r.time[k];
        let dw = (c.speed_at(t + 0.5 * dt) - c.speed_at(t - 0.5 * dt)) / RADIUS;
        // The recorded torque includes the load torque −b·ω (b = 3): the net torque on
        // the pulley is I·Δω/Δt to rounding.
        close(
            &format!("torque at {t}"),
            r.drive_torque[2 * k],
            INERTIA * dw / dt,
            1e-9 * (INERTIA * 6.0 / RADIUS),
        );
        assert_eq!(r.friction_torque[2 * k], 0.0);
        peak = peak.max(r.drive_torque[2 * k]);
    }
    // Cubic peak: 1.5·v0/T = 3 m/s², I·a/r = 150 N·m.
    close("peak torque", peak, 150.0, 0.01);

    // The same with a 50 N·m motor: it cannot hold the steep middle of the ramp
    // (150 N·m) and there accelerates at (50 − b·ω)/I.
    scene.pulleys[0].drive.as_mut().unwrap().max_torque = 50.0;
    let mut sim = Simulation::new(&scene).unwrap();
    sim.step((0.6 / dt) as u64).unwrap();
    let w0 = sim.state.pulley_omega[0];
    sim.step(1).unwrap();
    let w1 = sim.state.pulley_omega[0];
    close(
        "limited acceleration",
        (w1 - w0) / dt,
        (50.0 - 3.0 * w0) / INERTIA,
        1e-9,
    );
}

/// A brake and a speed-controlled drive on one pulley, a torque table with a curve, a speed
/// factor with a curve, a torque limit without a curve: each refused naming the field.
#[test]
fn conflicting_drive_settings_are_refused() {
    let base = loop_scene(StartShape::Harrison, 300.0);
    let expect = |s: Scene, field: &str, rule: &str| match Simulation::new(&s) {
        Err(BeltError::InvalidParameter {
            field: f, rule: r, ..
        }) => {
            assert_eq!(f, field);
            assert!(r.contains(rule), "{field}: {r}");
        }
        other => panic!("{field}: expected an error, got {:?}", other.map(|_| ())),
    };
    let mut s = base.clone();
    s.pulleys[0].brake = Some(BrakeSpec {
        capacity: Table::constant(1e3),
        ..Default::default()
    });
    expect(s, "pulleys[0].brake", "cannot also have a brake");
    let mut s = base.clone();
    s.pulleys[0].drive.as_mut().unwrap().torque = Table {
        x: vec![0.0, 1.0],
        y: vec![0.0, 5.0],
    };
    expect(s, "pulleys[0].drive.torque[1]", "not both");
    let mut s = base.clone();
    s.pulleys[0].drive.as_mut().unwrap().speed_factor = Table::constant(1.0);
    expect(s, "pulleys[0].drive.speed_factor", "no effect");
    let mut s = base.clone();
    s.pulleys[0].drive.as_mut().unwrap().max_torque = -1.0;
    expect(s, "pulleys[0].drive.max_torque", "> 0");
    let mut s = base.clone();
    s.pulleys[0].drive.as_mut().unwrap().max_torque = f64::NAN;
    expect(s, "pulleys[0].drive.max_torque", "> 0");
    let mut s = base.clone();
    s.pulleys[0].drive.as_mut().unwrap().start_curve = None;
    expect(
        s,
        "pulleys[0].drive.max_torque",
        "speed-controlled drive only",
    );
    let mut s = base.clone();
    s.pulleys[0]
        .drive
        .as_mut()
        .unwrap()
        .start_curve
        .as_mut()
        .unwrap()
        .ramp = f64::NAN;
    expect(s, "pulleys[0].drive.start_curve.ramp", "finite");
    // A torque drive does not pay for the speed mode: no speed_drives stage.
    let mut s = base;
    let d = s.pulleys[0].drive.as_mut().unwrap();
    d.start_curve = None;
    d.max_torque = f64::INFINITY;
    d.torque = Table::constant(10.0);
    let m = beltrs::Model::compile(&s).unwrap();
    assert!(m.has_stage(Stage::Drives) && !m.has_stage(Stage::SpeedDrives));
}

/// Work done by the drive equals the change of the system's energy (no damping, no
/// gravity; single nodes slip now and then, dissipating a little): the controller's torque
/// is booked as drive torque.
#[test]
fn drive_work_balances_the_energy() {
    let mut sim = relaxed(&loop_scene(StartShape::Harrison, f64::INFINITY));
    let e0 = sim.current_energies();
    assert_eq!(e0.drive_work, 0.0);
    let dt = sim.model.dt;
    sim.step((1.3 / dt) as u64).unwrap();
    let e = sim.current_energies();
    let gain = e.total() - e0.total();
    // Kinetic energy at 2 m/s: ½(262 kg)(2)² + ½·50·2² ≈ 623 J, so the work is not small.
    assert!(e.kinetic > 550.0, "kinetic energy {}", e.kinetic);
    // Explicit central differences conserve energy up to an O(Δt²) oscillation, the
    // penalty contact and the stick force exchange O((ωΔt)²) of the work they carry, and
    // single slipping nodes dissipate; measured 1.1e-3, allowed 1 %.
    let err = (gain - e.drive_work).abs() / e.drive_work;
    println!(
        "drive work {:.3} J, energy gain {:.3} J, relative difference {err:.2e}",
        e.drive_work, gain
    );
    assert!(
        err < 1e-2,
        "energy gain {gain} J against drive work {} J",
        e.drive_work
    );
}

/// A checkpoint carries the curve and the torque limit: the resumed run continues bit for
/// bit; the file of a torque drive keeps its old layout (tag 1).
#[test]
fn checkpoint_resumes_a_speed_drive_bit_for_bit() {
    let mut scene = loop_scene(StartShape::Nordell, 300.0);
    scene.pulleys[0].drive.as_mut().unwrap().start_curve = Some(StartCurve {
        shape: StartShape::Nordell,
        speed: -2.0,
        ramp: 1.0,
        start: 0.05,
        prestart: 0.2,
        creep_speed: Some(-0.3),
        creep_ramp: Some(0.1),
    });
    scene.pulleys[1].wrap = Wrap::CounterClockwise;
    let mut a = Simulation::new(&scene).unwrap();
    let dt = a.model.dt;
    a.step((0.4 / dt) as u64).unwrap();
    let bytes = checkpoint::encode(&a);
    let mut b = checkpoint::decode(&bytes).unwrap();
    assert_eq!(b.model.scene, a.model.scene);
    for sim in [&mut a, &mut b] {
        sim.begin_recording(Channels::default(), 5, usize::MAX);
        sim.advance((0.6 / dt) as u64).unwrap();
        sim.end_recording().unwrap();
    }
    assert!(
        a.recording.drive_torque.iter().any(|&t| t == -300.0),
        "never at the limit"
    );
    assert_eq!(a.recording, b.recording);
    assert_eq!(a.state, b.state);
}
