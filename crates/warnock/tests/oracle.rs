//! Cross-validation: Warnock to pixel size against the brute-force z-buffer
//! on the window-depth planes (bit for bit) and against the ray-cast oracle
//! (every non-tie pixel, with identical coverage).

mod common;

use common::{random_big_triangles, render, triangles_in_front_of_camera};
use glam::DVec3;
use hider_oracle::DEFAULT_TIE_TOLERANCE;
use hider_scene::geom::Camera;
use hider_scene::procedural::SplitMix64;
use hider_scene::{Scene, procedural};
use hider_testkit::{reference, screen};
use hider_warnock::WarnockOptions;
use proptest::prelude::*;

/// Checks one scene at one size; returns the oracle's tie count.
fn check(scene: &Scene, width: u32, height: u32) -> u64 {
    let screen = screen(scene, width, height);
    let (frame, stats) = render(&screen, WarnockOptions::default());
    let brute = reference::pixel_centre(&screen);
    // Same decisions as a LESS z-buffer in f64: ids and depths bit for bit.
    assert_eq!(
        frame.ids, brute.ids,
        "ids differ from the brute-force z-buffer"
    );
    assert_eq!(
        frame.depth,
        brute.depth_f32(),
        "depths differ from the brute-force z-buffer"
    );
    let reference = reference::ray_cast(&screen);
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

/// Layers of big triangles almost on top of each other: depth gaps from
/// 1e-9 to 1e-4 world units, slightly tilted, so that surrounders are
/// nearly tied with what they would cull. The rounding guard of the
/// corner test must never let a wrong surrounder win.
fn near_ties(count: u32, seed: u64, gap: f64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let tris: Vec<[DVec3; 3]> = (0..count)
        .map(|k| {
            let c = DVec3::new(rng.range(-1.5, 1.5), rng.range(-1.5, 1.5), 0.0);
            [(-1.0, -1.0), (3.0, -1.0), (-1.0, 3.0)].map(|(x, y)| {
                let p = c + DVec3::new(x, y, 0.0) * rng.range(1.0, 3.0);
                let tilt = rng.range(-1.0, 1.0) * gap;
                DVec3::new(p.x, p.y, f64::from(k % 3) * gap + tilt)
            })
        })
        .collect();
    triangles_in_front_of_camera(&tris)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Bit-for-bit equality with the z-buffer must survive near ties.
    #[test]
    fn near_ties_equal_the_brute_force_z_buffer(
        count in 2u32..8,
        seed in any::<u64>(),
        gap_exponent in 4i32..10,
        width in 4u32..40,
        height in 4u32..40,
    ) {
        let scene = near_ties(count, seed, 10f64.powi(-gap_exponent));
        let screen = screen(&scene, width, height);
        let (frame, _) = render(&screen, WarnockOptions::default());
        let brute = reference::pixel_centre(&screen);
        prop_assert_eq!(frame.depth, brute.depth_f32());
        prop_assert_eq!(frame.ids, brute.ids);
    }

    /// Big random triangles pierce each other all over the image: the
    /// surrounder test must see planes crossing and subdivide.
    #[test]
    fn random_intersecting_triangles_equal_the_oracle(
        count in 1u32..10,
        seed in any::<u64>(),
        width in 1u32..48,
        height in 1u32..48,
        orthographic in any::<bool>(),
    ) {
        let mut scene = random_big_triangles(count, seed);
        if orthographic {
            // Window depth is affine in camera depth here: a different
            // family of depth planes for the corner certificate.
            scene.camera = Some(Camera::orthographic(DVec3::new(0.0, 0.0, 4.0), DVec3::ZERO, 1.4, 0.5, 10.0));
        }
        check(&scene, width, height);
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
