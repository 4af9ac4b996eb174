//! Vertex and face arrays as a one-mesh scene.

use glam::DVec3;
use hider_scene::{Mesh, Scene};
use numpy::{PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::{FromPyObject, PyResult};

/// A vertex array as numpy holds it: float64 or float32, read in place
/// (float32 coordinates widen exactly to the scene's f64).
#[derive(FromPyObject)]
pub enum Vertices<'py> {
    /// `float64`.
    F64(PyReadonlyArray2<'py, f64>),
    /// `float32`.
    F32(PyReadonlyArray2<'py, f32>),
}

/// A face array as numpy holds it: int64, int32 or uint32, read in place.
#[derive(FromPyObject)]
pub enum Faces<'py> {
    /// `int64`.
    I64(PyReadonlyArray2<'py, i64>),
    /// `int32`.
    I32(PyReadonlyArray2<'py, i32>),
    /// `uint32`.
    U32(PyReadonlyArray2<'py, u32>),
}

impl Vertices<'_> {
    /// The positions, one `DVec3` per row.
    fn positions(&self) -> PyResult<Vec<DVec3>> {
        self.rows_as("vertices")
    }

    /// One `DVec3` per row, the array named `what` in messages.
    pub(crate) fn rows_as(&self, what: &str) -> PyResult<Vec<DVec3>> {
        match self {
            Vertices::F64(a) => rows(what, a, DVec3::from_array),
            Vertices::F32(a) => rows(what, a, |r| DVec3::from_array(r.map(f64::from))),
        }
    }
}

impl Faces<'_> {
    /// Each row as `i64` indices, through `f`.
    fn map<U>(&self, f: impl FnMut([i64; 3]) -> U) -> PyResult<Vec<U>> {
        let mut f = f;
        match self {
            Faces::I64(a) => rows("faces", a, f),
            Faces::I32(a) => rows("faces", a, |r| f(r.map(i64::from))),
            Faces::U32(a) => rows("faces", a, |r| f(r.map(i64::from))),
        }
    }
}

/// The mesh name that error messages about the arrays show.
pub const MESH_NAME: &str = "array";

/// Each row of an `(N, 3)` array mapped through `f` (the Python layer has
/// made it contiguous and checked its shape; checked again here for
/// direct callers), read straight from its memory when it is contiguous:
/// no copy of the array is made on the way to the scene (at 10^5 rows a
/// copy costs its page faults on every call).
fn rows<T: numpy::Element + Copy, U>(
    what: &str,
    a: &PyReadonlyArray2<'_, T>,
    mut f: impl FnMut([T; 3]) -> U,
) -> PyResult<Vec<U>> {
    let shape = a.shape();
    if shape[1] != 3 {
        return Err(PyValueError::new_err(format!(
            "{what} must have shape (N, 3), got ({}, {})",
            shape[0], shape[1]
        )));
    }
    if let Ok(flat) = a.as_slice() {
        return Ok(flat
            .chunks_exact(3)
            .map(|r| f([r[0], r[1], r[2]]))
            .collect());
    }
    let view = a.as_array();
    Ok(view
        .rows()
        .into_iter()
        .map(|r| f([r[0], r[1], r[2]]))
        .collect())
}

/// The one-mesh scene of `vertices` (`(N, 3)`, world space) and `faces`
/// (`(M, 3)` vertex indices), with every position and index checked: the
/// same messages as the front end's validation, naming the triangle or
/// vertex at fault.
pub fn scene_from_arrays(vertices: &Vertices<'_>, faces: &Faces<'_>) -> PyResult<Scene> {
    let positions = vertices.positions()?;
    let n = positions.len();
    // The first index out of range, with its triangle.
    let mut bad = None;
    let mut t = 0;
    let indices = faces.map(|tri| {
        if bad.is_none()
            && let Some(&i) = tri.iter().find(|&&i| i < 0 || i as u64 >= n as u64)
        {
            bad = Some((t, i));
        }
        t += 1;
        // In range of a vertex count, so below u32::MAX only if n is; the
        // front end refuses meshes of more vertices than ids can name.
        tri.map(|i| u32::try_from(i).unwrap_or(u32::MAX))
    })?;
    if let Some((t, i)) = bad {
        return Err(PyValueError::new_err(format!(
            "invalid scene: mesh 0 ('{MESH_NAME}') triangle {t} uses vertex {i}, but the mesh has {n} vertices"
        )));
    }
    let mut scene = Scene::default();
    scene.push_mesh(
        Mesh {
            name: MESH_NAME.to_owned(),
            positions,
            indices,
            ..Mesh::default()
        },
        None,
    );
    scene.validate().map_err(crate::errors::scene_error)?;
    Ok(scene)
}
