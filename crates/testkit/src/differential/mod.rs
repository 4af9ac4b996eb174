//! Differential cases: bytes decoded into scenes from the families that
//! broke hiders before (exact rotational and mirror symmetry about the view
//! axis, small integer and dyadic lattices, coincident and nearly
//! coincident planes, tiny near planes and huge far/near ratios, extreme
//! scales and offsets, dense pixels, repeated vertex lists, degenerate and
//! sliver triangles, parallel layers `1e-4` to `1e-9` apart under
//! telephoto, ordinary and tight depth ranges), and the check that every
//! exact hider equals the oracle on them off exact ties, with no tolerance
//! ([`check`](mod@check)).
//!
//! One decoder serves the `cargo fuzz` target and the workspace's
//! proptest, so a finding of either replays in the other. Built with the
//! `hostile` feature.
//!
//! ```
//! use hider_testkit::differential::{check_case, differential_case};
//!
//! let case = differential_case(&[0, 4, 0, 0, 9, 0, 0, 0, 0, 0, 0]).unwrap();
//! assert!(case.label.starts_with("pinwheel"));
//! let outcome = check_case(&case).unwrap();
//! assert!(outcome.hiders > 0);
//! ```

pub mod check;
mod families;

use glam::DVec3;
use hider_geom::{Camera, Projection};
use hider_scene::Scene;

pub use check::{Outcome, check_case};

/// A decoded case: a scene, the camera to see it through, an image size
/// and a label naming the family and every parameter, for reports.
#[derive(Clone, Debug)]
pub struct DiffCase {
    /// Family and parameters, one line.
    pub label: String,
    /// The scene in world space (scaled and offset).
    pub scene: Scene,
    /// Its camera (scaled and offset with it).
    pub camera: Camera,
    /// Image width and height in pixels.
    pub size: (u32, u32),
}

/// Reads bytes as small choices; past the end every read is 0, so any
/// input decodes.
pub(crate) struct Bytes<'a> {
    data: &'a [u8],
    at: usize,
}

impl<'a> Bytes<'a> {
    pub(crate) fn new(data: &'a [u8]) -> Self {
        Self { data, at: 0 }
    }

    /// The next byte (0 past the end).
    pub(crate) fn byte(&mut self) -> u8 {
        let b = self.data.get(self.at).copied().unwrap_or(0);
        self.at += 1;
        b
    }

    /// A choice in `0..n` (`n > 0`).
    pub(crate) fn pick(&mut self, n: u32) -> u32 {
        u32::from(self.byte()) % n
    }

    /// An integer in `lo..=hi`.
    pub(crate) fn int(&mut self, lo: i32, hi: i32) -> i32 {
        lo + (self.pick((hi - lo + 1) as u32) as i32)
    }

    /// A lattice point with coordinates `k * step`, `k` in `-r..=r`.
    pub(crate) fn lattice_point(&mut self, r: i32, step: f64) -> DVec3 {
        DVec3::new(
            f64::from(self.int(-r, r)) * step,
            f64::from(self.int(-r, r)) * step,
            f64::from(self.int(-r, r)) * step,
        )
    }
}

/// Decodes `data` into a case of one family, seen along the symmetry (z)
/// axis or obliquely at 8 to 256 pixels a side, then scaled by `10^e` (`e` from -20 to 20) and moved
/// by up to `1e17`, with a near plane from `1e-1` down to `1e-12` of the
/// scene size and far/near ratios up to `1e13`. `None` when the camera is
/// refused (a legitimate answer to a hostile camera, not a finding).
pub fn differential_case(data: &[u8]) -> Option<DiffCase> {
    let mut b = Bytes::new(data);
    let (family, scene, own) = families::family(&mut b);
    // Mostly small images (fast cases); one in eight dense, up to 256 a
    // side, where the cut lines of symmetric scenes meet many centres.
    let size = match b.pick(8) {
        0 => (64 + b.pick(193), 64 + b.pick(193)),
        _ => (8 + b.pick(57), 8 + b.pick(57)),
    };
    let scale_exp = match b.pick(4) {
        0 => 0,
        _ => b.int(-20, 20),
    };
    let offset_exp = match b.pick(3) {
        0 => None,
        _ => Some(b.int(0, 17)),
    };
    let near_exp = b.int(1, 12);
    let far_exp = b.int(0, 13);
    let scale = 10f64.powi(scale_exp);
    let offset = offset_exp.map_or(DVec3::ZERO, |e| {
        DVec3::new(1.0, f64::from(b.int(-1, 1)), f64::from(b.int(-1, 1))) * 10f64.powi(e)
    });
    let (camera, size) = own.unwrap_or_else(|| (view_axis_camera(&mut b, near_exp, far_exp), size));
    let label = format!(
        "{family}; {}x{}; scale 1e{scale_exp}; offset {}; near 1e-{near_exp}; far/near <= 1e{far_exp}",
        size.0,
        size.1,
        offset_exp.map_or("0".to_owned(), |e| format!("1e{e}")),
    );
    let scene = transform_scene(scene, scale, offset);
    let camera = transform_camera(camera, scale, offset);
    camera.validate().ok()?;
    Some(DiffCase {
        label,
        scene,
        camera,
        size,
    })
}

/// A perspective camera for scenes of radius about 4 to 6 around the
/// origin, framing a radius of about 5 at the origin:
/// on the z axis (the symmetry axis, three times in four) or oblique,
/// with the near plane at `10^-near_exp` and the far plane at the larger
/// of the scene's far side and `near * 10^far_exp`.
fn view_axis_camera(b: &mut Bytes<'_>, near_exp: i32, far_exp: i32) -> Camera {
    let eye = match b.pick(4) {
        0 => DVec3::new(f64::from(b.int(-5, 5)), f64::from(b.int(-5, 5)), 9.0),
        _ => DVec3::new(0.0, 0.0, 9.0),
    };
    let near = 10f64.powi(-near_exp);
    let far = (near * 10f64.powi(far_exp)).max(30.0);
    Camera {
        eye,
        target: DVec3::ZERO,
        up: DVec3::Y,
        projection: Projection::Perspective {
            fovy_degrees: 60.0,
            near,
            far,
        },
        lens: hider_geom::Lens::CENTRED,
    }
}

/// Every vertex `p` becomes `p * scale + offset`.
fn transform_scene(mut scene: Scene, scale: f64, offset: DVec3) -> Scene {
    for mesh in &mut scene.meshes {
        for p in &mut mesh.positions {
            *p = *p * scale + offset;
        }
    }
    scene.camera = None;
    scene
}

/// The camera that sees the transformed scene as `camera` saw the
/// original: positions moved like the vertices, distances scaled.
fn transform_camera(camera: Camera, scale: f64, offset: DVec3) -> Camera {
    let projection = match camera.projection {
        Projection::Perspective {
            fovy_degrees,
            near,
            far,
        } => Projection::Perspective {
            fovy_degrees,
            near: near * scale,
            far: far * scale,
        },
        Projection::Orthographic {
            half_height,
            near,
            far,
        } => Projection::Orthographic {
            half_height: half_height * scale,
            near: near * scale,
            far: far * scale,
        },
    };
    Camera {
        eye: camera.eye * scale + offset,
        target: camera.target * scale + offset,
        up: camera.up,
        projection,
        lens: camera.lens,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_input_decodes_deterministically() {
        let mut state = 1u64;
        let mut families = std::collections::BTreeSet::new();
        for len in 0..300 {
            let data: Vec<u8> = (0..len % 40)
                .map(|_| {
                    state = state.wrapping_mul(6364136223846793005).wrapping_add(1);
                    (state >> 56) as u8
                })
                .collect();
            let a = differential_case(&data);
            let b = differential_case(&data);
            assert_eq!(a.is_some(), b.is_some());
            if let (Some(a), Some(b)) = (a, b) {
                assert_eq!(a.label, b.label);
                assert_eq!(a.scene, b.scene);
                families.insert(a.label.split(' ').next().unwrap_or("").to_owned());
            }
        }
        assert!(families.len() >= 6, "{families:?}");
    }

    #[test]
    fn parallel_layers_decode_and_every_exact_hider_orders_them() {
        // 135 = 7 mod 8, in the upper half: the layers; then gap exponent
        // 4 + 5 = 9, 2 + 1 = 3 layers, seed 7, and each of the cameras.
        for camera in 0..3 {
            let case = differential_case(&[135, 5, 1, 7, camera, 40]).unwrap();
            assert!(
                case.label.starts_with("parallel_layers 3 gap 1e-9"),
                "{}",
                case.label
            );
            let outcome = check_case(&case).unwrap_or_else(|e| panic!("{e}"));
            assert!(
                outcome.refused.is_none() && outcome.hiders > 0,
                "{outcome:?}"
            );
        }
        // Below 128 the byte still means heavy overdraw, as stored cases
        // expect.
        let case = differential_case(&[7]).unwrap();
        assert!(case.label.starts_with("heavy_overdraw"), "{}", case.label);
    }

    #[test]
    fn reads_past_the_end_are_zero() {
        let mut b = Bytes::new(&[3]);
        assert_eq!(b.byte(), 3);
        assert_eq!((b.byte(), b.pick(5), b.int(-2, 2)), (0, 0, -2));
    }
}
