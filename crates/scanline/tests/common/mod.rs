//! A brute-force per-pixel reference (the z-buffer's decision, written as
//! plainly as possible) and scene helpers shared by the integration tests.

#![allow(dead_code)] // each test file uses a different part

use hider_scanline::{Scanline, ScanlineOptions, ScanlineStats};
use hider_scene::geom::glam::DVec3;
use hider_scene::geom::{Camera, Projection};
use hider_scene::{Frame, NO_ID, PrepareOptions, Scene, ScreenScene, View, prepare};

/// Window-depth gap under which two surfaces at a pixel are a tie: the
/// planes are evaluated in f64, whose rounding is ~1e-16 at depths near 1.
pub const TIE: f64 = 1e-12;

/// Per pixel: the nearest triangle's id by a LESS test in triangle order,
/// and the depth gap to the second nearest (infinite if fewer than two).
pub struct Brute {
    pub ids: Vec<u32>,
    pub gap: Vec<f64>,
}

pub fn brute(s: &ScreenScene) -> Brute {
    let (w, h) = (s.viewport.width, s.viewport.height);
    let mut ids = vec![NO_ID; (w * h) as usize];
    let mut gap = vec![f64::INFINITY; (w * h) as usize];
    for j in 0..h {
        for i in 0..w {
            let (x, y) = (i64::from(i) * 256 + 128, i64::from(j) * 256 + 128);
            let (mut best, mut second) = (f64::INFINITY, f64::INFINITY);
            let mut id = NO_ID;
            for t in &s.tris {
                if !t.edges().iter().all(|e| e.contains(x, y)) {
                    continue;
                }
                let d = t.depth.at_pixel(i, j);
                if d < best {
                    second = best;
                    best = d;
                    id = t.prim;
                } else if d < second {
                    second = d;
                }
            }
            let k = (j * w + i) as usize;
            ids[k] = id;
            gap[k] = second - best;
        }
    }
    Brute { ids, gap }
}

pub fn render(s: &ScreenScene, options: ScanlineOptions) -> (Frame, ScanlineStats) {
    let mut frame = Frame::new(s.viewport.width, s.viewport.height).unwrap();
    let stats = Scanline::with_options(options)
        .render_frame(s, &mut frame)
        .unwrap();
    (frame, stats)
}

/// Asserts identical coverage and identical ids on non-tie pixels; returns
/// the number of tie pixels.
pub fn assert_matches(s: &ScreenScene, frame: &Frame, what: &str) -> u64 {
    let r = brute(s);
    let w = s.viewport.width as usize;
    let mut ties = 0;
    for (k, (&got, &want)) in frame.ids.iter().zip(&r.ids).enumerate() {
        let (i, j) = (k % w, k / w);
        assert_eq!(
            got == NO_ID,
            want == NO_ID,
            "{what}: coverage differs at ({i}, {j})"
        );
        if r.gap[k] <= TIE {
            ties += 1;
            continue;
        }
        assert_eq!(
            got, want,
            "{what}: id differs at ({i}, {j}), gap {}",
            r.gap[k]
        );
        if got == NO_ID {
            assert_eq!(frame.depth[k], 1.0);
            continue;
        }
        // The depth written is the visible triangle's plane at the centre.
        let (x, y) = (i as i64 * 256 + 128, j as i64 * 256 + 128);
        let t = s
            .tris
            .iter()
            .find(|t| t.prim == got && t.edges().iter().all(|e| e.contains(x, y)))
            .expect("the id written covers the pixel");
        assert_eq!(frame.depth[k], t.depth.at_pixel(i as u32, j as u32) as f32);
    }
    ties
}

pub fn screen(scene: &Scene, camera: Option<Camera>, w: u32, h: u32) -> ScreenScene {
    let view = match camera {
        Some(c) => View::new(c, w, h).unwrap(),
        None => View::for_scene(scene, w, h).unwrap(),
    };
    prepare(scene, &view, &PrepareOptions::default()).unwrap()
}

/// A perspective camera at `eye` looking at the origin.
pub fn camera_at(eye: DVec3) -> Camera {
    Camera {
        eye,
        target: DVec3::ZERO,
        up: DVec3::Y,
        projection: Projection::Perspective {
            fovy_degrees: 60.0,
            near: 0.05,
            far: 50.0,
        },
    }
}

/// Fixed-point corners and their window depths.
pub type HandTri = ([(i32, i32); 3], [f64; 3]);

/// A screen scene made directly of triangles (fixed-point corners and
/// per-corner window depths), bypassing the projection: lets tests put
/// vertices and edges exactly on pixel centres, where the fill rule decides.
pub fn hand_made(w: u32, h: u32, tris: &[HandTri]) -> ScreenScene {
    use hider_scene::ScreenTri;
    use hider_scene::geom::{FixedPt, PlaneEq, orient2d};
    let mut s = prepare(
        &Scene::default(),
        &View::for_scene(&Scene::default(), w, h).unwrap(),
        &PrepareOptions::default(),
    )
    .unwrap();
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
