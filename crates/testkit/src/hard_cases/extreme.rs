//! Scenes at the edges of the input space: a triangle on the far plane,
//! a pile of tiny triangles over one pixel centre, a polygon whose vertex
//! list repeats itself and a sphere far from the origin.

use glam::DVec3;
use hider_scene::Scene;
use hider_scene::procedural::{self, SplitMix64};

use super::support::{colour, push, random_unit};
use crate::cameras::{ONE_PIXEL_CENTRE, far_plane_camera, one_pixel_camera};

/// One triangle lying exactly on the far plane of its camera
/// ([`far_plane_camera`](crate::cameras::far_plane_camera): eye at the origin looking down -Z, near 0.1,
/// far 16): corners `(-1, -1, -16)`, `(1, -1, -16)`, `(0, 1, -16)`. Its
/// window depth is exactly 1, the value a depth buffer is cleared to;
/// it is inside the view volume (the far plane is closed), so every
/// pixel centre it covers shows it.
pub fn far_plane_triangle() -> Scene {
    let mut s = Scene::default();
    push(
        &mut s,
        "far_plane".into(),
        vec![
            DVec3::new(-1.0, -1.0, -16.0),
            DVec3::new(1.0, -1.0, -16.0),
            DVec3::new(0.0, 1.0, -16.0),
        ],
        vec![[0, 1, 2]],
        [0.8, 0.5, 0.3],
    );
    s.camera = Some(far_plane_camera());
    s
}

/// `count` tiny triangles all covering one pixel centre at 64 x 64
/// ([`ONE_PIXEL_CENTRE`](crate::cameras::ONE_PIXEL_CENTRE) through
/// [`one_pixel_camera`](crate::cameras::one_pixel_camera)): each has that
/// point inside it with a margin of a few snapping steps, corners 0.15 to
/// 0.4 pixel away, a random tilt (normal within 45 degrees of the view
/// axis) and a random depth in `[-1, 1]`. Every one of them is a candidate
/// at the same pixel, and every span or edge list of that pixel's row holds
/// all of them at once: the worst case for anything quadratic in the
/// depth complexity of one pixel.
pub fn one_pixel_pile(count: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let pixel = 1.0 / 32.0;
    let mut positions = Vec::with_capacity(3 * count as usize);
    for _ in 0..count {
        let n = (DVec3::Z + random_unit(&mut rng) * 0.7).normalize();
        let u = n.any_orthonormal_vector();
        let v = n.cross(u);
        let centre = ONE_PIXEL_CENTRE + DVec3::Z * rng.range(-1.0, 1.0);
        let a0 = rng.range(0.0, std::f64::consts::TAU);
        for k in 0..3 {
            // Angular gaps below pi keep the centre inside whatever the
            // radii; the projection onto the screen keeps it inside too.
            let a = a0 + std::f64::consts::TAU * f64::from(k) / 3.0 + rng.range(-0.4, 0.4);
            let r = pixel * rng.range(0.15, 0.4) / n.z;
            positions.push(centre + (u * a.cos() + v * a.sin()) * r);
        }
    }
    let indices = (0..count).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    let mut s = Scene::default();
    push(
        &mut s,
        format!("pile_{count}"),
        positions,
        indices,
        [0.7, 0.5, 0.6],
    );
    s.camera = Some(one_pixel_camera());
    s
}

/// A quadrilateral face whose vertex list is written `repeats` times
/// (`1 2 3 4 1 2 3 4 ...`, `4 * repeats` entries), fan-split the way an
/// OBJ loader splits a polygon, `(v0, vi, vi+1)`: `4 * repeats - 2`
/// triangles, all in one tilted plane, most of them exact copies of the
/// face's two halves (the rest, such as `(1, 4, 1)`, are degenerate).
/// Every covered pixel holds hundreds of exactly equal-depth fragments of
/// the same surface.
pub fn repeated_polygon(repeats: u32) -> Scene {
    let quad = [
        DVec3::new(-1.0, -0.75, -0.25),
        DVec3::new(1.0, -0.75, 0.25),
        DVec3::new(1.0, 0.75, 0.25),
        DVec3::new(-1.0, 0.75, -0.25),
    ];
    let list: Vec<u32> = (0..4 * repeats.max(1)).map(|i| i % 4).collect();
    let indices = (1..list.len() - 1)
        .map(|i| [list[0], list[i], list[i + 1]])
        .collect();
    let mut s = Scene::default();
    push(
        &mut s,
        format!("repeated_{repeats}"),
        quad.to_vec(),
        indices,
        [0.4, 0.6, 0.9],
    );
    s
}

/// The unit UV sphere (`procedural::uv_sphere(segments)`) moved by
/// `(offset, offset, offset)`, with no camera: the fit camera has to frame
/// it. Beyond an offset of about `1e16` the sphere's own coordinates are
/// coarser than its radius in `f64` (spacing 16 at `1e17`), so only a front
/// end that keeps the eye's position out of the view transform still sees
/// a sphere.
pub fn offset_sphere(segments: u32, offset: f64) -> Scene {
    let mut s = procedural::uv_sphere(segments);
    for mesh in &mut s.meshes {
        for p in &mut mesh.positions {
            *p += DVec3::splat(offset);
        }
    }
    s.meshes[0].name = format!("sphere_at_{offset:e}");
    if let Some(m) = s.materials.first_mut() {
        m.diffuse = colour(2);
    }
    s
}
