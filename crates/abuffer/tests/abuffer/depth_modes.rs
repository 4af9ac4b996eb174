//! Exact per-sample depth against Carpenter's zmin/zmax approximation at an
//! intersection.

use hider_abuffer::{ABuffer, ABufferOptions, DepthMode, SsaaOptions, SupersampledZBuffer};
use hider_scene::{Frame, Hider, procedural};
use hider_testkit::{render, screen};

/// Sum over pixels of the largest channel difference, and the number of
/// pixels that differ by more than one step.
fn error(a: &Frame, b: &Frame) -> (u64, usize) {
    let per_pixel: Vec<u8> = a
        .color
        .iter()
        .zip(&b.color)
        .map(|(x, y)| (0..3).map(|c| x[c].abs_diff(y[c])).max().unwrap_or(0))
        .collect();
    (
        per_pixel.iter().map(|&d| u64::from(d)).sum(),
        per_pixel.iter().filter(|&&d| d > 1).count(),
    )
}

#[test]
fn per_sample_depth_is_exact_where_the_approximation_is_not() {
    // The pair pierces each other; the cyclic triple only overlaps in a
    // cycle (no depth order, but no intersection either).
    for (scene, pierces) in [
        (procedural::intersecting_pair(), true),
        (procedural::cyclic_triple(), false),
    ] {
        // An odd size: at 64 x 64 the symmetric pair crosses exactly on a
        // pixel boundary and no pixel holds the intersection.
        let s = screen(&scene, 61, 61);
        let exact = render(&mut SupersampledZBuffer::new(SsaaOptions::default()), &s).0;
        let mut per_sample = ABuffer::new(crate::common::lists());
        let (frame_ps, stats_ps) = render(&mut per_sample, &s);
        let (e_ps, bad_ps) = error(&frame_ps, &exact);
        assert_eq!(
            bad_ps, 0,
            "per-sample depth must equal the 32-sample z-buffer"
        );
        if !pierces {
            continue;
        }
        assert!(
            stats_ps.per_sample_pixels > 0,
            "the intersection needs the per-sample path"
        );

        let minmax = render(
            &mut ABuffer::new(ABufferOptions::default().with_depth(DepthMode::MinMax)),
            &s,
        )
        .0;
        let zmin = render(
            &mut ABuffer::new(ABufferOptions::default().with_depth(DepthMode::ZminOrder)),
            &s,
        )
        .0;
        let (e_mm, bad_mm) = error(&minmax, &exact);
        let (e_z, bad_z) = error(&zmin, &exact);
        // The paper's approximation costs accuracy at the intersection ...
        assert!(bad_mm > 0 && e_mm > e_ps, "minmax {e_mm} ({bad_mm} px)");
        // ... but less than ignoring interpenetration.
        assert!(
            e_mm < e_z,
            "minmax {e_mm} ({bad_mm} px) vs zmin order {e_z} ({bad_z} px)"
        );
        // Away from intersections all modes agree: the wrong pixels are few.
        assert!(bad_mm < 61 * 61 / 10, "{bad_mm}");
    }
}
