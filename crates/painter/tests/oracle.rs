//! The correct painter against the references, the naive one shown wrong.
//!
//! Two references, both from `hider-testkit`: the oracle's ray cast
//! (camera-space planes, ties within `DEFAULT_TIE_TOLERANCE`) and the
//! brute-force z-buffer on the same window-depth planes the hiders use,
//! whose tie band here (1e-8 in window depth) is a thousand times narrower
//! and which also gives the depth a z-buffer writes: the painter must be
//! pixel-exact against both outside their ties, depths included.

use glam::DVec3;
use hider_oracle::{DEFAULT_TIE_TOLERANCE, Reference};
use hider_painter::{
    NaivePainter, NaivePainterOptions, Painter, PainterOptions, SPLIT_BUDGET, SortKey,
};
use hider_scene::{Error, Frame, Hider, Mesh, Scene, ScreenScene, procedural};
use hider_testkit::reference;
use hider_testkit::score::Score;
use proptest::prelude::*;

/// Window-depth gap under which the brute-force reference calls a tie.
const WINDOW_TIE: f64 = 1e-8;

/// Square images throughout.
fn screen(scene: &Scene, size: u32) -> ScreenScene {
    hider_testkit::screen(scene, size, size)
}

/// The frame against the brute-force window-depth z-buffer: coverage
/// mismatches and wrong ids off ties are counted; the depth written on
/// every pixel off ties with the right id must be the reference's.
fn score(s: &ScreenScene, frame: &Frame) -> Score {
    let result = hider_testkit::score::score(&reference::pixel_centre(s), frame, WINDOW_TIE);
    assert_eq!(result.depth_mismatches, 0, "depths: {result}");
    result
}

fn render<H: Hider>(h: &mut H, s: &ScreenScene) -> Frame {
    let mut f = Frame::new(s.viewport.width, s.viewport.height).unwrap();
    h.render(s, &mut f).unwrap();
    f
}

fn oracle(s: &ScreenScene) -> Reference {
    reference::ray_cast(s)
}

fn assert_exact(s: &ScreenScene, what: &str) {
    let frame = render(&mut Painter::default(), s);
    let result = score(s, &frame);
    assert_eq!(
        (result.coverage_mismatches, result.wrong_ids),
        (0, 0),
        "{what}: painter vs window-depth brute force"
    );
    let agreement = oracle(s).compare(&frame.ids, DEFAULT_TIE_TOLERANCE);
    assert!(
        agreement.is_exact(),
        "{what}: painter vs oracle: {agreement}"
    );
}

#[test]
fn correct_painter_matches_the_references_on_the_hard_cases() {
    for (name, scene) in [
        ("intersecting_pair", procedural::intersecting_pair()),
        ("cyclic_triple", procedural::cyclic_triple()),
        ("coplanar_pair", procedural::coplanar_pair()),
        ("cube", procedural::cube()),
        ("uv_sphere", procedural::uv_sphere(10)),
        ("soup", procedural::random_soup(60, 3)),
    ] {
        assert_exact(&screen(&scene, 64), name);
    }
}

#[test]
fn naive_painter_is_wrong_on_intersections_and_cycles() {
    for key in [SortKey::FarthestVertex, SortKey::Centroid] {
        for (name, scene) in [
            ("intersecting_pair", procedural::intersecting_pair()),
            ("cyclic_triple", procedural::cyclic_triple()),
        ] {
            let s = screen(&scene, 64);
            let mut naive = NaivePainter::new(NaivePainterOptions::default().with_sort_key(key));
            let frame = render(&mut naive, &s);
            let result = score(&s, &frame);
            // Coverage is the shared exact one; visibility is not.
            assert_eq!(result.coverage_mismatches, 0, "{name} {key:?}");
            assert!(
                result.wrong_ids > 0,
                "{name} {key:?}: the naive sort got every pixel right"
            );
            let agreement = oracle(&s).compare(&frame.ids, DEFAULT_TIE_TOLERANCE);
            assert_eq!(agreement.coverage_mismatches, 0);
            assert!(agreement.wrong_ids > 0, "{name} {key:?}: {agreement}");
        }
    }
}

#[test]
fn naive_painter_is_right_where_a_depth_order_exists() {
    // Disjoint, non-intersecting layers: the sort alone is enough.
    let s = screen(&layers(), 48);
    let frame = render(&mut NaivePainter::default(), &s);
    assert!(score(&s, &frame).ids_exact());
}

fn layers() -> Scene {
    let mut scene = Scene::default();
    for k in 0..4 {
        let z = -0.3 * f64::from(k);
        let dx = 0.2 * f64::from(k);
        scene.push_mesh(
            Mesh {
                positions: vec![
                    DVec3::new(-1.0 + dx, -1.0, z),
                    DVec3::new(1.0 + dx, -0.8, z),
                    DVec3::new(dx, 1.0, z),
                ],
                indices: vec![[0, 1, 2]],
                ..Mesh::default()
            },
            None,
        );
    }
    scene
}

#[test]
fn splits_are_counted_and_pieces_keep_their_primitive() {
    let s = screen(&procedural::intersecting_pair(), 64);
    let mut p = Painter::default();
    let mut f = Frame::new(64, 64).unwrap();
    let stats = p.render(&s, &mut f).unwrap();
    assert!(stats.plane_splits >= 1);
    assert_eq!(stats.pieces_out, stats.triangles + stats.splits);
    assert_eq!(p.ordered_pieces().len() as u64, stats.pieces_out);
    let prims: Vec<u32> = p.ordered_pieces().map(|q| q.prim).collect();
    assert!(prims.contains(&0) && prims.contains(&1));
    assert!(prims.iter().all(|&id| id < 2));
    // Pieces of a split triangle are cut; at least one prim appears twice.
    assert!(p.ordered_pieces().any(|q| !q.is_uncut()));
    assert_eq!(stats.splits, stats.plane_splits + stats.line_splits);
    assert!(stats.comparisons >= 1);
}

#[test]
fn cycle_without_intersection_is_split_and_resolved() {
    let s = screen(&procedural::cyclic_triple(), 64);
    let mut f = Frame::new(64, 64).unwrap();
    let stats = Painter::default().render(&s, &mut f).unwrap();
    // Each strip's plane cuts the next strip's triangle (the triangles do
    // not meet, their planes do), so the first blocked pair is split at
    // once by a plane: no depth order of the three exists.
    assert!(stats.plane_splits >= 1, "{stats:?}");
    assert_eq!(stats.line_splits, 0, "{stats:?}");
}

#[test]
fn exhausted_split_budget_is_a_clear_error() {
    let s = screen(&procedural::intersecting_pair(), 32);
    let mut p = Painter::new(PainterOptions::default().with_max_splits(0));
    let mut f = Frame::new(32, 32).unwrap();
    let err = p.render(&s, &mut f).unwrap_err();
    // Typed: the limit, its value and the option that sets it, so that
    // the CLI and Python can word it with their own flag and keyword.
    assert!(
        matches!(err, Error::Limit { what, value: 1, limit: 0 } if what == SPLIT_BUDGET),
        "{err:?}"
    );
    let msg = err.to_string();
    assert!(
        msg.contains("split budget") && msg.contains("PainterOptions::max_splits"),
        "{msg}"
    );
    // Scenes that need no split still render with no budget at all.
    let ok = screen(&layers(), 32);
    assert_eq!(p.render(&ok, &mut f).unwrap().splits, 0);
}

#[test]
fn wrong_frame_size_and_bad_triangles_are_errors() {
    let s = screen(&procedural::cube(), 32);
    let mut f = Frame::new(16, 32).unwrap();
    assert!(Painter::default().render(&s, &mut f).is_err());
    assert!(NaivePainter::default().render(&s, &mut f).is_err());
    let mut bad = s.clone();
    bad.tris[3].depth.dx = f64::NAN;
    let mut f = Frame::new(32, 32).unwrap();
    let msg = Painter::default()
        .render(&bad, &mut f)
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("triangle 3") && msg.contains("not finite"),
        "{msg}"
    );
    let mut flipped = s.clone();
    flipped.tris[0].v.swap(1, 2);
    assert!(NaivePainter::default().render(&flipped, &mut f).is_err());
}

#[test]
fn scratch_is_reused_across_frames_with_identical_results() {
    let a = screen(&procedural::cyclic_triple(), 40);
    let b = screen(&procedural::random_soup(40, 9), 40);
    let mut p = Painter::default();
    let first = render(&mut p, &a);
    let _ = render(&mut p, &b);
    assert_eq!(render(&mut p, &a), first);
}

/// Soups large enough that most candidates overlap more than the first
/// few sorted entries in depth, so the bin grid decides most pairs: still
/// exact against both references, and the same frame on every run.
#[test]
fn binned_ordering_matches_the_references_on_larger_soups() {
    for (n, seed, size) in [(800, 1, 48), (2000, 5, 64), (3000, 8, 40)] {
        let s = screen(&procedural::random_soup(n, seed), size);
        let what = format!("soup {n} seed {seed}");
        assert_exact(&s, &what);
        let first = render(&mut Painter::default(), &s);
        assert_eq!(render(&mut Painter::default(), &s), first, "{what}");
    }
}

/// Random triangles with corners anywhere in a cube: large, so that they
/// intersect and overlap cyclically often.
fn big_triangles() -> impl Strategy<Value = Scene> {
    prop::collection::vec(prop::array::uniform9(-1.0f64..1.0), 2..14).prop_map(|tris| {
        let mut positions = Vec::new();
        for t in &tris {
            for c in 0..3 {
                positions.push(DVec3::new(t[3 * c], t[3 * c + 1], t[3 * c + 2]));
            }
        }
        Scene::from_triangles(positions)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn painter_equals_the_references_on_random_intersecting_scenes(scene in big_triangles()) {
        let s = screen(&scene, 40);
        let frame = render(&mut Painter::default(), &s);
        let result = score(&s, &frame);
        prop_assert_eq!((result.coverage_mismatches, result.wrong_ids), (0, 0));
        let agreement = oracle(&s).compare(&frame.ids, DEFAULT_TIE_TOLERANCE);
        prop_assert!(agreement.is_exact(), "{}", agreement);
    }

    #[test]
    fn painter_equals_the_references_on_random_soups(n in 2u32..120, seed in 0u64..1_000_000) {
        let s = screen(&procedural::random_soup(n, seed), 48);
        let frame = render(&mut Painter::default(), &s);
        let result = score(&s, &frame);
        prop_assert_eq!((result.coverage_mismatches, result.wrong_ids), (0, 0));
        let agreement = oracle(&s).compare(&frame.ids, DEFAULT_TIE_TOLERANCE);
        prop_assert!(agreement.is_exact(), "{}", agreement);
    }
}
