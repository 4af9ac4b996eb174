//! The `hider._hider` Python extension: the workspace's hidden-surface
//! algorithms for numpy arrays, and the screen-space entry points behind
//! `hider.mpl` (correct occlusion for matplotlib's 3D axes).
//!
//! The Python package `hider` wraps this module: it turns any numpy
//! vertex and face arrays into the contiguous `float64` and `int64` arrays
//! the functions here take, and gives them their keyword signatures and
//! docstrings. Hiders are built through `hider-plan`'s registry, scenes
//! are prepared by `hider-scene`'s front end and the camera is chosen as
//! the `hider` command line chooses it, so that an array rendered here is
//! bit for bit the command line's `--ids-out` and `--depth-out` dumps.
//!
//! Every error comes back as one Python exception carrying the command
//! line's one-line message: `MemoryError` when a hider's memory budget
//! runs out, `ValueError` for everything else the caller can fix.

mod camera;
mod cancel;
mod errors;
mod mesh;
mod pools;
mod render;
mod screen;
mod sigint;
mod surface;
mod vector;

use pyo3::prelude::*;

/// The extension module: `render`, `algorithms`, `algorithm_kinds`, `plan`,
/// the screen-space functions of `hider.mpl`, the `Cancel` token the
/// package stops them with, and `__version__` (the
/// workspace's version, which maturin also gives the Python package).
#[pymodule]
fn _hider(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(render::render, m)?)?;
    m.add_function(wrap_pyfunction!(render::algorithms, m)?)?;
    m.add_function(wrap_pyfunction!(render::algorithm_kinds, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(render::plan, m)?)?;
    m.add_function(wrap_pyfunction!(render::forget_threads_after_fork, m)?)?;
    m.add_function(wrap_pyfunction!(screen::screen_render, m)?)?;
    m.add_function(wrap_pyfunction!(screen::screen_pieces, m)?)?;
    m.add_function(wrap_pyfunction!(vector::svg, m)?)?;
    m.add_class::<cancel::PyCancel>()?;
    m.add_class::<sigint::SigintCancels>()?;
    m.add("CATCHES_SIGINT", sigint::CATCHES_SIGINT)?;
    Ok(())
}
