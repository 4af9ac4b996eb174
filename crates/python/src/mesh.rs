//! Vertex and face arrays as a one-mesh scene.

use glam::DVec3;
use hider_scene::{Mesh, Scene};
use numpy::{PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::PyResult;
use pyo3::exceptions::PyValueError;

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
pub fn scene_from_arrays(
    vertices: &PyReadonlyArray2<'_, f64>,
    faces: &PyReadonlyArray2<'_, i64>,
) -> PyResult<Scene> {
    let positions = rows("vertices", vertices, DVec3::from_array)?;
    let n = positions.len();
    // The first index out of range, with its triangle.
    let mut bad = None;
    let mut t = 0;
    let indices = rows("faces", faces, |tri| {
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
