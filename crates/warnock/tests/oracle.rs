//! Cross-validation: Warnock to pixel size against the brute-force z-buffer
//! (bit for bit) and against the ray-cast oracle (every non-tie pixel, with
//! identical coverage).

mod common;

use common::{brute_force, random_big_triangles, render, screen};
use hider_oracle::{DEFAULT_TIE_TOLERANCE, RayCastOracle};
use hider_scene::{Scene, procedural};
use hider_warnock::WarnockOptions;
use proptest::prelude::*;

/// Checks one scene at one size; returns the oracle's tie count.
fn check(scene: &Scene, width: u32, height: u32) -> u64 {
    let screen = screen(scene, width, height);
    let (frame, stats) = render(&screen, WarnockOptions::default());
    let (ids, depth) = brute_force(&screen);
    // Same decisions as a LESS z-buffer in f64: ids and depths bit for bit.
    assert_eq!(frame.ids, ids, "ids differ from the brute-force z-buffer");
    assert_eq!(
        frame.depth, depth,
        "depths differ from the brute-force z-buffer"
    );
    let reference = RayCastOracle::new().evaluate(&screen);
    let agreement = reference.compare(&frame.ids, DEFAULT_TIE_TOLERANCE);
    assert!(agreement.is_exact(), "{agreement} ({stats:?})");
    assert_eq!(agreement.coverage_mismatches, 0);
    agreement.ties
}

#[test]
fn hard_cases_equal_the_oracle() {
    let scenes = [
        ("cube", procedural::cube()),
        ("intersecting pair", procedural::intersecting_pair()),
        ("cyclic triple", procedural::cyclic_triple()),
        ("coplanar pair", procedural::coplanar_pair()),
        ("sphere", procedural::uv_sphere(12)),
    ];
    for (name, scene) in &scenes {
        for (w, h) in [(64, 48), (37, 53), (1, 40), (40, 1), (128, 128)] {
            let ties = check(scene, w, h);
            if *name == "coplanar pair" && (w, h) == (128, 128) {
                // Every overlapped pixel is a tie: counted, not skipped.
                assert!(ties > 0, "the coplanar pair must show ties");
            }
        }
    }
}

#[test]
fn soups_equal_the_oracle() {
    for seed in 0..4 {
        check(&procedural::random_soup(300, seed), 96, 80);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Big random triangles pierce each other all over the image: the
    /// surrounder test must see planes crossing and subdivide.
    #[test]
    fn random_intersecting_triangles_equal_the_oracle(
        count in 1u32..10,
        seed in any::<u64>(),
        width in 1u32..48,
        height in 1u32..48,
    ) {
        check(&random_big_triangles(count, seed), width, height);
    }

    #[test]
    fn random_soups_equal_the_oracle(
        count in 1u32..150,
        seed in any::<u64>(),
        width in 8u32..64,
        height in 8u32..64,
    ) {
        check(&procedural::random_soup(count, seed), width, height);
    }
}
