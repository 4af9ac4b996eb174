//! Exact vector drawings of a mesh from Python: the visible regions or the
//! hidden-line drawing as SVG, with the `VectorOptions` the command line's
//! vector flags set, as keywords.

use std::path::PathBuf;

use hider_scene::{PrepareOptions, ShadeMode, prepare};
use hider_vector::{
    SvgInfo, VectorOptions, hidden_lines_in, line_pairs, lines_document, regions_document,
    visible_regions, write_document,
};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::camera::CameraArgs;
use crate::cancel::{PyCancel, token};
use crate::errors::scene_error;
use crate::mesh::{Faces, Vertices};
use crate::render::scene_and_view;

/// Writes the SVG of the mesh of `vertices` and `faces`; see the Python
/// wrapper `hider.svg` for the arguments. `cancel` stops the drawing.
#[pyfunction]
#[pyo3(signature = (vertices, faces, path, width, height, eye, target, up, fovy, near, far,
    mode, crease_angle, stroke_width, stroke_mm, page_mm, hidden, background, seams,
    pose=None, intrinsics=None, orthographic=None, cancel=None))]
#[expect(
    clippy::too_many_arguments,
    reason = "the keyword arguments of the Python function, one for one"
)]
pub fn svg(
    py: Python<'_>,
    vertices: Vertices<'_>,
    faces: Faces<'_>,
    path: PathBuf,
    width: u32,
    height: u32,
    eye: Option<[f64; 3]>,
    target: Option<[f64; 3]>,
    up: Option<[f64; 3]>,
    fovy: Option<f64>,
    near: Option<f64>,
    far: Option<f64>,
    mode: &str,
    crease_angle: f64,
    stroke_width: f64,
    stroke_mm: Option<f64>,
    page_mm: Option<(f64, f64)>,
    hidden: &str,
    background: Option<String>,
    seams: bool,
    pose: Option<[[f64; 4]; 4]>,
    intrinsics: Option<[f64; 4]>,
    orthographic: Option<f64>,
    cancel: Option<PyCancel>,
) -> PyResult<()> {
    let lines = match mode {
        "regions" => false,
        "lines" => true,
        other => {
            return Err(PyValueError::new_err(format!(
                "mode must be 'regions' or 'lines', got '{other}'"
            )));
        }
    };
    let dashed = match hidden {
        "none" => false,
        "dashed" => true,
        other => {
            return Err(PyValueError::new_err(format!(
                "hidden must be 'none' or 'dashed', got '{other}'"
            )));
        }
    };
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
    let mut options = VectorOptions::default()
        .with_crease_degrees(crease_angle)
        .with_page_mm(page_mm)
        .with_dashed_hidden(dashed)
        .with_background(background)
        .with_cancel(token(cancel));
    if !seams {
        options = options.with_seam_stroke(0.0);
    }
    let options = match stroke_mm {
        Some(mm) => options.with_stroke_mm(mm, width, height),
        None => options.with_stroke_width(stroke_width),
    };
    py.detach(|| {
        let screen = prepare(&scene, &view, &PrepareOptions::default())?;
        let info = SvgInfo::for_scene(&scene, "numpy arrays", &screen);
        let document = if lines {
            let map = line_pairs(&screen, &options)?;
            let drawing = hidden_lines_in(&screen, &map, &options, &info.groups)?;
            lines_document(&screen, &drawing, &options, &info)
        } else {
            let map = visible_regions(&screen, &options, ShadeMode::Lambert)?;
            regions_document(&screen, &map, &options, &info)
        };
        write_document(&path, &document)
    })
    .map_err(scene_error)
}
