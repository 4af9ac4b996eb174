//! The depth-precision study: two parallel surfaces a small gap apart,
//! seen obliquely, the farther one drawn first; a depth format that cannot
//! tell them apart keeps the farther one (a LESS depth test keeps the
//! first of two equal depths), so the share of pixels showing the farther
//! surface measures what the format loses as the gap and the camera's
//! near/far ratio shrink.
//!
//! Window depth `z/w` crowds towards 1 with distance: its resolution at
//! distance `d` is about `d^2 / near` times the format's step, which is why
//! scratchapixel's depth-buffer lesson and Reed's "Depth Precision
//! Visualized" both show a small near distance (a small near/far ratio)
//! costing more than a far far plane, and why reversed-Z floating point
//! (Reed's recommendation) keeps the precision that fixed point loses.

use hider_geom::Camera;
use hider_geom::glam::DVec3;
use hider_scene::{Frame, Material, Mesh, Scene};

/// Distance from the eye to where the view axis meets the nearer surface.
const DISTANCE: f64 = 10.0;
/// Far plane distance over [`DISTANCE`]: every visible point of the
/// surfaces (at most about 4 distances away with the default field of
/// view) is inside the far plane.
const FAR_OVER_DISTANCE: f64 = 8.0;
/// Tilt of the surfaces away from facing the eye, degrees: oblique enough
/// that depth varies across the image, not so oblique that the horizon
/// shows.
const TILT_DEGREES: f64 = 45.0;
/// Half the side of each surface over [`DISTANCE`]: wider than the view,
/// so every pixel centre is covered by both.
const HALF_SIDE_OVER_DISTANCE: f64 = 20.0;

/// Primitive ids of the farther surface (its two triangles come first).
pub const FARTHER_PRIMS: [u32; 2] = [0, 1];

/// The scene name of one point of the sweep: `gap_1e-4_nf_1e-3`.
pub fn scene_name(gap: f64, ratio: f64) -> String {
    format!("gap_{gap:.0e}_nf_{ratio:.0e}")
}

/// The `(gap, near/far ratio)` a [`scene_name`] encodes, `None` for any
/// other name.
pub fn parse_scene_name(name: &str) -> Option<(f64, f64)> {
    let rest = name.strip_prefix("gap_")?;
    let (gap, ratio) = rest.split_once("_nf_")?;
    Some((gap.parse().ok()?, ratio.parse().ok()?))
}

/// Two parallel square surfaces, tilted 45 degrees from facing the eye,
/// `gap` times their distance (10 units) apart along their normal, filling
/// the view;
/// the farther one first (primitives [`FARTHER_PRIMS`]). The camera's far
/// plane is at 8 distances and its near plane at `ratio` times that.
pub fn near_coplanar(gap: f64, ratio: f64) -> Scene {
    let tilt = TILT_DEGREES.to_radians();
    // Normal towards the eye, and the two in-plane axes.
    let normal = DVec3::new(0.0, tilt.sin(), tilt.cos());
    let (u, v) = (DVec3::X, DVec3::new(0.0, tilt.cos(), -tilt.sin()));
    let half = HALF_SIDE_OVER_DISTANCE * DISTANCE;
    let centre = DVec3::new(0.0, 0.0, -DISTANCE);
    let mut positions = Vec::new();
    for offset in [-gap * DISTANCE, 0.0] {
        let c = centre + normal * offset;
        for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            positions.push(c + u * (a * half) + v * (b * half));
        }
    }
    // Counter-clockwise as seen from the eye.
    let indices = vec![[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]];
    let mut scene = Scene::default();
    scene.push_mesh(
        Mesh {
            name: scene_name(gap, ratio),
            positions,
            indices,
            ..Mesh::default()
        },
        Some(Material {
            name: "surfaces".into(),
            diffuse: [0.7, 0.7, 0.7],
            ..Material::default()
        }),
    );
    let far = FAR_OVER_DISTANCE * DISTANCE;
    scene.camera = Some(Camera::perspective(
        DVec3::ZERO,
        DVec3::new(0.0, 0.0, -1.0),
        ratio * far,
        far,
    ));
    scene
}

/// Pixels of `frame` showing the farther surface.
pub fn farther_pixels(frame: &Frame) -> u64 {
    frame
        .ids
        .iter()
        .filter(|id| FARTHER_PRIMS.contains(id))
        .count() as u64
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_plan::registry;
    use hider_testkit::screen;

    fn share(hider: &str, gap: f64, ratio: f64) -> f64 {
        let screen = screen(&near_coplanar(gap, ratio), 64, 64);
        let mut frame = Frame::new(64, 64).unwrap();
        let mut h = registry::by_name(hider).unwrap().make();
        h.render(&screen, &mut frame).unwrap();
        assert!(
            frame.ids.iter().all(|&id| id < 4),
            "{hider}: every pixel covered"
        );
        farther_pixels(&frame) as f64 / (64.0 * 64.0)
    }

    #[test]
    fn names_round_trip() {
        assert_eq!(scene_name(1e-4, 1e-3), "gap_1e-4_nf_1e-3");
        assert_eq!(parse_scene_name("gap_1e-4_nf_1e-3"), Some((1e-4, 1e-3)));
        assert_eq!(parse_scene_name("sphere_200"), None);
    }

    #[test]
    fn the_farther_surface_shows_only_when_the_format_runs_out() {
        // A wide gap: every format keeps the nearer surface.
        for h in ["zbuffer", "zbuffer-fixed16", "zbuffer-f64"] {
            assert_eq!(share(h, 1e-2, 1e-2), 0.0, "{h}");
        }
        // A hair's gap with a small near plane: 16-bit fixed point loses
        // most pixels, f64 none.
        assert!(share("zbuffer-fixed16", 1e-5, 1e-4) > 0.5);
        assert_eq!(share("zbuffer-f64", 1e-5, 1e-4), 0.0);
    }
}
