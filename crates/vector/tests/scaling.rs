//! Work counters, not times: on scenes whose drawing the image bounds
//! (more triangles piled on the same pixels), doubling the input must
//! less than triple the work of the regions and of the lines, where
//! testing every overlapping pair quadruples it. The cull that makes it so
//! must change no region, and the pair budget refuses a drawing naming
//! its option.

mod common;

use common::area2;
use hider_scene::{Error, Scene, ShadeMode, procedural};
use hider_testkit::hard_cases::heavy_overdraw;
use hider_testkit::screen;
use hider_vector::{
    LineStats, ObjectGroups, PAIRS_LIMIT, REGION_POINTS_LIMIT, RegionStats, VectorOptions,
    hidden_lines_in, line_pairs, visible_regions,
};
use i_overlay::i_shape::int::shape::IntShapes;

/// Image side: small, so that the piles are deep at CI sizes.
const SIZE: u32 = 64;

fn work(scene: &Scene) -> (RegionStats, LineStats) {
    let s = screen(scene, SIZE, SIZE);
    let options = VectorOptions::default();
    let map = visible_regions(&s, &options, ShadeMode::Lambert).unwrap();
    let pairs = line_pairs(&s, &options).unwrap();
    let lines = hidden_lines_in(&s, &pairs, &options, &ObjectGroups::default()).unwrap();
    (map.stats, lines.stats)
}

/// Asserts that every counter grows less than threefold from each size
/// to the next.
fn less_than_triples(family: &str, make: impl Fn(u32) -> Scene, sizes: &[u32]) {
    let runs: Vec<_> = sizes.iter().map(|&n| (n, work(&make(n)))).collect();
    for w in runs.windows(2) {
        let ((n0, (r0, l0)), (n1, (r1, l1))) = (&w[0], &w[1]);
        let counters = [
            (
                "overlapping pairs",
                r0.overlapping_pairs,
                r1.overlapping_pairs,
            ),
            ("cut pairs", r0.cut_pairs, r1.cut_pairs),
            ("differences", r0.differences, r1.differences),
            ("path points", r0.path_points, r1.path_points),
            (
                "outline triangles",
                r0.outline_triangles,
                r1.outline_triangles,
            ),
            ("region points", r0.region_points, r1.region_points),
            (
                "line features tested",
                l0.feature_edges - l0.culled_features,
                l1.feature_edges - l1.culled_features,
            ),
            ("occluder tests", l0.occluder_tests, l1.occluder_tests),
        ];
        for (what, a, b) in counters {
            assert!(
                b < 3 * a.max(1),
                "{family}: {what} {a} at {n0} triangles, {b} at {n1}\n{r1:?}\n{l1:?}"
            );
        }
    }
}

#[test]
fn doubling_a_pile_of_large_triangles_less_than_triples_the_work() {
    less_than_triples(
        "heavy overdraw",
        |n| heavy_overdraw(n, 1),
        &[500, 1_000, 2_000],
    );
}

#[test]
fn doubling_a_random_soup_less_than_triples_the_map_wide_work() {
    // The soup is sparse up to about 8,000 triangles (see docs/vector.md),
    // so its pairs grow with the density as well as with N; what the
    // regions send to the map-wide passes (the snap rounding, the
    // closing and the covered set's union tree) must grow with N only.
    let runs: Vec<_> = [1_000, 2_000, 4_000]
        .iter()
        .map(|&n| {
            let s = screen(&procedural::random_soup(n, 1), SIZE, SIZE);
            let map = visible_regions(&s, &VectorOptions::default(), ShadeMode::Lambert).unwrap();
            (n, map.stats)
        })
        .collect();
    for w in runs.windows(2) {
        let ((n0, r0), (n1, r1)) = (&w[0], &w[1]);
        for (what, a, b) in [
            ("region points", r0.region_points, r1.region_points),
            (
                "outline triangles",
                r0.outline_triangles,
                r1.outline_triangles,
            ),
            ("path points", r0.path_points, r1.path_points),
            ("differences", r0.differences, r1.differences),
        ] {
            assert!(
                b < 3 * a.max(1),
                "soup: {what} {a} at {n0} triangles, {b} at {n1}\n{r1:?}"
            );
        }
    }
}

#[test]
fn culling_changes_no_region() {
    for (name, scene) in [
        ("pile", heavy_overdraw(300, 5)),
        ("deeper pile", heavy_overdraw(600, 7)),
    ] {
        let s = screen(&scene, SIZE, SIZE);
        let culled = visible_regions(&s, &VectorOptions::default(), ShadeMode::Ids).unwrap();
        // Drawing hidden lines turns the cull off.
        let all = VectorOptions::default().with_dashed_hidden(true);
        let full = visible_regions(&s, &all, ShadeMode::Ids).unwrap();
        assert!(culled.stats.culled > 0, "{name}: {:?}", culled.stats);
        assert_eq!(full.stats.culled, 0);
        // The same primitives are seen, and each region's area and the
        // covered set's agree to within a band one grid unit wide along
        // their outlines: the whole map is snap rounded together (every
        // region's vertex is a hot pixel), so boundaries move by a unit
        // when the buried triangles are no longer in it.
        let prims =
            |map: &hider_vector::RegionMap| map.prims.iter().map(|r| r.prim).collect::<Vec<_>>();
        assert_eq!(prims(&culled), prims(&full), "{name}");
        let within_a_unit = |what: String, a: &IntShapes<i32>, b: &IntShapes<i32>| {
            let perimeter: f64 = b
                .iter()
                .flatten()
                .map(|c| {
                    (0..c.len())
                        .map(|k| {
                            let (p, q) = (c[k], c[(k + 1) % c.len()]);
                            f64::from(q.x - p.x).hypot(f64::from(q.y - p.y))
                        })
                        .sum::<f64>()
                })
                .sum();
            let gap = (area2(a) - area2(b)).abs() as f64;
            assert!(
                gap <= 2.0 * perimeter,
                "{name}: {what}: twice the area differs by {gap}, outline {perimeter}"
            );
        };
        within_a_unit("covered".into(), &culled.covered, &full.covered);
        for (a, b) in culled.prims.iter().zip(&full.prims) {
            within_a_unit(format!("prim {}", a.prim), &a.shapes, &b.shapes);
        }
    }
}

#[test]
fn the_pair_budget_is_refused_naming_its_option() {
    let s = screen(&heavy_overdraw(200, 1), SIZE, SIZE);
    let options = VectorOptions::default().with_max_pairs(100);
    for result in [
        visible_regions(&s, &options, ShadeMode::Lambert).map(|_| ()),
        line_pairs(&s, &options).map(|_| ()),
    ] {
        match result {
            Err(Error::Limit { what, limit, .. }) => {
                assert_eq!(what, PAIRS_LIMIT);
                assert_eq!(limit, 100);
            }
            other => panic!("not refused: {other:?}"),
        }
    }
    let line = visible_regions(&s, &options, ShadeMode::Lambert)
        .unwrap_err()
        .to_string();
    assert!(line.contains("max_pairs") && !line.contains('\n'), "{line}");
}

#[test]
fn the_region_point_budget_is_refused_naming_its_option() {
    let s = screen(&heavy_overdraw(200, 1), SIZE, SIZE);
    let needed = visible_regions(&s, &VectorOptions::default(), ShadeMode::Lambert)
        .unwrap()
        .stats
        .region_points;
    assert!(needed > 100, "{needed}");
    let options = VectorOptions::default().with_max_region_points(100);
    let error = visible_regions(&s, &options, ShadeMode::Lambert).unwrap_err();
    match &error {
        Error::Limit { what, value, limit } => {
            assert_eq!(*what, REGION_POINTS_LIMIT);
            assert_eq!(*limit, 100);
            assert!(*value > 100);
        }
        other => panic!("not refused: {other:?}"),
    }
    let line = error.to_string();
    assert!(
        line.contains("max_region_points") && !line.contains('\n'),
        "{line}"
    );
    // The budget is the regions': the pair phase alone ignores it, and
    // exactly the points needed pass.
    assert!(line_pairs(&s, &options).is_ok());
    let enough = VectorOptions::default().with_max_region_points(needed);
    assert!(visible_regions(&s, &enough, ShadeMode::Lambert).is_ok());
}

#[test]
fn the_64000_triangle_soup_has_its_regions() {
    // This scene's closing pass aborted the process (a 7.6 GB allocation
    // in `i_overlay` 4.5.2's contour walk, from its tree splitter; see
    // docs/vector.md, step 6). Its regions must come out, and partition
    // the covered set: disjoint, so their areas sum to its area exactly.
    // With `i_overlay` 9.1 choosing its splitters, the areas are those
    // the sweep-list splitter alone gave (twice the area, grid units).
    let s = screen(&procedural::random_soup(64_000, 1), 256, 256);
    let map = visible_regions(&s, &VectorOptions::default(), ShadeMode::Ids).unwrap();
    assert!(map.stats.culled > 50_000, "{:?}", map.stats);
    assert!(map.stats.visible_prims > 5_000, "{:?}", map.stats);
    let regions: i128 = map.prims.iter().map(|r| area2(&r.shapes)).sum();
    assert_eq!(regions, area2(&map.covered));
    assert_eq!(regions, 7_841_878_066_877);
    assert_eq!(map.prims.len(), 5_747);
    assert_eq!(map.stats.path_points, 176_163);
}
