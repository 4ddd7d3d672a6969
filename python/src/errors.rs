//! What crosses the boundary besides results: the core's errors as Python
//! exceptions ([`to_py`]), its notices as Python warnings ([`warn`]), a
//! Rust panic as an exception instead of a crash ([`guarded`]), and the
//! work a Python caller may watch and interrupt ([`Watch`]).

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, Ordering};

use dmpscope_core::{Error, Level, Notice};
use pyo3::exceptions::{PyFileNotFoundError, PyKeyboardInterrupt, PyUserWarning, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyString;

pyo3::create_exception!(
    dmpscope,
    DmpscopeError,
    PyValueError,
    "An error of dmpscope's core: the message names the file, topic and sample (or the \
     setting) at fault, in the CLI's words. A subclass of ValueError."
);

pyo3::create_exception!(
    dmpscope,
    DmpscopeWarning,
    PyUserWarning,
    "What dmpscope tells that is not a result: a topic or demo left out, a file cut short, \
     an optimum on the edge of the gain box (the CLI's `warning:` lines)."
);

pyo3::create_exception!(
    dmpscope,
    DmpscopeNote,
    DmpscopeWarning,
    "A notice worth knowing where nothing was lost (the CLI's `note:` lines)."
);

/// The core's error as a Python exception: a missing file as
/// `FileNotFoundError`, a cancelled computation as `KeyboardInterrupt`,
/// anything else as [`DmpscopeError`], with the core's message.
pub fn to_py(e: Error) -> PyErr {
    match &e {
        Error::Io { reason, .. } if reason.kind() == std::io::ErrorKind::NotFound => {
            PyFileNotFoundError::new_err(e.to_string())
        }
        Error::Cancelled => PyKeyboardInterrupt::new_err("cancelled"),
        _ => DmpscopeError::new_err(e.to_string()),
    }
}

/// A message of ours (an argument out of range) as [`DmpscopeError`].
pub fn invalid(message: impl Into<String>) -> PyErr {
    DmpscopeError::new_err(message.into())
}

/// Issues each notice as a Python warning (details are left out, as the
/// CLI leaves them out without `-v`): warnings and errors as
/// [`DmpscopeWarning`], notes as [`DmpscopeNote`]. `stacklevel` 1 is the
/// Python frame that called the public function (ours has no frame).
pub fn warn(py: Python<'_>, notices: &[Notice]) -> PyResult<()> {
    for n in notices {
        let category = match n.level {
            Level::Detail => continue,
            Level::Info => py.get_type::<DmpscopeNote>(),
            Level::Warning | Level::Error => py.get_type::<DmpscopeWarning>(),
        };
        let text = std::ffi::CString::new(n.text.replace('\0', " "))
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        PyErr::warn(py, &category, &text, 1)?;
    }
    Ok(())
}

/// Runs `work`, turning a panic into [`DmpscopeError`] ("internal error:
/// ..."): a bug in dmpscope never takes the interpreter down.
pub fn guarded<T>(work: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    match catch_unwind(AssertUnwindSafe(work)) {
        Ok(result) => result,
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| (*s).to_owned())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "a panic without a message".to_owned());
            Err(DmpscopeError::new_err(format!(
                "internal error (a bug in dmpscope, please report it): {what}"
            )))
        }
    }
}

/// A long computation's watcher: between pieces of work (with the GIL
/// released) it takes the GIL for a moment, runs Python's signal handlers
/// (Ctrl+C raises `KeyboardInterrupt` there) and the `progress(done,
/// total)` callback; the first exception of either sets `cancel`, which
/// stops the work, and is what the call raises.
pub struct Watch<'a> {
    cancel: &'a AtomicBool,
    progress: Option<&'a Py<PyAny>>,
    raised: Option<PyErr>,
}

impl<'a> Watch<'a> {
    /// A watcher setting `cancel` and calling `progress`, if given.
    pub fn new(cancel: &'a AtomicBool, progress: Option<&'a Py<PyAny>>) -> Self {
        Self {
            cancel,
            progress,
            raised: None,
        }
    }

    /// Called between pieces of work: signals, then the callback.
    pub fn tick(&mut self, done: usize, total: usize) {
        if self.raised.is_some() {
            return;
        }
        let outcome = Python::attach(|py| {
            py.check_signals()?;
            if let Some(callback) = self.progress {
                callback.call1(py, (done, total))?;
            }
            Ok::<(), PyErr>(())
        });
        if let Err(e) = outcome {
            self.raised = Some(e);
            self.cancel.store(true, Ordering::Relaxed);
        }
    }

    /// The exception to raise for a core error: the one a signal or the
    /// callback raised, if any, else the core's.
    pub fn error(&mut self, e: Error) -> PyErr {
        match self.raised.take() {
            Some(raised) => raised,
            None => to_py(e),
        }
    }
}

/// A Python string's text, or a `TypeError` naming `what`.
pub fn text_of(value: &Bound<'_, PyAny>, what: &str) -> PyResult<String> {
    if !value.is_instance_of::<PyString>() {
        let name = value
            .get_type()
            .name()
            .map_or_else(|_| "?".to_owned(), |n| n.to_string());
        return Err(pyo3::exceptions::PyTypeError::new_err(format!(
            "{what} must be a str, got {name}"
        )));
    }
    value.extract()
}
