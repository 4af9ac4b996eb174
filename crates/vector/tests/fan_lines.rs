//! Work counters, not times: the hidden lines of a flat fan of `N`
//! triangles and of a cone seen from its apex. The rim's edges are the
//! lines; the spokes converge at the centre, so square bins hold about
//! `sqrt(N)` of them each and every short rim edge had that many
//! candidate occluders (`N^1.5` over the rim) while only its neighbours
//! reach it. The lines find a star's triangles by their sectors at its
//! centre instead, so the candidates and the tests grow with `N`.

use hider_scene::Scene;
use hider_testkit::screen;
use hider_testkit::sheets::{self, lit};
use hider_vector::{LineStats, ObjectGroups, VectorOptions, hidden_lines_in, line_pairs};

fn lines(scene: &Scene) -> LineStats {
    let s = screen(scene, 256, 256);
    let options = VectorOptions::default();
    let pairs = line_pairs(&s, &options).unwrap();
    hidden_lines_in(&s, &pairs, &options, &ObjectGroups::default())
        .unwrap()
        .stats
}

#[test]
fn doubling_a_fan_or_a_cone_doubles_the_occluder_work() {
    for (name, apex) in [("fan", 0.0), ("cone", 0.5)] {
        let (a, b) = (
            lines(&lit(vec![sheets::fan(2_000, apex)])),
            lines(&lit(vec![sheets::fan(4_000, apex)])),
        );
        // The rim is the drawing: one line per rim edge.
        assert_eq!(a.feature_edges, 2_000, "{name}: {a:?}");
        assert_eq!(b.feature_edges, 4_000, "{name}: {b:?}");
        for (what, x, y) in [
            (
                "occluder candidates",
                a.occluder_candidates,
                b.occluder_candidates,
            ),
            ("occluder tests", a.occluder_tests, b.occluder_tests),
        ] {
            // Bins of spokes gave 2.8 times the work at twice the spokes.
            assert!(
                5 * y < 11 * x.max(1),
                "{name}: {what} {x} at 2,000 triangles, {y} at 4,000\n{b:?}"
            );
        }
        // A few occluders per rim edge: its neighbours.
        assert!(b.occluder_tests <= 4 * b.feature_edges, "{name}: {b:?}");
    }
}
