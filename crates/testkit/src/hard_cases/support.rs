//! What the generators share: pushing a coloured mesh, random directions
//! and triangles around a point.

use glam::DVec3;
use hider_scene::procedural::SplitMix64;
use hider_scene::{Material, Mesh, Scene};

/// Adds a mesh named `name` with a diffuse material of `colour`.
pub(super) fn push(
    scene: &mut Scene,
    name: String,
    positions: Vec<DVec3>,
    indices: Vec<[u32; 3]>,
    colour: [f32; 3],
) {
    let material = Material {
        name: name.clone(),
        diffuse: colour,
        ..Material::default()
    };
    scene.push_mesh(
        Mesh {
            name,
            positions,
            indices,
            ..Mesh::default()
        },
        Some(material),
    );
}

/// A colour from a hue-like index, so neighbouring meshes differ.
pub(super) fn colour(k: u32) -> [f32; 3] {
    let t = k as f32 * 0.618_034;
    let f = |s: f32| 0.35 + 0.5 * (std::f32::consts::TAU * (t + s)).sin().abs();
    [f(0.0), f(0.33), f(0.67)]
}

/// A unit vector in a uniformly random direction.
pub(super) fn random_unit(rng: &mut SplitMix64) -> DVec3 {
    loop {
        let v = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let l = v.length_squared();
        if l > 1e-4 && l <= 1.0 {
            return v / l.sqrt();
        }
    }
}

/// A triangle with centroid `c`, in the plane with normal `n`, corners at
/// distance about `size` from the centroid.
pub(super) fn triangle_around(rng: &mut SplitMix64, c: DVec3, n: DVec3, size: f64) -> [DVec3; 3] {
    let u = n.any_orthonormal_vector();
    let v = n.cross(u);
    let a0 = rng.range(0.0, std::f64::consts::TAU);
    let mut p = [DVec3::ZERO; 3];
    for (k, q) in p.iter_mut().enumerate() {
        let a = a0 + std::f64::consts::TAU * k as f64 / 3.0 + rng.range(-0.4, 0.4);
        let r = size * rng.range(0.7, 1.3);
        *q = u * (r * a.cos()) + v * (r * a.sin());
    }
    // Move the centroid onto c exactly (up to rounding).
    let g = (p[0] + p[1] + p[2]) / 3.0;
    p.map(|q| q - g + c)
}
