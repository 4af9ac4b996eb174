//! Scene helpers and a render shortcut shared by the integration tests;
//! `screen`, the cameras and the brute-force reference come from
//! `hider-testkit`.

#![allow(dead_code, reason = "each test file uses its own subset")]

use glam::DVec3;
use hider_scene::procedural::SplitMix64;
use hider_scene::{Frame, Hider, Mesh, Scene, ScreenScene};
use hider_testkit::cameras::look_at;
use hider_warnock::{Warnock, WarnockOptions, WarnockStats};

/// Renders with `options`, returning the frame and the stats.
pub fn render(screen: &ScreenScene, options: WarnockOptions) -> (Frame, WarnockStats) {
    hider_testkit::render(&mut Warnock::new(options), screen)
}

/// `count` big random triangles with corners in [-1, 1]^3: they overlap
/// and pierce each other everywhere.
pub fn random_big_triangles(count: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let mut positions = Vec::new();
    for _ in 0..count * 3 {
        positions.push(DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ));
    }
    Scene::from_triangles(positions)
}

/// Triangles given directly, seen by a camera at (0, 0, 5) looking at the
/// origin with a 60-degree field of view.
pub fn triangles_in_front_of_camera(tris: &[[DVec3; 3]]) -> Scene {
    let mut s = Scene::default();
    let positions = tris.iter().flatten().copied().collect();
    let indices = (0..tris.len() as u32)
        .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
        .collect();
    s.push_mesh(
        Mesh {
            positions,
            indices,
            ..Mesh::default()
        },
        None,
    );
    s.camera = Some(look_at(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 0.5, 50.0));
    s
}

/// A triangle at depth `z` that covers the whole view of
/// [`triangles_in_front_of_camera`] (about +-2.9 units at the origin).
pub fn backdrop(z: f64) -> [DVec3; 3] {
    [
        DVec3::new(-20.0, -20.0, z),
        DVec3::new(40.0, -20.0, z),
        DVec3::new(-20.0, 40.0, z),
    ]
}
