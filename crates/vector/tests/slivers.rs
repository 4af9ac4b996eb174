//! Work counters, not times: long thin parallel slivers, where square
//! bins give every segment along a sliver all the slivers of its bin row
//! as candidate occluders (the square of the input at a fixed image
//! size), while the slivers that can hide it are its few neighbours. The
//! lines' candidates and tests must grow with `N`, and the drawing must
//! keep every sliver's long edges.

use hider_scene::Scene;
use hider_testkit::screen;
use hider_testkit::sheets::{lit, slivers};
use hider_vector::{LineDrawing, ObjectGroups, VectorOptions, hidden_lines_in, line_pairs};

fn lines(scene: &Scene) -> LineDrawing {
    let s = screen(scene, 256, 256);
    let options = VectorOptions::default();
    let pairs = line_pairs(&s, &options).unwrap();
    hidden_lines_in(&s, &pairs, &options, &ObjectGroups::default()).unwrap()
}

#[test]
fn doubling_parallel_slivers_less_than_triples_the_lines_work() {
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
