//! Checkpoints: an exact resume, clear errors on damaged files, atomic writes.
use crate::common::case_h;
use beltrs::checkpoint::{self, write_atomic};
use beltrs::record::Channels;
use beltrs::scene::{BrakeSpec, DriveSpec, FrictionModel, IdlerSpec, Scene, Table};
use beltrs::{BeltError, Simulation};
use std::path::PathBuf;

/// Case H with every kind of state in play: friction on pulleys and an idler, a drive, a
/// brake, damping, a takeup.
fn busy_scene() -> Scene {
    let mut s = case_h(89);
    s.belt.damping_ratio = 0.02;
    let friction = FrictionModel::StickForce {
        static_coefficient: 0.5,
        kinetic_coefficient: 0.4,
    };
    for p in &mut s.pulleys {
        p.friction = friction;
    }
    s.pulleys[0].drive = Some(DriveSpec {
        torque: Table {
            x: vec![0.0, 0.2, 10.0],
            y: vec![0.0, 2e5, 2e5],
        },
        viscous: 10.0,
        ..Default::default()
    });
    s.pulleys[1].brake = Some(BrakeSpec {
        capacity: Table::constant(1e3),
        ..Default::default()
    });
    // An idler touching the right-hand strand (x = 5) from outside.
    s.idlers.push(IdlerSpec {
        center: [5.0 + 0.0635, 50.0],
        friction,
        ..Default::default()
    });
    s
}

fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("beltrs-ck-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn resumed_run_continues_bit_for_bit() {
    let dir = temp_dir("resume");
    let path = dir.join("run.ck");
    let mut a = Simulation::new(&busy_scene()).unwrap();
    a.step(400).unwrap();
    // A parameter changed during the run must travel with the checkpoint.
    let mut changed = a.model.scene.clone();
    changed.pulleys[1].takeup.as_mut().unwrap().counterweight = 33_000.0;
    a.set_scene(&changed).unwrap();
    a.step(100).unwrap();
    checkpoint::save(&a, &path).unwrap();
    // Stick-force friction's memory is in play: points slide on a pulley at the save.
    assert!(a.state.sliding.iter().any(|points| !points.is_empty()));

    let mut b = checkpoint::load(&path).unwrap();
    assert_eq!(b.state, a.state);
    assert_eq!(b.model.scene, a.model.scene);
    assert_eq!(b.model.dt.to_bits(), a.model.dt.to_bits());

    for sim in [&mut a, &mut b] {
        sim.begin_recording(
            Channels {
                energy: true,
                ..Channels::default()
            },
            3,
            usize::MAX,
        );
        sim.advance(700).unwrap();
        sim.end_recording().unwrap();
    }
    // The run must have exercised the state that a checkpoint has to carry.
    let r = &a.recording;
    assert!(
        r.pulley_speed.iter().any(|w| w.abs() > 1e-3),
        "pulleys never turned"
    );
    assert!(
        r.idler_speed.iter().any(|w| w.abs() > 1e-6),
        "idler never turned"
    );
    assert!(
        r.slipping_nodes.iter().any(|&n| n > 0.0)
            || r.friction_torque.iter().any(|t| t.abs() > 0.0)
    );
    assert!(a.state.drive_work != 0.0);
    // Bit for bit: every recorded value and the final state are identical.
    assert_eq!(a.recording, b.recording);
    assert_eq!(a.state, b.state);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a.recording.tension), bits(&b.recording.tension));
    assert_eq!(bits(&a.recording.energy), bits(&b.recording.energy));
    std::fs::remove_dir_all(dir).unwrap();
}

fn problem(err: BeltError) -> (String, String) {
    match err {
        BeltError::Checkpoint { path, problem } => (path, problem),
        other => panic!("expected a checkpoint error, got {other}"),
    }
}

#[test]
fn damaged_files_give_clear_errors() {
    let dir = temp_dir("damaged");
    let path = dir.join("good.ck");
    let sim = Simulation::new(&case_h(89)).unwrap();
    checkpoint::save(&sim, &path).unwrap();
    let good = std::fs::read(&path).unwrap();
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("truncated", good[..good.len() / 2].to_vec(), "truncated"),
        ("tiny", good[..10].to_vec(), "truncated"),
        ("empty", Vec::new(), "truncated"),
        (
            "flipped",
            {
                let mut b = good.clone();
                let k = b.len() / 2;
                b[k] ^= 0x10;
                b
            },
            "checksum mismatch",
        ),
        (
            "magic",
            {
                let mut b = good.clone();
                b[0] = b'X';
                b
            },
            "not a beltrs checkpoint",
        ),
        (
            "version",
            {
                let mut b = good.clone();
                b[8] = 99;
                b
            },
            "format version 99",
        ),
        (
            // Versions 1 to 3 (the hand-written scene encodings) are no longer read.
            "old version",
            {
                let mut b = good.clone();
                b[8] = 3;
                b
            },
            "format version 3; this build of beltrs reads versions 4 to",
        ),
        (
            "version 1",
            {
                let mut b = good.clone();
                b[8] = 1;
                b
            },
            "format version 1;",
        ),
        (
            "appended",
            {
                let mut b = good.clone();
                b.extend_from_slice(b"junk");
                b
            },
            "trailing data",
        ),
    ];
    for (name, bytes, expected) in cases {
        let p = dir.join(format!("{name}.ck"));
        std::fs::write(&p, bytes).unwrap();
        let (file, msg) = problem(checkpoint::load(&p).expect_err(name));
        assert_eq!(file, p.display().to_string());
        assert!(msg.contains(expected), "{name}: {msg}");
        if name.contains("version") && name != "version" {
            assert!(msg.contains("re-run from the scene file"), "{name}: {msg}");
        }
    }
    let (_, msg) = problem(checkpoint::load(&dir.join("missing.ck")).unwrap_err());
    assert!(msg.contains("cannot read"), "{msg}");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn checkpoint_for_another_scene_is_refused() {
    let dir = temp_dir("scene");
    let path = dir.join("h.ck");
    let scene = case_h(89);
    checkpoint::save(&Simulation::new(&scene).unwrap(), &path).unwrap();
    assert!(checkpoint::load_for(&path, &scene).is_ok());
    let mut other = scene.clone();
    other.pulleys[1].mass = 700.0;
    let (_, msg) = problem(checkpoint::load_for(&path, &other).unwrap_err());
    assert!(
        msg.contains("different scene") && msg.contains("pulleys[1]"),
        "{msg}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_crash_before_the_rename_leaves_the_old_checkpoint() {
    let dir = temp_dir("atomic");
    let path = dir.join("run.ck");
    let mut sim = Simulation::new(&case_h(89)).unwrap();
    checkpoint::save(&sim, &path).unwrap();
    let old = std::fs::read(&path).unwrap();
    sim.step(50).unwrap();
    let new = checkpoint::encode(&sim);
    assert_ne!(new, old);
    let mut seen_tmp = None;
    let err = write_atomic(&path, &new, |tmp| {
        // The complete new file exists beside the target, which is still the old one.
        assert_eq!(std::fs::read(tmp).unwrap(), new);
        assert_eq!(std::fs::read(&path).unwrap(), old);
        seen_tmp = Some(tmp.to_path_buf());
        Err(std::io::Error::other("simulated crash"))
    })
    .err()
    .unwrap();
    let (_, msg) = problem(err);
    assert!(msg.contains("simulated crash"), "{msg}");
    assert_eq!(std::fs::read(&path).unwrap(), old);
    assert!(!seen_tmp.unwrap().exists(), "temporary file left behind");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
    // The old checkpoint still loads.
    assert_eq!(checkpoint::load(&path).unwrap().state.step, 0);
    std::fs::remove_dir_all(dir).unwrap();
}

/// Stepping fuses each integration with the next step's axial pass unless profiling (which
/// times the stages one by one): the two must give the same run to the last bit, whatever
/// the step counts of the calls (each call starts with a complete evaluation), including
/// the recorded tensions and energies. A tension-only belt exercises the clipping too.
#[test]
fn fused_stepping_matches_stage_by_stage_bit_for_bit() {
    let mut scene = busy_scene();
    scene.belt.tension_only = true;
    let mut staged = Simulation::new(&scene).unwrap();
    staged.set_profiling(true);
    let mut fused = Simulation::new(&scene).unwrap();
    staged.step(600).unwrap();
    for steps in [1, 2, 3, 594] {
        fused.step(steps).unwrap();
    }
    assert_eq!(staged.state, fused.state);
    for sim in [&mut staged, &mut fused] {
        sim.begin_recording(
            Channels {
                energy: true,
                ..Channels::default()
            },
            7,
            usize::MAX,
        );
        sim.advance(350).unwrap();
        sim.end_recording().unwrap();
    }
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(
        bits(&staged.recording.tension),
        bits(&fused.recording.tension)
    );
    assert_eq!(
        bits(&staged.recording.energy),
        bits(&fused.recording.energy)
    );
    assert_eq!(staged.recording, fused.recording);
    assert_eq!(staged.state, fused.state);
    // The recorded tensions are those of the recorded state, and the drive did work.
    let n = staged.model.nodes;
    let last = &fused.recording.tension[fused.recording.tension.len() - n..];
    assert_eq!(bits(last), bits(fused.tensions()));
    assert!(fused.state.drive_work != 0.0);
}
