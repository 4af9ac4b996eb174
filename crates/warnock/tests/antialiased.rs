//! The sub-pixel mode against the oracle's analytic coverage.

mod common;

use common::{backdrop, random_big_triangles, render, triangles_in_front_of_camera};
use hider_oracle::analytic_coverage;
use hider_scene::{NO_ID, Scene, procedural};
use hider_testkit::screen;
use hider_warnock::{Rule, WarnockOptions};
use proptest::prelude::*;

/// Mean and largest absolute coverage error of the `n x n` mode, and how
/// many pixels needed the sub-pixel subdivision.
fn coverage_error(scene: &Scene, w: u32, h: u32, n: u32) -> (f64, f64, u64) {
    let screen = screen(scene, w, h);
    let (frame, stats) = render(&screen, WarnockOptions::default().with_samples_per_side(n));
    let truth = analytic_coverage(&screen);
    assert_eq!(frame.coverage.len(), truth.covered.len());
    let mut sum = 0.0;
    let mut max: f64 = 0.0;
    for (k, (&got, &want)) in frame.coverage.iter().zip(&truth.covered).enumerate() {
        let got = f64::from(got);
        // Exactly covered and exactly empty pixels are exact here too: the
        // shared edge functions leave no crack and no sample outside.
        if want > 1.0 - 1e-9 {
            assert_eq!(got, 1.0, "pixel {k} is fully covered");
        }
        if want == 0.0 {
            assert_eq!(got, 0.0, "pixel {k} is empty");
            assert_eq!(frame.ids[k], NO_ID);
        }
        assert_eq!(got > 0.0, frame.ids[k] != NO_ID);
        sum += (got - want).abs();
        max = max.max((got - want).abs());
    }
    (
        sum / truth.covered.len() as f64,
        max,
        stats.decided_by(Rule::PixelSubdivided),
    )
}

#[test]
fn coverage_error_shrinks_with_the_sample_count() {
    for scene in [
        procedural::uv_sphere(16),
        procedural::random_soup(150, 5),
        procedural::cyclic_triple(),
    ] {
        let errors: Vec<(f64, f64, u64)> = [2, 4, 8, 16]
            .iter()
            .map(|&n| coverage_error(&scene, 48, 40, n))
            .collect();
        eprintln!("coverage errors (mean, max, pixels subdivided) for 2, 4, 8, 16: {errors:?}");
        for pair in errors.windows(2) {
            assert!(pair[1].0 < pair[0].0, "mean error must shrink: {errors:?}");
        }
        // n x n samples see an edge crossing a pixel to within about one
        // row of samples.
        let (_, max4, subdivided) = errors[1];
        assert!(subdivided > 0, "edges meet inside pixels: {errors:?}");
        assert!(max4 <= 0.25, "{errors:?}");
        assert!(errors[1].0 < 0.005, "{errors:?}");
    }
}

#[test]
fn a_fully_covered_window_is_one_region_with_the_surface_colour() {
    let scene = triangles_in_front_of_camera(&[backdrop(-1.0), backdrop(0.0)]);
    let screen = screen(&scene, 32, 32);
    let (frame, stats) = render(&screen, WarnockOptions::default().with_samples_per_side(4));
    assert_eq!(stats.regions, 1);
    assert!(frame.coverage.iter().all(|&c| c == 1.0));
    assert!(frame.ids.iter().all(|&id| id == 1));
    let first = frame.color[0];
    assert!(first[..3].iter().any(|&c| c > 0));
    assert!(frame.color.iter().all(|&c| c == first));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Intersecting triangles: the sub-pixel subdivision keeps coverage
    /// within a sample row of the analytic answer everywhere.
    #[test]
    fn random_scenes_stay_close_to_analytic_coverage(
        count in 1u32..8,
        seed in any::<u64>(),
        width in 4u32..32,
        height in 4u32..32,
    ) {
        let (mean, max, _) = coverage_error(&random_big_triangles(count, seed), width, height, 4);
        prop_assert!(mean < 0.02 && max <= 0.5, "mean {mean}, max {max}");
    }
}
