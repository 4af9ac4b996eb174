//! The surface attributes of `hider.render`'s `outputs=` as numpy arrays.

use hider_scene::PixelSurface;
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods};
use pyo3::prelude::*;

/// Distance, view z, barycentrics, normals and vertex normals, each
/// `None` when not asked for: `(height, width)`, `(height, width)`,
/// `(height, width, 2)`, `(height, width, 3)`, `(height, width, 3)`, all
/// float32.
pub type Surface<'py> = (
    Option<Bound<'py, PyArrayDyn<f32>>>,
    Option<Bound<'py, PyArrayDyn<f32>>>,
    Option<Bound<'py, PyArrayDyn<f32>>>,
    Option<Bound<'py, PyArrayDyn<f32>>>,
    Option<Bound<'py, PyArrayDyn<f32>>>,
);

/// `values` (empty when not asked for) as a numpy array of `shape`
/// followed by `channels` (none for 1), handed to numpy without a copy.
fn array<'py>(
    py: Python<'py>,
    values: Vec<f32>,
    shape: [usize; 2],
    channels: usize,
) -> PyResult<Option<Bound<'py, PyArrayDyn<f32>>>> {
    if values.is_empty() {
        return Ok(None);
    }
    let flat = PyArray1::from_vec(py, values);
    let shaped = if channels == 1 {
        flat.reshape(shape.to_vec())?
    } else {
        flat.reshape(vec![shape[0], shape[1], channels])?
    };
    Ok(Some(shaped))
}

/// The attributes of `surface` for a frame of `shape` (`[height, width]`).
pub fn surface_arrays(
    py: Python<'_>,
    surface: PixelSurface,
    shape: [usize; 2],
) -> PyResult<Surface<'_>> {
    Ok((
        array(py, surface.distance, shape, 1)?,
        array(py, surface.view_z, shape, 1)?,
        array(py, surface.barycentrics.into_flattened(), shape, 2)?,
        array(py, surface.normals.into_flattened(), shape, 3)?,
        array(py, surface.vertex_normals.into_flattened(), shape, 3)?,
    ))
}
