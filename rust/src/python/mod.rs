//! Python bindings: the only module that knows PyO3. Thin wrappers that convert arguments,
//! call the core, and convert results and errors back. No panic crosses into Python.
//!
//! Over ~600 lines on purpose: PyO3 takes one `#[pymethods]` block per class (more need
//! its `multiple-pymethods` feature and the `inventory` crate), and the Simulation class's
//! block is most of this file; errors and Ctrl-C are in call.rs, module functions in
//! functions.rs.

mod call;
mod functions;
mod scene;
mod shared;

use crate::error::BeltError;
use crate::record::{Channels, Recording, ENERGY_COLUMNS};
use crate::simulation::Simulation;
use crate::{Relaxation, StabiliseOptions};
use call::{
    guarded, interruptible, interruptible_with_progress, to_py, BeltrsError, CheckpointError,
    DivergenceError, SceneError, TimeStepError,
};
use functions::{
    check_scene, check_scene_table, roll_wrap_speed, scene_defaults, start_curve_eval,
    unknown_key_rule,
};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use shared::{Guard, Shared};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

fn array<'py>(py: Python<'py>, data: &[f64], shape: &[usize]) -> PyResult<Bound<'py, PyAny>> {
    let a = PyArray1::from_slice(py, data);
    Ok(a.reshape(shape.to_vec())?.into_any())
}

/// The engine: a compiled model, its state and the current recording.
///
/// Thread safety: the simulation sits behind a fair lock ([`shared`]). A call from a
/// second thread waits (without the GIL) for its turn, so concurrent calls run one after
/// the other and none fails or loses anything; `Simulation.run` in Python calls the core in
/// short chunks, so e.g. a checkpoint saved from another thread lands between two chunks.
#[pyclass(name = "Simulation", module = "beltrs._beltrs")]
struct PySimulation {
    inner: Shared<Simulation>,
    interrupted: AtomicBool,
}

impl PySimulation {
    fn wrap(inner: Simulation) -> Self {
        PySimulation {
            inner: Shared::new(inner),
            interrupted: AtomicBool::new(false),
        }
    }

    /// The simulation, after any call already running or waiting on it from another
    /// thread.
    fn lock(&self, py: Python<'_>) -> Guard<'_, Simulation> {
        self.inner.lock(py)
    }
}

#[pymethods]
impl PySimulation {
    /// Compile a scene given in dict form (see `beltrs.Scene.to_dict`). Ctrl-C interrupts
    /// a long compile (KeyboardInterrupt).
    #[new]
    fn new(py: Python<'_>, scene: &Bound<'_, PyAny>) -> PyResult<Self> {
        let scene = guarded(|| scene::scene_from_py(scene).map_err(to_py))?;
        let inner = interruptible(py, || Simulation::new(&scene)).into_py()?;
        Ok(Self::wrap(inner))
    }

    /// Replace the scene parameters and keep the state.
    fn set_scene(&self, py: Python<'_>, scene: &Bound<'_, PyAny>) -> PyResult<()> {
        let scene = guarded(|| scene::scene_from_py(scene).map_err(to_py))?;
        let mut sim = self.lock(py);
        let sim = &mut *sim;
        interruptible(py, || sim.set_scene(&scene)).into_py()
    }

    /// Time step in use, s.
    #[getter]
    fn dt(&self, py: Python<'_>) -> f64 {
        self.lock(py).model.dt
    }

    /// Estimated stability limit of the time step, s.
    #[getter]
    fn dt_limit(&self, py: Python<'_>) -> f64 {
        self.lock(py).model.dt_limit
    }

    /// The stiffest term, which sets the stability limit.
    #[getter]
    fn dt_cause(&self, py: Python<'_>) -> String {
        self.lock(py).model.dt_cause.clone()
    }

    /// Names of the compiled stages, in the order they run.
    #[getter]
    fn stages(&self, py: Python<'_>) -> Vec<&'static str> {
        self.lock(py)
            .model
            .stages
            .iter()
            .map(|s| s.name())
            .collect()
    }

    /// Compiled PI speed controllers per pulley: (inertia kg·m², K_p N·m·s/rad, K_i N·m/rad,
    /// droop rad/s per N·m), or None.
    #[getter]
    fn controllers(&self, py: Python<'_>) -> Vec<Option<(f64, f64, f64, f64)>> {
        self.lock(py)
            .model
            .pulleys
            .iter()
            .map(|p| p.control.map(|c| (c.inertia, c.kp, c.ki, c.droop)))
            .collect()
    }

    /// Number of belt nodes (= elements for a closed loop; one more for an open belt).
    #[getter]
    fn nodes(&self, py: Python<'_>) -> usize {
        self.lock(py).model.nodes
    }

    /// Number of belt elements: the nodes of a closed loop, one fewer for an open belt.
    #[getter]
    fn elements(&self, py: Python<'_>) -> usize {
        self.lock(py).model.elements
    }

    /// Simulated time, s.
    #[getter]
    fn time(&self, py: Python<'_>) -> f64 {
        self.lock(py).state.time
    }

    /// Steps taken.
    #[getter]
    fn step_count(&self, py: Python<'_>) -> u64 {
        self.lock(py).state.step
    }

    /// Steps the adaptive integrator (RKF45) accepted since the model was compiled.
    #[getter]
    fn accepted_steps(&self, py: Python<'_>) -> u64 {
        self.lock(py).state.accepted_steps
    }

    /// Steps the adaptive integrator (RKF45) rejected and retried since the model was
    /// compiled.
    #[getter]
    fn rejected_steps(&self, py: Python<'_>) -> u64 {
        self.lock(py).state.rejected_steps
    }

    /// Length of the initial belt path, m.
    #[getter]
    fn path_length(&self, py: Python<'_>) -> f64 {
        self.lock(py).model.path.length
    }

    /// Wrap angle on each pulley on the initial path, rad.
    #[getter]
    fn wrap_angles(&self, py: Python<'_>) -> Vec<f64> {
        self.lock(py).model.path.wrap_angles.clone()
    }

    /// Element rest lengths, m (the rigid-body belt: the belt length each joint stands for).
    #[getter]
    fn rest_length<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let sim = self.lock(py);
        PyArray1::from_vec(py, sim.model.element_rest_length())
    }

    /// Node masses, kg.
    #[getter]
    fn node_mass<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.lock(py).model.mass)
    }

    /// Node masses now (belt and material), kg.
    fn node_masses<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.lock(py).state.node_mass)
    }

    /// Each load's zone now: rows of (start, end, length) in metres of unstretched belt
    /// from node 0 (start and end: the material coordinates of the belt points nearest the
    /// loading and discharge points; length: of the zone between them), shape (loads, 3).
    fn load_zones<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let sim = self.lock(py);
        let belt = sim.model.load_belt();
        let lengths = crate::loads::zone_lengths(&sim.model.loads, &sim.state.load_edges, belt);
        let rows: Vec<f64> = sim
            .state
            .load_edges
            .iter()
            .zip(lengths)
            .flat_map(|(e, len)| [e.start, e.end, len])
            .collect();
        array(py, &rows, &[sim.state.load_edges.len(), 3])
    }

    /// Whether the last run stopped on Ctrl-C.
    #[getter]
    fn interrupted(&self) -> bool {
        self.interrupted.load(Ordering::Relaxed)
    }

    /// Relax to static equilibrium. Returns a dict with steps, residual, converged, resets
    /// and interrupted (Ctrl-C stops the relaxation at rest and returns its report).
    /// `progress`, if given, is called with the steps of the current relaxation stage
    /// about every 20 ms.
    #[pyo3(signature = (method="fire", friction=false, tolerance=1e-7, max_steps=5_000_000, progress=None))]
    fn stabilise<'py>(
        &self,
        py: Python<'py>,
        method: &str,
        friction: bool,
        tolerance: f64,
        max_steps: u64,
        progress: Option<Py<PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let method = match method {
            "fire" => Relaxation::Fire,
            "kinetic" => Relaxation::KineticEnergy,
            other => {
                return Err(SceneError::new_err(format!(
                    "method = {other:?}: unknown relaxation (known: \"fire\", \"kinetic\")"
                )))
            }
        };
        let options = StabiliseOptions {
            method,
            friction,
            tolerance,
            max_steps,
        };
        let mut sim = self.lock(py);
        let sim = &mut *sim;
        let done = interruptible_with_progress(py, progress, || sim.stabilise(&options));
        // Ctrl-C ends the relaxation with its report marked interrupted (at rest, on the
        // scene's own model); another exception from a signal handler is raised.
        let report = match (done.result, done.signal) {
            (Ok(r), None) => r,
            (Err(e), None) => return Err(to_py(e)),
            (result, Some(signal)) => {
                if !signal.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py) {
                    return Err(signal);
                }
                match result {
                    Ok(mut r) => {
                        r.interrupted = true;
                        r
                    }
                    Err(BeltError::Interrupted) => interrupted_report(),
                    Err(e) => return Err(to_py(e)),
                }
            }
        };
        let d = PyDict::new(py);
        d.set_item("steps", report.steps)?;
        d.set_item("residual", report.residual)?;
        d.set_item("converged", report.converged)?;
        d.set_item("resets", report.resets)?;
        d.set_item("interrupted", report.interrupted)?;
        d.set_item(
            "holding_torque",
            PyArray1::from_slice(py, &report.holding_torque),
        )?;
        Ok(d)
    }

    /// Start a fresh recording, sampled now and every `every` steps, keeping at most
    /// `max_samples` (≥ 2) instants: when full, every other instant is dropped and the
    /// interval doubles.
    #[pyo3(signature = (every=1, tension=true, node_position=true, node_velocity=true, max_samples=usize::MAX, energy=false, contact_forces=false))]
    #[allow(clippy::too_many_arguments)]
    fn begin_recording(
        &self,
        py: Python<'_>,
        every: u64,
        tension: bool,
        node_position: bool,
        node_velocity: bool,
        max_samples: usize,
        energy: bool,
        contact_forces: bool,
    ) -> PyResult<()> {
        if every == 0 {
            return Err(SceneError::new_err("every = 0: must be ≥ 1"));
        }
        if max_samples < 2 {
            return Err(SceneError::new_err(format!(
                "max_samples = {max_samples}: must be ≥ 2"
            )));
        }
        let channels = Channels {
            tension,
            node_position,
            node_velocity,
            energy,
            contact_forces,
        };
        self.interrupted.store(false, Ordering::Relaxed);
        self.lock(py).begin_recording(channels, every, max_samples);
        Ok(())
    }

    /// Advance `steps` steps into the current recording (GIL released). Ctrl-C stops at a
    /// whole step and raises KeyboardInterrupt (the state and recording stay consistent).
    /// A blow-up raises DivergenceError and keeps the recording.
    fn advance(&self, py: Python<'_>, steps: u64) -> PyResult<()> {
        let mut sim = self.lock(py);
        let sim = &mut *sim;
        interruptible(py, || sim.advance(steps)).into_py()
    }

    /// Advance towards simulated time `end` (s) into the current recording, at most
    /// `max_steps` steps (GIL released; callers keep chunks short so that other threads get
    /// their turn). Returns True once the state is at `end` exactly (whole steps, then one
    /// shortened step). Ctrl-C stops at a whole step and raises KeyboardInterrupt (the state
    /// and recording stay consistent). A blow-up raises DivergenceError and keeps the
    /// recording.
    fn advance_to(&self, py: Python<'_>, end: f64, max_steps: u64) -> PyResult<bool> {
        let mut sim = self.lock(py);
        let sim = &mut *sim;
        interruptible(py, || sim.advance_to(end, max_steps)).into_py()
    }

    /// Close the current recording: sample the final state (the end of the run), or, when
    /// `interrupted`, only if it is on the recording grid. `interrupted` is stored for the
    /// `interrupted` getter.
    #[pyo3(signature = (interrupted=false))]
    fn end_recording(&self, py: Python<'_>, interrupted: bool) -> PyResult<()> {
        self.interrupted.store(interrupted, Ordering::Relaxed);
        let mut sim = self.lock(py);
        guarded(|| {
            if interrupted {
                sim.end_recording_on_grid().map_err(to_py)
            } else {
                sim.end_recording().map_err(to_py)
            }
        })
    }

    /// Steps between recorded instants now (doubled at each decimation).
    #[getter]
    fn record_every(&self, py: Python<'_>) -> u64 {
        self.lock(py).record_every()
    }

    /// Bytes one instant would take with these channels.
    #[pyo3(signature = (tension, node_position, node_velocity, energy=false, contact_forces=false))]
    fn sample_bytes(
        &self,
        py: Python<'_>,
        tension: bool,
        node_position: bool,
        node_velocity: bool,
        energy: bool,
        contact_forces: bool,
    ) -> usize {
        let sim = self.lock(py);
        let m = &sim.model;
        let r = Recording::new(
            Channels {
                tension,
                node_position,
                node_velocity,
                energy,
                contact_forces,
            },
            m.nodes,
            m.pulleys.len(),
            m.idlers.len(),
        );
        r.bytes_per_sample()
    }

    /// Bytes allocated by the recording buffers (capacity).
    fn recording_allocated_bytes(&self, py: Python<'_>) -> usize {
        self.lock(py).recording.allocated_bytes()
    }

    /// Save the scene and the full state to `path` atomically (see `beltrs.checkpoint`).
    fn save_checkpoint(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let sim = self.lock(py);
        let sim = &*sim;
        guarded(|| {
            py.detach(|| crate::checkpoint::save(sim, &path))
                .map_err(to_py)
        })
    }

    /// A simulation read back from the checkpoint at `path`. With `scene` (dict form) the
    /// checkpoint must hold exactly that scene. Ctrl-C interrupts it (KeyboardInterrupt).
    #[staticmethod]
    #[pyo3(signature = (path, scene=None))]
    fn load_checkpoint(
        py: Python<'_>,
        path: PathBuf,
        scene: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let expected = match scene {
            Some(d) => Some(guarded(|| scene::scene_from_py(d).map_err(to_py))?),
            None => None,
        };
        let inner = interruptible(py, || match &expected {
            Some(s) => crate::checkpoint::load_for(&path, s),
            None => crate::checkpoint::load(&path),
        })
        .into_py()?;
        Ok(Self::wrap(inner))
    }

    /// The scene of the compiled model, in dict form (the keys of `Scene.to_dict()`).
    fn scene_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        scene::to_py(py, &self.lock(py).model.scene)
    }

    /// Advance `steps` steps without recording. Ctrl-C stops at a whole step and raises
    /// KeyboardInterrupt (the state stays consistent).
    fn step(&self, py: Python<'_>, steps: u64) -> PyResult<()> {
        let mut sim = self.lock(py);
        let sim = &mut *sim;
        interruptible(py, || sim.step(steps)).into_py()
    }

    /// The current recording as a dict of NumPy arrays (copies; the recording stays).
    fn recording<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let rec = self.lock(py).recording.clone();
        recording_dict(py, rec)
    }

    /// The current recording as a dict of NumPy arrays that take over its buffers (no
    /// copy); the recording is left empty, so its memory is held once, by the arrays.
    fn take_recording<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let rec = self.lock(py).recording.take();
        recording_dict(py, rec)
    }

    /// The current state as a dict of NumPy arrays (copies).
    fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let sim = self.lock(py);
        let s = &sim.state;
        let d = PyDict::new(py);
        let n = s.position.len();
        let flat =
            |v: &[nalgebra::Vector2<f64>]| v.iter().flat_map(|p| [p.x, p.y]).collect::<Vec<f64>>();
        d.set_item("time", s.time)?;
        d.set_item("step", s.step)?;
        d.set_item("node_position", array(py, &flat(&s.position), &[n, 2])?)?;
        d.set_item(
            "node_velocity_half_step",
            array(py, &flat(&s.velocity), &[n, 2])?,
        )?;
        d.set_item("pulley_speed", PyArray1::from_slice(py, &s.pulley_omega))?;
        d.set_item("pulley_angle", PyArray1::from_slice(py, &s.pulley_angle))?;
        d.set_item("takeup_travel", PyArray1::from_slice(py, &s.takeup_travel))?;
        d.set_item("takeup_speed", PyArray1::from_slice(py, &s.takeup_speed))?;
        d.set_item("idler_speed", PyArray1::from_slice(py, &s.idler_omega))?;
        d.set_item("drive_work", s.drive_work)?;
        // The rigid-body belt's body angles (rad) and spins (rad/s); empty for the node belt.
        d.set_item("body_angle", PyArray1::from_slice(py, &s.body_angle))?;
        d.set_item("body_spin", PyArray1::from_slice(py, &s.body_spin))?;
        let windows: Vec<f64> = s
            .pulley_window
            .iter()
            .flat_map(|w| [w.first as f64, w.len as f64])
            .collect();
        d.set_item(
            "pulley_window",
            array(py, &windows, &[s.pulley_window.len(), 2])?,
        )?;
        d.set_item("idler_element", s.idler_element.clone())?;
        // Creep friction's memory: Δ (m) of each node on each pulley, [nodes, pulleys]
        // (empty without creep friction).
        let p = if s.creep.is_empty() {
            0
        } else {
            s.pulley_omega.len()
        };
        d.set_item(
            "creep_displacement",
            array(py, &s.creep, &[if p == 0 { 0 } else { n }, p])?,
        )?;
        Ok(d)
    }

    /// Element tensions at the current state, N.
    fn tensions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let mut sim = self.lock(py);
        let t = guarded(|| Ok(sim.tensions().to_vec()))?;
        Ok(PyArray1::from_vec(py, t))
    }

    /// Net force on each node at the current state, N, shape (n_nodes, 2).
    fn forces<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let mut sim = self.lock(py);
        let f: Vec<f64> = guarded(|| Ok(sim.forces().iter().flat_map(|p| [p.x, p.y]).collect()))?;
        let n = f.len() / 2;
        array(py, &f, &[n, 2])
    }

    /// Energies of the current state, J.
    fn energies<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let mut sim = self.lock(py);
        let e = guarded(|| Ok(sim.current_energies()))?;
        let d = PyDict::new(py);
        let values = [
            e.kinetic,
            e.strain,
            e.bending,
            e.gravity,
            e.contact,
            e.total(),
            e.drive_work,
        ];
        for (k, v) in ENERGY_COLUMNS.iter().zip(values) {
            d.set_item(*k, v)?;
        }
        Ok(d)
    }

    /// Turn per-stage timing on (zeroed) or off.
    fn set_profiling(&self, py: Python<'_>, on: bool) {
        self.lock(py).set_profiling(on);
    }

    /// Seconds spent in each stage since profiling was turned on (empty when off).
    fn profile<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let sim = self.lock(py);
        let d = PyDict::new(py);
        if let Some(p) = &sim.profile {
            for (s, t) in sim.model.stages.iter().zip(p) {
                d.set_item(s.name(), *t)?;
            }
        }
        Ok(d)
    }
}

/// The report of a relaxation that a signal stopped inside a recompile (of the contact
/// continuation): unconverged, residual unknown.
fn interrupted_report() -> crate::StabiliseReport {
    crate::StabiliseReport {
        steps: 0,
        residual: f64::NAN,
        converged: false,
        resets: 0,
        interrupted: true,
        holding_torque: Vec::new(),
    }
}

/// A recording as a dict of NumPy arrays that own its buffers (no copy).
fn recording_dict(py: Python<'_>, r: Recording) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    let t = r.len();
    let (n, p, q, e) = (r.nodes, r.pulleys, r.idlers, r.elements);
    let own = |v: Vec<f64>, shape: &[usize]| -> PyResult<Bound<'_, PyAny>> {
        Ok(PyArray1::from_vec(py, v)
            .reshape(shape.to_vec())?
            .into_any())
    };
    let channels = r.channels;
    let Recording {
        time,
        tension,
        node_position,
        node_velocity,
        pulley_position,
        takeup_travel,
        pulley_speed,
        friction_torque,
        drive_torque,
        brake_torque,
        pulley_force,
        normal_force,
        friction_force,
        contact_nodes,
        slipping_nodes,
        motor_speed,
        idler_force,
        idler_speed,
        energy,
        contact_normal,
        contact_friction,
        contact_angle,
        ..
    } = r;
    d.set_item("time", PyArray1::from_vec(py, time))?;
    if channels.tension {
        d.set_item("tension", own(tension, &[t, e])?)?;
    }
    if channels.node_position {
        d.set_item("node_position", own(node_position, &[t, n, 2])?)?;
    }
    if channels.node_velocity {
        d.set_item("node_velocity", own(node_velocity, &[t, n, 2])?)?;
    }
    d.set_item("pulley_position", own(pulley_position, &[t, p, 2])?)?;
    d.set_item("takeup_travel", own(takeup_travel, &[t, p])?)?;
    d.set_item("pulley_speed", own(pulley_speed, &[t, p])?)?;
    d.set_item("friction_torque", own(friction_torque, &[t, p])?)?;
    d.set_item("drive_torque", own(drive_torque, &[t, p])?)?;
    d.set_item("brake_torque", own(brake_torque, &[t, p])?)?;
    d.set_item("pulley_force", own(pulley_force, &[t, p, 2])?)?;
    d.set_item("normal_force", own(normal_force, &[t, p])?)?;
    d.set_item("friction_force", own(friction_force, &[t, p])?)?;
    d.set_item("contact_nodes", own(contact_nodes, &[t, p])?)?;
    d.set_item("slipping_nodes", own(slipping_nodes, &[t, p])?)?;
    d.set_item("motor_speed", own(motor_speed, &[t, p])?)?;
    d.set_item("idler_force", own(idler_force, &[t, q])?)?;
    d.set_item("idler_speed", own(idler_speed, &[t, q])?)?;
    if channels.energy {
        d.set_item("energy", own(energy, &[t, ENERGY_COLUMNS.len()])?)?;
    }
    if channels.contact_forces {
        d.set_item("contact_normal", own(contact_normal, &[t, p, n])?)?;
        d.set_item("contact_friction", own(contact_friction, &[t, p, n])?)?;
        d.set_item("contact_angle", own(contact_angle, &[t, p, n])?)?;
    }
    d.set_item("energy_columns", ENERGY_COLUMNS.to_vec())?;
    Ok(d)
}

/// The compiled extension module.
#[pymodule]
fn _beltrs(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PySimulation>()?;
    m.add_function(wrap_pyfunction!(start_curve_eval, m)?)?;
    m.add_function(wrap_pyfunction!(check_scene, m)?)?;
    m.add_function(wrap_pyfunction!(scene_defaults, m)?)?;
    m.add_function(wrap_pyfunction!(scene::case_k_scene, m)?)?;
    m.add_function(wrap_pyfunction!(check_scene_table, m)?)?;
    m.add_function(wrap_pyfunction!(unknown_key_rule, m)?)?;
    m.add_function(wrap_pyfunction!(roll_wrap_speed, m)?)?;
    m.add("BeltrsError", m.py().get_type::<BeltrsError>())?;
    m.add("SceneError", m.py().get_type::<SceneError>())?;
    m.add("TimeStepError", m.py().get_type::<TimeStepError>())?;
    m.add("DivergenceError", m.py().get_type::<DivergenceError>())?;
    m.add("CheckpointError", m.py().get_type::<CheckpointError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add(
        "DEFAULT_CONTACT_DAMPING_RATIO",
        crate::scene::DEFAULT_CONTACT_DAMPING_RATIO,
    )?;
    Ok(())
}
