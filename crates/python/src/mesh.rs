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
    /// One `DVec3` per row, the array named `what` in messages.
    pub(crate) fn rows_as(&self, what: &str) -> PyResult<Vec<DVec3>> {
        let mut out = Vec::new();
        self.rows_into(what, &mut out, |_, _| ())?;
        Ok(out)
    }

    /// The number of rows.
    fn rows(&self) -> PyResult<usize> {
        match self {
            Vertices::F64(a) => rows_of("vertices", a),
            Vertices::F32(a) => rows_of("vertices", a),
        }
    }

    /// [`Self::rows_as`] into `out` (cleared first), reusing its memory,
    /// with `visit` called on each row's index and position as it is
    /// copied.
    fn rows_into(
        &self,
        what: &str,
        out: &mut Vec<DVec3>,
        mut visit: impl FnMut(usize, DVec3),
    ) -> PyResult<()> {
        let mut k = 0;
        let mut seen = |p: DVec3| {
            visit(k, p);
            k += 1;
            p
        };
        match self {
            Vertices::F64(a) => rows_into(what, a, |r| seen(DVec3::from_array(r)), out),
            Vertices::F32(a) => {
                rows_into(what, a, |r| seen(DVec3::from_array(r.map(f64::from))), out)
            }
        }
    }
}

impl Faces<'_> {
    /// The number of rows (its shape checked when it is read).
    fn rows(&self) -> usize {
        match self {
            Faces::I64(a) => a.shape()[0],
            Faces::I32(a) => a.shape()[0],
            Faces::U32(a) => a.shape()[0],
        }
    }

    /// Each row as `i64` indices, through `f`.
    fn map<U>(&self, f: impl FnMut([i64; 3]) -> U) -> PyResult<Vec<U>> {
        let mut out = Vec::new();
        self.map_into(f, &mut out)?;
        Ok(out)
    }

    /// [`Self::map`] into `out` (cleared first), reusing its memory.
    fn map_into<U>(&self, mut f: impl FnMut([i64; 3]) -> U, out: &mut Vec<U>) -> PyResult<()> {
        match self {
            Faces::I64(a) => rows_into("faces", a, f, out),
            Faces::I32(a) => rows_into("faces", a, |r| f(r.map(i64::from)), out),
            Faces::U32(a) => rows_into("faces", a, |r| f(r.map(i64::from)), out),
        }
    }
}

/// The number of rows of an `(N, 3)` array (its shape checked).
fn rows_of<T: numpy::Element>(what: &str, a: &PyReadonlyArray2<'_, T>) -> PyResult<usize> {
    let shape = a.shape();
    if shape[1] != 3 {
        return Err(PyValueError::new_err(format!(
            "{what} must have shape (N, 3), got ({}, {})",
            shape[0], shape[1]
        )));
    }
    Ok(shape[0])
}

/// The mesh name that error messages about the arrays show.
pub const MESH_NAME: &str = "array";

/// Each row of an `(N, 3)` array mapped through `f` into `out` (cleared
/// first, its memory reused; the Python layer has made the array
/// contiguous and checked its shape, checked again here for direct
/// callers), read straight from its memory when it is contiguous:
/// no copy of the array is made on the way to the scene (at 10^5 rows a
/// copy costs its page faults on every call).
fn rows_into<T: numpy::Element + Copy, U>(
    what: &str,
    a: &PyReadonlyArray2<'_, T>,
    mut f: impl FnMut([T; 3]) -> U,
    out: &mut Vec<U>,
) -> PyResult<()> {
    rows_of(what, a)?;
    out.clear();
    if let Ok(flat) = a.as_slice() {
        out.extend(flat.chunks_exact(3).map(|r| f([r[0], r[1], r[2]])));
        return Ok(());
    }
    let view = a.as_array();
    out.extend(view.rows().into_iter().map(|r| f([r[0], r[1], r[2]])));
    Ok(())
}

thread_local! {
    /// The position, index and vertex-use vectors of the last scene
    /// [`recycle`]d on this thread, for the next [`scene_from_arrays`]: a
    /// frame loop over a large mesh otherwise allocates them anew every
    /// call, and the kernel faults in and zeroes their pages (12 MB a call
    /// on the UV sphere 500, about a tenth of `hider.render`'s time there).
    static SPARE: std::cell::RefCell<Spare> =
        const { std::cell::RefCell::new((Vec::new(), Vec::new(), Vec::new())) };
}

/// What [`SPARE`] keeps: positions, indices, which vertices are used.
type Spare = (Vec<DVec3>, Vec<[u32; 3]>, Vec<bool>);

/// Keeps the memory of a scene made by [`scene_from_arrays`] for the next
/// one on this thread.
pub fn recycle(scene: ArrayScene) {
    if let Some(mesh) = scene.scene.meshes.into_iter().next() {
        SPARE.with_borrow_mut(|spare| *spare = (mesh.positions, mesh.indices, scene.used));
    }
}

/// The one-mesh scene [`scene_from_arrays`] builds, with its bounds.
pub struct ArrayScene {
    /// The scene.
    pub scene: Scene,
    /// [`Scene::bounds`], computed while the scene was built.
    pub bounds: Option<(DVec3, DVec3)>,
    /// Which vertices a face uses (memory kept for the next scene).
    used: Vec<bool>,
}

/// The one-mesh scene of `vertices` (`(N, 3)`, world space) and `faces`
/// (`(M, 3)` vertex indices), with every position and index checked: the
/// same messages as the front end's validation, naming the triangle or
/// vertex at fault. Its bounds come with it.
///
/// Why the bounds here: the fit camera needs them, and [`Scene::bounds`]
/// reads every index again (to mark the vertices used) and every position
/// (0.47 ms on the UV sphere 500, against its frame's 8.5). Here the
/// faces pass marks the vertices it checks, and the positions are copied,
/// checked and bounded in one pass. That is [`Scene::bounds`]' own way for
/// a mesh whose vertices are shared (fewer than 1.5 per triangle): the
/// extremes over the used positions in order, so the same bits. Otherwise
/// (a triangle soup) [`Scene::bounds`] is asked, which takes the extremes
/// triangle by triangle (the same values, but the sign of a zero extreme
/// can depend on the order).
pub fn scene_from_arrays(vertices: &Vertices<'_>, faces: &Faces<'_>) -> PyResult<ArrayScene> {
    let (mut positions, mut indices, mut used) = SPARE.with_borrow_mut(std::mem::take);
    let n = vertices.rows()?;
    let shared = n.saturating_mul(2) < faces.rows().saturating_mul(3);
    used.clear();
    if shared {
        used.resize(n, false);
    }
    // Every call converts and checks every index: one branch-free pass
    // (a negative index is above any count as u64), and the search for
    // the culprit only when it fails.
    let limit = n as u64;
    let mut in_range = true;
    faces.map_into(
        |tri| {
            let ok = tri.iter().fold(true, |ok, &i| ok & ((i as u64) < limit));
            in_range &= ok;
            if shared && ok {
                for &i in &tri {
                    used[i as usize] = true;
                }
            }
            // In range of a vertex count, so below u32::MAX only if n is;
            // the front end refuses meshes of more vertices than ids can
            // name.
            tri.map(|i| u32::try_from(i).unwrap_or(u32::MAX))
        },
        &mut indices,
    )?;
    if !in_range {
        let mut bad = None;
        let mut t = 0;
        faces.map(|tri| {
            if bad.is_none()
                && let Some(&i) = tri.iter().find(|&&i| i < 0 || i as u64 >= limit)
            {
                bad = Some((t, i));
            }
            t += 1;
        })?;
        if let Some((t, i)) = bad {
            return Err(PyValueError::new_err(format!(
                "invalid scene: mesh 0 ('{MESH_NAME}') triangle {t} uses vertex {i}, but the mesh has {n} vertices"
            )));
        }
    }
    let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    let mut finite = true;
    vertices.rows_into("vertices", &mut positions, |k, p| {
        finite &= p.is_finite();
        if shared && used[k] {
            lo = lo.min(p);
            hi = hi.max(p);
        }
    })?;
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
    // With the indices in range, the rest of `Scene::validate` for a mesh
    // of positions and indices is that the positions are finite: checked
    // in the copy, and `validate` itself only to name the culprit.
    if !finite {
        scene.validate().map_err(crate::errors::scene_error)?;
    }
    let bounds = match (shared, scene.meshes[0].indices.is_empty()) {
        (_, true) => None,
        (true, false) => Some((lo, hi)),
        (false, false) => scene.bounds(),
    };
    Ok(ArrayScene {
        scene,
        bounds,
        used,
    })
}
