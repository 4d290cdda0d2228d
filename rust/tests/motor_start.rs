//! Direct-on-line motor starts (`drives::motor`, `drives::coupling`, docs/drives.md):
//! the Kloss curve through its rated and breakdown points, the run-up time of a rigid
//! inertia against its quadrature, the steady running point through a fluid coupling, and
//! the flywheel.
use crate::common::{close, free_pulley};
use beltrs::drives::coupling::{CouplingModel, FluidCoupling};
use beltrs::drives::motor::{Motor, MotorCurve, MotorModel};
use beltrs::record::Channels;
use beltrs::scene::{BrakeSpec, DriveSpec, InitialState, Scene, Wrap};
use beltrs::{BeltError, Simulation, Stage};

const INERTIA: f64 = 40.0;

/// A 110 kW 4-pole motor: 1485 rpm, synchronous 1500 rpm, breakdown 2.5 × rated.
fn motor() -> Motor {
    Motor {
        rated_power: 110e3,
        rated_speed: 1485.0 * std::f64::consts::PI / 30.0,
        synchronous_speed: 1500.0 * std::f64::consts::PI / 30.0,
        gear_ratio: 20.0,
        rotor_inertia: 1.2,
        ..Default::default()
    }
}

/// A free inertia of 40 kg·m² (`common::free_pulley`, radius 0.5 m, 60 elements) driven
/// by `drive`.
fn rigid_scene(drive: DriveSpec, dt: f64) -> Scene {
    free_pulley(drive, 0.5, INERTIA, 60, dt)
}

/// The Kloss curve passes through the rated point (T_r at n_r) and peaks at T_b = k·T_r at
/// the breakdown slip; it is zero at synchronous speed and negative above.
#[test]
fn kloss_curve_through_rated_and_breakdown_points() {
    let m = motor();
    let curve = MotorCurve::kloss(&m);
    let tr = m.rated_torque();
    close("rated", curve.torque(m.rated_speed), tr, 1e-9 * tr);
    let MotorCurve::Kloss {
        breakdown_slip: sb,
        synchronous_speed: ns,
        ..
    } = curve
    else {
        unreachable!()
    };
    close(
        "breakdown",
        curve.torque(ns * (1.0 - sb)),
        2.5 * tr,
        1e-9 * tr,
    );
    for ds in [-1e-3, 1e-3] {
        assert!(curve.torque(ns * (1.0 - sb - ds)) < 2.5 * tr);
    }
    assert_eq!(curve.torque(ns), 0.0);
    assert!(curve.torque(1.01 * ns) < 0.0);
}

/// Run-up of a rigid inertia: n' = i²·T(n)/J with J = I + i²·(J_r + J_f) at the pulley,
/// so the time to reach the motor speed n* is ∫₀^{n*} J/(i²·T(n)) dn (Simpson, 20 000
/// panels). The simulation's crossing time agrees to within the explicit scheme's O(Δt)
/// (2 steps) plus the record interval (1 step).
#[test]
fn run_up_time_matches_the_quadrature() {
    let dt = 1e-4;
    let m = motor();
    let flywheel = 0.8;
    let drive = DriveSpec {
        motor: Some(m.clone()),
        flywheel,
        ..Default::default()
    };
    let mut sim = Simulation::new(&rigid_scene(drive, dt)).unwrap();
    assert!(sim.model.has_stage(Stage::Motors));
    let i = m.gear_ratio;
    let j = INERTIA + i * i * (m.rotor_inertia + flywheel);
    close("pulley inertia", sim.model.pulleys[0].inertia, j, 1e-12 * j);
    let curve = MotorCurve::kloss(&m);
    let target = 0.95 * m.synchronous_speed;
    let panels = 20_000;
    let h = target / panels as f64;
    let f = |n: f64| j / (i * i * curve.torque(n));
    let mut quad = f(0.0) + f(target);
    for k in 1..panels {
        quad += f(k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    let quad = quad * h / 3.0;
    sim.begin_recording(Channels::default(), 1, usize::MAX);
    sim.advance((1.5 * quad / dt) as u64).unwrap();
    let r = &sim.recording;
    let k = (0..r.time.len())
        .find(|&k| r.pulley_speed[2 * k] * i >= target)
        .expect("never reached the speed");
    close("run-up time", r.time[k], quad, 3.0 * dt);
    // Finally at the no-load point: synchronous speed.
    let last = r.pulley_speed[2 * (r.time.len() - 1)] * i;
    assert!(last < m.synchronous_speed && last > 0.999 * m.synchronous_speed);
}

/// Through a fluid coupling against a viscous load b: at steady running the motor torque,
/// the coupling torque and the load agree, T_m(n_in) = T_c(n_in, n_out) = b·ω/i with
/// n_out = i·ω. The running point solved by bisection is reached to 1e-6 relative.
#[test]
fn coupled_start_settles_at_the_running_point() {
    let dt = 1e-4;
    let mut m = motor();
    m.coupling = Some(FluidCoupling::default());
    m.rotation = Wrap::Clockwise;
    let b = 400.0; // N·m·s/rad at the pulley: 3 kN·m at 7.5 rad/s
    let drive = DriveSpec {
        motor: Some(m.clone()),
        viscous: b,
        ..Default::default()
    };
    let mut sim = Simulation::new(&rigid_scene(drive, dt)).unwrap();
    sim.step((12.0 / dt) as u64).unwrap();
    let i = m.gear_ratio;
    let omega = sim.state.pulley_omega[0];
    assert!(omega < 0.0, "turns clockwise");
    let n_in = sim.state.drive_memory[0].motor_speed;
    let n_out = -omega * i;
    // Solve the running point: for an output speed n_out the load at the motor shaft is
    // b·(n_out/i)/i; the coupling's input speed gives that torque; the motor must too.
    let mm = MotorModel::compile(&m);
    let c = CouplingModel::compile(&FluidCoupling::default(), m.rated_torque(), m.rated_speed);
    let input_for = |out: f64| {
        let load = b * out / (i * i);
        let (mut lo, mut hi) = (out, 2.0 * m.synchronous_speed);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if c.torque(mid, out) < load {
                lo = mid
            } else {
                hi = mid
            }
        }
        0.5 * (lo + hi)
    };
    let (mut lo, mut hi) = (0.0, m.synchronous_speed);
    for _ in 0..200 {
        let out = 0.5 * (lo + hi);
        let nin = input_for(out);
        if mm.curve.torque(nin) > b * out / (i * i) {
            lo = out
        } else {
            hi = out
        }
    }
    let out = 0.5 * (lo + hi);
    close("output speed", n_out, out, 1e-6 * out);
    close("input speed", n_in, input_for(out), 1e-6 * out);
    let slip = (n_in - n_out) / n_in;
    assert!(slip > 0.005 && slip < 0.05, "slip {slip}");
}

/// Bad motor and coupling data are refused, naming the field.
#[test]
fn bad_motors_are_refused() {
    let refused = |m: Motor, field: &str| {
        let drive = DriveSpec {
            motor: Some(m),
            ..Default::default()
        };
        match Simulation::new(&rigid_scene(drive, 1e-4)) {
            Err(BeltError::InvalidParameter { field: f, .. }) => assert_eq!(f, field),
            other => panic!("{field}: {other:?}"),
        }
    };
    let f = "pulleys[0].drive.motor";
    refused(
        Motor {
            synchronous_speed: 100.0,
            ..motor()
        },
        &format!("{f}.synchronous_speed"),
    );
    refused(
        Motor {
            breakdown_torque_ratio: 0.9,
            ..motor()
        },
        &format!("{f}.breakdown_torque_ratio"),
    );
    refused(
        Motor {
            speed: Some(vec![0.0, 1.0]),
            ..motor()
        },
        &format!("{f}.torque"),
    );
    refused(
        Motor {
            coupling: Some(FluidCoupling::default()),
            rotor_inertia: 0.0,
            ..motor()
        },
        &format!("{f}.rotor_inertia"),
    );
    refused(
        Motor {
            coupling: Some(FluidCoupling {
                stall_torque_ratio: 40.0,
                ..Default::default()
            }),
            ..motor()
        },
        &format!("{f}.coupling.stall_torque_ratio"),
    );
    // Coupling tables: each rule names the key.
    let table = |slip: Vec<f64>, torque: Vec<f64>| FluidCoupling {
        slip: Some(slip),
        torque: Some(torque),
        ..Default::default()
    };
    let cases = [
        (table(vec![0.1, 0.05], vec![1.0, 2.0]), "slip[1]"),
        (table(vec![0.1, 1.5], vec![1.0, 2.0]), "slip[1]"),
        (table(vec![0.1, 0.5], vec![2.0, 1.0]), "torque[1]"),
        (table(vec![0.0, 0.5], vec![1.0, 2.0]), "torque[0]"),
        (table(vec![0.1, 0.5], vec![-1.0, 2.0]), "torque[0]"),
        (table(vec![0.0, 0.5], vec![0.0, 0.0]), "torque[1]"),
        (table(vec![0.1, 0.5], vec![1.0, f64::NAN]), "torque[1]"),
        (table(vec![0.1, 0.5], vec![1.0]), "torque"),
        (
            FluidCoupling {
                slip: Some(vec![0.1, 0.5]),
                ..Default::default()
            },
            "torque",
        ),
        (
            FluidCoupling {
                rated_slip: 0.05,
                ..table(vec![0.1, 0.5], vec![1.0, 2.0])
            },
            "rated_slip",
        ),
        (
            FluidCoupling {
                rated_torque: Some(100.0),
                ..table(vec![0.1, 0.5], vec![1.0, 2.0])
            },
            "rated_torque",
        ),
    ];
    for (coupling, key) in cases {
        refused(
            Motor {
                coupling: Some(coupling),
                ..motor()
            },
            &format!("{f}.coupling.{key}"),
        );
    }
}

/// A fluid coupling given as a torque table, against an output held at rest by a brake:
/// the slip is 1, so the coupling passes (n/n_r)²·T_n(1), and a motor of constant torque
/// T_m runs its rotor up as J_r·ṅ = T_m − T_n(1)·(n/n_r)², whose solution is
/// n(t) = n∞·tanh(t/τ), n∞ = n_r·√(T_m/T_n(1)), τ = J_r·n∞/T_m. The recorded motor speed
/// follows it to first order in Δt (the rotor's speed update is explicit): the error
/// halves with the step, and is below 1e-3·n∞ at Δt = 1e-4 s (τ = 0.3 s).
#[test]
fn coupling_table_runs_a_held_rotor_up_as_tanh() {
    let (n_r, t_m, t_stall, j_r): (f64, f64, f64, f64) = (150.0, 400.0, 900.0, 1.2);
    let n_inf = n_r * (t_m / t_stall).sqrt();
    let tau = j_r * n_inf / t_m;
    let worst = |dt: f64| {
        let m = Motor {
            speed: Some(vec![0.0, 200.0]),
            torque: Some(vec![t_m, t_m]),
            rotor_inertia: j_r,
            coupling: Some(FluidCoupling {
                rated_speed: Some(n_r),
                slip: Some(vec![0.02, 0.2, 1.0]),
                torque: Some(vec![300.0, 600.0, t_stall]),
                ..Default::default()
            }),
            ..motor()
        };
        let drive = DriveSpec {
            motor: Some(m),
            ..Default::default()
        };
        let mut scene = rigid_scene(drive, dt);
        scene.pulleys[0].brake = Some(BrakeSpec {
            torque: Some(1e9),
            ..Default::default()
        });
        let mut sim = Simulation::new(&scene).unwrap();
        sim.begin_recording(Channels::default(), 10, usize::MAX);
        sim.advance((1.5 / dt).round() as u64).unwrap();
        sim.end_recording().unwrap();
        let r = &sim.recording;
        let mut worst = 0.0f64;
        for (k, &t) in r.time.iter().enumerate() {
            assert_eq!(r.pulley_speed[2 * k], 0.0, "the brake holds the output");
            assert!(r.motor_speed[2 * k + 1].is_nan(), "pulley 1 has no motor");
            let exact = n_inf * (t / tau).tanh();
            worst = worst.max((r.motor_speed[2 * k] - exact).abs());
        }
        worst
    };
    let (coarse, fine) = (worst(1e-4), worst(5e-5));
    assert!(coarse < 1e-3 * n_inf, "worst error {coarse:e} rad/s");
    let order = coarse / fine;
    assert!(
        (1.8..2.2).contains(&order),
        "error ratio {order} (first order: 2)"
    );
}

/// The coupling table: linear between its points, from (0, 0) to the first, held beyond
/// the last, scaled by the square of the pump (faster) shaft's speed, odd in the slip.
#[test]
fn coupling_table_interpolates_and_scales_with_the_pump_speed() {
    let c = FluidCoupling {
        rated_speed: Some(100.0),
        slip: Some(vec![0.05, 0.25, 0.75]),
        torque: Some(vec![500.0, 1500.0, 2000.0]),
        ..Default::default()
    };
    let m = CouplingModel::compile(&c, 1.0, 1.0);
    let eps = 1e-12 * 2000.0;
    // At the rated input speed the slip is (100 − out)/100.
    close("s = 0", m.torque(100.0, 100.0), 0.0, eps);
    close(
        "s = 0.02 (below the first point)",
        m.torque(100.0, 98.0),
        200.0,
        eps,
    );
    close("s = 0.05", m.torque(100.0, 95.0), 500.0, eps);
    close("s = 0.15", m.torque(100.0, 85.0), 1000.0, eps);
    close("s = 0.5", m.torque(100.0, 50.0), 1750.0, eps);
    close("s = 1 (held)", m.torque(100.0, 0.0), 2000.0, eps);
    // Pump at 50 rad/s, slip 0.15: a quarter of the torque at 100 rad/s.
    close("pump²", m.torque(50.0, 42.5), 250.0, eps);
    // Overrunning: the output pumps, the torque reverses.
    close("odd", m.torque(85.0, 100.0), -1000.0, eps);
    // Steepest segment 500/0.05 = 10⁴ N·m per unit slip: top·10⁴/n_r² at top = 120 rad/s.
    close("slope", m.max_slope(120.0), 120.0 * 1e4 / 1e4, 1e-12);
}

/// At a running design start a fluid-coupled motor (switched on from t = 0) starts at its
/// running point on the coupling: T_motor(n) = T_coupling(n, σ·i·ω₀) (to 1e-9 of the
/// rated torque), with n above the output (the coupling slips forward). The rotor then
/// stays there: it moves by less than 1e-6 of n over 0.2 s, while a rotor left at rest
/// is dragged through the coupling (−σ·i·T_c on the pulley).
#[test]
fn coupled_motor_at_a_running_start_starts_at_its_running_point() {
    let mut m = motor();
    m.coupling = Some(FluidCoupling::default());
    let w0 = 0.9 * m.rated_speed / m.gear_ratio;
    let drive = DriveSpec {
        motor: Some(m.clone()),
        ..Default::default()
    };
    let mut scene = rigid_scene(drive, 1e-4);
    scene.pulleys[0].inertia = Some(1e12); // the pulley keeps its speed: only the rotor moves
    scene.initial = Some(InitialState {
        tension: vec![1000.0],
        speed: w0 * 0.5,
        ..Default::default()
    });
    scene.recording.stabilise = false;
    let mut sim = Simulation::new(&scene).unwrap();
    close("pulley speed", sim.state.pulley_omega[0], w0, 1e-12 * w0);
    let mm = MotorModel::compile(&m);
    let c = mm.coupling.clone().unwrap();
    let shaft = mm.factor * w0;
    let n = sim.state.drive_memory[0].motor_speed;
    assert!(
        n > shaft && n < m.synchronous_speed,
        "n = {n}, output {shaft}"
    );
    let tr = m.rated_torque();
    close(
        "balance",
        mm.curve.torque(n) - c.torque(n, shaft),
        0.0,
        1e-9 * tr,
    );
    sim.step(2000).unwrap();
    let moved = (sim.state.drive_memory[0].motor_speed - n).abs();
    assert!(moved < 1e-6 * n, "the rotor moved by {moved:e} rad/s");
}
