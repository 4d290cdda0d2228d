//! The rules of a scene: every check that needs no geometry (ranges, finiteness, pairs of
//! fields, overlaps). Path-dependent rules are checked when the model is compiled.

use super::*;

impl Table {
    /// Check the table given in a scene under the keys `{field}.{xkey}` and `{field}.{ykey}`
    /// (e.g. `pulleys[0].drive.time` and `pulleys[0].drive.torque`), so that every message
    /// names the key the user wrote.
    fn validate(&self, field: &str, xkey: &str, ykey: &str, non_negative: bool) -> BeltResult<()> {
        if self.x.len() != self.y.len() {
            return Err(BeltError::invalid(
                format!("{field}.{ykey}"),
                format!("{} values", self.y.len()),
                format!("needs as many values as {field}.{xkey} ({})", self.x.len()),
            ));
        }
        if self.x.is_empty() {
            return Err(BeltError::invalid(
                format!("{field}.{xkey}"),
                "[]",
                "a table needs at least one point",
            ));
        }
        for (i, (&x, &y)) in self.x.iter().zip(&self.y).enumerate() {
            check_finite(&format!("{field}.{xkey}[{i}]"), x)?;
            check_finite(&format!("{field}.{ykey}[{i}]"), y)?;
            if non_negative && y < 0.0 {
                return Err(BeltError::invalid(
                    format!("{field}.{ykey}[{i}]"),
                    y,
                    "must be ≥ 0",
                ));
            }
            if i > 0 && x <= self.x[i - 1] {
                return Err(BeltError::invalid(
                    format!("{field}.{xkey}[{i}]"),
                    x,
                    format!("must increase strictly (previous value {})", self.x[i - 1]),
                ));
            }
        }
        Ok(())
    }
}

impl DriveSpec {
    /// The rules of a speed-controlled drive (`pulley` names the pulley, e.g. `pulleys[0]`):
    /// a valid curve, no torque table, no speed factor, no brake on the same pulley, and a
    /// `max_torque` > 0 that is given only with a curve.
    fn validate_speed_control(&self, pulley: &str, has_brake: bool) -> BeltResult<()> {
        let f = format!("{pulley}.drive");
        if self.max_torque.is_nan() || self.max_torque <= 0.0 {
            return Err(BeltError::invalid(
                format!("{f}.max_torque"),
                self.max_torque,
                "must be > 0 (may be inf)",
            ));
        }
        let Some(curve) = &self.start_curve else {
            if self.max_torque != f64::INFINITY && self.follow.is_none() {
                // It would be silently ignored.
                return Err(BeltError::invalid(
                    format!("{f}.max_torque"),
                    self.max_torque,
                    format!("limits a speed-controlled drive only (or a torque follower): give {f}.start_curve or {f}.follow, or leave max_torque out"),
                ));
            }
            return Ok(());
        };
        curve.validate(&format!("{f}.start_curve"))?;
        if let Some((i, &y)) = self.torque.y.iter().enumerate().find(|(_, y)| **y != 0.0) {
            return Err(BeltError::invalid(
                format!("{f}.torque[{i}]"),
                y,
                format!("must be 0 with {f}.start_curve: a drive is either torque-controlled (time/torque table) or speed-controlled (start_curve), not both"),
            ));
        }
        if !self.speed_factor.x.is_empty() || !self.speed_factor.y.is_empty() {
            return Err(BeltError::invalid(
                format!("{f}.speed_factor"),
                format!("{:?}", self.speed_factor.y),
                format!("has no effect with {f}.start_curve (it scales the torque table, which a speed-controlled drive does not have): leave it out"),
            ));
        }
        if has_brake {
            return Err(BeltError::invalid(
                format!("{pulley}.brake"),
                "a brake",
                format!("a pulley with a speed-controlled drive ({f}.start_curve) cannot also have a brake that acts while the drive has power: the drive holds the pulley itself (remove one of them, or give the drive a power_off and the brake a torque applied no earlier)"),
            ));
        }
        Ok(())
    }
}

impl RecordingParams {
    /// Check every field: finite non-negative duration, positive interval, `every` ≥ 1, not
    /// both `interval` and `every`, `stabilise_friction` only with `stabilise`, known and
    /// distinct channel names.
    pub fn validate(&self) -> BeltResult<()> {
        check_non_negative("recording.duration", self.duration)?;
        if let Some(interval) = self.interval {
            check_positive("recording.interval", interval)?;
        }
        if let Some(every) = self.every {
            if every == 0 {
                return Err(BeltError::invalid("recording.every", every, "must be ≥ 1"));
            }
            if let Some(interval) = self.interval {
                return Err(BeltError::invalid(
                    "recording.every",
                    every,
                    format!(
                        "give recording.interval (here {interval}) or recording.every, not both"
                    ),
                ));
            }
        }
        if self.stabilise_friction && !self.stabilise {
            // It would be silently ignored.
            return Err(BeltError::invalid(
                "recording.stabilise_friction",
                true,
                "has no effect with recording.stabilise = false (set both, or neither)",
            ));
        }
        for (i, c) in self.channels.iter().enumerate() {
            if !RECORDING_CHANNELS.contains(&c.as_str()) {
                let hint = match crate::suggest::close_match(c, RECORDING_CHANNELS) {
                    Some(s) => format!(", did you mean \"{s}\"?"),
                    None => String::new(),
                };
                return Err(BeltError::invalid(
                    format!("recording.channels[{i}]"),
                    format!("{c:?}"),
                    format!(
                        "unknown channel{hint} (known: {})",
                        RECORDING_CHANNELS.join(", ")
                    ),
                ));
            }
            if self.channels[..i].contains(c) {
                return Err(BeltError::invalid(
                    format!("recording.channels[{i}]"),
                    format!("{c:?}"),
                    "listed twice",
                ));
            }
        }
        Ok(())
    }
}

/// Error unless `value` is finite.
pub(crate) fn check_finite(field: &str, value: f64) -> BeltResult<()> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(BeltError::invalid(field, value, "must be a finite number"))
    }
}

pub(super) fn check_positive(field: &str, value: f64) -> BeltResult<()> {
    check_finite(field, value)?;
    if value > 0.0 {
        Ok(())
    } else {
        Err(BeltError::invalid(field, value, "must be > 0"))
    }
}

pub(super) fn check_non_negative(field: &str, value: f64) -> BeltResult<()> {
    check_finite(field, value)?;
    if value >= 0.0 {
        Ok(())
    } else {
        Err(BeltError::invalid(field, value, "must be ≥ 0"))
    }
}

/// `contact_damping` (N·s/m) and `contact_damping_ratio` of the body `f`: each finite and
/// ≥ 0, and not both given.
fn check_contact_damping(f: &str, absolute: Option<f64>, ratio: Option<f64>) -> BeltResult<()> {
    if let Some(c) = absolute {
        check_non_negative(&format!("{f}.contact_damping"), c)?;
    }
    if let Some(z) = ratio {
        check_non_negative(&format!("{f}.contact_damping_ratio"), z)?;
    }
    if let (Some(c), Some(_)) = (absolute, ratio) {
        return Err(BeltError::invalid(
            format!("{f}.contact_damping"),
            c,
            format!("give contact_damping (N·s/m) or {f}.contact_damping_ratio (fraction of critical), not both"),
        ));
    }
    Ok(())
}

fn check_friction(field: &str, model: &FrictionModel) -> BeltResult<()> {
    if let FrictionModel::StickForce {
        static_coefficient,
        kinetic_coefficient,
    } = *model
    {
        // Named by the scene keys (`friction.static`, `friction.kinetic`).
        check_non_negative(&format!("{field}.static"), static_coefficient)?;
        check_non_negative(&format!("{field}.kinetic"), kinetic_coefficient)?;
        if kinetic_coefficient > static_coefficient {
            return Err(BeltError::invalid(
                format!("{field}.kinetic"),
                kinetic_coefficient,
                format!("must not exceed the static coefficient {static_coefficient}"),
            ));
        }
    }
    Ok(())
}

impl Scene {
    /// Check every parameter on its own and the pairwise rules that need no geometry
    /// (overlaps). Path-dependent rules (closure, belt length, element length) are checked
    /// when the path is built in [`crate::model::Model::compile`].
    pub fn validate(&self) -> BeltResult<()> {
        check_non_negative("gravity", self.gravity)?;
        self.recording.validate()?;
        if let Some(initial) = &self.initial {
            initial.validate()?;
            if let Some(length) = self.belt.length {
                return Err(BeltError::invalid(
                    "belt.length",
                    length,
                    "give belt.length or an [initial] design state, not both: the design tensions fix the unstretched length that fits the path",
                ));
            }
            if self.recording.stabilise {
                return Err(BeltError::invalid(
                    "recording.stabilise",
                    true,
                    "must be false with an [initial] design state: the design state replaces the static relaxation (which would undo its tensions and speeds)",
                ));
            }
        }
        self.validate_choices()?;
        let b = &self.belt;
        check_positive("belt.axial_stiffness", b.axial_stiffness)?;
        check_positive("belt.mass_per_length", b.mass_per_length)?;
        check_non_negative("belt.bending_stiffness", b.bending_stiffness)?;
        check_non_negative("belt.damping_ratio", b.damping_ratio)?;
        if let Some(length) = b.length {
            check_positive("belt.length", length)?;
        }
        if let Some(n) = b.elements {
            if n < 3 {
                return Err(BeltError::invalid(
                    "belt.elements",
                    n,
                    "a closed belt needs at least 3 elements",
                ));
            }
            if n > MAX_ELEMENTS {
                return Err(BeltError::invalid(
                    "belt.elements",
                    n,
                    format!("must be at most {MAX_ELEMENTS}"),
                ));
            }
        }
        check_positive("belt.max_placement_strain", b.max_placement_strain)?;
        check_positive("belt.max_element_angle", b.max_element_angle)?;
        if b.max_element_angle > std::f64::consts::FRAC_PI_3 {
            return Err(BeltError::invalid(
                "belt.max_element_angle",
                b.max_element_angle,
                "must be at most π/3 rad (60°): a longer element cuts through the pulley",
            ));
        }
        let s = &self.solver;
        if let Some(dt) = s.time_step {
            check_positive("solver.time_step", dt)?;
        }
        check_positive("solver.time_step_fraction", s.time_step_fraction)?;
        if s.time_step_fraction > 1.0 {
            return Err(BeltError::invalid(
                "solver.time_step_fraction",
                s.time_step_fraction,
                "must be in (0, 1]: 1 is the stability limit",
            ));
        }

        if self.pulleys.len() < 2 {
            return Err(BeltError::invalid(
                "pulleys",
                format!("{} pulley(s)", self.pulleys.len()),
                "a closed belt path needs at least 2 pulleys",
            ));
        }
        for (i, p) in self.pulleys.iter().enumerate() {
            let f = format!("pulleys[{i}]");
            if !p.name.is_empty() {
                if let Some(j) = self.pulleys[..i].iter().position(|q| q.name == p.name) {
                    return Err(BeltError::invalid(
                        format!("{f}.name"),
                        format!("{:?}", p.name),
                        format!("already the name of pulleys[{j}]: names must be unique (they pick a pulley in results and from Python)"),
                    ));
                }
            }
            check_finite(&format!("{f}.center[0]"), p.center[0])?;
            check_finite(&format!("{f}.center[1]"), p.center[1])?;
            check_positive(&format!("{f}.radius"), p.radius)?;
            check_positive(&format!("{f}.mass"), p.mass)?;
            if let Some(inertia) = p.inertia {
                check_positive(&format!("{f}.inertia"), inertia)?;
            }
            check_non_negative(&format!("{f}.contact_stiffness"), p.contact_stiffness)?;
            check_contact_damping(&f, p.contact_damping, p.contact_damping_ratio)?;
            check_non_negative(&format!("{f}.bearing_damping"), p.bearing_damping)?;
            check_friction(&format!("{f}.friction"), &p.friction)?;
            if p.contact_stiffness == 0.0 && !p.friction.is_none() {
                // Friction needs a normal force: it would be silently ignored.
                let mu = match p.friction {
                    FrictionModel::StickForce {
                        static_coefficient, ..
                    } => static_coefficient,
                    FrictionModel::None => 0.0,
                };
                return Err(BeltError::invalid(
                    format!("{f}.friction.static"),
                    mu,
                    format!("friction needs contact, and {f}.contact_stiffness = 0 switches contact with this pulley off (give contact_stiffness > 0, or no friction)"),
                ));
            }
            if let Some(t) = &p.takeup {
                check_finite(&format!("{f}.takeup.direction[0]"), t.direction[0])?;
                check_finite(&format!("{f}.takeup.direction[1]"), t.direction[1])?;
                let norm = t.direction[0].hypot(t.direction[1]);
                if (norm - 1.0).abs() > 1e-9 {
                    return Err(BeltError::invalid(
                        format!("{f}.takeup.direction"),
                        format!("[{}, {}]", t.direction[0], t.direction[1]),
                        format!("must be a unit vector (length 1 within 1e-9; its length is {norm}): it is the line the takeup moves on"),
                    ));
                }
                check_non_negative(&format!("{f}.takeup.counterweight"), t.counterweight)?;
                if t.travel_min.is_nan() || t.travel_min > 0.0 {
                    return Err(BeltError::invalid(
                        format!("{f}.takeup.travel_min"),
                        t.travel_min,
                        "must be ≤ 0 (travel is measured from the initial position)",
                    ));
                }
                if t.travel_max.is_nan() || t.travel_max < 0.0 {
                    return Err(BeltError::invalid(
                        format!("{f}.takeup.travel_max"),
                        t.travel_max,
                        "must be ≥ 0 (travel is measured from the initial position)",
                    ));
                }
            }
            if let Some(d) = &p.drive {
                d.torque
                    .validate(&format!("{f}.drive"), "time", "torque", false)?;
                if !d.speed_factor.x.is_empty() || !d.speed_factor.y.is_empty() {
                    d.speed_factor.validate(
                        &format!("{f}.drive"),
                        "speed",
                        "speed_factor",
                        false,
                    )?;
                }
                check_non_negative(&format!("{f}.drive.viscous"), d.viscous)?;
                check_non_negative(&format!("{f}.drive.inertia"), d.inertia)?;
                if let Some(off) = d.power_off {
                    check_finite(&format!("{f}.drive.power_off"), off)?;
                }
                let holds_with = p.brake.is_some() && !super::stops::brake_after_power_off(p);
                d.validate_speed_control(&f, holds_with)?;
            }
            if let Some(br) = &p.brake {
                br.capacity
                    .validate(&format!("{f}.brake"), "time", "capacity", true)?;
            }
        }
        crate::drives::sharing::validate(self)?;
        super::stops::check_stops(self)?;
        for (i, d) in self.idlers.iter().enumerate() {
            let f = format!("idlers[{i}]");
            check_finite(&format!("{f}.center[0]"), d.center[0])?;
            check_finite(&format!("{f}.center[1]"), d.center[1])?;
            check_positive(&format!("{f}.radius"), d.radius)?;
            check_positive(&format!("{f}.inertia"), d.inertia)?;
            check_positive(&format!("{f}.contact_stiffness"), d.contact_stiffness)?;
            check_contact_damping(&f, d.contact_damping, d.contact_damping_ratio)?;
            check_friction(&format!("{f}.friction"), &d.friction)?;
            check_non_negative(&format!("{f}.resistance"), d.resistance)?;
            check_non_negative(&format!("{f}.rotating_mass"), d.rotating_mass)?;
        }
        for (i, l) in self.loads.iter().enumerate() {
            let f = format!("loads[{i}]");
            check_non_negative(&format!("{f}.mass_per_length"), l.mass_per_length)?;
            for (key, p) in [("start", l.start), ("end", l.end)] {
                check_finite(&format!("{f}.{key}[0]"), p[0])?;
                check_finite(&format!("{f}.{key}[1]"), p[1])?;
            }
        }
        // Bodies must not overlap (thesis §4.3: pulleys and idlers never touch each other).
        let circles: Vec<(String, [f64; 2], f64)> = self
            .pulleys
            .iter()
            .enumerate()
            .map(|(i, p)| (format!("pulleys[{i}]"), p.center, p.radius))
            .chain(
                self.idlers
                    .iter()
                    .enumerate()
                    .map(|(i, d)| (format!("idlers[{i}]"), d.center, d.radius)),
            )
            .collect();
        for a in 0..circles.len() {
            for b in (a + 1)..circles.len() {
                let (na, ca, ra) = &circles[a];
                let (nb, cb, rb) = &circles[b];
                let dist = (ca[0] - cb[0]).hypot(ca[1] - cb[1]);
                if dist < ra + rb {
                    return Err(BeltError::invalid(
                        format!("{nb}.center"),
                        format!("[{}, {}]", cb[0], cb[1]),
                        format!(
                            "overlaps {na} (centres {dist:.6} m apart, radii sum {:.6} m)",
                            ra + rb
                        ),
                    ));
                }
            }
        }
        Ok(())
    }
}
