//! Property tests: the scanline equals the per-pixel reference (the
//! z-buffer decision) on every non-tie pixel, with identical coverage, on
//! random soups seen from random places (clipped, larger than the screen,
//! heavy overdraw and interpenetration), with and without the fallback.

mod common;

use common::{assert_matches, camera_at, render};
use hider_scanline::ScanlineOptions;
use hider_scene::geom::glam::DVec3;
use hider_scene::procedural;
use hider_testkit::{screen, screen_with};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn random_soup_matches_reference(
        count in 1u32..80,
        seed in any::<u64>(),
        w in 8u32..64,
        h in 8u32..64,
    ) {
        let s = screen(&procedural::random_soup(count, seed), w, h);
        let (frame, stats) = render(&s, ScanlineOptions::default());
        assert_matches(&s, &frame, "default");
        prop_assert_eq!(stats.pixels_written, frame.covered_count() as u64);
        let (forced, fstats) = render(&s, ScanlineOptions::default().with_max_splits_per_span(0));
        assert_matches(&s, &forced, "fallback always");
        prop_assert_eq!(fstats.splits, 0);
        prop_assert_eq!(fstats.fallback_spans, stats.split_spans);
    }

    #[test]
    fn soup_from_inside_and_around_matches_reference(
        seed in any::<u64>(),
        ex in -1.5f64..1.5,
        ey in -1.5f64..1.5,
        ez in 0.3f64..3.0,
        w in 8u32..48,
    ) {
        // The eye may sit inside the soup: triangles are near-clipped and
        // many reach far beyond the image.
        let cam = camera_at(DVec3::new(ex, ey, ez));
        let s = screen_with(&procedural::random_soup(40, seed), cam, w, 40);
        let (frame, _) = render(&s, ScanlineOptions::default());
        assert_matches(&s, &frame, "inside");
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn grid_aligned_triangles_match_reference(
        tris in prop::collection::vec(
            (prop::array::uniform3((-8i32..88, -8i32..88)), prop::array::uniform3(0.0f64..1.0)),
            1..24,
        ),
    ) {
        // Corners on a half-pixel grid (multiples of 128 units): vertices
        // and horizontal edges land exactly on pixel centres, where only
        // the top-left rule decides coverage.
        let tris: Vec<_> = tris
            .into_iter()
            .map(|(v, z)| (v.map(|(x, y)| (x * 128, y * 128)), z))
            .collect();
        let s = common::hand_made(40, 40, &tris);
        let (frame, _) = render(&s, ScanlineOptions::default());
        assert_matches(&s, &frame, "grid");
    }
}
