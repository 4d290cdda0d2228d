//! The scene's stops and takeup kinds (`docs/stops-takeups.md`): a drive's power failure
//! (`power_off`), brakes with a torque or a deceleration target, holdbacks, and gravity,
//! winch and screw takeups that may lock when a stop begins. Their types and rules live
//! here; [`super::Scene::validate`] calls [`check_stops`].

use super::validate::{check_finite, check_non_negative, check_positive};
use super::{BrakeSpec, DriveSpec, PulleySpec, Scene, Table, TakeupSpec, Wrap};
use crate::error::{BeltError, BeltResult};
use serde::{Deserialize, Serialize};

/// Kind of takeup (the `kind` key of a `takeup` table).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TakeupKind {
    /// `"gravity"`: a counterweight pulls the carriage along the line (thesis eq. 4.63),
    /// between its travel stops.
    #[default]
    Gravity,
    /// `"fixed"`: a screw takeup. The carriage is locked in dynamic runs; the static
    /// relaxation tightens it to `force` (it moves under that pull until the belt balances
    /// it), as a screw is set at rest.
    Fixed,
    /// `"winch"`: a winch keeps the pull at `force` while the carriage moves no faster than
    /// `max_speed`; at the limit the rope speed is held and the tension departs from the set
    /// force.
    Winch,
}

/// A holdback: a one-way clutch (backstop) that lets the pulley turn only in its forward
/// sense and stops it turning backwards, up to its capacity (`[pulleys.holdback]`). It acts
/// only against reverse rotation: while the pulley turns forwards it supplies nothing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HoldbackSpec {
    /// The sense the pulley turns when the conveyor runs forward, `"ccw"` or `"cw"`
    /// (a head drive whose carry strand runs towards +x on top turns `"cw"`). Required.
    pub forward: Option<Wrap>,
    /// Largest torque the holdback takes against reverse rotation, N·m, > 0, may be +∞.
    /// Default +∞.
    pub capacity: f64,
}

impl Default for HoldbackSpec {
    fn default() -> Self {
        HoldbackSpec {
            forward: None,
            capacity: f64::INFINITY,
        }
    }
}

impl DriveSpec {
    /// True while the motor has power at time `t` (s): before `power_off`.
    #[inline]
    pub fn powered(&self, t: f64) -> bool {
        self.power_off.is_none_or(|off| t < off)
    }
}

impl BrakeSpec {
    /// Torque capacity at time `t` (s), N·m: the table, or `torque` from `applied` on,
    /// built up linearly over `rise` (0 before `applied`).
    #[inline]
    pub fn capacity_at(&self, t: f64) -> f64 {
        match self.torque {
            None => self.capacity.eval(t),
            Some(_) if t < self.applied => 0.0,
            Some(torque) if t < self.applied + self.rise => torque * (t - self.applied) / self.rise,
            Some(torque) => torque,
        }
    }

    /// True while the brake is released at time `t` (s): before `applied` for a brake given
    /// by `torque` (a table brake is never released as a whole; its capacity may be 0).
    #[inline]
    pub fn released(&self, t: f64) -> bool {
        self.torque.is_some() && t < self.applied
    }
}

impl Scene {
    /// Time the first stop of the scene begins, s: the earliest drive `power_off` or brake
    /// `applied` time (brakes given by `torque`); `None` if the scene has no stop.
    pub fn stop_time(&self) -> Option<f64> {
        let events = self.pulleys.iter().flat_map(|p| {
            let off = p.drive.as_ref().and_then(|d| d.power_off);
            let applied = p.brake.as_ref().and_then(|b| b.torque.map(|_| b.applied));
            off.into_iter().chain(applied)
        });
        events.reduce(f64::min)
    }
}

/// The rules of every pulley's stops and takeup kind (`f` names the pulley, e.g.
/// `pulleys[0]`).
pub(super) fn check_stops(scene: &Scene) -> BeltResult<()> {
    for (i, p) in scene.pulleys.iter().enumerate() {
        let f = format!("pulleys[{i}]");
        if let Some(b) = &p.brake {
            check_brake(&f, b)?;
        }
        if let Some(h) = &p.holdback {
            check_holdback(&f, p, h)?;
        }
        if let Some(t) = &p.takeup {
            check_takeup_kind(&f, t, scene)?;
        }
    }
    Ok(())
}

/// Whether a speed-controlled drive and this pulley's brake never hold at the same time:
/// the brake is given by `torque` and applied no earlier than the drive's `power_off`.
pub(super) fn brake_after_power_off(p: &PulleySpec) -> bool {
    match (&p.drive, &p.brake) {
        (Some(d), Some(b)) => match (d.power_off, b.torque) {
            (Some(off), Some(_)) => b.applied >= off,
            _ => false,
        },
        _ => false,
    }
}

fn check_brake(f: &str, b: &BrakeSpec) -> BeltResult<()> {
    let key = |k: &str| format!("{f}.brake.{k}");
    let Some(torque) = b.torque else {
        // The timing keys shape `torque`; alone they would be silently ignored.
        for (name, value, default) in [
            ("deceleration", b.deceleration, None),
            ("applied", Some(b.applied), Some(0.0)),
            ("rise", Some(b.rise), Some(0.0)),
        ] {
            if value != default {
                return Err(BeltError::invalid(
                    key(name),
                    value.unwrap_or(f64::NAN),
                    format!("needs {f}.brake.torque (the braking torque, N·m); the time/capacity table brake takes none"),
                ));
            }
        }
        return Ok(());
    };
    check_positive(&key("torque"), torque)?;
    if b.capacity != Table::constant(0.0) {
        return Err(BeltError::invalid(
            key("capacity"),
            format!("{:?}", b.capacity.y),
            format!("give {f}.brake.torque or the time/capacity table, not both"),
        ));
    }
    if let Some(a) = b.deceleration {
        check_positive(&key("deceleration"), a)?;
    }
    check_finite(&key("applied"), b.applied)?;
    check_non_negative(&key("rise"), b.rise)?;
    Ok(())
}

fn check_holdback(f: &str, p: &PulleySpec, h: &HoldbackSpec) -> BeltResult<()> {
    let Some(forward) = h.forward else {
        return Err(BeltError::invalid(
            format!("{f}.holdback.forward"),
            "missing",
            "required: \"ccw\" or \"cw\", the sense the pulley turns when the conveyor runs forward",
        ));
    };
    if h.capacity.is_nan() || h.capacity <= 0.0 {
        return Err(BeltError::invalid(
            format!("{f}.holdback.capacity"),
            h.capacity,
            "must be > 0 (N·m, may be inf)",
        ));
    }
    if let Some(curve) = p.drive.as_ref().and_then(|d| d.start_curve.as_ref()) {
        if curve.speed * forward.sign() < 0.0 {
            let name = if forward == Wrap::Clockwise {
                "cw"
            } else {
                "ccw"
            };
            return Err(BeltError::invalid(
                format!("{f}.holdback.forward"),
                format!("{name:?}"),
                format!("the drive's start_curve.speed ({}) turns the pulley the other way: the holdback would stop the drive (forward is the sense the drive runs the conveyor)", curve.speed),
            ));
        }
    }
    Ok(())
}

fn check_takeup_kind(f: &str, t: &TakeupSpec, scene: &Scene) -> BeltResult<()> {
    let key = |k: &str| format!("{f}.takeup.{k}");
    let kind = match t.kind {
        TakeupKind::Gravity => "gravity",
        TakeupKind::Fixed => "fixed",
        TakeupKind::Winch => "winch",
    };
    match (t.kind, t.force) {
        (TakeupKind::Gravity, Some(force)) => {
            return Err(BeltError::invalid(
                key("force"),
                force,
                "a gravity takeup pulls with its counterweight: give counterweight (kg), or kind = \"winch\" or \"fixed\" with a force",
            ));
        }
        (TakeupKind::Gravity, None) => {}
        (_, None) => {
            return Err(BeltError::invalid(
                key("force"),
                "missing",
                format!("required for a {kind} takeup: the force (N) it pulls the pulley with along direction"),
            ));
        }
        (_, Some(force)) => {
            check_positive(&key("force"), force)?;
            if t.counterweight != 0.0 {
                return Err(BeltError::invalid(
                    key("counterweight"),
                    t.counterweight,
                    format!("a {kind} takeup has no counterweight (its force sets the pull): leave counterweight out"),
                ));
            }
        }
    }
    if t.max_speed.is_nan() || t.max_speed <= 0.0 {
        return Err(BeltError::invalid(
            key("max_speed"),
            t.max_speed,
            "must be > 0 (m/s, may be inf)",
        ));
    }
    if t.max_speed != f64::INFINITY && t.kind != TakeupKind::Winch {
        return Err(BeltError::invalid(
            key("max_speed"),
            t.max_speed,
            format!("limits a winch only (this takeup is kind = \"{kind}\"): leave max_speed out"),
        ));
    }
    if t.lock_on_stop {
        if t.kind == TakeupKind::Fixed {
            return Err(BeltError::invalid(
                key("lock_on_stop"),
                true,
                "a fixed (screw) takeup is always locked in a run: leave lock_on_stop out",
            ));
        }
        if scene.stop_time().is_none() {
            return Err(BeltError::invalid(
                key("lock_on_stop"),
                true,
                "the scene has no stop to lock on: give a drive power_off or a brake with torque and applied time",
            ));
        }
    }
    Ok(())
}
