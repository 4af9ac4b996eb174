//! Helpers shared by the integration tests: the reference check and
//! hand-made screen scenes. `screen`, the cameras and the brute-force
//! per-pixel reference (the z-buffer's decision on the window-depth planes)
//! come from `hider-testkit`.

#![allow(dead_code, reason = "each test file uses a different part")]

use hider_scanline::{Scanline, ScanlineOptions, ScanlineStats};
use hider_scene::geom::glam::DVec3;
use hider_scene::geom::{Camera, FixedPt, PlaneEq, orient2d};
use hider_scene::{Frame, Hider, Scene, ScreenScene, ScreenTri};
use hider_testkit::cameras::look_at;
use hider_testkit::{reference, score, screen};

/// Window-depth gap under which two surfaces at a pixel are a tie: the
/// planes are evaluated in f64, whose rounding is ~1e-16 at depths near 1.
pub const TIE: f64 = 1e-12;

pub fn render(s: &ScreenScene, options: ScanlineOptions) -> (Frame, ScanlineStats) {
    hider_testkit::render(&mut Scanline::new(options), s)
}

/// Asserts identical coverage, identical ids on non-tie pixels and, there,
/// the depth of the visible triangle's plane at the centre (background
/// depth 1), against the brute-force reference; returns the number of tie
/// pixels.
pub fn assert_matches(s: &ScreenScene, frame: &Frame, what: &str) -> u64 {
    let result = score::score(&reference::pixel_centre(s), frame, TIE);
    assert!(result.is_exact(), "{what}: {result}");
    result.ties
}

/// Prepares `scene` at `w x h` through `camera`, or the scene's own (fit)
/// camera.
pub fn screen_from(scene: &Scene, camera: Option<Camera>, w: u32, h: u32) -> ScreenScene {
    match camera {
        Some(c) => hider_testkit::screen_with(scene, c, w, h),
        None => screen(scene, w, h),
    }
}

/// A perspective camera at `eye` looking at the origin.
pub fn camera_at(eye: DVec3) -> Camera {
    look_at(eye, DVec3::ZERO, 0.05, 50.0)
}

/// Fixed-point corners and their window depths.
pub type HandTri = ([(i32, i32); 3], [f64; 3]);

/// A screen scene made directly of triangles (fixed-point corners and
/// per-corner window depths), bypassing the projection: lets tests put
/// vertices and edges exactly on pixel centres, where the fill rule decides.
pub fn hand_made(w: u32, h: u32, tris: &[HandTri]) -> ScreenScene {
    let mut s = screen(&Scene::default(), w, h);
    for (v, z) in tris {
        let mut v = v.map(|(x, y)| FixedPt::new(x, y));
        let mut z = *z;
        let area = orient2d(v[0], v[1], v[2]);
        if area == 0 {
            continue;
        }
        if area < 0 {
            v.swap(1, 2);
            z.swap(1, 2);
        }
        let prim = s.tris.len() as u32;
        s.tris.push(ScreenTri {
            v,
            z,
            w: [1.0; 3],
            depth: PlaneEq::from_points(&v, z).unwrap(),
            inv_w: PlaneEq::constant(1.0),
            prim,
            front_facing: true,
        });
    }
    s
}

/// `n` large triangles with random corners over a `size x size` window
/// and random corner depths: a knot of mutual interpenetration, so spans
/// split often.
pub fn knot(n: usize, size: u32, seed: u64) -> ScreenScene {
    let mut rng = hider_scene::procedural::SplitMix64::new(seed);
    let span = f64::from(size * 256);
    let tris: Vec<HandTri> = (0..n)
        .map(|_| {
            let mut corner = || {
                (
                    rng.range(-0.2 * span, 1.2 * span) as i32,
                    rng.range(-0.2 * span, 1.2 * span) as i32,
                )
            };
            let v = [corner(), corner(), corner()];
            (
                v,
                [
                    rng.range(0.0, 1.0),
                    rng.range(0.0, 1.0),
                    rng.range(0.0, 1.0),
                ],
            )
        })
        .collect();
    hand_made(size, size, &tris)
}
