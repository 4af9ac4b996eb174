//! Random triangles crossing in a cube: the family that made the painter,
//! the exact vector output and the analysis quadratic (issue 37), shared by
//! their scaling tests and benchmarks.

use hider_scene::Scene;
use hider_scene::glam::DVec3;
use hider_scene::procedural::SplitMix64;

/// `count` triangles with corners uniform in [-1, 1]^3 (from `seed`):
/// nearly every pair overlaps on screen and many pierce each other.
pub fn cube_triangles(count: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let positions = (0..count * 3)
        .map(|_| {
            DVec3::new(
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
            )
        })
        .collect();
    Scene::from_triangles(positions)
}
