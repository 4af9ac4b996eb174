//! Off-axis frustums: a camera's [`Lens`], and the pinhole [`Intrinsics`]
//! of OpenCV and open3d that make one.

use glam::DVec2;

use crate::camera::{CameraError, short};

/// An off-axis frustum: the image moved and stretched in NDC after the
/// symmetric projection. NDC `x' = x_scale * x + centre.x` and
/// `y' = y + centre.y`, so the view axis lands at `centre` (NDC, y up:
/// `(0, 0)` is the image centre, `(1, 1)` its top-right corner). A
/// perspective camera with a lens projects exactly as `glFrustum` does
/// (see [`Camera::projection_matrix`](crate::Camera::projection_matrix)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lens {
    /// NDC position of the view axis (the principal point).
    pub centre: DVec2,
    /// Horizontal scale against the symmetric frustum's, whose pixels
    /// are square: `fx / fy` of pinhole intrinsics.
    pub x_scale: f64,
}

impl Lens {
    /// The symmetric frustum: the view axis through the image centre,
    /// square pixels.
    pub const CENTRED: Self = Self {
        centre: DVec2::ZERO,
        x_scale: 1.0,
    };
}

impl Default for Lens {
    fn default() -> Self {
        Self::CENTRED
    }
}

/// Pinhole camera intrinsics as OpenCV's and open3d's camera matrix
/// `K = [[fx, 0, cx], [0, fy, cy], [0, 0, 1]]` holds them, in pixels of an
/// image `width x height` whose x runs right and y down from the top-left
/// corner of the top-left pixel. Pixel `(i, j)` is sampled at
/// `(i + 0.5, j + 0.5)`, as open3d's `create_rays_pinhole` samples it
/// (OpenCV puts pixel centres at integers: its `cx` is this one's
/// `cx - 0.5`). A camera-space point `(X, Y, Z)` with +Z forward and +Y
/// down projects to `(fx X / Z + cx, fy Y / Z + cy)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Intrinsics {
    /// Horizontal focal length, pixels.
    pub fx: f64,
    /// Vertical focal length, pixels.
    pub fy: f64,
    /// Principal point x, pixels from the left edge.
    pub cx: f64,
    /// Principal point y, pixels from the top edge.
    pub cy: f64,
    /// Image width, pixels.
    pub width: u32,
    /// Image height, pixels.
    pub height: u32,
}

impl Intrinsics {
    /// The vertical field of view of these intrinsics, degrees:
    /// `2 atan(height / (2 fy))`.
    pub fn fovy_degrees(&self) -> f64 {
        (2.0 * (f64::from(self.height) / (2.0 * self.fy)).atan()).to_degrees()
    }

    /// The lens that puts the principal point at `(cx, cy)` and stretches
    /// x by `fx / fy`: NDC centre `(2 cx / width - 1, 1 - 2 cy / height)`.
    pub fn lens(&self) -> Lens {
        Lens {
            centre: DVec2::new(
                2.0 * self.cx / f64::from(self.width) - 1.0,
                1.0 - 2.0 * self.cy / f64::from(self.height),
            ),
            x_scale: self.fx / self.fy,
        }
    }

    /// Checks that the intrinsics describe a camera: finite, positive
    /// focal lengths, a finite principal point, a non-empty image.
    pub fn validate(&self) -> Result<(), CameraError> {
        for (name, v) in [("fx", self.fx), ("fy", self.fy)] {
            if !(v > 0.0 && v.is_finite()) {
                return Err(CameraError(format!(
                    "intrinsics {name} {} must be a finite focal length > 0 (pixels)",
                    short(v)
                )));
            }
        }
        for (name, v) in [("cx", self.cx), ("cy", self.cy)] {
            if !v.is_finite() {
                return Err(CameraError(format!(
                    "intrinsics {name} {} must be finite",
                    short(v)
                )));
            }
        }
        if self.width == 0 || self.height == 0 {
            return Err(CameraError(format!(
                "intrinsics image size {} x {} must be at least 1 x 1",
                self.width, self.height
            )));
        }
        Ok(())
    }
}
