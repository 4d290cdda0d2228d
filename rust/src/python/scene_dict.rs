//! Reading a scene from the plain Python dict that `beltrs.Scene.to_dict()` produces.
//! Strict: an unknown key or a wrong type is an error naming the field path.

use crate::error::{BeltError, BeltResult};
use crate::scene::{
    BeltParams, BrakeSpec, DriveSpec, Formulation, FrictionModel, IdlerSpec, LoadSpec, PulleySpec,
    RecordingParams, Scene, SolverParams, Table, TakeupSpec, Wrap,
};
use crate::start_curve::{StartCurve, StartShape};
use crate::suggest::unknown_key_rule;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::collections::HashSet;

/// A dict being read, with the keys consumed so far.
struct Reader<'py> {
    dict: Bound<'py, PyDict>,
    path: String,
    used: HashSet<String>,
}

fn type_error(path: &str, value: &Bound<'_, PyAny>, expected: &str) -> BeltError {
    let shown = value
        .repr()
        .map(|r| r.to_string())
        .unwrap_or_else(|_| "?".into());
    BeltError::invalid(path, shown, format!("expected {expected}"))
}

impl<'py> Reader<'py> {
    fn new(value: &Bound<'py, PyAny>, path: &str) -> BeltResult<Self> {
        let dict = value
            .cast::<PyDict>()
            .map_err(|_| type_error(path, value, "a table (dict)"))?
            .clone();
        Ok(Reader {
            dict,
            path: path.to_string(),
            used: HashSet::new(),
        })
    }

    fn field(&self, key: &str) -> String {
        if self.path.is_empty() {
            key.to_string()
        } else {
            format!("{}.{key}", self.path)
        }
    }

    /// The value under `key`, or None if absent or None.
    fn get(&mut self, key: &str) -> Option<Bound<'py, PyAny>> {
        self.used.insert(key.to_string());
        match self.dict.get_item(key) {
            Ok(Some(v)) if !v.is_none() => Some(v),
            _ => None,
        }
    }

    fn opt_f64(&mut self, key: &str) -> BeltResult<Option<f64>> {
        match self.get(key) {
            None => Ok(None),
            Some(v) => {
                if v.is_instance_of::<pyo3::types::PyBool>() {
                    return Err(type_error(&self.field(key), &v, "a number"));
                }
                v.extract::<f64>()
                    .map(Some)
                    .map_err(|_| type_error(&self.field(key), &v, "a number"))
            }
        }
    }

    fn f64(&mut self, key: &str, default: f64) -> BeltResult<f64> {
        Ok(self.opt_f64(key)?.unwrap_or(default))
    }

    fn bool(&mut self, key: &str, default: bool) -> BeltResult<bool> {
        match self.get(key) {
            None => Ok(default),
            Some(v) => v
                .cast::<pyo3::types::PyBool>()
                .map(|b| b.is_true())
                .map_err(|_| type_error(&self.field(key), &v, "true or false")),
        }
    }

    fn opt_usize(&mut self, key: &str) -> BeltResult<Option<usize>> {
        match self.get(key) {
            None => Ok(None),
            Some(v) => {
                if v.is_instance_of::<pyo3::types::PyBool>() {
                    return Err(type_error(&self.field(key), &v, "a whole number"));
                }
                v.extract::<i64>()
                    .map_err(|_| type_error(&self.field(key), &v, "a whole number"))
                    .and_then(|n| {
                        usize::try_from(n)
                            .map_err(|_| BeltError::invalid(self.field(key), n, "must be ≥ 0"))
                    })
                    .map(Some)
            }
        }
    }

    fn string(&mut self, key: &str, default: &str) -> BeltResult<String> {
        match self.get(key) {
            None => Ok(default.to_string()),
            Some(v) => v
                .extract::<String>()
                .map_err(|_| type_error(&self.field(key), &v, "a string")),
        }
    }

    fn floats(&mut self, key: &str) -> BeltResult<Option<Vec<f64>>> {
        match self.get(key) {
            None => Ok(None),
            Some(v) => {
                let field = self.field(key);
                let list = v
                    .try_iter()
                    .map_err(|_| type_error(&field, &v, "a list of numbers"))?;
                let mut out = Vec::new();
                for (i, item) in list.enumerate() {
                    let item = item.map_err(|_| type_error(&field, &v, "a list of numbers"))?;
                    if item.is_instance_of::<pyo3::types::PyBool>() {
                        return Err(type_error(&format!("{field}[{i}]"), &item, "a number"));
                    }
                    out.push(
                        item.extract::<f64>()
                            .map_err(|_| type_error(&format!("{field}[{i}]"), &item, "a number"))?,
                    );
                }
                Ok(Some(out))
            }
        }
    }

    fn strings(&mut self, key: &str) -> BeltResult<Option<Vec<String>>> {
        match self.get(key) {
            None => Ok(None),
            Some(v) => {
                let field = self.field(key);
                if v.is_instance_of::<pyo3::types::PyString>() {
                    return Err(type_error(&field, &v, "a list of strings"));
                }
                let list = v
                    .try_iter()
                    .map_err(|_| type_error(&field, &v, "a list of strings"))?;
                let mut out = Vec::new();
                for (i, item) in list.enumerate() {
                    let item = item.map_err(|_| type_error(&field, &v, "a list of strings"))?;
                    out.push(
                        item.extract::<String>()
                            .map_err(|_| type_error(&format!("{field}[{i}]"), &item, "a string"))?,
                    );
                }
                Ok(Some(out))
            }
        }
    }

    fn vec2(&mut self, key: &str, default: [f64; 2]) -> BeltResult<[f64; 2]> {
        match self.floats(key)? {
            None => Ok(default),
            Some(v) if v.len() == 2 => Ok([v[0], v[1]]),
            Some(v) => Err(BeltError::invalid(
                self.field(key),
                format!("{v:?}"),
                "expected [x, y]",
            )),
        }
    }

    fn sub(&mut self, key: &str) -> BeltResult<Option<Reader<'py>>> {
        let field = self.field(key);
        match self.get(key) {
            None => Ok(None),
            Some(v) => Reader::new(&v, &field).map(Some),
        }
    }

    fn list(&mut self, key: &str) -> BeltResult<Vec<Reader<'py>>> {
        let field = self.field(key);
        match self.get(key) {
            None => Ok(Vec::new()),
            Some(v) => {
                let list = v
                    .cast::<PyList>()
                    .map_err(|_| type_error(&field, &v, "a list of tables"))?;
                list.iter()
                    .enumerate()
                    .map(|(i, item)| Reader::new(&item, &format!("{field}[{i}]")))
                    .collect()
            }
        }
    }

    /// Error on any key that was not read, suggesting the closest known key.
    fn finish(self) -> BeltResult<()> {
        for key in self.dict.keys() {
            let name = key.to_string();
            if !self.used.contains(&name) {
                return Err(BeltError::invalid(
                    self.field(&name),
                    key.repr().map(|r| r.to_string()).unwrap_or(name.clone()),
                    unknown_key_rule(&name, self.used.iter().map(|s| s.as_str())),
                ));
            }
        }
        Ok(())
    }
}

fn friction(r: &mut Reader<'_>) -> BeltResult<FrictionModel> {
    let Some(mut f) = r.sub("friction")? else {
        return Ok(FrictionModel::None);
    };
    let model = f.string("model", "stick_force")?;
    let mu_s = f.f64("static", 0.0)?;
    let mu_k = f.opt_f64("kinetic")?;
    let out = match model.as_str() {
        "none" => {
            // Coefficients with no friction model would be silently ignored: refuse them.
            if mu_s != 0.0 || mu_k.is_some_and(|k| k != 0.0) {
                let (key, value) = if mu_s != 0.0 {
                    ("static", mu_s)
                } else {
                    ("kinetic", mu_k.unwrap_or(0.0))
                };
                return Err(BeltError::invalid(
                    f.field(key),
                    value,
                    "friction model \"none\" takes no coefficients (use \"stick_force\")",
                ));
            }
            FrictionModel::None
        }
        "stick_force" => FrictionModel::StickForce {
            static_coefficient: mu_s,
            kinetic_coefficient: mu_k.unwrap_or(mu_s),
        },
        "creep" => {
            return Err(BeltError::invalid(
                f.field("model"),
                "\"creep\"",
                "the creep friction model is not implemented yet (available: \"none\", \"stick_force\")",
            ))
        }
        other => {
            let hint = match crate::suggest::close_match(other, ["none", "stick_force"]) {
                Some(s) => format!(", did you mean \"{s}\"?"),
                None => String::new(),
            };
            return Err(BeltError::invalid(
                f.field("model"),
                format!("{other:?}"),
                format!("unknown friction model{hint} (known: \"none\", \"stick_force\")"),
            ));
        }
    };
    f.finish()?;
    Ok(out)
}

fn table(r: &mut Reader<'_>, xkey: &str, ykey: &str) -> BeltResult<Option<Table>> {
    let x = r.floats(xkey)?;
    let y = r.floats(ykey)?;
    match (x, y) {
        (None, None) => Ok(None),
        (Some(x), Some(y)) => Ok(Some(Table { x, y })),
        (Some(_), None) => Err(BeltError::invalid(
            r.field(ykey),
            "missing",
            format!("needed with {xkey}"),
        )),
        (None, Some(y)) if y.len() == 1 => Ok(Some(Table { x: vec![0.0], y })),
        (None, Some(_)) => Err(BeltError::invalid(
            r.field(xkey),
            "missing",
            format!("needed with {ykey}"),
        )),
    }
}

/// A number that has no default: an error naming the key when it is absent.
fn required_f64(r: &mut Reader<'_>, key: &str) -> BeltResult<f64> {
    r.opt_f64(key)?
        .ok_or_else(|| BeltError::invalid(r.field(key), "missing", "required"))
}

/// A starting curve from its table (`[pulleys.drive.start_curve]`).
fn start_curve_from(mut c: Reader<'_>) -> BeltResult<StartCurve> {
    let d = StartCurve::default();
    let shape_name = c.string("shape", d.shape.name())?;
    let shape = StartShape::from_name(&shape_name).ok_or_else(|| {
        let hint = match crate::suggest::close_match(&shape_name, StartShape::NAMES) {
            Some(s) => format!(", did you mean \"{s}\"?"),
            None => String::new(),
        };
        BeltError::invalid(
            c.field("shape"),
            format!("{shape_name:?}"),
            format!(
                "unknown starting curve{hint} (known: {})",
                StartShape::NAMES.map(|n| format!("\"{n}\"")).join(", ")
            ),
        )
    })?;
    let curve = StartCurve {
        shape,
        speed: required_f64(&mut c, "speed")?,
        ramp: required_f64(&mut c, "ramp")?,
        start: c.f64("start", d.start)?,
        prestart: c.f64("prestart", d.prestart)?,
        creep_speed: c.opt_f64("creep_speed")?,
        creep_ramp: c.opt_f64("creep_ramp")?,
    };
    c.finish()?;
    Ok(curve)
}

/// A starting curve given on its own (as `beltrs.StartCurve.to_dict()`), named `field` in
/// messages, checked by the rules of a scene's curve.
pub fn start_curve_from_dict(value: &Bound<'_, PyAny>, field: &str) -> BeltResult<StartCurve> {
    let curve = start_curve_from(Reader::new(value, field)?)?;
    curve.validate(field)?;
    Ok(curve)
}

/// Build a [`Scene`] from its dict form.
pub fn scene_from_dict(value: &Bound<'_, PyAny>) -> BeltResult<Scene> {
    let mut root = Reader::new(value, "")?;
    let defaults = Scene::default();
    let gravity = root.f64("gravity", defaults.gravity)?;

    let bd = BeltParams::default();
    let belt = match root.sub("belt")? {
        None => bd,
        Some(mut b) => {
            let formulation = match b
                .string("formulation", Formulation::NodeKelvinVoigt.name())?
                .as_str()
            {
                "node_kelvin_voigt" => Formulation::NodeKelvinVoigt,
                other => {
                    return Err(BeltError::invalid(
                        b.field("formulation"),
                        format!("{other:?}"),
                        "unknown belt formulation (known: \"node_kelvin_voigt\")",
                    ))
                }
            };
            let p = BeltParams {
                formulation,
                axial_stiffness: b.f64("axial_stiffness", bd.axial_stiffness)?,
                mass_per_length: b.f64("mass_per_length", bd.mass_per_length)?,
                bending_stiffness: b.f64("bending_stiffness", bd.bending_stiffness)?,
                damping_ratio: b.f64("damping_ratio", bd.damping_ratio)?,
                length: b.opt_f64("length")?,
                elements: b.opt_usize("elements")?,
                max_element_angle: b.f64("max_element_angle", bd.max_element_angle)?,
                tension_only: b.bool("tension_only", bd.tension_only)?,
                max_placement_strain: b.f64("max_placement_strain", bd.max_placement_strain)?,
            };
            b.finish()?;
            p
        }
    };

    let mut pulleys = Vec::new();
    for mut p in root.list("pulleys")? {
        let pd = PulleySpec::default();
        let wrap = match p.string("wrap", "ccw")?.as_str() {
            "ccw" => Wrap::CounterClockwise,
            "cw" => Wrap::Clockwise,
            other => {
                return Err(BeltError::invalid(
                    p.field("wrap"),
                    format!("{other:?}"),
                    "expected \"ccw\" or \"cw\"",
                ))
            }
        };
        let takeup = match p.sub("takeup")? {
            None => None,
            Some(mut t) => {
                let td = TakeupSpec::default();
                let spec = TakeupSpec {
                    direction: t.vec2("direction", td.direction)?,
                    counterweight: t.f64("counterweight", td.counterweight)?,
                    travel_min: t.f64("travel_min", td.travel_min)?,
                    travel_max: t.f64("travel_max", td.travel_max)?,
                };
                t.finish()?;
                Some(spec)
            }
        };
        let drive = match p.sub("drive")? {
            None => None,
            Some(mut d) => {
                let dd = DriveSpec::default();
                let spec = DriveSpec {
                    torque: table(&mut d, "time", "torque")?.unwrap_or(dd.torque),
                    speed_factor: table(&mut d, "speed", "speed_factor")?.unwrap_or_default(),
                    viscous: d.f64("viscous", dd.viscous)?,
                    inertia: d.f64("inertia", dd.inertia)?,
                    start_curve: match d.sub("start_curve")? {
                        None => None,
                        Some(c) => Some(start_curve_from(c)?),
                    },
                    max_torque: d.f64("max_torque", dd.max_torque)?,
                };
                d.finish()?;
                Some(spec)
            }
        };
        let brake = match p.sub("brake")? {
            None => None,
            Some(mut b) => {
                let spec = BrakeSpec {
                    capacity: table(&mut b, "time", "capacity")?
                        .unwrap_or_else(|| Table::constant(0.0)),
                };
                b.finish()?;
                Some(spec)
            }
        };
        let spec = PulleySpec {
            name: p.string("name", "")?,
            center: p.vec2("center", pd.center)?,
            radius: p.f64("radius", pd.radius)?,
            mass: p.f64("mass", pd.mass)?,
            inertia: p.opt_f64("inertia")?,
            wrap,
            friction: friction(&mut p)?,
            contact_stiffness: p.f64("contact_stiffness", pd.contact_stiffness)?,
            contact_damping: p.opt_f64("contact_damping")?,
            contact_damping_ratio: p.opt_f64("contact_damping_ratio")?,
            takeup,
            drive,
            brake,
        };
        p.finish()?;
        pulleys.push(spec);
    }

    let mut idlers = Vec::new();
    for mut d in root.list("idlers")? {
        let dd = IdlerSpec::default();
        let spec = IdlerSpec {
            center: d.vec2("center", dd.center)?,
            radius: d.f64("radius", dd.radius)?,
            inertia: d.f64("inertia", dd.inertia)?,
            contact_stiffness: d.f64("contact_stiffness", dd.contact_stiffness)?,
            contact_damping: d.opt_f64("contact_damping")?,
            contact_damping_ratio: d.opt_f64("contact_damping_ratio")?,
            friction: friction(&mut d)?,
            resistance: d.f64("resistance", dd.resistance)?,
            rotating_mass: d.f64("rotating_mass", dd.rotating_mass)?,
        };
        d.finish()?;
        idlers.push(spec);
    }

    let mut loads = Vec::new();
    for mut l in root.list("loads")? {
        let ld = LoadSpec::default();
        let spec = LoadSpec {
            mass_per_length: l.f64("mass_per_length", ld.mass_per_length)?,
            start: l.vec2("start", ld.start)?,
            end: l.vec2("end", ld.end)?,
        };
        l.finish()?;
        loads.push(spec);
    }

    let sd = SolverParams::default();
    let solver = match root.sub("solver")? {
        None => sd,
        Some(mut s) => {
            let spec = SolverParams {
                time_step: s.opt_f64("time_step")?,
                time_step_fraction: s.f64("time_step_fraction", sd.time_step_fraction)?,
            };
            s.finish()?;
            spec
        }
    };
    // Run and recording settings are not part of the engine's scene, but they are checked
    // here by the same strict rules, so that nothing in a scene goes unchecked.
    if let Some(mut r) = root.sub("recording")? {
        let rd = RecordingParams::default();
        let spec = RecordingParams {
            duration: r.f64("duration", rd.duration)?,
            interval: r.opt_f64("interval")?,
            every: r.opt_usize("every")?.map(|n| n as u64),
            channels: r.strings("channels")?.unwrap_or(rd.channels),
            stabilise: r.bool("stabilise", rd.stabilise)?,
            stabilise_friction: r.bool("stabilise_friction", rd.stabilise_friction)?,
        };
        r.finish()?;
        spec.validate()?;
    }
    root.finish()?;
    Ok(Scene {
        belt,
        pulleys,
        idlers,
        loads,
        gravity,
        solver,
    })
}
