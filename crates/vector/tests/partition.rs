//! The region map is a partition: the output polygons of different
//! primitives share no area at all, measured exactly on the integer grid,
//! on scenes full of crossings (interpenetrating surfaces, cyclic overlap,
//! occluding edges crossing the edges behind them), where every cut point
//! has to be rounded; and their union is the covered set, to the last
//! grid unit.

mod common;

use common::{area2, edge_sum};
use hider_scene::{ShadeMode, procedural};
use hider_testkit::{hard_cases, screen};
use hider_vector::{RegionMap, VectorOptions, visible_regions};
use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay::{Overlay, ShapeType};
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::i_float::int::point::IntPoint;
use i_overlay::i_shape::int::shape::IntShapes;

fn bounds(shapes: &IntShapes<i32>) -> (IntPoint, IntPoint) {
    let mut lo = IntPoint::new(i32::MAX, i32::MAX);
    let mut hi = IntPoint::new(i32::MIN, i32::MIN);
    for p in shapes.iter().flatten().flatten() {
        lo = IntPoint::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = IntPoint::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    (lo, hi)
}

/// Twice the total area of the pairwise intersections of different
/// primitives' regions, and how many pairs have any.
fn overlap(map: &RegionMap) -> (i128, usize) {
    let boxes: Vec<_> = map.prims.iter().map(|r| bounds(&r.shapes)).collect();
    let (mut total, mut pairs) = (0, 0);
    for (a, ra) in map.prims.iter().enumerate() {
        for (b, rb) in map.prims.iter().enumerate().skip(a + 1) {
            let ((alo, ahi), (blo, bhi)) = (boxes[a], boxes[b]);
            if ahi.x <= blo.x || bhi.x <= alo.x || ahi.y <= blo.y || bhi.y <= alo.y {
                continue;
            }
            let mut o = Overlay::<i32>::new(64);
            o.add_source(&ra.shapes, ShapeType::Subject);
            o.add_source(&rb.shapes, ShapeType::Clip);
            let area = area2(&o.overlay(OverlayRule::Intersect, FillRule::NonZero));
            if area != 0 {
                total += area;
                pairs += 1;
            }
        }
    }
    (total, pairs)
}

fn assert_partition(name: &str, scene: &hider_scene::Scene, size: u32) -> RegionMap {
    let s = screen(scene, size, size);
    let map = visible_regions(&s, &VectorOptions::default(), ShadeMode::Ids).unwrap();
    let (area, pairs) = overlap(&map);
    assert_eq!(
        (area, pairs),
        (0, 0),
        "{name}: {pairs} pairs of regions overlap by {area} / 2 grid units^2 ({} cut pairs)",
        map.stats.cut_pairs
    );
    // Every region is a proper polygon set: positive area.
    for region in &map.prims {
        assert!(
            area2(&region.shapes) > 0,
            "{name}: empty region {}",
            region.prim
        );
    }
    let (gap, footprint) = xor_with_footprint(&map);
    assert_eq!(
        gap, 0,
        "{name}: union of regions XOR covered set is {gap} / 2 grid units^2 \
         (covered {footprint} / 2, {} cut pairs)",
        map.stats.cut_pairs
    );
    covered_is_the_triangles(name, &s, &map);
    map
}

/// Twice the area of (union of regions) XOR (covered set), and twice the
/// covered set's area.
///
/// What "covered set" means exactly on the grid: the union of the
/// triangles with their vertices on the grid and clipped to the image as
/// the region map clips them. Its outline crosses itself (surfaces
/// interpenetrate, triangles overlap) at points off the grid, so no integer
/// polygon equals it; the map carries it snap rounded in the same
/// arrangement as its regions (Hobby's "Practical segment intersection
/// with finite precision output"), where every boolean is exact. The
/// regions' union must equal that set to the last grid unit (checked
/// here), and that set must be the triangles' union moved by at most one
/// grid unit along its outline (checked by [`covered_is_the_triangles`]).
fn xor_with_footprint(map: &RegionMap) -> (i128, i128) {
    let mut regions = Overlay::<i32>::new(64);
    for r in &map.prims {
        regions.add_source(&r.shapes, ShapeType::Subject);
    }
    let union = regions.overlay(OverlayRule::Subject, FillRule::NonZero);
    (xor_area2(&union, &map.covered), area2(&map.covered))
}

/// Twice the area of `a` XOR `b`.
fn xor_area2(a: &IntShapes<i32>, b: &IntShapes<i32>) -> i128 {
    let mut o = Overlay::<i32>::new(64);
    o.add_source(a, ShapeType::Subject);
    o.add_source(b, ShapeType::Clip);
    area2(&o.overlay(OverlayRule::Xor, FillRule::NonZero))
}

/// The map's covered set differs from the plain union of the triangles on
/// the grid by at most a band one grid unit wide along that union's
/// outline (snap rounding moves an edge by less than one unit).
fn covered_is_the_triangles(name: &str, s: &hider_scene::ScreenScene, map: &RegionMap) {
    let mut o = Overlay::<i32>::new(64);
    for t in &s.tris {
        let poly = map.grid.clip_to_image(&map.grid.tri_points(t));
        if poly.len() >= 3 {
            o.add_contour(&poly, ShapeType::Subject);
        }
    }
    let raw = o.overlay(OverlayRule::Subject, FillRule::NonZero);
    let perimeter: f64 = edge_sum(&raw, |a, b| {
        f64::from(a.x - b.x).hypot(f64::from(a.y - b.y))
    });
    let moved = xor_area2(&raw, &map.covered) as f64 / 2.0;
    assert!(
        moved <= perimeter,
        "{name}: covered set moved by {moved} grid units^2 over an outline of {perimeter} units"
    );
}

#[test]
fn regions_of_the_hard_cases_share_no_area() {
    for seed in [1, 2, 3] {
        for (name, scene) in hard_cases::all(seed) {
            let _ = assert_partition(&format!("{name} seed {seed}"), &scene, 64);
        }
    }
}

#[test]
fn regions_of_cyclic_bars_and_crossing_surfaces_share_no_area() {
    let _ = assert_partition("bar_cycle", &hard_cases::bar_cycle(1e-3), 96);
    let _ = assert_partition("intersecting_pair", &procedural::intersecting_pair(), 96);
    let _ = assert_partition("cyclic_triple", &procedural::cyclic_triple(), 96);
    let _ = assert_partition(
        "interpenetrating_boxes",
        &hard_cases::interpenetrating_boxes(6, 5),
        128,
    );
}

/// A 12 x 12 grid on the plane `y = 0.4 x - 0.2 z`, seen from a point of
/// that plane: every triangle a sliver along one line.
fn edge_on_sheet() -> hider_scene::Scene {
    use glam::DVec3;
    let n = 12u32;
    let mut positions = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let x = -1.0 + 2.0 * f64::from(i) / f64::from(n - 1);
            let z = -1.0 + 2.0 * f64::from(j) / f64::from(n - 1);
            positions.push(DVec3::new(x, 0.4 * x - 0.2 * z, z));
        }
    }
    let mut indices = Vec::new();
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let k = j * n + i;
            indices.push([k, k + n, k + 1]);
            indices.push([k + 1, k + n, k + n + 1]);
        }
    }
    let mut scene = hider_scene::Scene::default();
    scene.push_mesh(
        hider_scene::Mesh {
            name: "sheet".into(),
            positions,
            indices,
            ..hider_scene::Mesh::default()
        },
        None,
    );
    scene.camera = Some(hider_geom::Camera::perspective(
        DVec3::new(3.0, 0.6, 3.0),
        DVec3::ZERO,
        0.5,
        20.0,
    ));
    scene
}

#[test]
fn regions_of_a_sheet_seen_edge_on_share_no_area() {
    let map = assert_partition("edge-on sheet", &edge_on_sheet(), 128);
    // Slivers, but many of them, overlapping each other along the line.
    assert!(map.stats.triangles > 100, "{:?}", map.stats);
    assert!(
        map.stats.overlapping_pairs > map.stats.triangles,
        "{:?}",
        map.stats
    );
}

#[test]
fn regions_of_random_soups_share_no_area() {
    for seed in 0..8 {
        let scene = procedural::random_soup(80, seed);
        let _ = assert_partition(&format!("random_soup seed {seed}"), &scene, 96);
    }
}
