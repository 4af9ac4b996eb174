//! Cameras the tests look through: the 60-degree look-at camera, a
//! random one for property tests, the cameras of the hard cases that need
//! their own, and a near-plane override.

use glam::DVec3;
use hider_geom::{Camera, Projection};
use hider_scene::Scene;
use hider_scene::procedural::SplitMix64;

/// A perspective camera (60 degree field of view) looking from `eye` at
/// `target` with +Y up: [`Camera::perspective`].
///
/// ```
/// use hider_testkit::cameras::look_at;
/// use glam::DVec3;
///
/// let camera = look_at(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 0.5, 50.0);
/// assert!(camera.validate().is_ok());
/// ```
pub fn look_at(eye: DVec3, target: DVec3, near: f64, far: f64) -> Camera {
    Camera::perspective(eye, target, near, far)
}

/// A camera looking at the scene's bounding-box centre from a random
/// direction at 2.5 to 6 radii, with a random up vector and a target
/// jittered by a few per cent (sub-pixel to pixel-sized shifts); one time
/// in four orthographic. The whole scene stays between near and far.
///
/// ```
/// use hider_scene::procedural::{self, SplitMix64};
/// use hider_testkit::cameras::random_camera;
///
/// let scene = procedural::cube();
/// let camera = random_camera(&scene, &mut SplitMix64::new(3));
/// assert!(camera.validate().is_ok());
/// ```
pub fn random_camera(scene: &Scene, rng: &mut SplitMix64) -> Camera {
    let (lo, hi) = scene.bounds().unwrap_or((DVec3::ZERO, DVec3::ZERO));
    let centre = (lo + hi) * 0.5;
    let r = ((hi - lo).length() * 0.5).max(1e-3);
    let dir = unit(rng);
    let mut up = unit(rng);
    if dir.cross(up).length() < 0.1 {
        up = dir.any_orthonormal_vector();
    }
    let dist = r * rng.range(2.5, 6.0);
    let target = centre + unit(rng) * (r * rng.range(0.0, 0.05));
    let projection = if rng.next_u64().is_multiple_of(4) {
        Projection::Orthographic {
            half_height: r * rng.range(0.8, 1.5),
            near: 0.1 * r,
            far: dist + 2.0 * r,
        }
    } else {
        Projection::Perspective {
            fovy_degrees: rng.range(30.0, 75.0),
            near: r * rng.range(0.05, 0.5),
            far: dist + r * rng.range(2.0, 50.0),
        }
    };
    Camera {
        eye: target + dir * dist,
        target,
        up,
        projection,
        lens: hider_geom::Lens::CENTRED,
    }
}

/// The camera of the pinwheel hard cases: on the view (z) axis at `z = 14`,
/// looking at the origin, with the given `near` plane distance and
/// `far = 100`. A tiny `near` (down to `1e-12`) squeezes every depth
/// difference of the scene into the last bits of window depth.
pub fn pinwheel_camera(near: f64) -> Camera {
    look_at(DVec3::new(0.0, 0.0, 14.0), DVec3::ZERO, near, 100.0)
}

/// The camera of the far-plane triangle hard case: eye at the origin
/// looking down -Z, near 0.1, far 16.
pub fn far_plane_camera() -> Camera {
    look_at(DVec3::ZERO, DVec3::NEG_Z, 0.1, 16.0)
}

/// The world point (in the plane `z = 0`) that [`one_pixel_camera`] maps
/// to a pixel centre at 64 x 64: column 32, row 31.
pub const ONE_PIXEL_CENTRE: DVec3 = DVec3::new(1.0 / 64.0, 1.0 / 64.0, 0.0);

/// An orthographic camera on the z axis looking down -Z, half height 1
/// (a pixel is `1/32` world units wide at 64 x 64), near 1, far 20: the
/// camera of the one-pixel pile hard case.
pub fn one_pixel_camera() -> Camera {
    Camera::orthographic(DVec3::new(0.0, 0.0, 10.0), DVec3::ZERO, 1.0, 1.0, 20.0)
}

/// `camera` with its near plane moved to `near` (the far plane kept):
/// the `--near` flag of the command line.
///
/// ```
/// use glam::DVec3;
/// use hider_geom::Projection;
/// use hider_testkit::cameras::{look_at, with_near};
///
/// let camera = with_near(look_at(DVec3::Z * 5.0, DVec3::ZERO, 0.5, 50.0), 1e-9);
/// assert!(matches!(camera.projection, Projection::Perspective { near, .. } if near == 1e-9));
/// ```
pub fn with_near(mut camera: Camera, near: f64) -> Camera {
    match &mut camera.projection {
        Projection::Perspective { near: n, .. } | Projection::Orthographic { near: n, .. } => {
            *n = near;
        }
    }
    camera
}

/// A unit vector in a uniformly random direction (rejection sampling).
fn unit(rng: &mut SplitMix64) -> DVec3 {
    loop {
        let v = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        if (1e-4..=1.0).contains(&v.length_squared()) {
            return v.normalize();
        }
    }
}
