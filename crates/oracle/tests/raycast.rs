//! The ray-cast oracle against an independent brute-force z-buffer and
//! against geometry whose answer is known in closed form.

use hider_oracle::{DEFAULT_TIE_TOLERANCE, RayCastOracle};
use hider_scene::geom::fixed::pixel_center;
use hider_scene::{NO_ID, PrepareOptions, Scene, ScreenScene, View, prepare, procedural};
use proptest::prelude::*;

/// A textbook z-buffer in f64 on the snapped window-depth planes, drawing
/// in id order with LESS: what every pixel-centre hider computes.
fn brute_force(s: &ScreenScene) -> (Vec<u32>, Vec<f64>) {
    let (w, h) = (s.viewport.width as usize, s.viewport.height as usize);
    let mut ids = vec![NO_ID; w * h];
    let mut depth = vec![f64::INFINITY; w * h];
    for t in &s.tris {
        let e = t.edges();
        for j in 0..h {
            for i in 0..w {
                let (px, py) = (
                    i64::from(pixel_center(i as i32)),
                    i64::from(pixel_center(j as i32)),
                );
                if e.iter().all(|e| e.contains(px, py)) {
                    let z = t.depth.eval(i as f64 + 0.5, j as f64 + 0.5);
                    if z < depth[j * w + i] {
                        depth[j * w + i] = z;
                        ids[j * w + i] = t.prim;
                    }
                }
            }
        }
    }
    (ids, depth)
}

fn screen(scene: &Scene, size: u32) -> ScreenScene {
    let view = View::for_scene(scene, size, size).unwrap();
    prepare(scene, &view, &PrepareOptions::default()).unwrap()
}

/// Largest reference gap at which the brute force disagrees (0 if none).
fn check_against_brute_force(s: &ScreenScene) -> f64 {
    let r = RayCastOracle::default().evaluate(s);
    let (ids, _) = brute_force(s);
    let a = r.compare(&ids, DEFAULT_TIE_TOLERANCE);
    assert_eq!(a.coverage_mismatches, 0, "{a}");
    assert!(a.is_exact(), "{a}");
    ids.iter()
        .zip(&r.ids)
        .zip(&r.gap)
        .filter(|((a, b), _)| a != b)
        .map(|(_, g)| *g)
        .fold(0.0, f64::max)
}

#[test]
fn fixed_scenes_match_the_brute_force_z_buffer() {
    let mut worst: f64 = 0.0;
    for scene in [
        procedural::cube(),
        procedural::uv_sphere(12),
        procedural::intersecting_pair(),
        procedural::cyclic_triple(),
        procedural::coplanar_pair(),
        procedural::random_soup(300, 1),
    ] {
        worst = worst.max(check_against_brute_force(&screen(&scene, 64)));
    }
    eprintln!("largest gap of a brute-force disagreement: {worst:e}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn random_soups_match_the_brute_force_z_buffer(seed in any::<u64>(), count in 1u32..200, size in 8u32..48) {
        let g = check_against_brute_force(&screen(&procedural::random_soup(count, seed), size));
        prop_assert!(g < DEFAULT_TIE_TOLERANCE);
    }
}
