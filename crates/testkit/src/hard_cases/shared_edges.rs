//! Meshes whose triangles share edges and vertices: a flat fan, a closed
//! double pyramid and a torus, for cracks and double hits.

use glam::{DQuat, DVec3};
use hider_scene::Scene;
use hider_scene::procedural::SplitMix64;

use super::support::push;
use crate::cameras::look_at;

/// A star-shaped disc in the plane `z = 0`: `segments` triangles around a
/// centre, rim radii jittered, every interior edge shared by two triangles
/// and the centre by all. Each pixel centre inside it must be covered
/// exactly once.
pub fn fan(segments: u32, seed: u64) -> Scene {
    let (positions, indices) = fan_mesh(segments, seed, 0.0);
    let mut s = Scene::default();
    push(&mut s, "fan".into(), positions, indices, [0.5, 0.6, 0.9]);
    s
}

/// The vertices and triangles of a star-shaped fan with its centre at
/// height `apex`.
fn fan_mesh(segments: u32, seed: u64, apex: f64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut rng = SplitMix64::new(seed);
    let n = segments.max(3);
    let mut positions = vec![DVec3::new(0.0, 0.0, apex)];
    for k in 0..n {
        let a = std::f64::consts::TAU * f64::from(k) / f64::from(n);
        let r = rng.range(0.6, 1.0);
        positions.push(DVec3::new(r * a.cos(), r * a.sin(), 0.0));
    }
    // Counter-clockwise seen from +z.
    let indices = (0..n).map(|k| [0, 1 + k, 1 + (k + 1) % n]).collect();
    (positions, indices)
}

/// A closed star-shaped double pyramid: two fans of `segments` triangles
/// sharing a jittered rim, apexes at `z = ±0.8`, wound outward. A closed
/// mesh whose pixel centres meet many shared vertices and edges.
pub fn bipyramid(segments: u32, seed: u64) -> Scene {
    let (mut positions, mut indices) = fan_mesh(segments, seed, 0.8);
    let n = positions.len() as u32 - 1;
    positions.push(DVec3::new(0.0, 0.0, -0.8));
    let bottom = n + 1;
    // The bottom fan is wound the other way, so it faces -z (outward).
    indices.extend((0..n).map(|k| [bottom, 1 + (k + 1) % n, 1 + k]));
    let rotation = DQuat::from_axis_angle(DVec3::new(1.0, 0.2, 0.0).normalize(), 0.9);
    let positions = positions.into_iter().map(|p| rotation * p).collect();
    let mut s = Scene::default();
    push(
        &mut s,
        "bipyramid".into(),
        positions,
        indices,
        [0.9, 0.6, 0.4],
    );
    s
}

/// A torus around the y axis: `major` segments around the ring (radius
/// `ring`), `minor` around the tube (radius `tube`), outward
/// counter-clockwise: a closed mesh that is not convex (two layers overlap
/// on screen). Segment counts are clamped to at least 3.
pub fn torus(major: u32, minor: u32, ring: f64, tube: f64) -> Scene {
    let (major, minor) = (major.max(3), minor.max(3));
    let mut positions = Vec::with_capacity((major * minor) as usize);
    for i in 0..major {
        let u = std::f64::consts::TAU * f64::from(i) / f64::from(major);
        for j in 0..minor {
            let v = std::f64::consts::TAU * f64::from(j) / f64::from(minor);
            let r = ring + tube * v.cos();
            positions.push(DVec3::new(r * u.cos(), tube * v.sin(), -r * u.sin()));
        }
    }
    let at = |i: u32, j: u32| (i % major) * minor + (j % minor);
    let mut indices = Vec::with_capacity((2 * major * minor) as usize);
    for i in 0..major {
        for j in 0..minor {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            indices.push([a, b, c]);
            indices.push([a, c, d]);
        }
    }
    let mut s = Scene::default();
    push(
        &mut s,
        format!("torus_{major}x{minor}"),
        positions,
        indices,
        [0.6, 0.8, 0.7],
    );
    // Tilted view so the hole and both layers show.
    s.camera = Some(look_at(
        DVec3::new(0.0, 1.6 * (ring + tube), 2.4 * (ring + tube)),
        DVec3::ZERO,
        0.1 * ring,
        20.0 * ring,
    ));
    s
}
