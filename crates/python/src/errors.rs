//! Rust errors as Python exceptions, with the command line's one-line
//! messages.

use hider_plan::{PlanError, error_line};
use pyo3::PyErr;
use pyo3::exceptions::{PyMemoryError, PyValueError};

/// Whether a scene error is a memory budget running out (a hider's
/// `max_bytes`), which Python callers expect as `MemoryError`; the other
/// limits (image size, thread count) are bad values.
fn is_memory_budget(error: &hider_scene::Error) -> bool {
    matches!(error, hider_scene::Error::Limit { what, .. }
        if what.contains("bytes") || what.contains("memory"))
}

/// A scene crate error as a Python exception.
pub fn scene_error(error: hider_scene::Error) -> PyErr {
    let line = error_line(&error);
    if is_memory_budget(&error) {
        PyMemoryError::new_err(line)
    } else {
        PyValueError::new_err(line)
    }
}

/// A plan crate error as a Python exception.
pub fn plan_error(error: PlanError) -> PyErr {
    match error {
        PlanError::Scene(e) => scene_error(e),
        other => PyValueError::new_err(error_line(&other)),
    }
}
