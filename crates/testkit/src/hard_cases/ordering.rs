//! Scenes with no right per-triangle depth order: pairs and boxes that
//! pierce each other, strips in cyclic overlap, and heavy overdraw.

use glam::{DQuat, DVec3};
use hider_scene::Scene;
use hider_scene::procedural::{self, SplitMix64};

use super::support::{colour, push, random_unit, triangle_around};

/// `count` pairs of triangles that pierce each other: both triangles of a
/// pair have their centroid at the same point but different planes, so
/// they cross along a line through it. No per-triangle depth order is
/// right for both halves of either triangle.
pub fn intersecting_pairs(count: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let mut s = Scene::default();
    for k in 0..count {
        let c = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-0.5, 0.5),
        );
        let size = rng.range(0.3, 0.6);
        let na = random_unit(&mut rng);
        let nb = (random_unit(&mut rng) + na * -0.5).normalize();
        let a = triangle_around(&mut rng, c, na, size);
        let b = triangle_around(&mut rng, c, nb, size);
        let positions = [a, b].concat();
        push(
            &mut s,
            format!("pair_{k}"),
            positions,
            vec![[0, 1, 2], [3, 4, 5]],
            colour(k),
        );
    }
    s
}

/// The 12 triangles of `procedural::cube()` (outward, counter-clockwise),
/// scaled, rotated and moved.
fn box_mesh(half: DVec3, rotation: DQuat, centre: DVec3) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let cube = procedural::cube();
    let m = &cube.meshes[0];
    let positions = m
        .positions
        .iter()
        .map(|&p| rotation * (p * half) + centre)
        .collect();
    (positions, m.indices.clone())
}

/// `count` boxes with random sizes and rotations, centred close together so
/// they interpenetrate. Each box is a closed mesh.
pub fn interpenetrating_boxes(count: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let mut s = Scene::default();
    for k in 0..count {
        let half = DVec3::new(
            rng.range(0.2, 0.6),
            rng.range(0.2, 0.6),
            rng.range(0.2, 0.6),
        );
        let rotation =
            DQuat::from_axis_angle(random_unit(&mut rng), rng.range(0.0, std::f64::consts::TAU));
        let centre = DVec3::new(
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
        );
        let (p, i) = box_mesh(half, rotation, centre);
        push(&mut s, format!("box_{k}"), p, i, colour(k));
    }
    s
}

/// `n` (at least 3) long strips in cyclic overlap: strip `k` runs along
/// the side `P_k -> P_{k+1}` of a regular `n`-gon, high at its base before
/// `P_k` and low at its tip beyond `P_{k+1}`, so it passes under strip
/// `k + 1` near `P_{k+1}` and over strip `k - 1` near `P_k`. No depth
/// order of the strips exists.
pub fn cyclic_overlap(n: u32) -> Scene {
    let n = n.max(3);
    let corner = |k: u32| {
        let a =
            std::f64::consts::TAU * f64::from(k % n) / f64::from(n) + std::f64::consts::FRAC_PI_2;
        DVec3::new(a.cos(), a.sin(), 0.0)
    };
    let mut s = Scene::default();
    for k in 0..n {
        let (p, q) = (corner(k), corner(k + 1));
        let along = q - p;
        let side = DVec3::new(-along.y, along.x, 0.0).normalize() * (0.3 * along.length());
        let base = p - along * 0.3 + DVec3::Z * 0.3;
        let tip = q + along * 0.8 - DVec3::Z * 0.3;
        push(
            &mut s,
            format!("strip_{k}"),
            vec![base + side, base - side, tip],
            vec![[0, 1, 2]],
            colour(k),
        );
    }
    s
}

/// `count` large random triangles (corners up to 0.6 from centres uniform
/// in `[-0.5, 0.5]^3`) piled on the same screen area: every pixel is covered
/// by many layers (heavy overdraw), and many pairs interpenetrate.
pub fn heavy_overdraw(count: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let mut positions = Vec::with_capacity(3 * count as usize);
    for _ in 0..count {
        let c = DVec3::new(
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
        );
        for _ in 0..3 {
            positions.push(
                c + DVec3::new(
                    rng.range(-0.6, 0.6),
                    rng.range(-0.6, 0.6),
                    rng.range(-0.6, 0.6),
                ),
            );
        }
    }
    let indices = (0..count).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    let mut s = Scene::default();
    push(
        &mut s,
        format!("overdraw_{count}"),
        positions,
        indices,
        [0.7, 0.6, 0.5],
    );
    s
}
