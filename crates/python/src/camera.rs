//! The camera keywords of `hider.render`: look-at values over the fit
//! camera (the command line's rule), a 4x4 camera-to-world pose, pinhole
//! intrinsics and an orthographic projection.

use glam::{DMat4, DVec3};
use hider_geom::{Camera, Intrinsics, Projection};
use hider_scene::{CameraOverrides, Scene};
use pyo3::PyResult;
use pyo3::exceptions::PyValueError;

/// The camera values a caller gives; `None` keeps the fit camera's.
#[derive(Clone, Copy, Debug, Default)]
pub struct CameraArgs {
    pub(crate) eye: Option<[f64; 3]>,
    pub(crate) target: Option<[f64; 3]>,
    pub(crate) up: Option<[f64; 3]>,
    pub(crate) fovy: Option<f64>,
    pub(crate) near: Option<f64>,
    pub(crate) far: Option<f64>,
    /// Camera to world, OpenGL's axes (x right, y up, looking down -z),
    /// rows as numpy gives them; the Python layer has converted an OpenCV
    /// pose and checked that the rotation is one.
    pub(crate) pose: Option<[[f64; 4]; 4]>,
    /// `(fx, fy, cx, cy)`, pixels, for the image being rendered.
    pub(crate) intrinsics: Option<[f64; 4]>,
    /// Half the view's height in world units: an orthographic camera.
    pub(crate) orthographic: Option<f64>,
}

impl CameraArgs {
    /// The camera for a `width x height` image of `scene`, whose
    /// [`Scene::bounds`] are `bounds`: the fit camera with the look-at
    /// overrides applied (the command line's rule for `--eye`, `--fovy`
    /// and the rest), then the pose, the projection and the intrinsics.
    pub(crate) fn camera(
        &self,
        scene: &Scene,
        bounds: Option<(DVec3, DVec3)>,
        width: u32,
        height: u32,
    ) -> PyResult<Camera> {
        let mut c = CameraOverrides {
            eye: self.eye.map(DVec3::from_array),
            target: self.target.map(DVec3::from_array),
            up: self.up.map(DVec3::from_array),
            fovy: self.fovy,
            near: self.near,
            far: self.far,
        }
        .apply_to_bounds(scene.camera, bounds);
        if let Some(rows) = self.pose {
            // numpy's rows are glam's columns transposed.
            let pose = DMat4::from_cols_array_2d(&rows).transpose();
            let eye = pose.w_axis.truncate();
            c.eye = eye;
            c.target = eye - pose.z_axis.truncate();
            c.up = pose.y_axis.truncate();
            let (near, far) = range_from(bounds, eye, -pose.z_axis.truncate());
            set_range(&mut c, self.near.unwrap_or(near), self.far.unwrap_or(far));
        }
        if let Some(half_height) = self.orthographic {
            let (near, far) = range(&c);
            c.projection = Projection::Orthographic {
                half_height,
                near,
                far,
            };
        }
        if let Some([fx, fy, cx, cy]) = self.intrinsics {
            let k = Intrinsics {
                fx,
                fy,
                cx,
                cy,
                width,
                height,
            };
            k.validate()
                .map_err(|e| PyValueError::new_err(e.to_string()))?;
            c = c.with_intrinsics(&k);
        }
        Ok(c)
    }
}

/// A camera's near and far distances.
fn range(c: &Camera) -> (f64, f64) {
    match c.projection {
        Projection::Perspective { near, far, .. } | Projection::Orthographic { near, far, .. } => {
            (near, far)
        }
    }
}

/// Sets a camera's near and far distances.
fn set_range(c: &mut Camera, n: f64, f: f64) {
    match &mut c.projection {
        Projection::Perspective { near, far, .. } | Projection::Orthographic { near, far, .. } => {
            (*near, *far) = (n, f);
        }
    }
}

/// Near and far for an eye placed by a pose looking along `forward`, so
/// that a pose anywhere sees the whole mesh as a ray caster would: the
/// view depths of the bounding box's corners (view depth is linear, so
/// they bound the box's), widened by 1%, near at least a ten-thousandth
/// of far (which clips only what is closer when the eye is in the box).
fn range_from(bounds: Option<(DVec3, DVec3)>, eye: DVec3, forward: DVec3) -> (f64, f64) {
    let (lo, hi) = bounds.unwrap_or((DVec3::ZERO, DVec3::ZERO));
    let forward = hider_geom::camera::rescaled(forward).normalize();
    let (mut nearest, mut farthest) = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..8 {
        let corner = DVec3::new(
            if k & 1 == 0 { lo.x } else { hi.x },
            if k & 2 == 0 { lo.y } else { hi.y },
            if k & 4 == 0 { lo.z } else { hi.z },
        );
        let depth = (corner - eye).dot(forward);
        nearest = nearest.min(depth);
        farthest = farthest.max(depth);
    }
    let far = if farthest > 0.0 && farthest.is_finite() {
        farthest * 1.01
    } else {
        1.0
    };
    ((nearest * 0.99).max(far * 1e-4), far)
}
