//! The ordering with star partners against the bins alone and the full
//! scan, on fans, cones, stars of several fans, folded fans, books and
//! clutter; and the comparisons of a growing cone.

use glam::DVec3;
use hider_scene::procedural::SplitMix64;
use hider_scene::{PrepareOptions, Scene, ScreenScene, View, prepare};

use crate::order::tests::ordered;

/// Triangles around `centre`: a fan (kind 0), a cone (1), a folded fan
/// (2), a book of pages around one edge (3), random triangles sharing the
/// centre (4); in order around (tiling) or at random angles (overlapping).
fn family(r: &mut SplitMix64, centre: DVec3, kind: usize, out: &mut Vec<DVec3>) {
    let n = 12 + r.below(40);
    let axis = if r.below(3) == 0 {
        DVec3::Z
    } else {
        r.direction()
    };
    let u = axis.any_orthonormal_vector();
    let v = axis.cross(u);
    let ordered = r.below(2) == 0;
    let mut angles: Vec<f64> = (0..n)
        .map(|k| {
            if ordered {
                std::f64::consts::TAU * k as f64 / n as f64
            } else {
                r.range(0.0, std::f64::consts::TAU)
            }
        })
        .collect();
    if ordered {
        angles.push(angles[0]);
    }
    let rim = |a: f64, lift: f64| centre + u * a.cos() + v * a.sin() + axis * lift;
    for w in angles.windows(2) {
        let tri = match kind {
            0 => [centre, rim(w[0], 0.0), rim(w[1], 0.0)],
            1 => [centre, rim(w[0], -0.5), rim(w[1], -0.5)],
            2 => [
                centre,
                rim(w[0], r.range(-0.3, 0.3)),
                rim(w[1], r.range(-0.3, 0.3)),
            ],
            3 => [centre, centre + axis, rim(w[0], r.range(0.0, 1.0))],
            _ => [centre, centre + r.direction(), centre + r.direction()],
        };
        out.extend(tri);
    }
}

fn scene(r: &mut SplitMix64) -> Scene {
    let mut positions = Vec::new();
    let centre = DVec3::new(r.range(-0.5, 0.5), r.range(-0.5, 0.5), r.range(-0.5, 0.5));
    for _ in 0..1 + r.below(3) {
        let kind = r.below(5);
        // Most families around one centre, some elsewhere.
        let c = if r.below(3) == 0 {
            r.direction()
        } else {
            centre
        };
        family(r, c, kind, &mut positions);
    }
    for _ in 0..r.below(10) {
        let p = DVec3::new(r.range(-1.5, 1.5), r.range(-1.5, 1.5), r.range(-1.5, 1.5));
        positions.extend([p, p + r.direction(), p + r.direction()]);
    }
    Scene::from_triangles(positions)
}

/// Star partners drop only mates that cannot block, so the order, the
/// splits and the moves are those of the bins alone. (The bins alone and
/// the full scan, `linear_scan: usize::MAX`, differ on many of these
/// scenes where pieces cover one centre each, before the stars too: the
/// centre index is asked for a blocker after the bins, not in key order;
/// see docs/notes/2026-11-28-fan-pairs.md.)
#[test]
fn star_partners_give_the_same_order_as_the_bins_alone() {
    let mut r = SplitMix64::new(1974);
    let mut skipped = 0;
    for round in 0..80 {
        let scene = scene(&mut r);
        let size = [24, 64, 128][round % 3];
        let view = View::for_scene(&scene, size, size).unwrap();
        let s = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
        let (bins, bins_stats) = ordered(&s, crate::blocker::LINEAR_SCAN, true);
        let (stars, stats) = ordered(&s, crate::blocker::LINEAR_SCAN, false);
        assert!(stars == bins, "round {round}: the order differs");
        assert_eq!(
            (stats.splits, stats.moves),
            (bins_stats.splits, bins_stats.moves),
            "{round}"
        );
        skipped += bins_stats.comparisons.saturating_sub(stats.comparisons);
    }
    // The stars did spare comparisons.
    assert!(skipped > 1000, "{skipped}");
}

/// A cone of `n` triangles, apex towards the camera (the pole of a UV
/// sphere), seen along its axis.
fn cone(n: usize) -> ScreenScene {
    let rim = |k: usize| {
        let a = std::f64::consts::TAU * (k % n) as f64 / n as f64;
        DVec3::new(a.cos(), a.sin(), 0.0)
    };
    let positions = (0..n)
        .flat_map(|k| [DVec3::new(0.0, 0.0, 0.5), rim(k), rim(k + 1)])
        .collect();
    let scene = Scene::from_triangles(positions);
    let view = View::for_scene(&scene, 256, 256).unwrap();
    prepare(&scene, &view, &PrepareOptions::default()).unwrap()
}

/// Doubling the cone less than triples the comparisons (every pair of
/// the cone's triangles was compared before the stars: 4x).
#[test]
fn cone_comparisons_grow_linearly() {
    let work = |n| ordered(&cone(n), crate::blocker::LINEAR_SCAN, false).1;
    let (small, large) = (work(1000), work(2000));
    assert_eq!((small.splits, large.splits), (0, 0));
    assert!(
        large.comparisons < 3 * small.comparisons,
        "{} then {}",
        small.comparisons,
        large.comparisons
    );
}
