//! Work counters, not times: `N` long thin parallel triangles in seven
//! planes (`sheets::slivers`), each plane's slivers one face group of
//! separate pieces. Square bins met every sliver of a row of bins with
//! every other in every bin (`N^2` visits), and a face group's union as
//! one boolean gave `i_overlay` all `N / 7` slivers at once (its sweep
//! list is quadratic in segments spanning one x, its fragment splitter
//! cuts each long segment `sqrt(N)` times): 72% of the time at 32,000.

use hider_scene::{Scene, ShadeMode};
use hider_testkit::screen;
use hider_testkit::sheets::{self, lit};
use hider_vector::{RegionStats, VectorOptions, visible_regions};

fn stats(n: u32) -> RegionStats {
    let scene: Scene = lit(vec![sheets::slivers(n)]);
    let s = screen(&scene, 256, 256);
    visible_regions(&s, &VectorOptions::default(), ShadeMode::Lambert)
        .unwrap()
        .stats
}

#[test]
fn doubling_the_slivers_less_than_triples_the_work() {
    let (a, b) = (stats(2_000), stats(4_000));
    assert_eq!(b.groups, 7, "{b:?}");
    assert!(b.visible_prims > 3_000, "{b:?}");
    for (what, x, y) in [
        ("bin visits", a.bin_visits, b.bin_visits),
        ("candidate pairs", a.candidate_pairs, b.candidate_pairs),
        ("snap segments", a.snap_segments, b.snap_segments),
        ("sweep tests", a.sweep_tests, b.sweep_tests),
        (
            "map boolean segments",
            a.map_boolean_segments,
            b.map_boolean_segments,
        ),
    ] {
        assert!(
            y < 3 * x.max(1),
            "{what} {x} at 2,000 slivers, {y} at 4,000\n{b:?}"
        );
    }
    // The map-wide booleans are many small ones: no one of them grows
    // with the input.
    assert!(
        b.largest_boolean < a.largest_boolean * 3 / 2,
        "largest boolean {} at 2,000 slivers, {} at 4,000",
        a.largest_boolean,
        b.largest_boolean
    );
}
