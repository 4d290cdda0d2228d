//! How a binding calls the core: the Python exception classes and the mapping of core
//! errors onto them, Rust panics caught at the boundary (an internal `BeltrsError`, never a
//! crash), and long calls run without the GIL while Ctrl-C is polled.

use crate::error::{BeltError, BeltResult};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::{Arc, Mutex, PoisonError};

create_exception!(
    _beltrs,
    BeltrsError,
    PyException,
    "Base class of every beltrs error."
);
create_exception!(
    _beltrs,
    SceneError,
    BeltrsError,
    "A scene parameter is invalid; the message names the field, the value and the rule."
);
create_exception!(
    _beltrs,
    TimeStepError,
    SceneError,
    "The requested time step exceeds the explicit stability limit."
);
create_exception!(
    _beltrs,
    DivergenceError,
    BeltrsError,
    "The state became non-finite during a run; results recorded before are kept."
);

create_exception!(
    _beltrs,
    CheckpointError,
    BeltrsError,
    "A checkpoint cannot be written, read or resumed; the message names the file and the problem."
);

pub(super) fn to_py(err: BeltError) -> PyErr {
    let msg = err.to_string();
    match err {
        BeltError::InvalidParameter { .. } => SceneError::new_err(msg),
        BeltError::TimeStepTooLarge { .. } => TimeStepError::new_err(msg),
        BeltError::Diverged { .. } => DivergenceError::new_err(msg),
        BeltError::Checkpoint { .. } => CheckpointError::new_err(msg),
        BeltError::Usage(_) => BeltrsError::new_err(msg),
        BeltError::Interrupted => {
            pyo3::exceptions::PyKeyboardInterrupt::new_err("interrupted (beltrs)")
        }
    }
}

/// What an interruptible call ended with: the core's result, and the exception a Python
/// signal handler raised while it ran (usually `KeyboardInterrupt`), if any.
pub(super) struct Interruptible<T> {
    pub(super) result: BeltResult<T>,
    pub(super) signal: Option<PyErr>,
}

impl<T> Interruptible<T> {
    /// The result, with a caught signal taking precedence (re-raised as Python raised it).
    pub(super) fn into_py(self) -> PyResult<T> {
        match self.signal {
            Some(e) => Err(e),
            None => self.result.map_err(to_py),
        }
    }
}

/// Run `f` without the GIL, with an interrupt hook that takes the GIL about every
/// [`crate::interrupt::POLL_INTERVAL`] and runs Python's signal handlers: Ctrl-C (or any
/// handler that raises) stops `f` at the next whole step or element.
pub(super) fn interruptible<T: Send>(
    py: Python<'_>,
    f: impl FnOnce() -> BeltResult<T> + Send,
) -> Interruptible<T> {
    interruptible_with_progress(py, None, f)
}

/// [`interruptible`], also calling `progress(done)` at each poll with what the core last
/// reported ([`crate::interrupt::report`]); an exception from it is ignored, except a
/// `KeyboardInterrupt`, which stops the call like one from the signal check.
pub(super) fn interruptible_with_progress<T: Send>(
    py: Python<'_>,
    progress: Option<Py<PyAny>>,
    f: impl FnOnce() -> BeltResult<T> + Send,
) -> Interruptible<T> {
    let caught: Arc<Mutex<Option<PyErr>>> = Arc::new(Mutex::new(None));
    let hook_caught = caught.clone();
    let hook = move || {
        Python::attach(|py| {
            // A Ctrl-C may land in the callback's Python code: it must not be lost.
            let shown = match &progress {
                Some(callback) => callback.call1(py, (crate::interrupt::reported(),)).err(),
                None => None,
            };
            if let Some(e) = shown {
                if e.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py) {
                    *hook_caught.lock().unwrap_or_else(PoisonError::into_inner) = Some(e);
                    return true;
                }
            }
            match py.check_signals() {
                Ok(()) => false,
                Err(e) => {
                    *hook_caught.lock().unwrap_or_else(PoisonError::into_inner) = Some(e);
                    true
                }
            }
        })
    };
    let result = py.detach(move || {
        match catch_unwind(AssertUnwindSafe(|| crate::interrupt::with_hook(hook, f))) {
            Ok(r) => Ok(r),
            Err(payload) => Err(panic_message(payload)),
        }
    });
    let signal = caught.lock().unwrap_or_else(PoisonError::into_inner).take();
    match result {
        Ok(result) => Interruptible { result, signal },
        Err(what) => Interruptible {
            result: Err(BeltError::Usage(what.clone())),
            signal: Some(internal_error(&what)),
        },
    }
}

pub(super) fn panic_message(payload: Box<dyn std::any::Any + Send>) -> String {
    payload
        .downcast_ref::<String>()
        .cloned()
        .or_else(|| payload.downcast_ref::<&str>().map(|s| s.to_string()))
        .unwrap_or_else(|| "unknown panic".into())
}

pub(super) fn internal_error(what: &str) -> PyErr {
    BeltrsError::new_err(format!("internal error in beltrs (please report): {what}"))
}

/// Run `f`, turning a Rust panic into a `BeltrsError` instead of crossing into Python.
pub(super) fn guarded<T>(f: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(r) => r,
        Err(payload) => Err(internal_error(&panic_message(payload))),
    }
}
