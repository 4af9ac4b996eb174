//! Coverage converges to the analytic oracle as samples grow.

use hider_abuffer::{ABuffer, ABufferOptions, SamplePattern, SsaaOptions, SupersampledZBuffer};
use hider_oracle::analytic_coverage;
use hider_scene::{Hider, procedural};
use hider_testkit::{render, screen};

#[test]
fn coverage_error_shrinks_with_the_sample_count() {
    let scenes = [
        procedural::random_soup(40, 5),
        procedural::intersecting_pair(),
        procedural::cyclic_triple(),
        procedural::uv_sphere(10),
    ];
    let mut errors = [0.0f64; 5];
    for scene in &scenes {
        let s = screen(scene, 40, 40);
        let exact = analytic_coverage(&s);
        for (k, pattern) in SamplePattern::ALL.into_iter().enumerate() {
            let fa = render(
                &mut ABuffer::new(ABufferOptions::default().with_pattern(pattern)),
                &s,
            )
            .0;
            let fz = render(
                &mut SupersampledZBuffer::new(SsaaOptions::default().with_pattern(pattern)),
                &s,
            )
            .0;
            // Same samples, same coverage.
            assert_eq!(fa.coverage, fz.coverage, "{pattern:?}");
            errors[k] += exact.mean_coverage_error(&fa.coverage);
        }
    }
    // Mean absolute coverage error per pixel, over the scenes:
    // 1 > 4 > 8 > 16 > 32 samples.
    for k in 1..5 {
        assert!(errors[k] < errors[k - 1], "{errors:?}");
    }
    assert!(errors[4] < 0.25 * errors[0], "{errors:?}");
}

/// On the cube's silhouette the 8 x 4 mask errs by at most a quarter of
/// the pixel: one cell per crossed column for a near-horizontal edge.
#[test]
fn a_single_edge_is_resolved_to_a_few_cells() {
    let s = screen(&procedural::cube(), 48, 48);
    let exact = analytic_coverage(&s);
    let f = render(&mut ABuffer::new(ABufferOptions::default()), &s).0;
    let worst = exact
        .covered
        .iter()
        .zip(&f.coverage)
        .map(|(e, c)| (e - f64::from(*c)).abs())
        .fold(0.0, f64::max);
    // A silhouette edge crosses at most 8 columns; with one sample per cell
    // the error is at most about one cell per crossed column: 8/32.
    assert!(worst <= 0.25 + 1e-9, "worst pixel coverage error {worst}");
    assert!(worst > 0.0, "a silhouette pixel is not exactly sampled");
}
