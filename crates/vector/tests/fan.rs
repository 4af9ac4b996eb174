//! Work counters, not times: a flat fan of `N` triangles around one
//! vertex (a disc or cylinder cap as CAD files triangulate it) and a cone
//! seen from its apex (a sphere's pole). Every spoke meets the centre, so
//! binning pairs of edges or triangles by area makes the snap rounding
//! and the pair phase test about `N^2 / 2` pairs while nothing crosses;
//! the crossing sweep, the hot pixel quadtree and the pair phase (which
//! pairs the triangles at a shared vertex by their sectors there) must
//! grow with `N`. The same holds for two fans on one centre, whose
//! triangles overlap across the fans there.

use hider_scene::{Scene, ShadeMode};
use hider_testkit::screen;
use hider_testkit::sheets::{self, lit};
use hider_vector::{RegionStats, VectorOptions, visible_regions};

/// A fan of `n` triangles around the origin, its centre raised by
/// `apex` (0: flat).
fn fan(n: u32, apex: f64) -> Scene {
    lit(vec![sheets::fan(n, apex)])
}

fn stats(scene: &Scene) -> RegionStats {
    let s = screen(scene, 256, 256);
    visible_regions(&s, &VectorOptions::default(), ShadeMode::Lambert)
        .unwrap()
        .stats
}

#[test]
fn doubling_a_fan_or_a_cone_less_than_triples_the_work() {
    for (name, apex) in [("fan", 0.0), ("cone", 0.5)] {
        let (a, b) = (stats(&fan(2_000, apex)), stats(&fan(4_000, apex)));
        // The map is non-trivial: every spoke is an edge of the map.
        assert!(a.snap_segments > 2_000, "{name}: {a:?}");
        for (what, x, y) in [
            ("snap segments", a.snap_segments, b.snap_segments),
            ("sweep events", a.sweep_events, b.sweep_events),
            ("sweep tests", a.sweep_tests, b.sweep_tests),
            ("snap nodes visited", a.snap_nodes, b.snap_nodes),
            ("candidate pairs", a.candidate_pairs, b.candidate_pairs),
        ] {
            assert!(
                y < 3 * x.max(1),
                "{name}: {what} {x} at 2,000 triangles, {y} at 4,000\n{b:?}"
            );
        }
        // Neighbouring triangles meet along their spokes: nothing
        // overlaps, nothing is cut.
        assert_eq!(b.overlapping_pairs, 0, "{name}: {b:?}");
    }
}

#[test]
fn two_fans_on_one_centre_pair_by_their_sectors() {
    let two = |n: u32| stats(&lit(vec![sheets::two_fans(n, 0.5)]));
    let (a, b) = (two(1_000), two(2_000));
    // The fans overlap: each tilted triangle meets its flat neighbours.
    assert!(a.overlapping_pairs >= 1_000, "{a:?}");
    for (what, x, y) in [
        ("candidate pairs", a.candidate_pairs, b.candidate_pairs),
        ("bin visits", a.bin_visits, b.bin_visits),
    ] {
        assert!(
            y < 3 * x.max(1),
            "{what} {x} at 1,000 per fan, {y} at 2,000\n{b:?}"
        );
    }
}

/// The snapped regions of two fans on one centre (tilted by 0.3, as in
/// `vector_scaling`): the snapping reroutes a few regions at the centre,
/// whose boxes meet every other region's there. The ownership pass
/// differenced each region after them against every earlier one (`N^2`
/// segments; 3.5 billion on the 128,000-triangle cone, whose spokes crowd
/// within a grid unit of the apex only at that size); only regions
/// overlapping some other region are clips now.
#[test]
fn doubling_two_snapped_fans_less_than_triples_the_ownership_work() {
    let two = |n: u32| stats(&lit(vec![sheets::two_fans(n / 2, 0.3)]));
    let (a, b) = (two(3_000), two(6_000));
    // The snapping rerouted regions at the centre, and the regions after
    // them were differenced.
    assert!(a.snapped > 0 && b.snapped > 0, "{a:?}\n{b:?}");
    assert!(a.ownership_differences > 100, "{a:?}");
    for (what, x, y) in [
        (
            "ownership segments",
            a.ownership_segments,
            b.ownership_segments,
        ),
        (
            "map boolean segments",
            a.map_boolean_segments,
            b.map_boolean_segments,
        ),
    ] {
        assert!(
            y < 3 * x.max(1),
            "{what} {x} at 3,000 triangles, {y} at 6,000\n{a:?}\n{b:?}"
        );
    }
}
