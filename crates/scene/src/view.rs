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

/// The camera values a caller sets over a scene's own camera (or the
/// [`fit_camera`]): what the command line's `--eye`, `--target`, `--up`,
/// `--fovy`, `--near` and `--far` and the Python keywords of the same
/// names mean. `None` keeps the scene's value; the field of view and clip
/// distances apply to a perspective camera. When the eye or the target is
/// moved, a clip distance left out is fitted to the new position instead
/// (the scene's bounding sphere between near and far, near at least
/// 1/10000 of far): the scene's own planes were chosen for its own eye, and
/// kept for another they cut the scene or show nothing.
///
/// ```
/// use hider_scene::{CameraOverrides, glam::DVec3, procedural};
/// let scene = procedural::cube();
/// let camera = CameraOverrides { eye: Some(DVec3::new(3.0, 2.0, 4.0)), ..Default::default() }
///     .apply(&scene);
/// assert_eq!(camera.eye, DVec3::new(3.0, 2.0, 4.0));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CameraOverrides {
    /// The eye position.
    pub eye: Option<DVec3>,
    /// The point looked at.
    pub target: Option<DVec3>,
    /// The up direction.
    pub up: Option<DVec3>,
    /// The vertical field of view, degrees.
    pub fovy: Option<f64>,
    /// The near clip distance.
    pub near: Option<f64>,
    /// The far clip distance.
    pub far: Option<f64>,
}

impl CameraOverrides {
    /// `scene`'s camera (its own, or the fit camera) with these values set.
    pub fn apply(&self, scene: &Scene) -> Camera {
        self.apply_with(scene.camera, || scene.bounds())
    }

    /// [`Self::apply`] for a scene whose own camera is `own` and whose
    /// [`Scene::bounds`] are `bounds`, for a caller that has them already:
    /// computing them reads every index and position of the scene (about
    /// 0.5 ms on a mesh of 500,000 triangles), and `hider.render` gets
    /// them while it builds the scene from its arrays.
    pub fn apply_to_bounds(&self, own: Option<Camera>, bounds: Option<(DVec3, DVec3)>) -> Camera {
        self.apply_with(own, || bounds)
    }

    /// [`Self::apply`] with the bounds computed at most once, and only when
    /// they are needed (no fit camera and no moved eye: not at all).
    fn apply_with(
        &self,
        own: Option<Camera>,
        bounds: impl FnOnce() -> Option<(DVec3, DVec3)>,
    ) -> Camera {
        let mut bounds = Some(bounds);
        let mut known = None;
        let mut bounds = move || {
            if let Some(f) = bounds.take() {
                known = f();
            }
            known
        };
        let mut c = own.unwrap_or_else(|| fit_camera_to_bounds(bounds()));
        let moved =
            self.eye.is_some_and(|e| e != c.eye) || self.target.is_some_and(|t| t != c.target);
        c.eye = self.eye.unwrap_or(c.eye);
        c.target = self.target.unwrap_or(c.target);
        c.up = self.up.unwrap_or(c.up);
        let fitted = moved.then(|| clip_around_bounds(bounds(), c.eye));
        if let hider_geom::Projection::Perspective {
            fovy_degrees,
            near,
            far,
        } = &mut c.projection
        {
            *fovy_degrees = self.fovy.unwrap_or(*fovy_degrees);
            let (fit_near, fit_far) = fitted.unwrap_or((*near, *far));
            *near = self.near.unwrap_or(fit_near);
            *far = self.far.unwrap_or(fit_far);
        }
        c
    }
}

/// Near and far distances from `eye` that enclose the bounding sphere of
/// a scene whose bounds are `bounds` with 1% to spare, near at least
/// 1/10000 of far (for an eye inside the scene).
fn clip_around_bounds(bounds: Option<(DVec3, DVec3)>, eye: DVec3) -> (f64, f64) {
    let (lo, hi) = bounds.unwrap_or((DVec3::ZERO, DVec3::ZERO));
    let centre = lo * 0.5 + hi * 0.5;
    let r = scaled_length(hi * 0.5 - lo * 0.5);
    let r = if r > 0.0 && r.is_finite() { r } else { 1.0 };
    let d = scaled_length(centre - eye);
    let far = (d + r) * 1.01;
    let near = ((d - r) * 0.99).max(far * 1e-4);
    (near, far)
}

/// The length of `v` without squaring its components: coordinates near
/// 1e200 (which `fit_camera` accepts) overflow a plain `length`.
fn scaled_length(v: DVec3) -> f64 {
    let m = v.abs().max_element();
    if m > 0.0 && m.is_finite() {
        m * (v / m).length()
    } else {
        m
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
///
/// Huge but finite coordinates keep this camera: the centre and the
/// diagonal are computed from halved corners and a rescaled length
/// ([`hider_geom::camera::length`]), which overflow nowhere below the
/// largest `f64` and give the same bits as the plain formulas wherever
/// those do not overflow. When the scene is so small against its distance
/// from the origin that `c + 2.5 R` rounds back to about `c` (a unit sphere
/// offset by 1e17, where the spacing of `f64` is 16), the eye moves back to
/// the nearest distance `D` the centre's precision resolves (16 units of
/// its last place) and the field of view narrows to
/// `2 atan(tan 30° · 2.5 R / D)`, with near `0.04 D` and far `4 D`, so the
/// scene fills the image as it would at the origin.
pub fn fit_camera(scene: &Scene) -> Camera {
    fit_camera_to_bounds(scene.bounds())
}

/// [`fit_camera`] of a scene whose [`Scene::bounds`] are `bounds`, for a
/// caller that has them already (see [`CameraOverrides::apply_to_bounds`]).
///
/// ```
/// use hider_scene::{fit_camera, fit_camera_to_bounds, procedural};
/// let cube = procedural::cube();
/// assert_eq!(fit_camera_to_bounds(cube.bounds()), fit_camera(&cube));
/// ```
pub fn fit_camera_to_bounds(bounds: Option<(DVec3, DVec3)>) -> Camera {
    let (lo, hi) = bounds.unwrap_or((DVec3::ZERO, DVec3::ZERO));
    // Halving is exact, so these equal `(lo + hi) * 0.5` and
    // `(hi - lo).length() * 0.5` wherever the sums do not overflow.
    let centre = lo * 0.5 + hi * 0.5;
    let r = hider_geom::camera::length(hi * 0.5 - lo * 0.5);
    let r = if r > 0.0 && r.is_finite() { r } else { 1.0 };
    let distance = 2.5 * r;
    let eye = centre + DVec3::new(0.0, 0.0, distance);
    if eye.z - centre.z >= 0.5 * distance {
        return Camera::perspective(eye, centre, 0.1 * r, 10.0 * r);
    }
    let resolvable = centre.abs().max_element() * f64::EPSILON * 16.0;
    let eye = centre + DVec3::new(0.0, 0.0, resolvable.max(distance));
    let d = eye.z - centre.z;
    let half = (Camera::DEFAULT_FOVY_DEGREES.to_radians() * 0.5).tan() * distance / d;
    Camera::perspective(eye, centre, 0.04 * d, 4.0 * d)
        .with_fovy_degrees((2.0 * half.atan()).to_degrees())
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

    fn sphere(scale: f64, offset: f64) -> Scene {
        let mut s = crate::procedural::uv_sphere(12);
        for p in &mut s.meshes[0].positions {
            *p = *p * scale + DVec3::splat(offset);
        }
        s
    }

    #[test]
    fn fit_camera_survives_huge_coordinates() {
        // Coordinates near 1e200: the squared diagonal overflowed, R fell
        // back to 1 and the eye rounded onto the target. Scaled by a power
        // of two, the camera is the unit sphere's camera scaled exactly.
        let k = 2f64.powi(664);
        let (unit, big) = (fit_camera(&sphere(1.0, 0.0)), fit_camera(&sphere(k, 0.0)));
        assert!(big.validate().is_ok(), "{:?}", big.validate());
        assert_eq!(big.eye, unit.eye * k);
        let Projection::Perspective { near, far, .. } = unit.projection else {
            unreachable!()
        };
        assert_eq!(
            big.projection,
            Projection::Perspective {
                fovy_degrees: 60.0,
                near: near * k,
                far: far * k
            }
        );
        // A unit sphere offset by 1e17: the spacing of f64 there is 16, so
        // c + 2.5 R rounded back onto the centre.
        let far_away = fit_camera(&sphere(1.0, 1e17));
        assert!(far_away.validate().is_ok(), "{:?}", far_away.validate());
        assert!(View::for_scene(&sphere(1.0, 1e17), 64, 64).is_ok());
    }

    #[test]
    fn a_moved_eye_gets_clip_planes_around_the_scene_unless_given() {
        let cube = crate::procedural::cube();
        let own = fit_camera(&cube);
        let planes = |c: Camera| match c.projection {
            Projection::Perspective { near, far, .. } => (near, far),
            Projection::Orthographic { .. } => unreachable!(),
        };
        // Far away: the fit camera's far plane (for its own eye) would
        // cut the whole cube off.
        let eye = DVec3::new(0.0, 0.0, 100.0);
        let far_off = CameraOverrides {
            eye: Some(eye),
            ..Default::default()
        }
        .apply(&cube);
        let (near, far) = planes(far_off);
        let (lo, hi) = cube.bounds().unwrap();
        let r = (hi - lo).length() / 2.0;
        assert!(
            near < 100.0 - r && far > 100.0 + r && near > 0.0,
            "{near} {far}"
        );
        assert!(
            planes(own).1 < 100.0 - r,
            "the old planes would show nothing"
        );
        // Given planes are kept; an unmoved eye keeps the scene's planes.
        let given = CameraOverrides {
            eye: Some(eye),
            near: Some(0.5),
            ..Default::default()
        }
        .apply(&cube);
        assert_eq!(planes(given), (0.5, far));
        let unmoved = CameraOverrides {
            fovy: Some(30.0),
            eye: Some(own.eye),
            ..Default::default()
        }
        .apply(&cube);
        assert_eq!(planes(unmoved), planes(own));
        // Given the scene's bounds, the same cameras.
        for o in [
            CameraOverrides::default(),
            CameraOverrides {
                eye: Some(eye),
                ..Default::default()
            },
            CameraOverrides {
                eye: Some(eye),
                near: Some(0.5),
                ..Default::default()
            },
        ] {
            assert_eq!(
                o.apply_to_bounds(cube.camera, cube.bounds()),
                o.apply(&cube)
            );
        }
        // Huge coordinates: the sphere's radius does not overflow.
        let big = sphere(2f64.powi(664), 0.0);
        let moved = CameraOverrides {
            eye: Some(fit_camera(&big).eye * 2.0),
            ..Default::default()
        }
        .apply(&big);
        assert!(moved.validate().is_ok(), "{:?}", moved.validate());
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
