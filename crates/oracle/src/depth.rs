//! Depth without interpolation: the camera quantities of a frame, and the
//! camera-space planes the pixel rays are intersected with.

use glam::{DMat4, DVec3, DVec4};
use hider_geom::Projection;
use hider_scene::{ScreenScene, ScreenTri};

/// A plane in camera space: a point on it and its (unnormalised) normal.
pub(crate) type Plane = (DVec3, DVec3);

/// The camera quantities the per-pixel depth needs, computed once a frame.
pub(crate) struct DepthModel {
    projection: DMat4,
    inverse: DMat4,
    near: f64,
    far: f64,
    perspective: bool,
}

impl DepthModel {
    pub(crate) fn new(scene: &ScreenScene) -> Self {
        let (near, far, perspective) = match scene.camera.projection {
            Projection::Perspective { near, far, .. } => (near, far, true),
            Projection::Orthographic { near, far, .. } => (near, far, false),
        };
        Self {
            projection: scene.projection_matrix,
            inverse: scene.projection_matrix.inverse(),
            near,
            far,
            perspective,
        }
    }

    /// The denominator of the relative gap: the view depth itself for a
    /// perspective camera (at least `near`), the depth range for an
    /// orthographic one (whose window depth is linear in view depth).
    pub(crate) fn gap_scale(&self, d: f64) -> f64 {
        if self.perspective {
            d.max(self.near)
        } else {
            self.far - self.near
        }
    }

    /// View depth (distance in front of the eye along -Z) of window depth
    /// `zw`.
    pub(crate) fn view_depth_of_window(&self, zw: f64) -> f64 {
        let p = self.inverse * DVec4::new(0.0, 0.0, 2.0 * zw - 1.0, 1.0);
        -p.z / p.w
    }

    /// Window depth of view depth `d`.
    pub(crate) fn window_of_view_depth(&self, d: f64) -> f64 {
        let c = self.projection * DVec4::new(0.0, 0.0, -d, 1.0);
        (c.z / c.w + 1.0) * 0.5
    }

    /// View depth at the centre of pixel `(i, j)` of `tri`, whose window
    /// depth there is `zw`: `1 / (1/w)` from the affine 1/w plane for a
    /// perspective camera (well conditioned where window depth is all but
    /// 1), linear in window depth for an orthographic one.
    pub(crate) fn view_depth(&self, tri: &ScreenTri, i: u32, j: u32, zw: f64) -> f64 {
        if self.perspective {
            1.0 / tri.inv_w.at_pixel(i, j)
        } else {
            self.near + zw * (self.far - self.near)
        }
    }

    /// View depths of a piece's corners: clip w for a perspective camera,
    /// linear in window depth for an orthographic one.
    pub(crate) fn corner_depths(&self, tri: &ScreenTri) -> [f64; 3] {
        if self.perspective {
            tri.w
        } else {
            tri.z.map(|z| self.near + z * (self.far - self.near))
        }
    }
}

/// The plane of a camera-space triangle.
pub(crate) fn source_plane(c: [DVec3; 3]) -> Plane {
    (c[0], (c[1] - c[0]).cross(c[2] - c[0]))
}

/// View depth where the ray `origin + t dir` meets the plane, or `None`
/// when the ray is (nearly) parallel to it or the triangle is degenerate.
pub(crate) fn ray_plane_depth((a, n): Plane, origin: DVec3, dir: DVec3) -> Option<f64> {
    let denom = n.dot(dir);
    // Relative test: a plane seen exactly edge-on, or a zero normal from a
    // degenerate source triangle, has no usable intersection.
    let usable = denom.abs() > 1e-12 * n.length() * dir.length();
    if !usable {
        return None;
    }
    let t = n.dot(a - origin) / denom;
    let d = -(origin.z + t * dir.z);
    d.is_finite().then_some(d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_plane_depth_of_a_facing_plane() {
        let plane = source_plane([
            DVec3::new(-1.0, -1.0, -4.0),
            DVec3::new(1.0, -1.0, -4.0),
            DVec3::new(0.0, 1.0, -4.0),
        ]);
        let d = ray_plane_depth(plane, DVec3::ZERO, DVec3::new(0.1, 0.2, -0.5)).unwrap();
        assert!((d - 4.0).abs() < 1e-12);
        // Edge-on: no intersection.
        let edge_on = source_plane([
            DVec3::ZERO,
            DVec3::new(0.0, 0.0, -1.0),
            DVec3::new(0.0, 1.0, -1.0),
        ]);
        assert_eq!(
            ray_plane_depth(edge_on, DVec3::ZERO, DVec3::new(0.0, 0.3, -1.0)),
            None
        );
        // Degenerate source triangle.
        let line = source_plane([DVec3::ZERO, DVec3::X, DVec3::X * 2.0]);
        assert_eq!(ray_plane_depth(line, DVec3::ZERO, DVec3::NEG_Z), None);
    }
}
