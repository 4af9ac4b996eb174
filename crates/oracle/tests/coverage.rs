//! Analytic coverage against closed-form areas and 64 x 64 supersampling.

use std::collections::BTreeMap;

use hider_oracle::analytic_coverage;
use hider_scene::geom::Camera;
use hider_scene::geom::glam::DVec3;
use hider_scene::{Mesh, Scene, ScreenScene, procedural};
use hider_testkit::screen;
use proptest::prelude::*;

/// Per pixel, the fraction of a 64 x 64 grid of samples each primitive
/// wins (LESS on the window-depth planes, ties to the lower id, exact
/// edge functions): what an ideal 4096-sample MSAA would resolve.
fn supersample(s: &ScreenScene) -> Vec<BTreeMap<u32, f64>> {
    const N: i64 = 64;
    let (w, h) = (s.viewport.width as i64, s.viewport.height as i64);
    let mut out = vec![BTreeMap::new(); (w * h) as usize];
    let edges: Vec<_> = s.tris.iter().map(|t| t.edges()).collect();
    for j in 0..h {
        for i in 0..w {
            let cell = &mut out[(j * w + i) as usize];
            for sy in 0..N {
                for sx in 0..N {
                    // Sample centres at 2 + 4k fixed-point units: exact.
                    let (x, y) = (i * 256 + 2 + 4 * sx, j * 256 + 2 + 4 * sy);
                    let mut best: Option<(f64, u32)> = None;
                    for (t, e) in s.tris.iter().zip(&edges) {
                        if e.iter().all(|e| e.contains(x, y)) {
                            let z = t.depth.eval(x as f64 / 256.0, y as f64 / 256.0);
                            if best.is_none_or(|b| z < b.0 || (z == b.0 && t.prim < b.1)) {
                                best = Some((z, t.prim));
                            }
                        }
                    }
                    if let Some((_, p)) = best {
                        *cell.entry(p).or_insert(0.0) += 1.0 / (N * N) as f64;
                    }
                }
            }
        }
    }
    out
}

/// Checks analytic coverage against supersampling. A straight boundary
/// crossing a pixel moves at most one sample per column of a 64-grid, so
/// each boundary segment in a pixel can change an area by at most 1/64;
/// the bound allows one segment per triangle edge and per pair of
/// triangles (their intersection line). Returns the mean absolute error.
fn check_against_supersampling(s: &ScreenScene) -> f64 {
    let c = analytic_coverage(s);
    let ss = supersample(s);
    let w = s.viewport.width;
    let mut err_sum = 0.0;
    for (k, cell) in ss.iter().enumerate() {
        let (x, y) = (k as u32 % w, k as u32 / w);
        let frags: BTreeMap<u32, f64> = c.pixel_fragments(x, y).collect();
        let n = s
            .tris
            .iter()
            .filter(|t| {
                let (lo_x, hi_x) = (
                    t.v.iter().map(|p| p.x).min().unwrap(),
                    t.v.iter().map(|p| p.x).max().unwrap(),
                );
                let (lo_y, hi_y) = (
                    t.v.iter().map(|p| p.y).min().unwrap(),
                    t.v.iter().map(|p| p.y).max().unwrap(),
                );
                lo_x < (x as i32 + 1) * 256
                    && hi_x > x as i32 * 256
                    && lo_y < (y as i32 + 1) * 256
                    && hi_y > y as i32 * 256
            })
            .count() as f64;
        let bound = (3.0 * n + n * (n - 1.0) / 2.0) / 64.0 + 1e-9;
        let total: f64 = cell.values().sum();
        let frag_total: f64 = frags.values().sum();
        assert!(
            (frag_total - c.covered[k]).abs() < 1e-9,
            "fragments sum to coverage"
        );
        assert!((0.0..=1.0).contains(&c.covered[k]));
        assert!(
            (c.covered[k] - total).abs() <= bound,
            "pixel ({x},{y}): analytic {} vs sampled {total}",
            c.covered[k]
        );
        for p in frags.keys().chain(cell.keys()) {
            let a = frags.get(p).copied().unwrap_or(0.0);
            let b = cell.get(p).copied().unwrap_or(0.0);
            assert!(
                (a - b).abs() <= bound,
                "pixel ({x},{y}) prim {p}: analytic {a} vs sampled {b}"
            );
        }
        err_sum += (c.covered[k] - total).abs();
    }
    err_sum / ss.len() as f64
}

fn quad(z_left: f64, z_right: f64, half: f64) -> Mesh {
    Mesh {
        positions: vec![
            DVec3::new(-half, -half, z_left),
            DVec3::new(half, -half, z_right),
            DVec3::new(half, half, z_right),
            DVec3::new(-half, half, z_left),
        ],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        ..Mesh::default()
    }
}

#[test]
fn a_screen_filling_quad_covers_every_pixel_fully() {
    let mut scene = Scene::default();
    scene.push_mesh(quad(0.0, 0.0, 10.0), None);
    scene.camera = procedural_camera();
    let s = screen(&scene, 8, 8);
    let c = analytic_coverage(&s);
    for (k, &cov) in c.covered.iter().enumerate() {
        assert!((cov - 1.0).abs() < 1e-12, "pixel {k}: {cov}");
    }
    // The diagonal splits pixels between the two triangles; their areas add
    // up to the whole image.
    let total: f64 = c.fragments.iter().map(|f| f.2).sum();
    assert!((total - 64.0).abs() < 1e-9);
    assert!(c.fragments.iter().any(|f| f.1 == 0) && c.fragments.iter().any(|f| f.1 == 1));
}

/// The camera of the hand-made quads: 5 units up the +Z axis looking at
/// the origin.
fn procedural_camera() -> Option<Camera> {
    Some(Camera::perspective(
        DVec3::new(0.0, 0.0, 5.0),
        DVec3::ZERO,
        1.0,
        20.0,
    ))
}

#[test]
fn crossing_planes_split_each_pixel_along_their_intersection() {
    // Two screen-filling quads tilted opposite ways cross at x = 0: the
    // left half of the image shows one, the right half the other.
    let mut scene = Scene::default();
    scene.push_mesh(quad(-1.0, 1.0, 10.0), None); // prims 0, 1: nearer on the right
    scene.push_mesh(quad(1.0, -1.0, 10.0), None); // prims 2, 3: nearer on the left
    scene.camera = procedural_camera();
    let s = screen(&scene, 8, 8);
    let c = analytic_coverage(&s);
    let mut left = 0.0;
    let mut right = 0.0;
    for &(_, prim, a) in &c.fragments {
        if prim < 2 { right += a } else { left += a }
    }
    assert!(
        (left - 32.0).abs() < 1e-6 && (right - 32.0).abs() < 1e-6,
        "{left} {right}"
    );
    check_against_supersampling(&s);
}

#[test]
fn coplanar_overlap_goes_to_the_lower_id() {
    let s = screen(&procedural::coplanar_pair(), 16, 16);
    let c = analytic_coverage(&s);
    let first: f64 = c.fragments.iter().filter(|f| f.1 == 0).map(|f| f.2).sum();
    // Triangle 0 is never hidden: its visible area is its whole area.
    let t = &s.tris[0];
    let whole = f64::from(hider_geom::orient2d(t.v[0], t.v[1], t.v[2]).unsigned_abs() as u32)
        / (2.0 * 256.0 * 256.0);
    assert!((first - whole).abs() < 1e-9, "{first} vs {whole}");
    check_against_supersampling(&s);
}

#[test]
fn hard_scenes_match_supersampling() {
    for scene in [
        procedural::intersecting_pair(),
        procedural::cyclic_triple(),
        procedural::cube(),
        procedural::uv_sphere(6),
    ] {
        let err = check_against_supersampling(&screen(&scene, 12, 12));
        // Boundary pixels are a fraction of the image and each is off by
        // at most a few 1/64 steps.
        assert!(err < 0.005, "mean coverage error {err}");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]
    #[test]
    fn random_soups_match_supersampling(seed in any::<u64>(), count in 1u32..12) {
        let err = check_against_supersampling(&screen(&procedural::random_soup(count, seed), 8, 8));
        prop_assert!(err < 0.01, "mean coverage error {err}");
    }
}
