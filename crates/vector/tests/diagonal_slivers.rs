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
