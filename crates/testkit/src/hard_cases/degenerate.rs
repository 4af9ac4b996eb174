//! Near-degenerate triangles: needles and fans of tiny wedges.

use glam::{DQuat, DVec3};
use hider_scene::Scene;
use hider_scene::procedural::SplitMix64;

use super::support::{push, random_unit};

/// `count` needles: two corners far apart and the third within
/// `10^-6 .. 10^-2` of the segment between them (relative to its length),
/// some exactly on it (zero area). Planes of such triangles are
/// ill-conditioned; most cover no pixel centre at all after snapping.
pub fn slivers(count: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let mut s = Scene::default();
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    for k in 0..count {
        let a = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let b = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let t = rng.range(0.1, 0.9);
        let off = if k % 5 == 0 {
            0.0
        } else {
            10f64.powf(rng.range(-6.0, -2.0)) * (b - a).length()
        };
        let c = a + (b - a) * t + random_unit(&mut rng) * off;
        let base = positions.len() as u32;
        positions.extend([a, b, c]);
        indices.push([base, base + 1, base + 2]);
    }
    push(
        &mut s,
        "slivers".into(),
        positions,
        indices,
        [0.8, 0.75, 0.3],
    );
    s
}

/// A fan of `segments` triangles around a centre whose wedges have random,
/// mostly tiny angles (down to `1e-6` rad), a few repeated rim vertices
/// (zero-area wedges) and a tilted plane: near-degenerate triangles
/// sharing edges.
pub fn near_degenerate_fan(segments: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let segments = segments.max(3);
    let mut weights: Vec<f64> = (0..segments)
        .map(|k| match k % 4 {
            0 => 1.0,
            1 => 10f64.powf(rng.range(-6.0, -2.0)),
            2 => 0.0,
            _ => rng.range(0.05, 0.5),
        })
        .collect();
    let total: f64 = weights.iter().sum();
    weights
        .iter_mut()
        .for_each(|w| *w *= std::f64::consts::TAU / total);
    let tilt = DQuat::from_axis_angle(DVec3::new(1.0, 1.0, 0.0).normalize(), 0.6);
    let mut positions = vec![DVec3::ZERO];
    let mut angle: f64 = 0.0;
    for w in &weights {
        positions.push(tilt * DVec3::new(angle.cos(), angle.sin(), 0.0));
        angle += w;
    }
    let indices = (0..segments)
        .map(|k| [0, 1 + k, 1 + (k + 1) % segments])
        .collect();
    let mut s = Scene::default();
    push(
        &mut s,
        "near_degenerate_fan".into(),
        positions,
        indices,
        [0.4, 0.8, 0.5],
    );
    s
}
