//! Load sharing between drives on one belt (head, tail, booster; `docs/drives.md`).
//!
//! - **Master–slave torque sharing** (`[pulleys.drive.follow]`): a follower drive has no
//!   speed reference of its own; each step it applies `ratio` times its master's motor
//!   torque (within its own `max_torque`), in the sense that drives the belt the same way
//!   (a pulley the belt wraps the other way round turns the other way). The master is a
//!   PI speed-controlled drive ([`super::controller`]), a DOL motor ([`super::motor`]) or
//!   a torque-table drive; its torque
//!   is known before the friction solve, so master and followers act in the same step.
//!   An ideal speed follower's torque comes out of its pulley's friction solve, after the
//!   followers' would be needed, and cannot be a master.
//! - **Speed control with droop** is a property of each PI controller
//!   ([`super::controller::SpeedController::droop`]).

use crate::error::{BeltError, BeltResult};
use crate::model::PulleyModel;
use crate::pipeline::Scratch;
use crate::scene::Scene;
use crate::state::State;
use serde::{Deserialize, Serialize};

/// A torque follower (`[pulleys.drive.follow]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TorqueFollow {
    /// Name of the master drive's pulley. Required.
    pub master: String,
    /// Follower torque / master torque at the pulleys, dimensionless, > 0 (for equal
    /// shares of belt force on drums of radii r_f and r_m give r_f/r_m). Default 1.
    #[serde(default = "one")]
    pub ratio: f64,
}

fn one() -> f64 {
    1.0
}

impl Default for TorqueFollow {
    fn default() -> Self {
        TorqueFollow {
            master: String::new(),
            ratio: 1.0,
        }
    }
}

/// A compiled follower: the master's index and the signed factor on its torque.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Follower {
    /// Index of the master pulley.
    pub master: usize,
    /// ratio × (wrap sign of the follower / wrap sign of the master).
    pub factor: f64,
}

/// The rules of the drives that need the whole scene: controllers need a starting curve,
/// followers a master that exists, has a drive with a torque known before the friction
/// solve and is not a follower itself; a follower has no reference of its own.
pub fn validate(scene: &Scene) -> BeltResult<()> {
    for (i, p) in scene.pulleys.iter().enumerate() {
        let Some(d) = &p.drive else { continue };
        let f = format!("pulleys[{i}].drive");
        if let Some(c) = &d.controller {
            c.validate(&format!("{f}.controller"))?;
            if d.start_curve.is_none() {
                return Err(BeltError::invalid(
                    format!("{f}.controller"),
                    "a PI controller",
                    format!("needs a speed reference: give {f}.start_curve"),
                ));
            }
        }
        if !(d.flywheel.is_finite() && d.flywheel >= 0.0) {
            return Err(BeltError::invalid(
                format!("{f}.flywheel"),
                d.flywheel,
                "must be finite and ≥ 0 (kg·m²)",
            ));
        }
        if let Some(m) = &d.motor {
            m.validate(&format!("{f}.motor"))?;
            let other = if d.start_curve.is_some() {
                Some(("start_curve", "a DOL motor runs on its torque curve without a speed reference; a VFD is start_curve with max_torque (and a controller)"))
            } else if d.follow.is_some() {
                Some((
                    "follow",
                    "a DOL motor's torque is its curve's; a follower takes its master's",
                ))
            } else if d.torque.y.iter().any(|&y| y != 0.0) {
                Some((
                    "torque",
                    "the motor's curve is the drive torque: leave the time/torque table out",
                ))
            } else if !d.speed_factor.x.is_empty() {
                Some((
                    "speed_factor",
                    "the motor's curve already depends on speed: leave it out",
                ))
            } else {
                None
            };
            if let Some((key, why)) = other {
                return Err(BeltError::invalid(
                    format!("{f}.{key}"),
                    "given",
                    format!("cannot be combined with {f}.motor: {why}"),
                ));
            }
        }
        let Some(follow) = &d.follow else { continue };
        check_ratio(&format!("{f}.follow.ratio"), follow.ratio)?;
        let names: Vec<&str> = scene.pulleys.iter().map(|q| q.name.as_str()).collect();
        let Some(k) = scene.pulleys.iter().position(|q| q.name == follow.master) else {
            let hint = match crate::suggest::close_match(&follow.master, names.iter().copied()) {
                Some(s) => format!(", did you mean \"{s}\"?"),
                None => String::new(),
            };
            return Err(BeltError::invalid(
                format!("{f}.follow.master"),
                format!("{:?}", follow.master),
                format!("no pulley has this name{hint} (names: {names:?})"),
            ));
        };
        let refuse = |rule: String| {
            Err(BeltError::invalid(
                format!("{f}.follow.master"),
                format!("{:?}", follow.master),
                rule,
            ))
        };
        if k == i {
            return refuse("a drive cannot follow itself".into());
        }
        let Some(md) = &scene.pulleys[k].drive else {
            return refuse(format!("pulleys[{k}] has no drive to follow"));
        };
        if md.follow.is_some() {
            return refuse(format!(
                "pulleys[{k}] follows a master itself: name the master it follows"
            ));
        }
        if md.start_curve.is_some() && md.controller.is_none() {
            return refuse(format!("pulleys[{k}] is an ideal speed follower, whose torque is solved with its pulley's friction after the followers' torques are needed: give it a PI controller (pulleys[{k}].drive.controller)"));
        }
        if d.start_curve.is_some() {
            return Err(BeltError::invalid(
                format!("{f}.start_curve"),
                "a starting curve",
                format!("a torque follower ({f}.follow) takes its torque from its master and has no speed reference: leave start_curve out"),
            ));
        }
        if let Some((j, &y)) = d.torque.y.iter().enumerate().find(|(_, y)| **y != 0.0) {
            return Err(BeltError::invalid(
                format!("{f}.torque[{j}]"),
                y,
                format!("must be 0 with {f}.follow: a follower's torque is its master's times the ratio"),
            ));
        }
        if !d.speed_factor.x.is_empty() {
            return Err(BeltError::invalid(
                format!("{f}.speed_factor"),
                format!("{:?}", d.speed_factor.y),
                format!("has no effect with {f}.follow: leave it out"),
            ));
        }
    }
    Ok(())
}

fn check_ratio(field: &str, ratio: f64) -> BeltResult<()> {
    if ratio.is_finite() && ratio > 0.0 {
        Ok(())
    } else {
        Err(BeltError::invalid(
            field,
            ratio,
            "must be finite and > 0 (follower torque / master torque)",
        ))
    }
}

/// The compiled follower of pulley `i` of `scene` (validated), if it has one.
pub fn compile(scene: &Scene, i: usize) -> Option<Follower> {
    let follow = scene.pulleys[i].drive.as_ref()?.follow.as_ref()?;
    let k = scene.pulleys.iter().position(|q| q.name == follow.master)?;
    let sense = scene.pulleys[i].wrap.sign() * scene.pulleys[k].wrap.sign();
    Some(Follower {
        master: k,
        factor: follow.ratio * sense,
    })
}

/// The motor torque of the master pulley `k` this evaluation, N·m: a PI controller's
/// applied torque (computed earlier in the same stage), or a torque table's f(t)·g(ω)
/// (without the viscous load).
fn master_torque(p: &PulleyModel, k: usize, s: &State, sc: &Scratch) -> f64 {
    if p.control.is_some() {
        return sc.control[k].applied;
    }
    if p.motor.is_some() {
        return sc.motor[k].pulley_torque;
    }
    p.drive.as_ref().map_or(0.0, |d| {
        d.torque_at(s.time, s.pulley_omega[k]) + d.viscous * s.pulley_omega[k]
    })
}

/// Add each follower's torque, ratio × its master's (within its own `max_torque`).
pub fn follow_torques(m: &crate::model::Model, s: &State, sc: &mut Scratch) {
    for (j, p) in m.pulleys.iter().enumerate() {
        let Some(f) = p.follow else { continue };
        if p.drive.as_ref().is_some_and(|d| !d.powered(s.time)) {
            continue; // this drive has lost power (`power_off`)
        }
        let limit = p.drive.as_ref().map_or(f64::INFINITY, |d| d.max_torque);
        let torque = f.factor * master_torque(&m.pulleys[f.master], f.master, s, sc);
        sc.drive_torque[j] += torque.clamp(-limit, limit);
    }
}
