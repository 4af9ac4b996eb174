//! Shared helpers of the integration tests: the translucent scenes, colour
//! differences, the per-sample compositing reference, and the comparisons
//! of two renders that several files make. Scenes are prepared and
//! rendered with `hider_testkit`.

use glam::DVec3;
use hider_abuffer::{
    ABuffer, ABufferOptions, ABufferStats, DepthMode, SamplePattern, SsaaOptions,
    SupersampledZBuffer,
};
use hider_scene::geom::fixed::SUBPIXEL_SCALE;
use hider_scene::shade::{prim_color, to_srgb8};
use hider_scene::{Frame, Hider, Material, Mesh, Scene, ScreenScene, ShadeMode, procedural};
use hider_testkit::render;
use proptest::prelude::*;

/// Every depth mode.
pub const DEPTH_MODES: [DepthMode; 3] = [
    DepthMode::PerSample,
    DepthMode::MinMax,
    DepthMode::ZminOrder,
];

/// The default options with every tile on fragment lists (no sample
/// buffer for opaque tiles): what the tests of the lists' own machinery
/// (culling, pruning, merging, memory) render with.
pub fn lists() -> ABufferOptions {
    ABufferOptions::default().with_sample_tiles(false)
}

/// Largest per-channel difference between two colour buffers.
pub fn max_color_diff(a: &Frame, b: &Frame) -> u8 {
    a.color
        .iter()
        .zip(&b.color)
        .flat_map(|(x, y)| (0..3).map(move |c| x[c].abs_diff(y[c])))
        .max()
        .unwrap_or(0)
}

fn tri_mesh(name: &str, p: [DVec3; 3]) -> Mesh {
    Mesh {
        name: name.into(),
        positions: p.to_vec(),
        indices: vec![[0, 1, 2]],
        ..Mesh::default()
    }
}

fn glass(name: &str, diffuse: [f32; 3], opacity: f32) -> Material {
    Material {
        name: name.into(),
        diffuse,
        opacity,
        ..Material::default()
    }
}

/// Three overlapping translucent triangles at different depths, the first
/// two piercing each other, in the given submission order.
pub fn three_glass(order: [usize; 3]) -> Scene {
    let tris = [
        (
            "red",
            [
                DVec3::new(-1.0, -0.8, -0.3),
                DVec3::new(0.9, -0.6, 0.3),
                DVec3::new(-0.2, 0.9, 0.0),
            ],
            [0.9, 0.15, 0.1],
            0.5,
        ),
        (
            "green",
            [
                DVec3::new(-0.9, 0.7, 0.35),
                DVec3::new(-0.1, -1.0, -0.35),
                DVec3::new(1.0, 0.5, 0.0),
            ],
            [0.1, 0.85, 0.2],
            0.6,
        ),
        (
            "blue",
            [
                DVec3::new(-0.5, -0.2, 0.5),
                DVec3::new(0.6, -0.9, 0.5),
                DVec3::new(0.4, 0.8, 0.5),
            ],
            [0.15, 0.3, 0.95],
            0.4,
        ),
    ];
    let mut s = Scene::default();
    for k in order {
        let (name, p, c, a) = tris[k];
        s.push_mesh(tri_mesh(name, p), Some(glass(name, c, a)));
    }
    s
}

/// Makes every material of `scene` translucent with `opacity`.
pub fn with_opacity(mut scene: Scene, opacity: f32) -> Scene {
    for m in &mut scene.materials {
        m.opacity = opacity;
    }
    scene
}

/// A random soup of `count` triangles, translucent (opacity 0.5) if
/// `glass`: the scenes of the soup properties.
pub fn soup(count: u32, seed: u64, glass: bool) -> Scene {
    let scene = procedural::random_soup(count, seed);
    if glass {
        with_opacity(scene, 0.5)
    } else {
        scene
    }
}

/// The counters that say what was done, without the memory figures (each
/// thread has a pool of its own).
fn work(s: &ABufferStats) -> ABufferStats {
    ABufferStats {
        pool_fragments: 0,
        bytes: 0,
        ..*s
    }
}

/// Asserts that a render `got` gave what a reference render `want` of the
/// same scene gave: the same frame, sample ids and work counters (frame,
/// sample ids, counters in each). `at` says which render, in every message.
pub fn assert_same_render(
    at: &str,
    want: (&Frame, &[u32], &ABufferStats),
    got: (&Frame, &[u32], &ABufferStats),
) {
    // `assert!`, not `assert_eq!`: a dump of a whole frame or of every
    // sample would bury the message.
    assert!(want.0 == got.0, "{at}: frames differ");
    assert!(want.1 == got.1, "{at}: sample ids differ");
    assert_eq!(work(want.2), work(got.2), "{at}");
}

/// Checks, in a `proptest!` body (`?`), that two frames of one scene agree
/// where only the compositing's rounding may differ: the same coverage and
/// centre ids, colours within one 8-bit step.
pub fn same_image(a: &Frame, b: &Frame) -> Result<(), TestCaseError> {
    prop_assert_eq!(&a.coverage, &b.coverage);
    prop_assert_eq!(&a.ids, &b.ids);
    prop_assert!(max_color_diff(a, b) <= 1);
    Ok(())
}

/// Checks, in a `proptest!` body (`?`), that `a`, which rendered `s` into
/// `fa`, sampled it as the supersampled z-buffer with `options` does: every
/// sample's front-most primitive, the coverage and the centre ids. Returns
/// the z-buffer's frame for the caller's further checks.
pub fn equals_supersampling(
    s: &ScreenScene,
    options: SsaaOptions,
    a: &ABuffer,
    fa: &Frame,
) -> Result<Frame, TestCaseError> {
    let mut z = SupersampledZBuffer::new(options);
    let fz = render(&mut z, s).0;
    prop_assert_eq!(a.sample_ids(), z.sample_ids().to_vec());
    prop_assert_eq!(&fa.coverage, &fz.coverage);
    prop_assert_eq!(&fa.ids, &fz.ids);
    Ok(fz)
}

/// An independent reference for per-sample compositing: for every sample
/// of `pattern`, every triangle covering it (shared edge test), sorted by
/// its `f64` plane depth (lower id on ties), composited front to back over
/// black; pixel = mean of samples, sRGB.
///
/// Kept here rather than delegated to `hider-oracle`: the oracle answers
/// which surface is visible at a pixel centre and how much of a pixel is
/// covered, not the colour of translucent layers composited at the
/// A-buffer's sub-pixel samples, which is what this checks.
pub fn brute_force_colors(s: &ScreenScene, pattern: SamplePattern) -> Vec<[u8; 3]> {
    let (w, h) = (s.viewport.width, s.viewport.height);
    let colors: Vec<([f32; 3], f32)> = (0..s.prims.len() as u32)
        .map(|p| prim_color(s, p, ShadeMode::Lambert))
        .collect();
    let scale = f64::from(SUBPIXEL_SCALE);
    let mut out = Vec::new();
    for j in 0..h {
        for i in 0..w {
            let mut sum = [0.0f64; 3];
            for &(sx, sy) in pattern.positions() {
                let x = i64::from(i) * 256 + i64::from(sx);
                let y = i64::from(j) * 256 + i64::from(sy);
                let mut hits: Vec<(f64, u32)> = s
                    .tris
                    .iter()
                    .filter(|t| t.edges().iter().all(|e| e.contains(x, y)))
                    .map(|t| (t.depth.eval(x as f64 / scale, y as f64 / scale), t.prim))
                    .collect();
                hits.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                let mut transmit = 1.0f64;
                for (_, prim) in hits {
                    let (rgb, a) = colors[prim as usize];
                    for c in 0..3 {
                        sum[c] += transmit * f64::from(a) * f64::from(rgb[c]);
                    }
                    transmit *= 1.0 - f64::from(a);
                }
            }
            let n = pattern.count() as f64;
            out.push(sum.map(|c| to_srgb8((c / n) as f32)));
        }
    }
    out
}

/// Largest channel difference between a frame and reference colours.
pub fn max_diff_to(frame: &Frame, reference: &[[u8; 3]]) -> u8 {
    frame
        .color
        .iter()
        .zip(reference)
        .flat_map(|(x, y)| (0..3).map(move |c| x[c].abs_diff(y[c])))
        .max()
        .unwrap_or(0)
}
