//! Masks against the shared coverage test, one sample at a time.

use hider_geom::{FixedPt, PlaneEq, orient2d};
use hider_scene::ScreenTri;
use proptest::prelude::*;

use super::*;
use crate::pattern::{CENTRE, SamplePattern};

fn tri(v: [FixedPt; 3]) -> Option<ScreenTri> {
    let mut v = v;
    let area = orient2d(v[0], v[1], v[2]);
    if area == 0 {
        return None;
    }
    if area < 0 {
        v.swap(1, 2);
    }
    Some(ScreenTri {
        v,
        z: [0.5; 3],
        w: [1.0; 3],
        depth: PlaneEq::constant(0.5),
        inv_w: PlaneEq::constant(1.0),
        prim: 0,
        front_facing: true,
    })
}

fn brute(t: &ScreenTri, pattern: SamplePattern, i: u32, j: u32) -> (u32, bool) {
    let covers = |(sx, sy): (i32, i32)| {
        let x = i64::from(i) * 256 + i64::from(sx);
        let y = i64::from(j) * 256 + i64::from(sy);
        t.edges().iter().all(|e| e.contains(x, y))
    };
    let mask = pattern
        .positions()
        .iter()
        .enumerate()
        .fold(0, |m, (k, &p)| m | (u32::from(covers(p)) << k));
    (mask, covers(CENTRE))
}

/// Whether `row` (span clipping included) yields exactly the pixels of
/// row `j` (0..14) that `at` finds non-empty.
fn row_is_complete(setup: &TriCoverage, j: u32) -> bool {
    let from_row: Vec<(u32, Coverage)> = setup.row(0, 13, j).collect();
    let direct: Vec<(u32, Coverage)> = (0..14)
        .map(|i| (i, setup.at(setup.corner_values(i, j))))
        .filter(|(_, c)| !c.is_empty())
        .collect();
    from_row == direct
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// Masks (fast path, reject and per-sample path alike) equal the
    /// per-sample shared coverage test, and nothing is covered outside
    /// `pixel_range`.
    #[test]
    fn masks_equal_the_shared_coverage_test(
        c in proptest::array::uniform6(-256i32..16 * 256),
        pattern_index in 0usize..5,
    ) {
        let v = [FixedPt::new(c[0], c[1]), FixedPt::new(c[2], c[3]), FixedPt::new(c[4], c[5])];
        let Some(t) = tri(v) else { return Ok(()) };
        let pattern = SamplePattern::ALL[pattern_index];
        let setup = TriCoverage::new(&t, pattern);
        let range = pixel_range(&t, pattern, 14, 14);
        for j in 0..14 {
            for i in 0..14 {
                let got = setup.at(setup.corner_values(i, j));
                let (mask, centre) = brute(&t, pattern, i, j);
                prop_assert_eq!((got.mask, got.centre), (mask, centre), "pixel {} {}", i, j);
                if got.full {
                    prop_assert_eq!(mask, pattern.full_mask());
                }
                if i == 0 {
                    prop_assert!(row_is_complete(&setup, j), "row {}", j);
                }
                let inside = range.is_some_and(|(x0, y0, x1, y1)| (x0..=x1).contains(&i) && (y0..=y1).contains(&j));
                if !inside {
                    prop_assert!(mask == 0 && !centre, "pixel {} {} outside range {:?}", i, j, range);
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    /// Long edges (beyond the 32-bit path) and edges passing close to
    /// the pixels give the same masks as the shared test too.
    #[test]
    fn masks_of_huge_triangles_equal_the_shared_coverage_test(
        c in proptest::array::uniform6(-(1i32 << 23)..(1i32 << 23)),
        shift in proptest::array::uniform2(-2048i32..2048),
        pattern_index in 0usize..5,
    ) {
        // Move the first vertex near the 14 x 14 window so that edges
        // cross it.
        let v = [
            FixedPt::new(c[0] % 4096 + shift[0], c[1] % 4096 + shift[1]),
            FixedPt::new(c[2], c[3]),
            FixedPt::new(c[4], c[5]),
        ];
        let Some(t) = tri(v) else { return Ok(()) };
        let pattern = SamplePattern::ALL[pattern_index];
        let setup = TriCoverage::new(&t, pattern);
        for j in 0..14 {
            for i in 0..14 {
                let got = setup.at(setup.corner_values(i, j));
                prop_assert_eq!((got.mask, got.centre), brute(&t, pattern, i, j), "pixel {} {}", i, j);
            }
            prop_assert!(row_is_complete(&setup, j), "row {}", j);
        }
    }
}

#[test]
fn incremental_step_matches_direct_evaluation() {
    let t = tri([
        FixedPt::new(100, 50),
        FixedPt::new(3000, 700),
        FixedPt::new(900, 2900),
    ])
    .unwrap();
    let s = TriCoverage::new(&t, SamplePattern::Grid32);
    let mut base = s.corner_values(0, 5);
    for i in 0..12 {
        assert_eq!(base, s.corner_values(i, 5));
        let step = s.step_x();
        base = [0, 1, 2].map(|e| base[e] + step[e]);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]
    /// The AVX2 offsets and grid mask are the portable ones, bit for bit,
    /// at every pixel around random triangles of the 32-bit path (every
    /// pattern, centre included).
    #[test]
    fn avx2_masks_equal_portable_masks(
        c in proptest::array::uniform6(-512i32..20 * 256),
        pattern_index in 0usize..5,
    ) {
        let Some(avx2) = hider_geom::isa::Avx2::detect() else { return Ok(()) };
        let v = [FixedPt::new(c[0], c[1]), FixedPt::new(c[2], c[3]), FixedPt::new(c[4], c[5])];
        let Some(t) = tri(v) else { return Ok(()) };
        let pattern = SamplePattern::ALL[pattern_index];
        let mut wide = TriCoverage::new(&t, pattern);
        wide.avx2 = Some(avx2);
        let mut portable = wide.clone();
        portable.avx2 = None;
        portable.reset(&t, pattern);
        prop_assert!(wide.narrow);
        prop_assert_eq!(wide.noff, portable.noff);
        for j in 0..22 {
            for i in 0..22 {
                let base = wide.corner_values(i, j);
                prop_assert_eq!(wide.at(base), portable.at(base), "pixel {} {}", i, j);
                prop_assert_eq!(wide.partial(base), portable.partial(base), "pixel {} {}", i, j);
            }
        }
    }
}

/// [`TriCoverage::classify`] of every pixel of `(x0, y0)` to `(x1, y1)`.
fn classes(setup: &TriCoverage, (x0, y0, x1, y1): (u32, u32, u32, u32)) -> Vec<Class> {
    (y0..=y1)
        .flat_map(|j| (x0..=x1).map(move |i| setup.classify(setup.corner_values(i, j))))
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2048))]
    /// The classes of whole rectangles and of runs of 8 pixels agree with
    /// the pixels' own: a rectangle is full only when every pixel is, empty
    /// only when every pixel is, and a run's bits are the pixels' classes
    /// (with AVX2 and without), for small and huge triangles and every
    /// pattern.
    #[test]
    fn rectangle_and_run_classes_agree_with_the_pixels(
        c in proptest::array::uniform6(-4i32..24),
        huge in any::<bool>(),
        rect in proptest::array::uniform4(0u32..8),
        pattern_index in 0usize..5,
    ) {
        // Whole pixels plus a hull corner's or the centre's offset: edges
        // run through hull corners, samples and centres, where a strict
        // test and a loose one differ.
        let c = c.map(|c| c.div_euclid(4) * 256 + [16, 32, 224, 240][c.rem_euclid(4) as usize]);
        let scale = if huge { 1 << 8 } else { 1 };
        let v = [
            FixedPt::new(c[0] % 6000, c[1] % 6000),
            FixedPt::new(c[2] * scale, c[3] * scale),
            FixedPt::new(c[4] * scale, c[5] * scale),
        ];
        let Some(t) = tri(v) else { return Ok(()) };
        let pattern = SamplePattern::ALL[pattern_index];
        let setup = TriCoverage::new(&t, pattern);
        let (x0, x1) = (rect[0].min(rect[1]), rect[0].max(rect[1]));
        let (y0, y1) = (rect[2].min(rect[3]), rect[2].max(rect[3]));
        let pixels = classes(&setup, (x0, y0, x1, y1));
        match setup.classify_rect((x0, y0, x1, y1)) {
            Class::Full => prop_assert!(pixels.iter().all(|&c| c == Class::Full)),
            Class::Empty => prop_assert!(pixels.iter().all(|&c| c == Class::Empty)),
            Class::Partial => prop_assert!(!pixels.iter().all(|&c| c == Class::Full)),
        }
        for j in y0..=y1 {
            for i in x0..=x1 {
                // One pixel's rectangle is that pixel's class, exactly.
                let one = setup.classify(setup.corner_values(i, j));
                prop_assert_eq!(setup.classify_rect((i, j, i, j)), one, "pixel {} {}", i, j);
            }
            let (full, touched) = setup.classify_run(setup.corner_values(x0, j));
            // The portable run is the AVX2 one, where the CPU has AVX2.
            let mut portable = setup.clone();
            portable.avx2 = None;
            prop_assert_eq!(portable.classify_run(setup.corner_values(x0, j)), (full, touched));
            for (k, class) in classes(&setup, (x0, j, x0 + 7, j)).into_iter().enumerate() {
                prop_assert_eq!(full >> k & 1 == 1, class == Class::Full, "pixel {} {}", x0 + k as u32, j);
                prop_assert_eq!(touched >> k & 1 == 1, class != Class::Empty, "pixel {} {}", x0 + k as u32, j);
            }
        }
    }
}
