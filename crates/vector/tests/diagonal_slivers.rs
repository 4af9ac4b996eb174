//! Work counters, not times: `N` long thin parallel slivers in seven
//! planes (`sheets::slivers`) turned 45 degrees in their planes. Their
//! boxes are square, so bins shaped by the boxes stayed square and held
//! about `sqrt(N)` slivers each, every sliver meeting `sqrt(N)` bins: the
//! pair phase's candidates and a sliver edge's candidate occluders grew
//! as `N^2` (526,502 candidate pairs at 2,000 slivers, 2.9 times that at
//! 4,000). The bins turn to the slivers' direction instead.

use glam::DMat3;
use hider_scene::{Scene, ShadeMode};
use hider_testkit::screen;
use hider_testkit::sheets::{lit, slivers};
use hider_vector::{
    LineStats, ObjectGroups, RegionStats, VectorOptions, hidden_lines_in, line_pairs,
    visible_regions,
};

fn diagonal(n: u32) -> Scene {
    let mut mesh = slivers(n);
    let turn = DMat3::from_rotation_z(std::f64::consts::FRAC_PI_4);
    for p in &mut mesh.positions {
        *p = turn * *p;
    }
    lit(vec![mesh])
}

fn work(n: u32) -> (RegionStats, LineStats) {
    let s = screen(&diagonal(n), 256, 256);
    let options = VectorOptions::default();
    let map = visible_regions(&s, &options, ShadeMode::Lambert).unwrap();
    let pairs = line_pairs(&s, &options).unwrap();
    let lines = hidden_lines_in(&s, &pairs, &options, &ObjectGroups::default()).unwrap();
    (map.stats, lines.stats)
}

#[test]
fn doubling_diagonal_slivers_doubles_the_candidates() {
    let ((ra, la), (rb, lb)) = (work(2_000), work(4_000));
    // Every sliver is seen, and its three edges are lines.
    assert!(rb.visible_prims > 3_000, "{rb:?}");
    assert_eq!(lb.feature_edges, 12_000, "{lb:?}");
    for (what, x, y) in [
        ("candidate pairs", ra.candidate_pairs, rb.candidate_pairs),
        ("bin visits", ra.bin_visits, rb.bin_visits),
        (
            "occluder candidates",
            la.occluder_candidates,
            lb.occluder_candidates,
        ),
        ("occluder tests", la.occluder_tests, lb.occluder_tests),
    ] {
        assert!(
            2 * y < 5 * x.max(1),
            "{what} {x} at 2,000 slivers, {y} at 4,000\n{rb:?}\n{lb:?}"
        );
    }
    // A few candidates per sliver: its neighbours along the bins' rows.
    assert!(rb.candidate_pairs < 8 * 4_000, "{rb:?}");
    assert!(lb.occluder_candidates < 16 * lb.feature_edges, "{lb:?}");
}

/// The map-wide booleans' counters of the regions of `n` diagonal slivers.
fn booleans(n: u32) -> RegionStats {
    let s = screen(&diagonal(n), 256, 256);
    visible_regions(&s, &VectorOptions::default(), ShadeMode::Lambert)
        .unwrap()
        .stats
}

/// Shapes whose boxes chain together were one boolean: every diagonal
/// sliver's box meets its neighbours', so the closing pass and the face
/// groups' unions were each one boolean over the whole map (14,830
/// segments at 2,000 slivers, 32,924 at 4,000), whose splitter costs
/// more than linearly in long diagonal segments (6.5 s at 8,000). Split
/// by actual contact, each boolean holds a few slivers that touch.
#[test]
fn diagonal_slivers_booleans_stay_local() {
    let (a, b) = (booleans(1_000), booleans(2_000));
    assert!(b.visible_prims > 1_500, "{b:?}");
    // The largest boolean does not grow with the slivers.
    assert!(
        2 * b.largest_boolean < 3 * a.largest_boolean,
        "largest boolean {} at 1,000 slivers, {} at 2,000\n{b:?}",
        a.largest_boolean,
        b.largest_boolean
    );
    assert!(b.largest_boolean < 4_000, "{b:?}");
    // All booleans together grow with them.
    assert!(
        b.map_boolean_segments < 3 * a.map_boolean_segments,
        "{a:?}\n{b:?}"
    );
}
