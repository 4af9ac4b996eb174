//! The hard cases: interpenetration, cycles, coplanar overlap, closed
//! meshes, and what the statistics say about them.

mod common;

use common::{assert_matches, camera_at, render};
use hider_scanline::{Scanline, ScanlineOptions};
use hider_scene::geom::fixed::pixel_center;
use hider_scene::geom::glam::DVec3;
use hider_scene::{Frame, Hider, HiderStats, NO_ID, procedural};
use hider_testkit::{reference, screen, screen_with};
use proptest::prelude::*;

#[test]
fn intersecting_pair_splits_spans_at_the_intersection() {
    let s = screen(&procedural::intersecting_pair(), 64, 64);
    let (frame, stats) = render(&s, ScanlineOptions::default());
    assert_eq!(assert_matches(&s, &frame, "pair"), 0);
    assert!(
        stats.split_spans > 0 && stats.splits >= stats.split_spans,
        "{stats:?}"
    );
    assert_eq!(stats.fallback_spans, 0);
    assert!(frame.ids.contains(&0) && frame.ids.contains(&1));
    // Some row shows both triangles over the same covered run: the split.
    let both_rows = frame
        .ids
        .chunks(64)
        .filter(|r| r.contains(&0) && r.contains(&1))
        .count();
    assert!(both_rows > 0);
}

#[test]
fn cyclic_triple_is_resolved_where_no_depth_order_exists() {
    let s = screen(&procedural::cyclic_triple(), 64, 64);
    let (frame, _) = render(&s, ScanlineOptions::default());
    assert_eq!(assert_matches(&s, &frame, "cycle"), 0);
    // Each strip is visible somewhere and hidden somewhere by another one:
    // a painter's sort has no order to give; per span there is one.
    for id in 0..3 {
        assert!(frame.ids.contains(&id), "strip {id} hidden");
        let piece = s.tris.iter().find(|t| t.prim == id).unwrap();
        let hidden = (0..64 * 64).any(|k: u32| {
            let (i, j) = (k % 64, k / 64);
            let (x, y) = (
                i64::from(pixel_center(i as i32)),
                i64::from(pixel_center(j as i32)),
            );
            piece.edges().iter().all(|e| e.contains(x, y)) && frame.ids[k as usize] != id
        });
        assert!(hidden, "strip {id} is never behind another");
    }
}

#[test]
fn coplanar_pair_covers_the_union_and_picks_one_of_the_two() {
    let s = screen(&procedural::coplanar_pair(), 64, 64);
    let (frame, _) = render(&s, ScanlineOptions::default());
    let ties = assert_matches(&s, &frame, "coplanar");
    assert!(ties > 0, "the overlap should be all ties");
    let r = reference::pixel_centre(&s);
    for (k, &id) in frame.ids.iter().enumerate() {
        assert!(id == NO_ID || id == 0 || id == 1);
        assert_eq!(id == NO_ID, r.ids[k] == NO_ID);
    }
}

#[test]
fn knot_of_big_triangles_matches_with_and_without_fallback() {
    let s = common::knot(16, 80, 11);
    let (frame, stats) = render(&s, ScanlineOptions::default());
    assert_eq!(assert_matches(&s, &frame, "knot"), 0);
    assert!(
        stats.split_spans > 10 && stats.splits >= stats.split_spans,
        "{stats:?}"
    );
    assert!(stats.span_polygons_max >= 4);
    for max_splits in [0, 1, 2] {
        let options = ScanlineOptions::default().with_max_splits_per_span(max_splits);
        let (other, st) = render(&s, options);
        assert_eq!(other.ids, frame.ids);
        assert_eq!(other.depth, frame.depth);
        if max_splits == 0 {
            assert_eq!(st.fallback_spans, stats.split_spans);
        }
    }
}

#[test]
fn cube_from_a_corner_covers_each_pixel_once_without_splits() {
    let cam = camera_at(DVec3::new(3.0, 2.5, 4.0));
    let s = screen_with(&procedural::cube(), cam, 64, 48);
    let (frame, stats) = render(&s, ScanlineOptions::default());
    assert_eq!(assert_matches(&s, &frame, "cube"), 0);
    // A convex closed mesh has no interpenetration: front faces never
    // cross the back faces inside a span.
    assert_eq!((stats.splits, stats.fallback_spans), (0, 0));
    assert!(stats.span_polygons_max >= 2);
    assert_eq!(stats.polygons, 12);
}

#[test]
fn sphere_matches_and_reports_its_work() {
    let s = screen(&procedural::uv_sphere(24), 96, 96);
    let (frame, stats) = render(&s, ScanlineOptions::default());
    assert_matches(&s, &frame, "sphere");
    assert_eq!(stats.rows, 96);
    assert_eq!(stats.pixels_written, frame.covered_count() as u64);
    assert!(stats.active_polygons_max > 0);
    assert!(stats.active_polygons_mean() > 0.0);
    assert!(stats.active_polygons_mean() <= stats.active_polygons_max as f64);
    assert!(stats.edges <= 3 * stats.polygons);
    assert_eq!(stats.crossings % 2, 0);
}

#[test]
fn one_triangle_has_one_span_per_covered_row() {
    let mut scene = procedural::intersecting_pair();
    scene.meshes.truncate(1);
    let s = screen(&scene, 40, 40);
    let (frame, stats) = render(&s, ScanlineOptions::default());
    assert_matches(&s, &frame, "single");
    let rows = frame.ids.chunks(40).filter(|r| r.contains(&0)).count() as u64;
    assert_eq!(stats.spans, rows);
    assert_eq!(stats.crossings, 2 * rows);
    assert_eq!(stats.edges, 3);
    assert_eq!(stats.span_polygons_max, 1);
    assert_eq!(stats.depth_evaluations, 0);
}

#[test]
fn tables_are_reused_between_frames() {
    let a = screen(&procedural::uv_sphere(12), 48, 32);
    let b = screen(&procedural::random_soup(30, 9), 20, 50);
    let mut hider = Scanline::default();
    let mut fa = Frame::new(48, 32).unwrap();
    let mut fb = Frame::new(20, 50).unwrap();
    let first = hider.render(&a, &mut fa).unwrap();
    let ids = fa.ids.clone();
    hider.render(&b, &mut fb).unwrap();
    assert_matches(&b, &fb, "second scene");
    let again = hider.render(&a, &mut fa).unwrap();
    assert_eq!(fa.ids, ids);
    // The same work (peak bytes aside: the tables grew for the other scene).
    assert_eq!(first.table().counters, again.table().counters);
    assert_eq!(hider.name(), "scanline");
    assert!(!hider.resolves_color());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn hard_cases_from_anywhere(
        which in 0usize..5,
        theta in 0.0f64..std::f64::consts::TAU,
        phi in -1.3f64..1.3,
        dist in 1.2f64..5.0,
        w in 8u32..64,
        h in 8u32..64,
        max_splits in prop_oneof![Just(u32::MAX), Just(16u32), Just(1u32), Just(0u32)],
    ) {
        let scene = match which {
            0 => procedural::intersecting_pair(),
            1 => procedural::coplanar_pair(),
            2 => procedural::cyclic_triple(),
            3 => procedural::cube(),
            _ => procedural::uv_sphere(10),
        };
        let eye = DVec3::new(theta.cos() * phi.cos(), phi.sin(), theta.sin() * phi.cos()) * dist;
        let s = screen_with(&scene, camera_at(eye), w, h);
        let (frame, stats) = render(&s, ScanlineOptions::default().with_max_splits_per_span(max_splits));
        assert_matches(&s, &frame, "hard case");
        prop_assert!(stats.splits <= u64::from(max_splits).saturating_mul(stats.split_spans));
    }
}

#[test]
fn recorded_runs_tile_the_covered_pixels_and_name_the_splits() {
    use hider_scanline::Resolution;
    let s = common::knot(12, 64, 4);
    for max_splits in [u32::MAX, 0] {
        let options = ScanlineOptions::default()
            .with_record_spans(true)
            .with_max_splits_per_span(max_splits);
        let mut hider = Scanline::new(options);
        let mut frame = Frame::new(64, 64).unwrap();
        let stats = hider.render(&s, &mut frame).unwrap();
        let mut ids = vec![NO_ID; 64 * 64];
        let mut last = None;
        for r in hider.spans() {
            assert!(r.x0 <= r.x1 && r.x1 < 64);
            // Row order, left to right, no overlap.
            if let Some((row, x1)) = last {
                assert!(r.row > row || (r.row == row && r.x0 > x1), "{r:?}");
            }
            last = Some((r.row, r.x1));
            for x in r.x0..=r.x1 {
                ids[(r.row * 64 + x) as usize] = r.prim;
            }
        }
        assert_eq!(ids, frame.ids);
        let count = |how| hider.spans().iter().filter(|r| r.how == how).count() as u64;
        if max_splits == 0 {
            assert_eq!(count(Resolution::Split), 0);
            assert!(count(Resolution::Fallback) >= stats.fallback_spans);
            assert!(stats.fallback_spans > 0);
        } else {
            assert_eq!(count(Resolution::Fallback), 0);
            assert_eq!(count(Resolution::Split), stats.splits + stats.split_spans);
        }
    }
    // Off by default.
    let mut hider = Scanline::default();
    let mut frame = Frame::new(64, 64).unwrap();
    hider.render(&s, &mut frame).unwrap();
    assert!(hider.spans().is_empty());
}
