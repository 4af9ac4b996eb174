//! The page's orbit camera: yaw and pitch about the scene's target, a zoom
//! factor and a pan, turned into the same [`CameraOverrides`] the `hider`
//! command line builds from `--eye --target --up --fovy --near --far`, so
//! that a page view and a command line give the same camera bit for bit.

use glam::DVec3;
use hider_scene::{Camera, CameraOverrides, Projection, Scene};

/// Orbit parameters relative to the scene's own camera (its file's, or
/// the fit camera).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Orbit {
    /// Turn about the up axis, in radians.
    pub yaw: f64,
    /// Turn up or down, in radians (kept within +-89 degrees).
    pub pitch: f64,
    /// Distance from the target as a power of two of the base distance
    /// (0: the base camera's distance).
    pub zoom: f64,
    /// Pan along the view's right and up axes, in units of the distance.
    pub pan: [f64; 2],
}

impl Orbit {
    /// The camera flags this orbit sets over `scene`'s camera: all six
    /// given (a perspective base camera; an orthographic one keeps its own
    /// projection and gets eye, target and up).
    pub fn overrides(&self, scene: &Scene) -> CameraOverrides {
        let base = CameraOverrides::default().apply(scene);
        if *self == Self::default() {
            return Self::explicit(base);
        }
        let offset = base.eye - base.target;
        let distance = offset.length() * self.zoom.exp2();
        let up = base.up.normalize_or(DVec3::Y);
        let forward = (-offset).normalize_or(DVec3::NEG_Z);
        let right = forward.cross(up).normalize_or(DVec3::X);
        let true_up = right.cross(forward);
        let limit = 89f64.to_radians();
        let pitch = self.pitch.clamp(-limit, limit);
        // Spherical coordinates in the base camera's frame: yaw about its
        // up, pitch towards it.
        let back = -forward;
        let dir =
            (back * self.yaw.cos() + right * self.yaw.sin()) * pitch.cos() + true_up * pitch.sin();
        let target = base.target + (right * self.pan[0] + true_up * self.pan[1]) * distance;
        let scale = self.zoom.exp2();
        let mut camera = base;
        camera.eye = target + dir * distance;
        camera.target = target;
        camera.up = up;
        if let Projection::Perspective { near, far, .. } = &mut camera.projection {
            *near *= scale;
            *far *= scale;
        }
        Self::explicit(camera)
    }

    /// Every field of `camera` as an override.
    fn explicit(camera: Camera) -> CameraOverrides {
        let (fovy, near, far) = match camera.projection {
            Projection::Perspective {
                fovy_degrees,
                near,
                far,
            } => (Some(fovy_degrees), Some(near), Some(far)),
            _ => (None, None, None),
        };
        CameraOverrides {
            eye: Some(camera.eye),
            target: Some(camera.target),
            up: Some(camera.up),
            fovy,
            near,
            far,
        }
    }
}

/// The command-line flags of `overrides` (Rust's shortest round-trip form
/// of each number, so the command line parses the same `f64`s back).
pub fn cli_flags(overrides: &CameraOverrides) -> Vec<String> {
    let v = |v: DVec3| format!("{},{},{}", v.x, v.y, v.z);
    let mut flags = Vec::new();
    for (flag, value) in [
        ("--eye", overrides.eye.map(v)),
        ("--target", overrides.target.map(v)),
        ("--up", overrides.up.map(v)),
        ("--fovy", overrides.fovy.map(|x| x.to_string())),
        ("--near", overrides.near.map(|x| x.to_string())),
        ("--far", overrides.far.map(|x| x.to_string())),
    ] {
        if let Some(value) = value {
            flags.push(flag.to_owned());
            flags.push(value);
        }
    }
    flags
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rest_orbit_is_the_scene_camera_and_orbiting_keeps_the_distance() {
        let scene = hider_scene::procedural::cube();
        let base = CameraOverrides::default().apply(&scene);
        assert_eq!(Orbit::default().overrides(&scene).apply(&scene), base);
        let turned = Orbit {
            yaw: 1.0,
            pitch: 0.5,
            ..Orbit::default()
        }
        .overrides(&scene)
        .apply(&scene);
        let d0 = (base.eye - base.target).length();
        let d1 = (turned.eye - turned.target).length();
        assert!((d0 - d1).abs() < 1e-9 * d0, "{d0} {d1}");
        assert_ne!(turned.eye, base.eye);
        let flags = cli_flags(&Orbit::default().overrides(&scene));
        assert_eq!(flags.len(), 12);
        assert_eq!(flags[0], "--eye");
    }
}
