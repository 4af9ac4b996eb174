//! Work on the deepest pile one pixel can hold: `N` tiny triangles all
//! covering one pixel centre (`hard_cases::one_pixel_pile`). Every level of
//! the subdivision holds all `N` in the one quadrant containing that
//! pixel, so the counted work must grow linearly in `N`: this checks the
//! counters, never the time (the scaling example measures that).

use hider_scene::HiderStats;
use hider_testkit::hard_cases::one_pixel_pile;
use hider_testkit::screen;
use hider_warnock::{Rule, WarnockOptions, WarnockStats};

mod common;

/// 64 x 64 is 2^6: the pixel is reached at level 6.
const PIXEL_LEVEL: usize = 6;

fn pile_stats(n: u32) -> WarnockStats {
    let s = screen(&one_pixel_pile(n, 5), 64, 64);
    assert_eq!(s.tris.len(), n as usize, "the pile is not clipped");
    let (frame, stats) = common::render(&s, WarnockOptions::default());
    // One pixel shows the pile; everything else is background.
    let covered = frame.ids.iter().filter(|&&id| id != hider_scene::NO_ID);
    assert_eq!(covered.count(), 1);
    stats
}

/// `b / a`, for counters of the pile at `2N` and `N`.
fn ratio(b: u64, a: u64) -> f64 {
    b as f64 / a.max(1) as f64
}

#[test]
fn work_on_a_one_pixel_pile_grows_linearly() {
    let (small, large) = (4_000, 8_000);
    let a = pile_stats(small);
    let b = pile_stats(large);
    // The same regions at both sizes: the pile only lengthens the lists.
    assert_eq!(a.regions_per_level, b.regions_per_level);
    assert_eq!(a.max_level(), PIXEL_LEVEL);
    assert_eq!(a.sample_resolves, b.sample_resolves);
    for (name, x, y) in [
        ("classified", a.polygons_classified, b.polygons_classified),
        ("copied", a.candidates_copied, b.candidates_copied),
        (
            "depth evaluations",
            a.depth_evaluations,
            b.depth_evaluations,
        ),
    ] {
        let r = ratio(y, x);
        assert!(r <= 2.1, "{name}: {x} at N = {small}, {y} at 2N: x{r:.3}");
    }
    for (level, (&x, &y)) in a
        .candidates_per_level
        .iter()
        .zip(&b.candidates_per_level)
        .enumerate()
    {
        let r = ratio(y, x);
        assert!(r <= 2.1, "level {level}: {x} then {y} candidates: x{r:.3}");
    }
    // The pixel under the pile is resolved by the depth test over all N.
    assert_eq!(b.decided_by(Rule::Sample), 1);
    let table = b.table();
    assert!(
        table
            .counters
            .contains(&("sample resolves", b.sample_resolves))
    );
}

/// The pile is looked at twice: classified against the whole window, then
/// resolved at its pixel. The quadrants beside the one holding the pixel are
/// settled empty from the survivors' bounding box, the levels between are
/// passed through (nothing can surround them), and the list, every
/// candidate of which survives, is handed on without a copy. Before that,
/// every level classified the pile in all four quadrants (`4N` per level,
/// `25N` in all) and copied it once more (`7N` in all).
#[test]
fn a_one_pixel_pile_is_examined_twice_and_never_copied() {
    let n = 3_000;
    let stats = pile_stats(n);
    let mut per_level = vec![0; PIXEL_LEVEL + 1];
    per_level[0] = u64::from(n);
    per_level[PIXEL_LEVEL] = u64::from(n);
    assert_eq!(stats.candidates_per_level, per_level);
    assert_eq!(stats.polygons_classified, 2 * u64::from(n));
    // The root list is the only one written.
    assert_eq!(stats.candidates_copied, u64::from(n));
    assert_eq!(stats.peak_candidates, u64::from(n));
    // Three quadrants beside the pile at each of the six splits; the five
    // levels between the window and the pixel's 2 x 2 block passed through.
    assert_eq!(stats.empty_by_bounds, 3 * PIXEL_LEVEL as u64);
    assert_eq!(stats.decided_by(Rule::Empty), 3 * PIXEL_LEVEL as u64);
    assert_eq!(stats.passed_through, PIXEL_LEVEL as u64 - 1);
    assert_eq!(stats.regions, 1 + 4 * PIXEL_LEVEL as u64);
    assert_eq!(stats.sample_resolves, 1);
}
