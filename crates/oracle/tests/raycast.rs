//! The ray-cast oracle against the brute-force window-depth z-buffer (an
//! independent computation of the same visibility).

use hider_oracle::{DEFAULT_TIE_TOLERANCE, RayCastOracle};
use hider_scene::{ScreenScene, procedural};
use hider_testkit::{reference, screen};
use proptest::prelude::*;

/// Largest reference gap at which the brute force disagrees (0 if none).
fn check_against_brute_force(s: &ScreenScene) -> f64 {
    let r = RayCastOracle::default().evaluate(s);
    let ids = reference::pixel_centre(s).ids;
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
        worst = worst.max(check_against_brute_force(&screen(&scene, 64, 64)));
    }
    eprintln!("largest gap of a brute-force disagreement: {worst:e}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn random_soups_match_the_brute_force_z_buffer(seed in any::<u64>(), count in 1u32..200, size in 8u32..48) {
        let g = check_against_brute_force(&screen(&procedural::random_soup(count, seed), size, size));
        prop_assert!(g < DEFAULT_TIE_TOLERANCE);
    }
}
