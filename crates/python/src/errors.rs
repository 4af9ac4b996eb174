//! Rust errors as Python exceptions, chosen by the errors' types (never by
//! their text) and worded with the Python API's keywords.

use hider_plan::{AlgoName, Knob, PlanError, error_line};
use hider_scene::Cancelled;
use pyo3::PyErr;
use pyo3::exceptions::{PyKeyboardInterrupt, PyMemoryError, PyTimeoutError, PyValueError};

/// A scene crate error as a Python exception: a memory budget that ran out
/// ([`hider_scene::Error::Budget`], a hider's `max_bytes`) is a
/// `MemoryError`; a render past its `timeout=` a `TimeoutError`, one
/// cancelled (Ctrl-C) a `KeyboardInterrupt`; every other error (a bad
/// value, a size over a limit, a camera that cannot be used) is a
/// `ValueError`.
pub fn scene_error(error: hider_scene::Error) -> PyErr {
    let line = error_line(&error);
    match error {
        hider_scene::Error::Budget { .. } => PyMemoryError::new_err(line),
        hider_scene::Error::Cancelled(Cancelled::TimedOut { .. }) => {
            PyTimeoutError::new_err(format!("{line} (the timeout= keyword, in seconds)"))
        }
        hider_scene::Error::Cancelled(Cancelled::Requested) => PyKeyboardInterrupt::new_err(line),
        _ => PyValueError::new_err(line),
    }
}

/// Hider names joined by ", ".
fn joined(algos: &[AlgoName]) -> String {
    algos
        .iter()
        .map(|a| a.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}

/// The Python keyword that sets a knob.
fn knob_keyword(knob: Knob) -> &'static str {
    match knob {
        Knob::DepthFormat => "depth format",
        Knob::DepthSource => "depth source",
        Knob::OrderedPolygons => "ordered polygons",
        Knob::MaxSplits => "split budget (max_splits)",
        Knob::MaxListLen => "fragment list length",
        Knob::Overflow => "fragment list overflow policy",
    }
}

/// A plan crate error as a Python exception, in the words of the Python
/// API (`algo=`).
pub fn plan_error(error: PlanError) -> PyErr {
    match error {
        PlanError::Scene(e) => scene_error(e),
        PlanError::UnknownHider { name, known } => PyValueError::new_err(format!(
            "unknown algo '{name}' (one of: auto, {})",
            joined(&known)
        )),
        PlanError::KnobNotApplicable {
            hider,
            knob,
            takers,
        } => PyValueError::new_err(format!(
            "the {} applies to algo {} only, not to '{hider}'",
            knob_keyword(knob),
            joined(&takers)
        )),
        PlanError::PainterBudget {
            needed,
            pairs,
            budget,
            triangles,
        } => PyMemoryError::new_err(format!(
            "the painter needs at least {needed} splits for the {pairs} interpenetrating pairs \
             in view, over its split budget of {budget} for {triangles} triangles; use the \
             regions (mode=\"regions\") or a raster image, which need no splits"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Errors map by type: a memory budget is a `MemoryError` whatever its
    /// wording, a file size over a limit is not (its message says "bytes").
    #[test]
    fn exceptions_follow_the_error_types() {
        pyo3::Python::initialize();
        pyo3::Python::attach(|py| {
            let budget = scene_error(hider_scene::Error::Budget {
                what: "scanline table",
                value: 2,
                limit: 1,
            });
            assert!(budget.is_instance_of::<PyMemoryError>(py));
            let limit = scene_error(hider_scene::Error::Limit {
                what: "OBJ file size in bytes",
                value: 2,
                limit: 1,
            });
            assert!(limit.is_instance_of::<PyValueError>(py));
            let unknown = plan_error(hider_plan::registry::find("nope").unwrap_err());
            assert!(unknown.is_instance_of::<PyValueError>(py));
            let text = unknown.value(py).to_string();
            assert!(
                text.starts_with("unknown algo 'nope' (one of: auto, zbuffer"),
                "{text}"
            );
            assert!(!text.contains("--"), "{text}");
            let late = scene_error(hider_scene::Error::Cancelled(Cancelled::TimedOut {
                timeout: std::time::Duration::from_millis(1500),
            }));
            assert!(late.is_instance_of::<PyTimeoutError>(py));
            assert_eq!(
                late.value(py).to_string(),
                "render timed out after 1.5s (the timeout= keyword, in seconds)"
            );
            let stopped = scene_error(hider_scene::Error::Cancelled(Cancelled::Requested));
            assert!(stopped.is_instance_of::<PyKeyboardInterrupt>(py));
        });
    }
}
