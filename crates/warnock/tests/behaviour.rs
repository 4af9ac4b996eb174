//! What the subdivision does: its rules, statistics, region record, limits
//! and errors.

mod common;

use common::{backdrop, random_big_triangles, render, triangles_in_front_of_camera};
use glam::DVec3;
use hider_scene::{Error, Frame, Hider, HiderStats, NO_ID, Scene, procedural};
use hider_testkit::{reference, screen};
use hider_warnock::{Rule, Warnock, WarnockOptions, WarnockStats};

/// Two backdrops tilted against each other, crossing on the line `x = at`.
fn crossing_backdrops(at: f64) -> [[DVec3; 3]; 2] {
    let tilt = |k: f64| backdrop(0.0).map(|p| DVec3::new(p.x, p.y, k * (p.x - at)));
    [tilt(0.2), tilt(-0.2)]
}

fn check_stats_consistency(stats: &WarnockStats) {
    assert_eq!(stats.regions, stats.regions_per_level.iter().sum::<u64>());
    assert_eq!(
        stats.polygons_classified,
        stats.disjoint + stats.surrounding + stats.contained + stats.intersecting
    );
    assert_eq!(
        stats.polygons_classified,
        stats.candidates_per_level.iter().sum::<u64>()
    );
}

#[test]
fn an_empty_scene_is_one_empty_region() {
    let screen = screen(&Scene::default(), 64, 32);
    let (frame, stats) = render(&screen, WarnockOptions::default());
    assert_eq!(stats.regions, 1);
    assert_eq!(stats.decided_by(Rule::Empty), 1);
    assert!(frame.ids.iter().all(|&id| id == NO_ID));
}

#[test]
fn a_surrounder_alone_fills_the_window_in_one_region() {
    let scene = triangles_in_front_of_camera(&[backdrop(0.0)]);
    let screen = screen(&scene, 64, 64);
    let (frame, stats) = render(&screen, WarnockOptions::default());
    assert_eq!(stats.regions, 1);
    assert_eq!(stats.decided_by(Rule::SurrounderAlone), 1);
    assert!(frame.ids.iter().all(|&id| id == 0));
    assert_eq!(frame.depth, reference::pixel_centre(&screen).depth_f32());
}

#[test]
fn a_surrounder_in_front_hides_the_one_behind_at_the_root() {
    // The nearer backdrop is drawn second: the test must not depend on
    // drawing order.
    let scene = triangles_in_front_of_camera(&[backdrop(-1.0), backdrop(0.0)]);
    let screen = screen(&scene, 64, 64);
    let (frame, stats) = render(&screen, WarnockOptions::default());
    assert_eq!(stats.regions, 1);
    assert_eq!(stats.decided_by(Rule::SurrounderInFront), 1);
    assert_eq!(stats.culled_behind_surrounder, 1);
    assert!(frame.ids.iter().all(|&id| id == 1));
}

#[test]
fn crossing_planes_are_subdivided_down_to_the_crossing_line() {
    // Two backdrops tilted against each other cross on a vertical line:
    // neither is in front over the whole window. The line is placed at
    // x = 36.8 pixels (about 11.09 pixels per unit at the origin), between
    // the centres 36.5 and 37.5, which only a level-6 (one-pixel) split
    // separates. (On a coarser region boundary with no centre between it
    // and the line, the subdivision rightly stops earlier.)
    let scene = triangles_in_front_of_camera(&crossing_backdrops(0.433));
    let screen = screen(&scene, 64, 64);
    let (frame, stats) = render(&screen, WarnockOptions::default());
    assert_eq!(frame.ids, reference::pixel_centre(&screen).ids);
    assert!(stats.surrounder_undecided > 0);
    assert_eq!(
        stats.max_level(),
        6,
        "the crossing is resolved at single pixels"
    );
    // Both halves are decided by a surrounder in front, not per pixel.
    assert!(stats.decided_by(Rule::SurrounderInFront) > 0);
    // Far fewer regions than pixels: only the column at the crossing goes
    // down to pixel size.
    assert!(stats.regions < 64 * 64 / 4, "{stats:?}");
    assert!(frame.ids.contains(&0) && frame.ids.contains(&1));
    check_stats_consistency(&stats);
}

#[test]
fn coplanar_ties_go_to_the_earlier_primitive() {
    // The same backdrop twice: an exact tie everywhere, never certified, so
    // resolved per pixel by the z-buffer rule, which keeps the first.
    let scene = triangles_in_front_of_camera(&[backdrop(0.0), backdrop(0.0)]);
    let screen = screen(&scene, 16, 16);
    let (frame, stats) = render(&screen, WarnockOptions::default());
    assert!(frame.ids.iter().all(|&id| id == 0));
    assert_eq!(stats.decided_by(Rule::Sample), 16 * 16);
}

#[test]
fn recorded_leaf_regions_tile_the_window_and_match_the_rule_counts() {
    for (scene, w, h) in [
        (procedural::uv_sphere(10), 80, 60),
        (random_big_triangles(6, 3), 33, 71),
        (procedural::random_soup(200, 1), 50, 50),
    ] {
        let screen = screen(&scene, w, h);
        let mut warnock = Warnock::new(WarnockOptions::default().with_record_regions(true));
        let mut frame = Frame::new(w, h).unwrap();
        let stats = warnock.render(&screen, &mut frame).unwrap();
        let leaves = warnock.leaf_regions();
        let mut hits = vec![0u8; (w * h) as usize];
        for leaf in leaves {
            for y in leaf.y0..leaf.y1 {
                for x in leaf.x0..leaf.x1 {
                    hits[(y * w + x) as usize] += 1;
                }
            }
        }
        assert!(hits.iter().all(|&n| n == 1), "leaves must tile the window");
        assert_eq!(leaves.len() as u64, stats.decided.iter().sum::<u64>());
        for rule in Rule::ALL {
            let n = leaves.iter().filter(|l| l.rule == rule).count() as u64;
            assert_eq!(n, stats.decided_by(rule), "{rule:?}");
        }
        // Every visited region is a leaf or was split into 2 or 4: the
        // internal regions are the visits that are not leaves.
        assert!(stats.regions > leaves.len() as u64 || stats.regions == 1);
        check_stats_consistency(&stats);
    }
}

#[test]
fn a_16384_pixel_tall_window_does_not_overflow_and_stays_exact() {
    // A 4-pixel-wide window with the fit camera's 60-degree vertical field:
    // the crossing line runs down its whole height, so the subdivision goes
    // to single pixels, 14 levels deep, all along it.
    let scene = triangles_in_front_of_camera(&crossing_backdrops(0.0003));
    let screen = screen(&scene, 4, 16384);
    let (frame, stats) = render(&screen, WarnockOptions::default());
    assert_eq!(frame.ids, reference::pixel_centre(&screen).ids);
    assert!(frame.ids.contains(&0) && frame.ids.contains(&1));
    assert_eq!(stats.max_level(), 14);
}

#[test]
fn scratch_memory_is_reused_across_frames_and_scenes() {
    let big = screen(&procedural::random_soup(400, 2), 64, 64);
    let small = screen(&procedural::cube(), 64, 64);
    let mut warnock = Warnock::default();
    let mut frame = Frame::new(64, 64).unwrap();
    for s in [&big, &small, &big] {
        warnock.render(s, &mut frame).unwrap();
        assert_eq!(frame.ids, reference::pixel_centre(s).ids);
    }
}

#[test]
fn bad_input_is_a_typed_error_and_leaves_the_frame_alone() {
    let screen = screen(&procedural::cube(), 32, 32);
    let mut wrong = Frame::new(31, 32).unwrap();
    assert!(matches!(
        Warnock::default().render(&screen, &mut wrong),
        Err(Error::Render { .. })
    ));
    let mut frame = Frame::new(32, 32).unwrap();
    frame.ids[5] = 7;
    for n in [0, 3, 32] {
        let options = WarnockOptions::default().with_samples_per_side(n);
        let err = Warnock::new(options).render(&screen, &mut frame);
        assert!(matches!(err, Err(Error::OutOfRange { .. })), "{n}: {err:?}");
    }
    let tight = WarnockOptions::default().with_max_bytes(100);
    let err = Warnock::new(tight).render(&screen, &mut frame);
    assert!(matches!(err, Err(Error::Budget { .. })), "{err:?}");
    assert_eq!(frame.ids[5], 7, "an error is reported before drawing");
}

#[test]
fn the_hider_trait_reports_name_colour_and_counters() {
    let screen = screen(&procedural::cube(), 32, 32);
    let mut frame = Frame::new(32, 32).unwrap();
    let mut plain = Warnock::default();
    assert_eq!(plain.name(), "warnock");
    assert!(!plain.resolves_color());
    let stats = plain.render(&screen, &mut frame).unwrap();
    assert!(stats.regions > 1);
    assert_eq!(stats.regions_per_level[0], 1);
    // The uniform table the benchmark prints carries the same counters.
    let table = stats.table();
    assert!(table.counters.contains(&("regions", stats.regions)));
    assert!(table.counters.contains(&("regions at level 0", 1)));
    let in_front = stats.decided_by(Rule::SurrounderInFront);
    assert!(
        table
            .counters
            .contains(&("decided surrounder in front", in_front))
    );
    let aa = Warnock::new(WarnockOptions::default().with_samples_per_side(4));
    assert_eq!(aa.name(), "warnock-4x4");
    assert!(aa.resolves_color());
}
