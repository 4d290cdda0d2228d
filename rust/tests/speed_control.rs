//! The PI speed controller (docs/drives.md, `drives::controller`) against the closed-form
//! response of a rigid load, its torque limit and anti-windup, its stage and stable-step
//! bound, its checkpoint, and torque followers (`drives::sharing`).
use crate::common::{close, free_pulley};
use beltrs::checkpoint;
use beltrs::drives::controller::{gains, SpeedController};
use beltrs::drives::sharing::TorqueFollow;
use beltrs::record::Channels;
use beltrs::scene::{DriveSpec, InitialState, Scene, Table};
use beltrs::{BeltError, Simulation, Stage, StartCurve, StartShape};

const INERTIA: f64 = 50.0;
const RADIUS: f64 = 1.0;
const OMEGA_C: f64 = 10.0;

/// A free rigid inertia of 50 kg·m² (`common::free_pulley`, 120 elements), driven by a PI
/// controller tuned on exactly that inertia, following a linear ramp to 2 rad/s over 1 s
/// from t = 0.
fn rigid_scene(max_torque: f64, dt: f64) -> Scene {
    let drive = DriveSpec {
        start_curve: Some(StartCurve {
            shape: StartShape::Linear,
            speed: 2.0,
            ramp: 1.0,
            ..Default::default()
        }),
        max_torque,
        controller: Some(SpeedController {
            bandwidth: OMEGA_C,
            inertia: Some(INERTIA),
            ..Default::default()
        }),
        ..Default::default()
    };
    free_pulley(drive, RADIUS, INERTIA, 120, dt)
}

/// The speed error ω_ref − ω (rad/s) of a critically damped PI loop on a rigid inertia
/// following a ramp of slope α that starts at 0 and ends at T: α·t·e^(−ω_c·t), minus the
/// same response started at T (the ramp's end is a step of −α in the slope).
fn exact_error(t: f64, alpha: f64, ramp: f64) -> f64 {
    let h = |t: f64| {
        if t > 0.0 {
            alpha * t * (-OMEGA_C * t).exp()
        } else {
            0.0
        }
    };
    h(t) - h(t - ramp)
}

/// Largest |recorded error − exact error| over 2 s, rad/s.
fn max_deviation(dt: f64) -> (f64, f64) {
    let mut sim = Simulation::new(&rigid_scene(f64::INFINITY, dt)).unwrap();
    let steps = (2.0 / dt).round() as u64;
    sim.begin_recording(Channels::default(), 10, usize::MAX);
    sim.advance(steps).unwrap();
    sim.end_recording().unwrap();
    let r = &sim.recording;
    let (mut worst, mut peak) = (0.0f64, 0.0f64);
    for (k, &t) in r.time.iter().enumerate() {
        let reference = 2.0 * t.min(1.0);
        let error = reference - r.pulley_speed[2 * k];
        worst = worst.max((error - exact_error(t, 2.0, 1.0)).abs());
        peak = peak.max(error.abs());
    }
    (worst, peak)
}

/// The default gains place both poles at −ω_c: K_p = 2ω_c·J, K_i = ω_c²·J.
#[test]
fn default_gains_are_critically_damped_on_the_inertia() {
    let (kp, ki) = gains(OMEGA_C, 1.0, INERTIA);
    assert_eq!((kp, ki), (1000.0, 5000.0));
    let sim = Simulation::new(&rigid_scene(f64::INFINITY, 1e-4)).unwrap();
    let c = sim.model.pulleys[0].control.unwrap();
    assert_eq!((c.kp, c.ki, c.inertia), (1000.0, 5000.0, INERTIA));
    assert!(sim.model.has_stage(Stage::SpeedControl));
    assert!(!sim.model.has_stage(Stage::SpeedDrives));
}

/// On a rigid inertia the loop follows the ramp with the closed-form error
/// α·t·e^(−ω_c·t) (peak α/(e·ω_c) = 0.0736 rad/s at t = 1/ω_c), and the deviation from it
/// is first order in Δt: the controller sees the half-step speed, Δt/2 late, an error of
/// about |ė|·Δt/2 ≤ α·Δt/2 (1e-4 rad/s at Δt = 1e-4 s); halving Δt halves it.
#[test]
fn pi_follows_a_ramp_with_the_closed_form_error() {
    let (coarse, peak) = max_deviation(1e-4);
    close(
        "peak error",
        peak,
        2.0 / (std::f64::consts::E * OMEGA_C),
        2e-4,
    );
    assert!(coarse <= 2.0 * 1e-4 / 2.0, "deviation {coarse:e} rad/s");
    let (fine, _) = max_deviation(0.5e-4);
    let order = (coarse / fine).log2();
    assert!(
        (0.8..1.2).contains(&order),
        "order of convergence {order} ({coarse:e} → {fine:e})"
    );
}

/// With a 60 N·m limit against the 100 N·m the ramp needs (I·α), the torque never exceeds
/// the limit, the pulley accelerates at exactly limit/I while limited, so the error grows
/// at α − limit/I = 0.8 rad/s²; after the ramp it catches up, and the conditional
/// integration keeps the overshoot small (a wound-up integral of ∫e ≈ 0.4 rad would give
/// K_i·0.4/… ≈ 2 N·m·s of excess impulse, an overshoot of several % of ω₀).
#[test]
fn pi_saturates_at_its_torque_limit_and_does_not_wind_up() {
    let dt = 1e-4;
    let mut sim = Simulation::new(&rigid_scene(60.0, dt)).unwrap();
    sim.begin_recording(Channels::default(), 1, usize::MAX);
    sim.advance((3.0 / dt) as u64).unwrap();
    let r = &sim.recording;
    let torque: Vec<f64> = (0..r.time.len()).map(|k| r.drive_torque[2 * k]).collect();
    assert!(torque.iter().all(|t| t.abs() <= 60.0), "over the limit");
    let limited = torque.iter().filter(|&&t| t == 60.0).count();
    assert!(
        limited as f64 * dt > 0.5,
        "limited for {} s only",
        limited as f64 * dt
    );
    // Error slope in the middle of the ramp (limited there).
    let at = |t: f64| ((t / dt).round()) as usize;
    let (k0, k1) = (at(0.5), at(0.9));
    assert_eq!(torque[k0], 60.0);
    assert_eq!(torque[k1], 60.0);
    let e = |k: usize| 2.0 * r.time[k].min(1.0) - r.pulley_speed[2 * k];
    close(
        "error growth while limited",
        (e(k1) - e(k0)) / (r.time[k1] - r.time[k0]),
        2.0 - 60.0 / INERTIA,
        1e-9,
    );
    let overshoot = r
        .pulley_speed
        .iter()
        .step_by(2)
        .fold(0.0f64, |m, &w| m.max(w - 2.0));
    assert!(overshoot < 0.01 * 2.0, "overshoot {overshoot} rad/s");
    let last = r.pulley_speed[2 * (r.time.len() - 1)];
    close("settled", last, 2.0, 1e-4);
}

/// The proportional and integral gains act on the pulley as a damper and a spring: the
/// stable step names the controller when they set it, and a fixed step above is refused.
#[test]
fn stiff_gains_set_the_stable_step() {
    let mut scene = rigid_scene(f64::INFINITY, 1e-4);
    scene.solver.time_step = None;
    let c = scene.pulleys[0].drive.as_mut().unwrap();
    c.controller.as_mut().unwrap().proportional_gain = Some(1e8);
    let sim = Simulation::new(&scene).unwrap();
    assert!(
        sim.model.dt_cause.contains("speed controller"),
        "{}",
        sim.model.dt_cause
    );
    close("limit", sim.model.dt_limit, INERTIA / 1e8, 1e-12);
    scene.solver.time_step = Some(1e-4);
    match Simulation::new(&scene) {
        Err(BeltError::TimeStepTooLarge { cause, .. }) => {
            assert!(cause.contains("speed controller"))
        }
        other => panic!("{other:?}"),
    }
}

/// Checkpoints carry the controller's integral: a resumed run continues bit for bit.
#[test]
fn checkpoint_resumes_a_pi_drive_bit_for_bit() {
    let mut scene = rigid_scene(60.0, 1e-4);
    scene.pulleys[0]
        .drive
        .as_mut()
        .unwrap()
        .controller
        .as_mut()
        .unwrap()
        .torque_time_constant = 0.01;
    let mut a = Simulation::new(&scene).unwrap();
    a.step(4000).unwrap();
    assert!(a.state.drive_memory[0].integral != 0.0);
    let mut b = checkpoint::decode(&checkpoint::encode(&a)).unwrap();
    for sim in [&mut a, &mut b] {
        sim.begin_recording(Channels::default(), 7, usize::MAX);
        sim.advance(8000).unwrap();
        sim.end_recording().unwrap();
    }
    assert_eq!(a.recording, b.recording);
    assert_eq!(a.state, b.state);
}

/// The torque lag: with τ the applied torque follows a held command as 1 − e^(−t/τ).
/// While the ramp is limited the command is the limit, and the lag is integrated exactly
/// per step.
#[test]
fn torque_lag_is_first_order() {
    let tau = 0.02;
    let mut scene = rigid_scene(60.0, 1e-4);
    scene.pulleys[0]
        .drive
        .as_mut()
        .unwrap()
        .controller
        .as_mut()
        .unwrap()
        .torque_time_constant = tau;
    let mut sim = Simulation::new(&scene).unwrap();
    sim.begin_recording(Channels::default(), 1, usize::MAX);
    sim.advance(1000).unwrap();
    let r = &sim.recording;
    // Once the command sits at the limit (from about 0.03 s: K_p·e alone passes 60 N·m
    // at e = 0.06 rad/s) the gap to it shrinks by e^(−Δt/τ) every step, exactly.
    let decay = (-1e-4 / tau).exp();
    for k in 400..999 {
        let (now, next) = (r.drive_torque[2 * k], r.drive_torque[2 * k + 2]);
        assert!(now < 60.0 && now > 0.0);
        close("lag", (next - 60.0) / (now - 60.0), decay, 1e-9);
    }
    // τ at or above K_p/K_i (= 0.2 s here) is refused, naming the field.
    scene.pulleys[0]
        .drive
        .as_mut()
        .unwrap()
        .controller
        .as_mut()
        .unwrap()
        .torque_time_constant = 0.25;
    match Simulation::new(&scene) {
        Err(BeltError::InvalidParameter { field, .. }) => {
            assert_eq!(field, "pulleys[0].drive.controller.torque_time_constant")
        }
        other => panic!("{other:?}"),
    }
}

/// A follower applies ratio × its master's torque (here a torque table on a rigid
/// pulley), with the sign of its wrap; ideal-follower masters, unknown masters and
/// followers with references are refused, naming the field.
#[test]
fn followers_apply_their_share_of_the_master_torque() {
    let mut scene = rigid_scene(f64::INFINITY, 1e-4);
    scene.pulleys[0].drive = Some(DriveSpec {
        torque: Table {
            x: vec![0.0, 1.0],
            y: vec![0.0, 100.0],
        },
        ..Default::default()
    });
    scene.pulleys[0].name = "head".into();
    scene.pulleys[1].name = "tail".into();
    scene.pulleys[1].drive = Some(DriveSpec {
        follow: Some(TorqueFollow {
            master: "head".into(),
            ratio: 0.5,
        }),
        max_torque: 40.0,
        ..Default::default()
    });
    let mut sim = Simulation::new(&scene).unwrap();
    assert!(sim.model.has_stage(Stage::SpeedControl));
    sim.begin_recording(Channels::default(), 100, usize::MAX);
    sim.advance(15000).unwrap();
    let r = &sim.recording;
    for k in 0..r.time.len() {
        let master = 100.0 * r.time[k].min(1.0);
        close("master", r.drive_torque[2 * k], master, 1e-9);
        close(
            "follower",
            r.drive_torque[2 * k + 1],
            (0.5 * master).min(40.0),
            1e-9,
        );
    }
    let refused = |scene: &Scene, field: &str| match Simulation::new(scene) {
        Err(BeltError::InvalidParameter { field: f, .. }) => assert_eq!(f, field),
        other => panic!("{field}: {other:?}"),
    };
    let mut s = scene.clone();
    s.pulleys[1]
        .drive
        .as_mut()
        .unwrap()
        .follow
        .as_mut()
        .unwrap()
        .master = "haed".into();
    refused(&s, "pulleys[1].drive.follow.master");
    let mut s = scene.clone();
    s.pulleys[1]
        .drive
        .as_mut()
        .unwrap()
        .follow
        .as_mut()
        .unwrap()
        .ratio = -1.0;
    refused(&s, "pulleys[1].drive.follow.ratio");
    let mut s = scene.clone();
    s.pulleys[0].drive = Some(DriveSpec {
        start_curve: Some(StartCurve {
            speed: 1.0,
            ramp: 1.0,
            ..Default::default()
        }),
        ..Default::default()
    });
    refused(&s, "pulleys[1].drive.follow.master");
    let mut s = scene.clone();
    s.pulleys[1].drive.as_mut().unwrap().start_curve = Some(StartCurve {
        speed: 1.0,
        ramp: 1.0,
        ..Default::default()
    });
    refused(&s, "pulleys[1].drive.start_curve");
    // A controller without a reference.
    let mut s = rigid_scene(f64::INFINITY, 1e-4);
    s.pulleys[0].drive.as_mut().unwrap().start_curve = None;
    refused(&s, "pulleys[0].drive.controller");
    // Droop without its torque, and the torque without droop.
    let mut s = rigid_scene(f64::INFINITY, 1e-4);
    s.pulleys[0]
        .drive
        .as_mut()
        .unwrap()
        .controller
        .as_mut()
        .unwrap()
        .droop = 0.02;
    refused(&s, "pulleys[0].drive.controller.rated_torque");
}

/// No controller, no stage: a scene without one compiles no `speed_control` stage.
#[test]
fn unused_controller_costs_nothing() {
    let mut scene = rigid_scene(f64::INFINITY, 1e-4);
    scene.pulleys[0].drive.as_mut().unwrap().controller = None;
    let sim = Simulation::new(&scene).unwrap();
    assert!(!sim.model.has_stage(Stage::SpeedControl));
    assert!(sim.model.has_stage(Stage::SpeedDrives));
    assert!(!sim.model.has_drive_memory);
}

/// A checkpoint written before the drives' memory was added (it ends after the load
/// zones) still reads, with zero memory.
#[test]
fn checkpoint_without_drive_memory_reads_as_zero_memory() {
    let mut scene = rigid_scene(f64::INFINITY, 1e-4);
    scene.pulleys[0].drive.as_mut().unwrap().controller = None;
    let mut a = Simulation::new(&scene).unwrap();
    a.step(100).unwrap();
    let bytes = checkpoint::encode(&a);
    // Make it a version 4 file of before the drives' memory: version 4 in the header, no
    // formulation and integrator names (added in version 5) after the engine version, and
    // the state ending after the load zones: drop the drives' memory (a count and three
    // numbers per pulley), the brake ramps (a count and one number per pulley) and
    // version 5's tail (two empty body arrays for the node belt, the adaptive step and two
    // step counts, the empty friction memory, the empty viscoelastic arm forces and
    // lengths, and stick-force friction's sliding points: a count and an empty list per
    // pulley). Then fix the payload length and the checksum.
    let p = scene.pulleys.len();
    let tail = (8 + 24 * p) + (8 + 8 * p) + 8 + 8 + 8 + 8 + 8 + 8 + 8 + 8 + (8 + 8 * p);
    let string_end =
        |at: usize| at + 8 + u64::from_le_bytes(bytes[at..at + 8].try_into().unwrap()) as usize;
    let engine_end = string_end(24);
    let tags_end = string_end(string_end(engine_end));
    let end = bytes.len() - 4 - tail;
    let mut old = bytes[..engine_end].to_vec();
    old.extend_from_slice(&bytes[tags_end..end]);
    old[8..12].copy_from_slice(&4u32.to_le_bytes());
    let payload = (old.len() - 24) as u64;
    old[16..24].copy_from_slice(&payload.to_le_bytes());
    let crc = checkpoint::crc32(&old);
    old.extend_from_slice(&crc.to_le_bytes());
    let b = checkpoint::decode(&old).unwrap();
    assert_eq!(b.state, a.state);
    assert!(b
        .state
        .drive_memory
        .iter()
        .all(|m| *m == Default::default()));
}

/// A PI drive at a running design start (`[initial]`, the curve already ended) holds its
/// speed from t = 0: its integral starts at the torque that holds the pulley, here the
/// drive's viscous load b·ω₀ (1 kN·m), so the speed stays at ω₀ to rounding; also with a
/// torque lag (the lagged torque starts there too). With droop the first step's net
/// torque is zero (the speed then drifts to its drooped value, as droop asks). An empty
/// integral, as before priming, lets the pulley sag by ~0.7 rad/s (b·ω₀/(J·ω_c·e)).
#[test]
fn pi_drive_at_a_running_start_holds_its_speed_from_the_start() {
    let (b, w0) = (500.0, 2.0);
    let run = |tau: f64, droop: f64, primed: bool| {
        let mut scene = rigid_scene(f64::INFINITY, 1e-4);
        let d = scene.pulleys[0].drive.as_mut().unwrap();
        d.viscous = b;
        d.start_curve.as_mut().unwrap().start = -2.0; // at 2 rad/s since t = −1 s
        let c = d.controller.as_mut().unwrap();
        c.torque_time_constant = tau;
        if droop > 0.0 {
            c.droop = droop;
            c.rated_torque = Some(2.0 * b * w0);
        }
        scene.initial = Some(InitialState {
            tension: vec![1000.0],
            speed: w0 * RADIUS,
            ..Default::default()
        });
        scene.recording.stabilise = false;
        let mut sim = Simulation::new(&scene).unwrap();
        assert_eq!(
            sim.state.pulley_omega[0], w0,
            "turns counter-clockwise at ω₀"
        );
        if !primed {
            sim.state.drive_memory[0] = Default::default();
        }
        sim.begin_recording(Channels::default(), 10, usize::MAX);
        sim.advance(10_000).unwrap();
        sim.end_recording().unwrap();
        let r = &sim.recording;
        let sag = (0..r.time.len())
            .map(|k| (r.pulley_speed[2 * k] - w0).abs())
            .fold(0.0, f64::max);
        (sag, r.drive_torque[0])
    };
    for tau in [0.0, 0.01] {
        let (sag, net) = run(tau, 0.0, true);
        assert!(
            sag <= 1e-12 * w0,
            "τ = {tau}: speed left ω₀ by {sag:e} rad/s"
        );
        assert!(
            net.abs() <= 1e-9 * b * w0,
            "τ = {tau}: net drive torque {net:e}"
        );
    }
    let (_, net) = run(0.0, 0.05, true);
    assert!(
        net.abs() <= 1e-9 * b * w0,
        "droop: net drive torque {net:e}"
    );
    let (sag, _) = run(0.0, 0.0, false);
    assert!(sag > 0.5, "an empty integral sags by {sag} rad/s only");
}
