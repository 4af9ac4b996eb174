//! Hostile front-end inputs from raw floats: any camera, up to five
//! triangles with any `f32` corners (huge, tiny, infinite, NaN), a window
//! of a few pixels. The fuzz targets decode their bytes with
//! [`front_end_case`]; property tests that draw the floats themselves (the
//! A-buffer's lean front end, which cannot use the `hostile` feature: that
//! feature renders through `hider-plan`, which depends on the A-buffer)
//! build the same scenes with [`case_from_floats`] and [`soup_from_floats`].
//!
//! ```
//! use hider_scene::TransformPrecision;
//! use hider_testkit::front_end_input::case_from_floats;
//!
//! // eye, target, up, then fovy (positive: perspective), near, far.
//! let camera = [0.0f32, 0.0, 5.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 45.0, 0.1, 10.0];
//! let corners = [-1.0f32, -1.0, 0.0, 1.0, -1.0, 0.0, 0.0, 1.0, 0.0];
//! let case = case_from_floats(&camera, &corners, (8, 8), TransformPrecision::F64).unwrap();
//! assert_eq!(case.scene.triangle_count(), 1);
//! ```

use glam::DVec3;
use hider_geom::{Camera, Projection};
use hider_scene::{Mesh, PrepareOptions, Scene, TransformPrecision, View};

/// A decoded front-end case: a scene, a view and front-end options.
#[derive(Clone, Debug)]
pub struct Case {
    /// Up to 5 triangles with arbitrary `f32` corners.
    pub scene: Scene,
    /// An arbitrary camera (perspective or orthographic) and a window of
    /// 1 to 16 pixels a side.
    pub view: View,
    /// f32 or f64 transform.
    pub options: PrepareOptions,
}

/// The camera of 13 floats: eye, target and up, then a sign choosing the
/// projection (negative: orthographic) and its three numbers (fovy or
/// half height, near, far; the perspective ones taken as magnitudes).
pub fn camera_from_floats(c: &[f32; 13]) -> Camera {
    let v3 = |k: usize| DVec3::new(c[k].into(), c[k + 1].into(), c[k + 2].into());
    let projection = if c[9].is_sign_negative() {
        Projection::Orthographic {
            half_height: c[10].abs().into(),
            near: c[11].into(),
            far: c[12].into(),
        }
    } else {
        Projection::Perspective {
            fovy_degrees: c[10].abs().into(),
            near: c[11].abs().into(),
            far: c[12].abs().into(),
        }
    };
    Camera {
        eye: v3(0),
        target: v3(3),
        up: v3(6),
        projection,
        lens: hider_geom::Lens::CENTRED,
    }
}

/// One mesh of separate triangles, three corners (nine floats) each, from
/// the first five whole triangles of `corners`.
pub fn soup_from_floats(corners: &[f32]) -> Scene {
    let positions: Vec<DVec3> = corners
        .chunks_exact(3)
        .take(15)
        .map(|c| DVec3::new(c[0].into(), c[1].into(), c[2].into()))
        .collect();
    let n = positions.len() as u32 / 3;
    let mut scene = Scene::default();
    scene.push_mesh(
        Mesh {
            positions,
            indices: (0..n).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect(),
            ..Mesh::default()
        },
        None,
    );
    scene
}

/// The case of a camera, corners, a window size and a transform precision;
/// `None` when the camera or size is refused.
pub fn case_from_floats(
    camera: &[f32; 13],
    corners: &[f32],
    (w, h): (u32, u32),
    precision: TransformPrecision,
) -> Option<Case> {
    let view = View::new(camera_from_floats(camera), w, h).ok()?;
    Some(Case {
        scene: soup_from_floats(corners),
        view,
        options: PrepareOptions::default().with_precision(precision),
    })
}

/// Decodes bytes as `[13 camera floats][triangle corner floats...]`
/// (little-endian `f32`), the first bytes doubling as window size and
/// precision. `None` when too short or when the camera or size is refused
/// (which is itself the behaviour under test: refused, not panicking).
pub fn front_end_case(data: &[u8]) -> Option<Case> {
    if data.len() < 4 * 13 {
        return None;
    }
    let f: Vec<f32> = data
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    let camera: [f32; 13] = f[..13].try_into().ok()?;
    let size = (1 + u32::from(data[0]) % 16, 1 + u32::from(data[1]) % 16);
    let precision = if data[2] & 1 == 0 {
        TransformPrecision::F64
    } else {
        TransformPrecision::F32
    };
    case_from_floats(&camera, &f[13..], size, precision)
}
