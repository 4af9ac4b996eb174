//! Screen-space scenes for `hider.mpl`: points already projected by
//! matplotlib, rendered and painted without a second projection.
//!
//! matplotlib's `Axes3D` projects with its own matrix (`ax.get_proj()`),
//! perspective divide included. A projective map keeps planes planar, so
//! the projected triangles can be ordered and split as they are: each
//! point `(x, y, t)` (window pixels with y down, and a depth `t` in
//! `[0, 1]` that grows away from the viewer) is placed at world
//! `(x, height - y, -t)` in front of an orthographic camera whose view
//! volume is exactly the window, so the front end maps it back to window
//! `(x, y)` with a window depth linear in `t`.

use glam::DVec3;
use hider_geom::Camera;
use hider_painter::{Painter, PainterOptions};
use hider_scene::{Hider, Material, PrepareOptions, Scene, ScreenScene, View, prepare};
use numpy::ndarray::{Array1, Array2};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::cancel::{PyCancel, token};
use crate::errors::{plan_error, scene_error};
use crate::mesh::{Faces, Vertices, scene_from_arrays};
use crate::render::{Buffers, render_buffers};

/// Distance from the eye to depth `t = 0`; `t = 1` is one unit farther.
const EYE_TO_FRONT: f64 = 1.0;
/// The near plane, half a unit before `t = 0`.
const NEAR: f64 = 0.5;
/// The far plane, half a unit past `t = 1`.
const FAR: f64 = 2.5;

/// The scene of screen-space `points` and `faces` and the orthographic
/// view that maps it back onto the `width x height` window.
fn screen_view(
    points: &PyReadonlyArray2<'_, f64>,
    faces: &PyReadonlyArray2<'_, i64>,
    width: u32,
    height: u32,
) -> PyResult<(Scene, View)> {
    let mut scene =
        scene_from_arrays(&Vertices::F64(points.clone()), &Faces::I64(faces.clone()))?.scene;
    let h = f64::from(height);
    for mesh in &mut scene.meshes {
        for p in &mut mesh.positions {
            *p = DVec3::new(p.x, h - p.y, -p.z);
        }
    }
    let centre = DVec3::new(f64::from(width) * 0.5, h * 0.5, 0.0);
    let camera = Camera::orthographic(centre + DVec3::Z * EYE_TO_FRONT, centre, h * 0.5, NEAR, FAR);
    let view = View::new(camera, width, height).map_err(scene_error)?;
    Ok((scene, view))
}

/// Gives each face of the one-mesh `scene` an opaque or a translucent
/// material (per-triangle materials), so that the painter's culling treats
/// translucent faces as hiding nothing.
fn mark_translucent(scene: &mut Scene, translucent: &[bool]) -> PyResult<()> {
    let faces = scene.triangle_count();
    if translucent.len() != faces {
        return Err(PyValueError::new_err(format!(
            "translucent: {} flags for {faces} faces",
            translucent.len()
        )));
    }
    if !translucent.contains(&true) {
        return Ok(());
    }
    scene.materials = vec![
        Material::default(),
        Material {
            name: "translucent".into(),
            opacity: 0.5,
            ..Material::default()
        },
    ];
    if let Some(mesh) = scene.meshes.first_mut() {
        mesh.triangle_materials = translucent.iter().map(|&t| u32::from(t)).collect();
    }
    Ok(())
}

/// Renders screen-space points and faces (see the module docs) with the
/// registered hider `algo`: the ids and window depths, `(height, width)`.
#[pyfunction]
#[pyo3(signature = (points, faces, width, height, algo, cancel=None))]
pub fn screen_render<'py>(
    py: Python<'py>,
    points: PyReadonlyArray2<'py, f64>,
    faces: PyReadonlyArray2<'py, i64>,
    width: u32,
    height: u32,
    algo: &str,
    cancel: Option<PyCancel>,
) -> PyResult<Buffers<'py>> {
    let (scene, view) = screen_view(&points, &faces, width, height)?;
    render_buffers(py, &scene, &view, algo, (1, token(cancel)))
}

/// The painter's pieces in paint order (farthest first).
type Pieces<'py> = (
    Bound<'py, PyArray1<i64>>,
    Bound<'py, PyArray1<i64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<bool>>,
);

/// What the ordering hands back, as plain vectors: per piece its face and
/// whether it is uncut, the offsets of its corners, the corners' x, y.
type PieceLists = (Vec<i64>, Vec<i64>, Vec<f64>, Vec<bool>);

/// Orders and splits screen-space faces with Newell, Newell & Sancha's
/// painter and returns its pieces in paint order, farthest first:
/// `(faces, offsets, xy, uncut)`, where piece `k` is a convex polygon of
/// face `faces[k]` with the window-pixel corners
/// `xy[offsets[k]:offsets[k+1]]`, and `uncut[k]` says whether it is the
/// whole face.
/// Drawn in that order, each over the ones before, they show every face
/// exactly where it is the nearest.
///
/// `max_splits` bounds the painter's splits (exactly that many: its
/// [`PainterOptions::max_splits`]); `None` keeps the painter's automatic
/// budget. A frame that needs more stops with a `ValueError` (the
/// painter's split-budget error), which `hider.mpl` turns into a warning
/// and matplotlib's own drawing.
///
/// `translucent` (one flag per face, default none) marks the faces the
/// caller will draw see-through: the painter drops pieces hidden behind
/// opaque faces before ordering (what makes overlapping scenes cheap), and
/// a translucent face hides nothing, so what lies behind it is kept.
///
/// `cancel` stops the ordering (`KeyboardInterrupt`, or `TimeoutError`
/// past its deadline, which `hider.mpl` also turns into a warning).
#[pyfunction]
#[pyo3(signature = (points, faces, width, height, max_splits=None, translucent=None, cancel=None))]
#[expect(
    clippy::too_many_arguments,
    reason = "the arguments of the Python function, one for one"
)]
pub fn screen_pieces<'py>(
    py: Python<'py>,
    points: PyReadonlyArray2<'py, f64>,
    faces: PyReadonlyArray2<'py, i64>,
    width: u32,
    height: u32,
    max_splits: Option<u64>,
    translucent: Option<PyReadonlyArray1<'py, bool>>,
    cancel: Option<PyCancel>,
) -> PyResult<Pieces<'py>> {
    let (mut scene, view) = screen_view(&points, &faces, width, height)?;
    if let Some(translucent) = translucent {
        mark_translucent(&mut scene, translucent.as_slice()?)?;
    }
    let run = || -> hider_plan::Result<PieceLists> {
        let screen: ScreenScene = prepare(&scene, &view, &PrepareOptions::default())?;
        let mut options = PainterOptions::default().with_cancel(token(cancel));
        if let Some(max_splits) = max_splits {
            options = options.with_max_splits(max_splits);
        }
        let mut painter = Painter::new(options);
        // The pieces are drawn by the caller: no raster pass, no frame.
        painter.order(&screen)?;
        let pieces = painter.ordered_pieces();
        let mut prims = Vec::with_capacity(pieces.len());
        let mut uncut = Vec::with_capacity(pieces.len());
        let mut offsets = Vec::with_capacity(pieces.len() + 1);
        let mut xy = Vec::new();
        offsets.push(0);
        for piece in pieces {
            prims.push(i64::from(piece.prim));
            uncut.push(piece.is_uncut());
            for v in &piece.polygon {
                xy.extend([v.x, v.y]);
            }
            offsets.push((xy.len() / 2) as i64);
        }
        Ok((prims, offsets, xy, uncut))
    };
    let (prims, offsets, xy, uncut) = py.detach(run).map_err(plan_error)?;
    let corners = xy.len() / 2;
    let xy = Array2::from_shape_vec((corners, 2), xy)
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok((
        Array1::from(prims).into_pyarray(py),
        Array1::from(offsets).into_pyarray(py),
        xy.into_pyarray(py),
        Array1::from(uncut).into_pyarray(py),
    ))
}
