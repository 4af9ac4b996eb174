//! Work counters, not times: `N` long thin parallel triangles in seven
//! planes (`sheets::slivers`), each plane's slivers one face group of
//! separate pieces. Square bins met every sliver of a row of bins with
//! every other in every bin (`N^2` visits, and every segment along a
//! sliver had all the slivers of its bin row as candidate occluders,
//! while the slivers that can hide it are its few neighbours), and a face
//! group's union as one boolean gave `i_overlay` all `N / 7` slivers at
//! once (its sweep list is quadratic in segments spanning one x, its
//! fragment splitter cuts each long segment `sqrt(N)` times): 72% of the
//! regions' time at 32,000.

use hider_scene::{Scene, ShadeMode};
use hider_testkit::screen;
use hider_testkit::sheets::{lit, slivers};
use hider_vector::{
    LineDrawing, ObjectGroups, RegionStats, VectorOptions, hidden_lines_in, line_pairs,
    visible_regions,
};

fn regions(n: u32) -> RegionStats {
    let scene: Scene = lit(vec![slivers(n)]);
    let s = screen(&scene, 256, 256);
    visible_regions(&s, &VectorOptions::default(), ShadeMode::Lambert)
        .unwrap()
        .stats
}

fn lines(scene: &Scene) -> LineDrawing {
    let s = screen(scene, 256, 256);
    let options = VectorOptions::default();
    let pairs = line_pairs(&s, &options).unwrap();
    hidden_lines_in(&s, &pairs, &options, &ObjectGroups::default()).unwrap()
}

#[test]
fn doubling_the_slivers_less_than_triples_the_regions_work() {
    let (a, b) = (regions(2_000), regions(4_000));
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

#[test]
fn doubling_the_slivers_less_than_triples_the_lines_work() {
    let (a, b) = (
        lines(&lit(vec![slivers(2_000)])),
        lines(&lit(vec![slivers(4_000)])),
    );
    let (x, y) = (a.stats, b.stats);
    // Every sliver's edges are lines (boundaries), and little is hidden:
    // the slivers lie side by side.
    assert_eq!(x.feature_edges, 6_000, "{x:?}");
    assert!(a.visible_segments() > 2_000, "{x:?}");
    for (what, p, q) in [
        (
            "occluder candidates",
            x.occluder_candidates,
            y.occluder_candidates,
        ),
        ("occluder tests", x.occluder_tests, y.occluder_tests),
    ] {
        assert!(
            q < 3 * p.max(1),
            "{what} {p} at 2,000 slivers, {q} at 4,000\n{y:?}"
        );
    }
}
