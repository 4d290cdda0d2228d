//! Module-level functions of `beltrs._beltrs`: the scene schema's checks and defaults for
//! the Python dataclasses, and starting-curve evaluation.

use super::call::{guarded, to_py};
use super::scene;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A one-dimensional float array handed to Python.
type Array1<'py> = Bound<'py, PyArray1<f64>>;

/// Belt speed (m/s) and acceleration (m/s²) of a starting curve (given in the dict form of
/// `beltrs.StartCurve.to_dict()`) at each of `times` (s): two arrays.
#[pyfunction]
pub(super) fn start_curve_eval<'py>(
    py: Python<'py>,
    curve: &Bound<'py, PyAny>,
    times: Vec<f64>,
) -> PyResult<(Array1<'py>, Array1<'py>)> {
    guarded(|| {
        let curve = scene::start_curve_from_py(curve, "start_curve").map_err(to_py)?;
        let (speed, accel): (Vec<f64>, Vec<f64>) = times.iter().map(|&t| curve.evaluate(t)).unzip();
        Ok((PyArray1::from_vec(py, speed), PyArray1::from_vec(py, accel)))
    })
}

/// Check a scene in dict form against the scene schema (unknown keys, types), raising
/// `SceneError` naming the full path, the value and the rule. Values are checked when the
/// scene compiles.
#[pyfunction]
pub(super) fn check_scene(scene: &Bound<'_, PyAny>) -> PyResult<()> {
    guarded(|| scene::scene_from_py(scene).map(|_| ()).map_err(to_py))
}

/// The belt speed (m/s) the idler rolls' wrap contact sizes its circles for, in a scene
/// given in dict form (`contact::roll_wrap::scene_speed`: the design start's speed, each
/// speed-controlled drive's curve and creep speeds, each direct-on-line motor's no-load belt
/// speed; 0 if none gives one). Raises `SceneError` for a scene that does not read.
#[pyfunction]
pub(super) fn roll_wrap_speed(scene: &Bound<'_, PyAny>) -> PyResult<f64> {
    guarded(|| {
        let scene = scene::scene_from_py(scene).map_err(to_py)?;
        Ok(crate::contact::roll_wrap::scene_speed(&scene))
    })
}

/// Check `value` as the scene table `table` (`"start_curve"`, `"pulley"`, ...), naming paths
/// from `path`; raises `SceneError`.
#[pyfunction]
pub(super) fn check_scene_table(table: &str, value: &Bound<'_, PyAny>, path: &str) -> PyResult<()> {
    guarded(|| scene::check_table(table, value, path).map_err(to_py))
}

/// The rule text for an unknown key `key` among `known`: "unknown key, did you mean 'x'?
/// (known keys here: ...)", the suggestion being the scene reader's (difflib's choice).
#[pyfunction]
pub(super) fn unknown_key_rule(key: &str, known: Vec<String>) -> String {
    crate::suggest::unknown_key_rule(key, known.iter().map(String::as_str))
}

/// The defaults of every table of the scene format (`"scene"`, `"belt"`, `"pulley"`,
/// `"friction"`, `"takeup"`, `"drive"`, `"start_curve"`, `"brake"`, `"idler"`, `"load"`,
/// `"solver"`, `"recording"`), each a dict of every key; required keys hold None.
#[pyfunction]
pub(super) fn scene_defaults(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    guarded(|| scene::defaults(py))
}
