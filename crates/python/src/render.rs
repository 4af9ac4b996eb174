//! `hider.render`: a mesh from numpy arrays through any registered hider,
//! as the `hider render` command line does it.

use std::cell::RefCell;

use hider_plan::{HiderConfig, Planned, RenderOptions, auto, registry};
use hider_scene::{
    Cancel, DynHider, Frame, FrameBuffers, PixelSurface, PrepareOptions, Scene, ScreenScene,
    SurfaceOutputs, View, surface_at_pixels,
};
use numpy::PyArray2;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::camera::CameraArgs;
use crate::cancel::{PyCancel, token};
use crate::errors::{plan_error, scene_error};
use crate::mesh::{ArrayScene, Faces, Vertices, scene_from_arrays};
use crate::pools::pool;
use crate::surface::{Surface, surface_arrays};

/// The ids (`-1` for background) and window depths (`1.0` for background)
/// of a frame, as two `(height, width)` arrays.
pub type Buffers<'py> = (Bound<'py, PyArray2<i32>>, Bound<'py, PyArray2<f32>>);

/// Checks the thread count as the command line does.
fn check_threads(threads: usize) -> PyResult<()> {
    if threads == 0 || threads > 1024 {
        return Err(PyValueError::new_err(format!(
            "threads must be 1 to 1024, got {threads}"
        )));
    }
    Ok(())
}

/// What a render leaves for [`buffers`]: the frame's ids and depths,
/// taken out of the workspace's frame (which gets recycled memory in their
/// place, see [`take_frame`]), and the frame's `[height, width]`.
pub struct Rendered {
    /// Ids as the frame holds them ([`hider_scene::NO_ID`] for none).
    ids: Vec<u32>,
    /// Window depths.
    depth: Vec<f32>,
    /// The frame's `[height, width]`.
    shape: [usize; 2],
}

/// The memory of the arrays `hider.render` returns: the frame's own id
/// and depth buffers, handed to numpy without a copy. When numpy frees
/// both arrays the buffers go back to [`RECYCLED`] for a later frame of
/// the same size.
///
/// Why: a frame loop (`ids, depth = hider.render(...)` in a loop) used to
/// get fresh arrays every call, 8 MB at 1024 x 1024, copied from the
/// workspace's frame into memory the kernel had to fault in and zero
/// first: on the spider that was half of the call (1.1 ms against the
/// frame's 0.56). Now a frame is read back straight into memory that is
/// already mapped, and nothing is copied.
#[pyclass(frozen)]
struct FrameMemory {
    ids: Vec<u32>,
    depth: Vec<f32>,
}

impl Drop for FrameMemory {
    fn drop(&mut self) {
        let ids = std::mem::take(&mut self.ids);
        let depth = std::mem::take(&mut self.depth);
        let mut recycled = RECYCLED.lock().unwrap_or_else(|e| e.into_inner());
        // Two sets cover a loop that rebinds its arrays (the previous
        // frame's are freed after the next call returns); more would only
        // hold memory. The newest is kept: it is the likeliest to be in
        // cache still.
        if recycled.len() >= 2 {
            recycled.remove(0);
        }
        recycled.push((ids, depth));
    }
}

/// Id and depth buffers of frames whose arrays numpy has freed, oldest
/// first, for the next frames' read-back ([`refill_frame`]).
static RECYCLED: std::sync::Mutex<Vec<(Vec<u32>, Vec<f32>)>> = std::sync::Mutex::new(Vec::new());

/// Takes `frame`'s ids and depths out for numpy, leaving the frame without
/// them until [`refill_frame`] gives it buffers for its next render.
fn take_frame(frame: &mut Frame) -> Rendered {
    Rendered {
        ids: std::mem::take(&mut frame.ids),
        depth: std::mem::take(&mut frame.depth),
        shape: [frame.height() as usize, frame.width() as usize],
    }
}

/// Gives `frame` id and depth buffers of its size, right before a render,
/// when [`take_frame`] took its own: the most recently freed set of that
/// size (or new ones). Every render writes all of the ids and depths it
/// is asked for, so what they held does not matter.
///
/// Why at the next render and the newest set: a caller that is done with
/// a frame's arrays before the next call (`visible_faces`, a loop that
/// reduces each frame to a few numbers) then renders into the same 8 MB
/// every time (at 1024 x 1024), still in the last-level cache, where
/// handing over a set at the end of each call cycled through two.
fn refill_frame(frame: &mut Frame) {
    let n = frame.width() as usize * frame.height() as usize;
    if frame.ids.len() == n && frame.depth.len() == n {
        return;
    }
    let spare = {
        let mut recycled = RECYCLED.lock().unwrap_or_else(|e| e.into_inner());
        recycled
            .iter()
            .rposition(|(i, d)| i.len() == n && d.len() == n)
            .map(|k| recycled.remove(k))
    };
    (frame.ids, frame.depth) = spare.unwrap_or_else(|| {
        (
            vec![hider_scene::NO_ID; n],
            vec![hider_scene::frame::BACKGROUND_DEPTH; n],
        )
    });
}

/// A hider with its frame and screen scene, kept from one call to the next
/// on the thread that made them, as a frame loop keeps them: at 1024 x 1024
/// allocating (and the kernel zeroing) the frame and the hider's scratch
/// buffers again would cost more than many renders.
struct Workspace {
    algo: String,
    threads: usize,
    /// The token the hider polls: the calling thread's, the same at every
    /// call (the package re-arms it), so the workspace is kept.
    cancel: Cancel,
    hider: Box<dyn DynHider>,
    frame: Frame,
}

thread_local! {
    /// This thread's last hider and frame.
    static WORKSPACE: RefCell<Option<Workspace>> = const { RefCell::new(None) };
}

/// The frame of a workspace: Python returns the ids and depths, so the
/// colour is not asked for, and is allocated without being written
/// ([`Frame::new_for`]): the tiled z-buffer never touches it (1 GB at
/// 16384 x 16384), a hider that resolves colour anyway still may.
fn workspace_frame(width: u32, height: u32) -> hider_scene::Result<Frame> {
    Frame::new_for(width, height, FrameBuffers::IDS_DEPTH)
}

/// Renders with this thread's workspace, made anew when the hider, the
/// thread count or the cancel token differs from the last call's.
fn render_with_workspace(
    scene: &Scene,
    view: &View,
    entry: &registry::Entry,
    (threads, cancel): (usize, Cancel),
) -> hider_plan::Result<Rendered> {
    WORKSPACE.with_borrow_mut(|slot| {
        let (width, height) = (view.viewport.width, view.viewport.height);
        let reuse = slot
            .as_ref()
            .is_some_and(|w| w.algo == entry.name && w.threads == threads && w.cancel == cancel);
        if !reuse {
            // Drop the old workspace first: its memory is reused.
            *slot = None;
            let config = HiderConfig::default()
                .with_threads(threads)
                .with_cancel(cancel);
            let hider = entry.build(&config)?;
            // A size over the hider's memory budget is refused before the
            // frame is allocated (at 16384 x 16384, gigabytes).
            hider.check_size(width, height)?;
            *slot = Some(Workspace {
                algo: entry.name.to_owned(),
                threads,
                cancel,
                hider,
                frame: workspace_frame(width, height)?,
            });
        }
        let ws = slot.as_mut().expect("the workspace was just made");
        if ws.frame.width() != width || ws.frame.height() != height {
            ws.hider.check_size(width, height)?;
            // A new frame, not `resize`, which would write the colour
            // too; the old frame's memory is given back first.
            ws.frame = workspace_frame(1, 1)?;
            ws.frame = workspace_frame(width, height)?;
        }
        refill_frame(&mut ws.frame);
        let options = PrepareOptions::default()
            .with_parallel(threads > 1)
            .with_cancel(cancel);
        // The hider's whole pipeline, as `hider render --repeat` times it:
        // the tiled z-buffer runs its lean depth-only front end, which
        // keeps the shared front end's numbers bit for bit.
        let mut screen = empty_screen(view);
        let result = ws
            .hider
            .render_scene(scene, view, &options, &mut screen, &mut ws.frame);
        if let Err(e) = result {
            // A failed render may leave the hider's state half built.
            *slot = None;
            return Err(e.into());
        }
        Ok(take_frame(&mut ws.frame))
    })
}

/// In a forked child, on the thread that forked (the package calls it
/// from `os.register_at_fork`): forgets this thread's pool and workspace,
/// whose worker threads were not copied into the child (a render handed
/// to them would wait forever), without dropping them (dropping a pool
/// signals threads that are not there). The memory stays the parent's
/// copy, unused.
#[pyfunction]
pub fn forget_threads_after_fork() {
    crate::pools::forget_after_fork();
    if let Some(workspace) = WORKSPACE.with_borrow_mut(Option::take) {
        std::mem::forget(workspace);
    }
}

/// The name `algo` asks the planner to choose ([`plan_scene`]), as the
/// command line's `--algo auto`.
pub const AUTO: &str = "auto";

/// What the planner chooses for `scene` seen through `view` when only the
/// ids and depths are wanted (no shading, no anti-aliasing, no vector
/// output), as `hider render --algo auto` would for that request. The
/// pair searches, which decide only the painter plans and take seconds on
/// large scenes, are left out as the command line leaves them out.
pub fn plan_scene(
    scene: &Scene,
    view: &View,
    threads: usize,
    cancel: Cancel,
) -> hider_plan::Result<Planned> {
    let options = RenderOptions::default()
        .with_cancel(cancel)
        .with_size(view.viewport.width, view.viewport.height)
        .with_camera(Some(view.camera))
        .with_shading(false)
        .with_pair_searches(false)
        .with_prepare(
            PrepareOptions::default()
                .with_parallel(threads > 1)
                .with_cancel(cancel),
        );
    auto(scene, &options)
}

/// Renders `scene` for `view` with the registered hider `algo` on
/// `threads` threads: the command line's path from the model to its dumps
/// (the registry's hider, the f64 front end, parallel above one thread).
/// `algo` [`AUTO`] renders with the planner's choice ([`plan_scene`]),
/// which gives the same buffers as naming that hider. `cancel` stops it
/// (`KeyboardInterrupt`, or `TimeoutError` past its deadline).
pub fn render_scene(
    scene: &Scene,
    view: &View,
    algo: &str,
    (threads, cancel): (usize, Cancel),
) -> PyResult<Rendered> {
    check_threads(threads)?;
    let planned;
    let algo = if algo == AUTO {
        planned = plan_scene(scene, view, threads, cancel).map_err(plan_error)?;
        planned.plan.algo
    } else {
        algo
    };
    let entry = registry::find(algo).map_err(plan_error)?;
    let result = if threads > 1 {
        pool(threads)?.install(|| render_with_workspace(scene, view, &entry, (threads, cancel)))
    } else {
        render_with_workspace(scene, view, &entry, (threads, cancel))
    };
    result.map_err(plan_error)
}

/// An empty screen scene for `view`, for
/// [`DynHider::render_scene`] to fill
/// (or to leave as it is, for a hider with a front end of its own).
fn empty_screen(view: &View) -> ScreenScene {
    ScreenScene::empty(view)
}

/// The ids (as stored in dumps, `-1` for background) and window depths of
/// a rendered frame, as numpy arrays of shape `(height, width)` over the
/// frame's own memory (see [`FrameMemory`]).
pub fn buffers(py: Python<'_>, rendered: Rendered) -> PyResult<Buffers<'_>> {
    // The dumps' int32 id (`hider_scene::frame::id_to_i32`) is the id's
    // bit pattern, NO_ID (u32::MAX) being -1: the ids are viewed as int32.
    const { assert!(hider_scene::NO_ID == u32::MAX) };
    let Rendered { ids, depth, shape } = rendered;
    let memory = Bound::new(py, FrameMemory { ids, depth })?;
    let owner = memory.get();
    let as_array = |e: numpy::ndarray::ShapeError| PyValueError::new_err(e.to_string());
    let ids_view =
        numpy::ndarray::ArrayView2::from_shape(shape, &owner.ids[..]).map_err(as_array)?;
    let depth_view =
        numpy::ndarray::ArrayView2::from_shape(shape, &owner.depth[..]).map_err(as_array)?;
    #[allow(
        unsafe_code,
        reason = "numpy arrays over the frame's buffers, owned by their base object"
    )]
    // SAFETY: both views borrow `FrameMemory`'s vectors, which `memory`
    // owns and never reallocates (the class is frozen, its fields
    // private), and `memory` becomes the arrays' base object, kept alive
    // by numpy as long as either array (or a view of one) is. The arrays
    // stay writeable, as the copies they replace were: Rust touches the
    // vectors again only in `Drop`, after numpy has let go of both.
    let (ids, depth) = unsafe {
        (
            PyArray2::borrow_from_array(&ids_view, memory.clone().into_any()),
            PyArray2::borrow_from_array(&depth_view, memory.clone().into_any()),
        )
    };
    let ids = ids
        .call_method1("view", ("int32",))?
        .cast_into::<PyArray2<i32>>()?;
    Ok((ids, depth))
}

/// Renders `scene` as [`render_scene`] does, with the GIL released so
/// that other Python threads run meanwhile, and returns the frame as
/// [`buffers`] does.
pub fn render_buffers<'py>(
    py: Python<'py>,
    scene: &Scene,
    view: &View,
    algo: &str,
    (threads, cancel): (usize, Cancel),
) -> PyResult<Buffers<'py>> {
    let rendered = py.detach(|| render_scene(scene, view, algo, (threads, cancel)))?;
    buffers(py, rendered)
}

/// Renders `scene` as [`render_buffers`] does and computes the surface
/// attributes `wanted` at the pixel centres from the ids
/// ([`surface_at_pixels`]), all with the GIL released.
pub fn render_surface<'py>(
    py: Python<'py>,
    scene: &Scene,
    view: &View,
    algo: &str,
    (threads, cancel): (usize, Cancel),
    wanted: SurfaceOutputs,
) -> PyResult<(Buffers<'py>, Surface<'py>)> {
    let (rendered, surface) = py.detach(|| {
        let rendered = render_scene(scene, view, algo, (threads, cancel))?;
        let surface = if !wanted.any() {
            PixelSurface::default()
        } else {
            let solve = || surface_at_pixels(scene, view, &rendered.ids, wanted);
            // Above one thread the bands of rows run in the caller's pool of
            // `threads` (`wanted.parallel`), never in rayon's global one.
            if threads > 1 {
                pool(threads)?.install(solve)
            } else {
                solve()
            }
            .map_err(scene_error)?
        };
        PyResult::Ok((rendered, surface))
    })?;
    let shape = [view.viewport.height as usize, view.viewport.width as usize];
    Ok((buffers(py, rendered)?, surface_arrays(py, surface, shape)?))
}

/// The one-mesh scene of the arrays and the view of `size` pixels through
/// its camera with the caller's overrides.
pub(crate) fn scene_and_view(
    vertices: &Vertices<'_>,
    faces: &Faces<'_>,
    (width, height): (u32, u32),
    camera: &CameraArgs,
) -> PyResult<(ArrayScene, View)> {
    let array = scene_from_arrays(vertices, faces)?;
    let camera = camera.camera(&array.scene, array.bounds, width, height)?;
    let view = View::new(camera, width, height).map_err(scene_error)?;
    Ok((array, view))
}

/// Renders the mesh of `vertices` and `faces`; see the Python wrapper
/// `hider.render` for the arguments. Returns the ids and window depths,
/// then the surface attributes asked for by `want` (distance, view z,
/// barycentrics, normals, vertex normals), each `None` when not asked.
/// `cancel` (the package's per-thread token) stops the render.
#[pyfunction]
#[pyo3(signature = (vertices, faces, width, height, eye, target, up, fovy, near, far, algo, threads, pose=None, intrinsics=None, orthographic=None, normals=None, want=(false, false, false, false, false), cancel=None))]
#[expect(
    clippy::too_many_arguments,
    reason = "the keyword arguments of the Python function, one for one"
)]
pub fn render<'py>(
    py: Python<'py>,
    vertices: Vertices<'py>,
    faces: Faces<'py>,
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
    pose: Option<[[f64; 4]; 4]>,
    intrinsics: Option<[f64; 4]>,
    orthographic: Option<f64>,
    normals: Option<Vertices<'py>>,
    want: (bool, bool, bool, bool, bool),
    cancel: Option<PyCancel>,
) -> PyResult<(Buffers<'py>, Surface<'py>)> {
    let camera = CameraArgs {
        eye,
        target,
        up,
        fovy,
        near,
        far,
        pose,
        intrinsics,
        orthographic,
    };
    let (mut array, view) = scene_and_view(&vertices, &faces, (width, height), &camera)?;
    if let Some(normals) = normals {
        set_vertex_normals(&mut array.scene, &normals)?;
    }
    let (distance, view_z, barycentrics, normals, vertex_normals) = want;
    let wanted = SurfaceOutputs {
        distance,
        view_z,
        barycentrics,
        normals,
        vertex_normals,
        parallel: threads > 1,
    };
    let result = render_surface(
        py,
        &array.scene,
        &view,
        algo,
        (threads, token(cancel)),
        wanted,
    );
    crate::mesh::recycle(array);
    result
}

/// Gives the one mesh of `scene` the per-vertex `normals` (`(N, 3)`, one
/// per vertex), for the interpolated vertex normals.
fn set_vertex_normals(scene: &mut Scene, normals: &Vertices<'_>) -> PyResult<()> {
    let normals = normals.rows_as("normals")?;
    let mesh = &mut scene.meshes[0];
    if normals.len() != mesh.positions.len() {
        return Err(PyValueError::new_err(format!(
            "normals must have one row per vertex: {} rows for {} vertices",
            normals.len(),
            mesh.positions.len()
        )));
    }
    if let Some(k) = normals.iter().position(|n| !n.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "normals row {k} is not finite: {}",
            normals[k]
        )));
    }
    mesh.normals = normals.into_iter().map(|n| n.as_vec3()).collect();
    Ok(())
}

/// The names of the registered hiders, in the registry's order.
#[pyfunction]
pub fn algorithms() -> Vec<&'static str> {
    registry::names()
}

/// Every registered hider as `(name, kind, description)`, in the
/// registry's order; the kind is how the registry checks it
/// ([`registry::Kind`]): `"exact"` (equals the exact reference on every
/// pixel that is not a depth tie), `"approximate"` (wrong by design in
/// documented cases), `"multisample"` (several samples per pixel) or
/// `"reference"` (the exact ray-cast oracle).
#[pyfunction]
pub fn algorithm_kinds() -> Vec<(&'static str, &'static str, &'static str)> {
    registry::all()
        .into_iter()
        .map(|e| {
            let kind = match e.kind {
                registry::Kind::ExactPixelCentre => "exact",
                registry::Kind::ApproximatePixelCentre => "approximate",
                registry::Kind::MultiSample => "multisample",
                registry::Kind::Reference => "reference",
            };
            (e.name, kind, e.description)
        })
        .collect()
}

/// The planner's choice for the mesh of `vertices` and `faces`, as
/// `render` with `algo="auto"` makes it: `(algo, reason, summary)`, the
/// registry name, why in one sentence, and the command line's one-line
/// summary. See the Python wrapper `hider.plan` for the arguments.
#[pyfunction]
#[pyo3(signature = (vertices, faces, width, height, eye, target, up, fovy, near, far, threads, pose=None, intrinsics=None, orthographic=None, cancel=None))]
#[expect(
    clippy::too_many_arguments,
    reason = "the keyword arguments of the Python function, one for one"
)]
pub fn plan<'py>(
    py: Python<'py>,
    vertices: Vertices<'py>,
    faces: Faces<'py>,
    width: u32,
    height: u32,
    eye: Option<[f64; 3]>,
    target: Option<[f64; 3]>,
    up: Option<[f64; 3]>,
    fovy: Option<f64>,
    near: Option<f64>,
    far: Option<f64>,
    threads: usize,
    pose: Option<[[f64; 4]; 4]>,
    intrinsics: Option<[f64; 4]>,
    orthographic: Option<f64>,
    cancel: Option<PyCancel>,
) -> PyResult<(&'static str, String, String)> {
    check_threads(threads)?;
    let camera = CameraArgs {
        eye,
        target,
        up,
        fovy,
        near,
        far,
        pose,
        intrinsics,
        orthographic,
    };
    let (array, view) = scene_and_view(&vertices, &faces, (width, height), &camera)?;
    let scene = array.scene;
    let planned = py
        .detach(|| plan_scene(&scene, &view, threads, token(cancel)))
        .map_err(plan_error)?;
    let summary = planned.summary();
    Ok((planned.plan.algo, planned.plan.reason, summary))
}
