//! `hider.render`: a mesh from numpy arrays through any registered hider,
//! as the `hider render` command line does it.

use glam::DVec3;
use hider_geom::{Camera, Projection};
use hider_plan::{HiderConfig, registry};
use hider_scene::frame::id_to_i32;
use hider_scene::{Frame, PrepareOptions, Scene, View, fit_camera, prepare};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::errors::{plan_error, scene_error};
use crate::mesh::scene_from_arrays;

/// The ids (`-1` for background) and window depths (`1.0` for background)
/// of a frame, as two `(height, width)` arrays.
pub type Buffers<'py> = (Bound<'py, PyArray2<i32>>, Bound<'py, PyArray2<f32>>);

/// The camera overrides a caller gives; `None` keeps the fit camera's.
#[derive(Clone, Copy, Debug, Default)]
pub struct CameraArgs {
    eye: Option<[f64; 3]>,
    target: Option<[f64; 3]>,
    up: Option<[f64; 3]>,
    fovy: Option<f64>,
    near: Option<f64>,
    far: Option<f64>,
}

impl CameraArgs {
    /// The scene's camera (the fit camera for arrays) with the overrides
    /// applied: the command line's rule for `--eye`, `--fovy` and the rest.
    fn camera(&self, scene: &Scene) -> Camera {
        let mut c = scene.camera.unwrap_or_else(|| fit_camera(scene));
        c.eye = self.eye.map_or(c.eye, DVec3::from_array);
        c.target = self.target.map_or(c.target, DVec3::from_array);
        c.up = self.up.map_or(c.up, DVec3::from_array);
        if let Projection::Perspective {
            fovy_degrees,
            near,
            far,
        } = &mut c.projection
        {
            *fovy_degrees = self.fovy.unwrap_or(*fovy_degrees);
            *near = self.near.unwrap_or(*near);
            *far = self.far.unwrap_or(*far);
        }
        c
    }
}

/// Checks the thread count as the command line does.
fn check_threads(threads: usize) -> PyResult<()> {
    if threads == 0 || threads > 1024 {
        return Err(PyValueError::new_err(format!(
            "threads must be 1 to 1024, got {threads}"
        )));
    }
    Ok(())
}

/// Renders `scene` for `view` with the registered hider `algo` on
/// `threads` threads: the command line's path from the model to its dumps
/// (the registry's hider, the f64 front end, parallel above one thread).
pub fn render_scene(scene: &Scene, view: &View, algo: &str, threads: usize) -> PyResult<Frame> {
    check_threads(threads)?;
    let config = HiderConfig::default().with_threads(threads);
    let entry = registry::find(algo).map_err(plan_error)?;
    let options = PrepareOptions::default().with_parallel(threads > 1);
    let run = || -> hider_plan::Result<Frame> {
        let mut hider = entry.build(&config)?;
        let screen = prepare(scene, view, &options)?;
        let mut frame = Frame::new(view.viewport.width, view.viewport.height)?;
        hider.render(&screen, &mut frame)?;
        Ok(frame)
    };
    let result = if threads > 1 {
        // A pool of the caller's size for this call only: the command line
        // sizes rayon's global pool, which a library must leave alone.
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| PyValueError::new_err(format!("cannot start the thread pool: {e}")))?;
        pool.install(run)
    } else {
        run()
    };
    result.map_err(plan_error)
}

/// A frame's ids and depths as numpy arrays of shape `(height, width)`.
pub fn buffers(py: Python<'_>, frame: Frame) -> PyResult<Buffers<'_>> {
    let shape = (frame.height() as usize, frame.width() as usize);
    let ids: Vec<i32> = frame.ids.iter().map(|&id| id_to_i32(id)).collect();
    let shape_error = |e: numpy::ndarray::ShapeError| PyValueError::new_err(e.to_string());
    let ids = Array2::from_shape_vec(shape, ids).map_err(shape_error)?;
    let depth = Array2::from_shape_vec(shape, frame.depth).map_err(shape_error)?;
    Ok((ids.into_pyarray(py), depth.into_pyarray(py)))
}

/// Renders the mesh of `vertices` and `faces`; see the Python wrapper
/// `hider.render` for the arguments.
#[pyfunction]
#[pyo3(signature = (vertices, faces, width, height, eye, target, up, fovy, near, far, algo, threads))]
#[expect(
    clippy::too_many_arguments,
    reason = "the keyword arguments of the Python function, one for one"
)]
pub fn render<'py>(
    py: Python<'py>,
    vertices: PyReadonlyArray2<'py, f64>,
    faces: PyReadonlyArray2<'py, i64>,
    width: u32,
    height: u32,
    eye: Option<[f64; 3]>,
    target: Option<[f64; 3]>,
    up: Option<[f64; 3]>,
    fovy: Option<f64>,
    near: Option<f64>,
    far: Option<f64>,
    algo: &str,
    threads: usize,
) -> PyResult<Buffers<'py>> {
    let scene = scene_from_arrays(&vertices, &faces)?;
    let args = CameraArgs {
        eye,
        target,
        up,
        fovy,
        near,
        far,
    };
    let view = View::new(args.camera(&scene), width, height).map_err(scene_error)?;
    let frame = py.detach(|| render_scene(&scene, &view, algo, threads))?;
    buffers(py, frame)
}

/// The names of the registered hiders, in the registry's order.
#[pyfunction]
pub fn algorithms() -> Vec<&'static str> {
    registry::names()
}
