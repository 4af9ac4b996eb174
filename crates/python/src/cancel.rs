//! The cancel token as a Python object: the package keeps one per thread
//! that renders, hands it to every call, cancels it on Ctrl-C and gives it
//! the `timeout=` of each call.

use std::time::Duration;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// `hider._hider.Cancel`: a [`hider_scene::Cancel`] that Python can hold.
/// The package's private machinery (`hider._interruptible`), not API.
#[pyclass(name = "Cancel", module = "hider._hider", frozen, from_py_object)]
#[derive(Clone, Copy)]
pub struct PyCancel(pub hider_scene::Cancel);

#[pymethods]
impl PyCancel {
    /// A live token, not cancelled, without a deadline.
    #[new]
    fn new() -> Self {
        Self(hider_scene::Cancel::new())
    }

    /// Stops the render running with this token at its next poll.
    fn cancel(&self) {
        self.0.cancel();
    }

    /// Clears the cancel and the deadline, for the next call.
    fn reset(&self) {
        self.0.reset();
    }

    /// Gives the token a deadline `seconds` from now, or none (`None`).
    #[pyo3(signature = (seconds))]
    fn set_timeout(&self, seconds: Option<f64>) -> PyResult<()> {
        self.arm(seconds)
    }

    /// Whether `cancel` was called since the last `reset`.
    fn cancelled(&self) -> bool {
        self.0.check() == Err(hider_scene::Cancelled::Requested)
    }
}

impl PyCancel {
    /// Gives the token a deadline `seconds` from now, or none: the
    /// `timeout=` of a call, checked.
    pub fn arm(&self, seconds: Option<f64>) -> PyResult<()> {
        let timeout = seconds
            .map(|s| {
                Duration::try_from_secs_f64(s).map_err(|_| {
                    PyValueError::new_err(format!(
                        "timeout must be a number of seconds >= 0, got {s}"
                    ))
                })
            })
            .transpose()?;
        self.0.set_timeout(timeout);
        Ok(())
    }
}

/// The token of an optional `cancel` argument (the never-cancelled one for
/// `None`).
pub fn token(cancel: Option<PyCancel>) -> hider_scene::Cancel {
    cancel.map(|c| c.0).unwrap_or_default()
}
