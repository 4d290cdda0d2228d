//! Scenes across the boundary. A Python value (the dict of `beltrs.Scene.to_dict()`, a
//! parsed TOML file) becomes a plain [`Value`] tree, read by the one scene schema
//! ([`crate::scene::read`]: unknown keys, types, full paths); a scene goes back to Python
//! through the same serde types (`pythonize`), and so do the schema's defaults, which the
//! dataclasses of `beltrs.scene` take as theirs. No key of the format is named here.

use crate::contact::nonlinear::NonlinearContact;
use crate::drives::controller::SpeedController;
use crate::drives::coupling::FluidCoupling;
use crate::drives::motor::Motor;
use crate::drives::sharing::TorqueFollow;
use crate::error::{BeltError, BeltResult};
use crate::scene::read::{from_value, Value, MAX_DEPTH};
use crate::scene::{
    BeltParams, BrakeSpec, DriveSpec, FrictionKeys, HoldbackSpec, IdlerSpec, InitialState,
    LoadSpec, PulleySpec, RecordingParams, Scene, SolverParams, TakeupSpec,
};
use crate::start_curve::StartCurve;
use pyo3::prelude::*;
use pyo3::types::{
    PyBool, PyByteArray, PyBytes, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple,
};

/// A value nested deeper than [`MAX_DEPTH`]: the keys and indices to it, innermost first.
struct TooDeep(Vec<String>);

fn repr(obj: &Bound<'_, PyAny>) -> String {
    obj.repr()
        .map(|r| r.to_string())
        .unwrap_or_else(|_| format!("<{} object>", obj.get_type()))
}

fn key_text(k: &Bound<'_, PyAny>) -> String {
    match k.cast::<PyString>() {
        Ok(s) => s
            .to_cow()
            .map(|c| c.into_owned())
            .unwrap_or_else(|_| repr(k)),
        Err(_) => repr(k),
    }
}

fn items<'py>(
    pairs: impl Iterator<Item = (Bound<'py, PyAny>, Bound<'py, PyAny>)>,
    depth: usize,
) -> Result<Value, TooDeep> {
    let mut out = Vec::new();
    for (k, v) in pairs {
        let key = key_text(&k);
        match to_value(&v, depth + 1) {
            Ok(v) => out.push((key, v)),
            Err(TooDeep(mut path)) => {
                path.push(format!(".{key}"));
                return Err(TooDeep(path));
            }
        }
    }
    Ok(Value::Map(out))
}

fn seq<'py>(
    values: impl Iterator<Item = Bound<'py, PyAny>>,
    depth: usize,
) -> Result<Value, TooDeep> {
    let mut out = Vec::new();
    for (i, v) in values.enumerate() {
        match to_value(&v, depth + 1) {
            Ok(v) => out.push(v),
            Err(TooDeep(mut path)) => {
                path.push(format!("[{i}]"));
                return Err(TooDeep(path));
            }
        }
    }
    Ok(Value::Seq(out))
}

/// A Python value as a plain value: None, bool, int, float, str, dict (or any mapping),
/// list, tuple (or any sequence, e.g. a NumPy array), and NumPy scalars; anything else is
/// [`Value::Other`], which no key accepts. Never raises: a value that cannot be read is
/// shown by its `repr` in the error the schema gives.
fn to_value(obj: &Bound<'_, PyAny>, depth: usize) -> Result<Value, TooDeep> {
    if obj.is_none() {
        return Ok(Value::Null);
    }
    if let Ok(b) = obj.cast::<PyBool>() {
        return Ok(Value::Bool(b.is_true()));
    }
    if let Ok(i) = obj.cast::<PyInt>() {
        return Ok(match (i.extract::<i64>(), i.extract::<f64>()) {
            (Ok(v), _) => Value::Int(v),
            (_, Ok(x)) => Value::Float(x), // beyond i64: a number, but never a whole count
            _ => Value::Other(repr(obj)),
        });
    }
    if let Ok(f) = obj.cast::<PyFloat>() {
        return Ok(Value::Float(f.value()));
    }
    if let Ok(s) = obj.cast::<PyString>() {
        return Ok(match s.to_cow() {
            Ok(s) => Value::Str(s.into_owned()),
            Err(_) => Value::Other(repr(obj)), // e.g. a lone surrogate
        });
    }
    if obj.is_instance_of::<PyBytes>() || obj.is_instance_of::<PyByteArray>() {
        return Ok(Value::Other(repr(obj)));
    }
    if depth >= MAX_DEPTH {
        return Err(TooDeep(Vec::new()));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        return items(d.iter(), depth);
    }
    if let Ok(l) = obj.cast::<PyList>() {
        return seq(l.iter(), depth);
    }
    if let Ok(t) = obj.cast::<PyTuple>() {
        return seq(t.iter(), depth);
    }
    if let Ok(m) = obj.cast::<pyo3::types::PyMapping>() {
        if let Ok(pairs) = m.items() {
            let pairs: Vec<_> = pairs
                .iter()
                .filter_map(|p| p.extract::<(Bound<'_, PyAny>, Bound<'_, PyAny>)>().ok())
                .collect();
            return items(pairs.into_iter(), depth);
        }
    }
    // NumPy scalars and other numbers: whole numbers through __index__, others __float__.
    if let Ok(v) = obj.extract::<i64>() {
        return Ok(Value::Int(v));
    }
    if let Ok(x) = obj.extract::<f64>() {
        return Ok(Value::Float(x));
    }
    // Other sized iterables (a NumPy array, a Sequence): a list.
    if obj.len().is_ok() {
        if let Ok(it) = obj.try_iter() {
            if let Ok(values) = it.collect::<PyResult<Vec<_>>>() {
                return seq(values.into_iter(), depth);
            }
        }
    }
    Ok(Value::Other(repr(obj)))
}

/// `obj` read as `T` by the scene schema; messages name paths from `root`.
fn read<T: serde::de::DeserializeOwned>(obj: &Bound<'_, PyAny>, root: &str) -> BeltResult<T> {
    match to_value(obj, 0) {
        Ok(value) => from_value(&value, root),
        Err(TooDeep(path)) => {
            let inner: String = path.iter().rev().map(String::as_str).collect();
            let field = format!("{root}{inner}");
            let field = field.trim_start_matches('.').to_string();
            Err(BeltError::invalid(
                if field.is_empty() {
                    "scene".into()
                } else {
                    field
                },
                "a value nested deeper still",
                format!("nested deeper than any scene key ({MAX_DEPTH} levels at most)"),
            ))
        }
    }
}

/// A scene from its dict form: keys and types checked (values are checked when it
/// compiles).
pub fn scene_from_py(obj: &Bound<'_, PyAny>) -> BeltResult<Scene> {
    read(obj, "")
}

/// A starting curve given on its own (as `beltrs.StartCurve.to_dict()`), named `field` in
/// messages, checked by the rules of a scene's curve.
pub fn start_curve_from_py(obj: &Bound<'_, PyAny>, field: &str) -> BeltResult<StartCurve> {
    let curve: StartCurve = read(obj, field)?;
    curve.validate(field)?;
    Ok(curve)
}

/// Check `obj` as the scene table `table` (a key of [`defaults`]), messages naming paths
/// from `path` (e.g. `conveyor.drives[0].start_curve`): unknown keys, types, required keys.
pub fn check_table(table: &str, obj: &Bound<'_, PyAny>, path: &str) -> BeltResult<()> {
    match table {
        "scene" => read::<Scene>(obj, path).map(drop),
        "belt" => read::<BeltParams>(obj, path).map(drop),
        "pulley" => read::<PulleySpec>(obj, path).map(drop),
        "friction" => read::<FrictionKeys>(obj, path).map(drop),
        "nonlinear_contact" => read::<NonlinearContact>(obj, path).map(drop),
        "takeup" => read::<TakeupSpec>(obj, path).map(drop),
        "drive" => read::<DriveSpec>(obj, path).map(drop),
        "start_curve" => read::<StartCurve>(obj, path).map(drop),
        "controller" => read::<SpeedController>(obj, path).map(drop),
        "follow" => read::<TorqueFollow>(obj, path).map(drop),
        "motor" => read::<Motor>(obj, path).map(drop),
        "coupling" => read::<FluidCoupling>(obj, path).map(drop),
        "brake" => read::<BrakeSpec>(obj, path).map(drop),
        "holdback" => read::<HoldbackSpec>(obj, path).map(drop),
        "idler" => read::<IdlerSpec>(obj, path).map(drop),
        "load" => read::<LoadSpec>(obj, path).map(drop),
        "solver" => read::<SolverParams>(obj, path).map(drop),
        "recording" => read::<RecordingParams>(obj, path).map(drop),
        "initial" => read::<InitialState>(obj, path).map(drop),
        other => Err(BeltError::invalid(
            "table",
            format!("{other:?}"),
            "not a table of the scene format",
        )),
    }
}

/// A scene (or part) as Python data, in the form of `beltrs.Scene.to_dict()`: dicts, lists
/// (also for `[x, y]`, which serde hands over as tuples), floats, strings, None.
pub fn to_py<'py, T: serde::Serialize>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    lists(pythonize::pythonize(py, value)?)
}

fn lists(obj: Bound<'_, PyAny>) -> PyResult<Bound<'_, PyAny>> {
    if let Ok(d) = obj.cast::<PyDict>() {
        for (k, v) in d.iter() {
            d.set_item(k, lists(v)?)?;
        }
    } else if let Ok(l) = obj.cast::<PyList>() {
        for (i, v) in l.iter().enumerate() {
            l.set_item(i, lists(v)?)?;
        }
    } else if let Ok(t) = obj.cast::<PyTuple>() {
        let items = t.iter().map(lists).collect::<PyResult<Vec<_>>>()?;
        return Ok(PyList::new(obj.py(), items)?.into_any());
    }
    Ok(obj)
}

/// The defaults of every table of the scene format, by table (`"pulley"`, `"drive"`, ...),
/// as dicts; keys without a default (required) hold None.
pub fn defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("scene", to_py(py, &Scene::default())?)?;
    d.set_item("belt", to_py(py, &BeltParams::default())?)?;
    d.set_item("pulley", to_py(py, &PulleySpec::default())?)?;
    d.set_item("friction", to_py(py, &FrictionKeys::default())?)?;
    d.set_item(
        "nonlinear_contact",
        to_py(py, &NonlinearContact::default())?,
    )?;
    d.set_item("takeup", to_py(py, &TakeupSpec::default())?)?;
    d.set_item("drive", to_py(py, &DriveSpec::default())?)?;
    let curve = to_py(py, &StartCurve::default())?;
    for key in StartCurve::REQUIRED {
        curve.set_item(key, py.None())?;
    }
    d.set_item("start_curve", curve)?;
    d.set_item("controller", to_py(py, &SpeedController::default())?)?;
    let follow = to_py(py, &TorqueFollow::default())?;
    follow.set_item("master", py.None())?; // required
    d.set_item("follow", follow)?;
    let motor = to_py(py, &Motor::default())?;
    for key in Motor::REQUIRED {
        motor.set_item(key, py.None())?;
    }
    d.set_item("motor", motor)?;
    d.set_item("coupling", to_py(py, &FluidCoupling::default())?)?;
    d.set_item("brake", to_py(py, &BrakeSpec::default())?)?;
    d.set_item("holdback", to_py(py, &HoldbackSpec::default())?)?;
    d.set_item("idler", to_py(py, &IdlerSpec::default())?)?;
    d.set_item("load", to_py(py, &LoadSpec::default())?)?;
    d.set_item("solver", to_py(py, &SolverParams::default())?)?;
    d.set_item("recording", to_py(py, &RecordingParams::default())?)?;
    d.set_item("initial", to_py(py, &InitialState::default())?)?;
    Ok(d)
}

/// Case K (Kubas 2014) as a scene dict (`crate::presets::case_k`): the drive torque's
/// ramp time (s) and the belt's pre-strain on its path (dimensionless).
#[pyfunction]
pub fn case_k_scene(
    py: Python<'_>,
    ramp_time: f64,
    preload_strain: f64,
) -> PyResult<Bound<'_, PyAny>> {
    super::guarded(|| to_py(py, &crate::presets::case_k(ramp_time, preload_strain)))
}
