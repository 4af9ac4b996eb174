//! Views: a camera plus an image size, and the *fit* camera of the GL
//! reference renders.

use glam::DVec3;
use hider_geom::fixed::MAX_IMAGE_SIDE;
use hider_geom::{Camera, Viewport};

use crate::error::{Error, Result};
use crate::model::Scene;

/// What to render: a camera and an image size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// The camera.
    pub camera: Camera,
    /// Image size.
    pub viewport: Viewport,
}

impl View {
    /// A view of `width x height` pixels, checking the size (1 to
    /// [`MAX_IMAGE_SIDE`] on each side) and the camera.
    pub fn new(camera: Camera, width: u32, height: u32) -> Result<Self> {
        check_image_size(width, height)?;
        camera.validate().map_err(|e| Error::Camera(e.0))?;
        Ok(Self {
            camera,
            viewport: Viewport::new(width, height),
        })
    }

    /// The scene's own camera if it has one, else the [`fit_camera`].
    pub fn for_scene(scene: &Scene, width: u32, height: u32) -> Result<Self> {
        let camera = scene.camera.unwrap_or_else(|| fit_camera(scene));
        Self::new(camera, width, height)
    }
}

/// Checks an image size against the limits, before anything is allocated.
pub fn check_image_size(width: u32, height: u32) -> Result<()> {
    for (what, v) in [("image width", width), ("image height", height)] {
        if v == 0 {
            return Err(Error::OutOfRange {
                what,
                expected: "at least 1 pixel",
                value: v.to_string(),
            });
        }
        if v > MAX_IMAGE_SIDE {
            return Err(Error::Limit {
                what,
                value: v.into(),
                limit: MAX_IMAGE_SIDE.into(),
            });
        }
    }
    Ok(())
}

/// The camera of the Mesa llvmpipe reference renders the project compares with:
/// centre `c` = centre of the bounding box of all triangle vertices, `R` =
/// half its diagonal (1 if 0); the eye at `c + (0, 0, 2.5 R)` looking down
/// -Z with +Y up; fovy 60 degrees, near `0.1 R`, far `10 R`.
pub fn fit_camera(scene: &Scene) -> Camera {
    let (lo, hi) = scene.bounds().unwrap_or((DVec3::ZERO, DVec3::ZERO));
    let centre = (lo + hi) * 0.5;
    let r = (hi - lo).length() * 0.5;
    let r = if r > 0.0 && r.is_finite() { r } else { 1.0 };
    Camera::perspective(
        centre + DVec3::new(0.0, 0.0, 2.5 * r),
        centre,
        0.1 * r,
        10.0 * r,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Mesh;
    use hider_geom::Projection;

    #[test]
    fn fit_camera_matches_the_gl_reference_convention() {
        let mut s = Scene::default();
        s.push_mesh(
            Mesh {
                positions: vec![
                    DVec3::new(-1.0, -2.0, -2.0),
                    DVec3::new(1.0, 2.0, 2.0),
                    DVec3::ZERO,
                ],
                indices: vec![[0, 1, 2]],
                ..Mesh::default()
            },
            None,
        );
        let c = fit_camera(&s);
        assert_eq!(c.eye, DVec3::new(0.0, 0.0, 7.5)); // R = 3
        assert_eq!(
            c.projection,
            Projection::Perspective {
                fovy_degrees: 60.0,
                near: 0.30000000000000004,
                far: 30.0
            }
        );
    }

    #[test]
    fn sizes_are_checked() {
        assert!(check_image_size(1, 16384).is_ok());
        assert!(
            check_image_size(0, 10)
                .unwrap_err()
                .to_string()
                .contains("width")
        );
        let e = check_image_size(10, 16385).unwrap_err().to_string();
        assert!(e.contains("16385") && e.contains("16384"), "{e}");
    }
}
