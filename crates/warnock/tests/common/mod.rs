//! Shared helpers of the integration tests: scenes and a brute-force
//! reference.

#![allow(dead_code)] // each test file uses its own subset

use glam::DVec3;
use hider_scene::procedural::SplitMix64;
use hider_scene::{
    Frame, Mesh, NO_ID, PrepareOptions, Scene, ScreenScene, View, geom::Camera, geom::Projection,
    prepare,
};
use hider_warnock::{Warnock, WarnockOptions, WarnockStats};

/// The tiny brute-force reference: a `LESS` z-buffer in `f64` drawing the
/// triangles in order, pixel centres, shared edge functions; the
/// "one depth variable" loop of the lecture seed.
pub fn brute_force(screen: &ScreenScene) -> (Vec<u32>, Vec<f32>) {
    let vp = screen.viewport;
    let n = (vp.width * vp.height) as usize;
    let mut ids = vec![NO_ID; n];
    let mut depth = vec![1.0f32; n];
    for j in 0..vp.height {
        for i in 0..vp.width {
            let (x, y) = (i64::from(i) * 256 + 128, i64::from(j) * 256 + 128);
            let mut best = f64::INFINITY;
            for t in &screen.tris {
                if t.edges().iter().all(|e| e.contains(x, y)) {
                    let d = t.depth.eval(f64::from(i) + 0.5, f64::from(j) + 0.5);
                    if d < best {
                        best = d;
                        let k = (j * vp.width + i) as usize;
                        ids[k] = t.prim;
                        depth[k] = d as f32;
                    }
                }
            }
        }
    }
    (ids, depth)
}

/// Prepares `scene` with its fit camera at `width x height`.
pub fn screen(scene: &Scene, width: u32, height: u32) -> ScreenScene {
    let view = View::for_scene(scene, width, height).unwrap();
    prepare(scene, &view, &PrepareOptions::default()).unwrap()
}

/// Renders with `options`, returning the frame and the stats.
pub fn render(screen: &ScreenScene, options: WarnockOptions) -> (Frame, WarnockStats) {
    let mut frame = Frame::new(screen.viewport.width, screen.viewport.height).unwrap();
    let stats = Warnock::new(options)
        .render_frame(screen, &mut frame)
        .unwrap();
    (frame, stats)
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
    s.camera = Some(Camera {
        eye: DVec3::new(0.0, 0.0, 5.0),
        target: DVec3::ZERO,
        up: DVec3::Y,
        projection: Projection::Perspective {
            fovy_degrees: 60.0,
            near: 0.5,
            far: 50.0,
        },
    });
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
