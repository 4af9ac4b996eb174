//! The visible regions against the z-buffer: evaluated at every pixel
//! centre with the exact crossing-number test, they give the z-buffer's id
//! on every pixel that is not a depth tie, on every hard case and on
//! random scenes; they never overlap, and together they cover exactly what
//! the triangles cover.

mod common;

use common::area2;
use hider_geom::edge::top_left_bias;
use hider_geom::polygon::{IPoint, crossing_number_inside};
use hider_oracle::{DEFAULT_TIE_TOLERANCE, window_depth_reference};
use hider_scene::{Hider, NO_ID, ScreenScene, ShadeMode, procedural};
use hider_testkit::{hard_cases, render, screen};
use hider_vector::{RegionMap, VectorOptions, visible_regions};
use hider_zbuffer::{DepthFormat, ZBuffer, ZBufferOptions};
use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay::{Overlay, ShapeType};
use i_overlay::core::overlay_rule::OverlayRule;

/// Per pixel: the primitive whose region holds the centre (`NO_ID` for
/// none), and how many pixel centres fell in more than one region.
///
/// The crossing-number test's half-open rule decides a centre on an edge
/// as if the centre were moved right by an infinitesimal, and down by a
/// far smaller one: the fill rule that owns left and top edges. When the
/// front end's rule owns bottom edges instead (GL's row order), the test
/// runs on the mirror image in y, which moves the centre up.
fn region_ids(s: &ScreenScene, map: &RegionMap) -> (Vec<u32>, usize) {
    let bottom_edges_owned = top_left_bias(-1, 0) == 1;
    let my = |y: i64| if bottom_edges_owned { -y } else { y };
    let (w, h) = (s.viewport.width, s.viewport.height);
    let mut ids = vec![NO_ID; (w * h) as usize];
    let mut doubles = 0;
    for region in &map.prims {
        for shape in &region.shapes {
            let contours: Vec<Vec<IPoint>> = shape
                .iter()
                .map(|c| {
                    c.iter()
                        .map(|p| (i64::from(p.x), my(i64::from(p.y))))
                        .collect()
                })
                .collect();
            let (mut x0, mut y0, mut x1, mut y1) = (i64::MAX, i64::MAX, i64::MIN, i64::MIN);
            for &(x, y) in contours.iter().flatten() {
                let y = my(y);
                (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
            }
            let unit = map.grid.units_per_pixel() as i64;
            let to_px = |v: i64, n: u32| (v / unit).clamp(0, i64::from(n) - 1) as u32;
            for j in to_px(y0, h)..=to_px(y1, h) {
                for i in to_px(x0, w)..=to_px(x1, w) {
                    let (cx, cy) = map.grid.pixel_centre(i, j);
                    let c = (cx, my(cy));
                    let inside = contours.iter().fold(false, |acc, contour| {
                        acc ^ crossing_number_inside(contour, c)
                    });
                    if inside {
                        let k = (j * w + i) as usize;
                        if ids[k] != NO_ID {
                            doubles += 1;
                        }
                        ids[k] = region.prim;
                    }
                }
            }
        }
    }
    (ids, doubles)
}

/// Twice the total area of pairwise overlaps between different
/// primitives' regions, and twice the area where the union of the regions
/// and the union of the triangles differ, in grid units squared.
fn overlap_and_cover(s: &ScreenScene, map: &RegionMap) -> (i128, i128) {
    let mut overlap = 0;
    for (a, ra) in map.prims.iter().enumerate() {
        for rb in &map.prims[a + 1..] {
            let mut o = Overlay::<i32>::new(16);
            for shape in &ra.shapes {
                o.add_source(shape, ShapeType::Subject);
            }
            for shape in &rb.shapes {
                o.add_source(shape, ShapeType::Clip);
            }
            overlap += area2(&o.overlay(OverlayRule::Intersect, FillRule::NonZero)).abs();
        }
    }
    let mut o = Overlay::<i32>::new(16);
    for region in &map.prims {
        for shape in &region.shapes {
            o.add_source(shape, ShapeType::Subject);
        }
    }
    for t in &s.tris {
        let poly = map.grid.clip_to_image(&map.grid.tri_points(t));
        if poly.len() >= 3 {
            o.add_contour(&poly, ShapeType::Clip);
        }
    }
    let differ = area2(&o.overlay(OverlayRule::Xor, FillRule::NonZero)).abs();
    (overlap, differ)
}

/// Checks one scene; returns (pixels compared, ties skipped).
fn check(name: &str, s: &ScreenScene) -> (usize, usize) {
    let map = visible_regions(s, &VectorOptions::default(), ShadeMode::Ids).unwrap();
    let mut zbuffer = ZBuffer::new(ZBufferOptions::default().with_depth_format(DepthFormat::F64));
    let (frame, _) = render(&mut zbuffer, s);
    let reference = window_depth_reference(s);
    let (ids, doubles) = region_ids(s, &map);
    assert_eq!(doubles, 0, "{name}: pixel centres inside two regions");
    let (mut compared, mut ties) = (0, 0);
    for (k, (&mine, &z)) in ids.iter().zip(&frame.ids).enumerate() {
        assert_eq!(
            mine == NO_ID,
            z == NO_ID,
            "{name}: coverage differs at pixel {k}"
        );
        if reference.is_tie(k, DEFAULT_TIE_TOLERANCE) {
            ties += 1;
            continue;
        }
        compared += 1;
        assert_eq!(mine, z, "{name}: pixel {k} ({}, {})", k % 64, k / 64);
    }
    (compared, ties)
}

#[test]
fn regions_give_the_zbuffer_id_on_every_hard_case() {
    for seed in [1, 2] {
        for (name, scene) in hard_cases::all(seed) {
            let s = screen(&scene, 64, 64);
            let (compared, ties) = check(name, &s);
            eprintln!("{name}: {compared} pixels agree, {ties} ties skipped");
        }
    }
}

#[test]
fn regions_give_the_zbuffer_id_on_random_scenes() {
    for seed in 0..12 {
        let scene = procedural::random_soup(60, seed);
        check(&format!("random_soup seed {seed}"), &screen(&scene, 64, 64));
    }
}

/// Hard cases made of meshes whose faces meet only along shared edges.
const MESHES: &[&str] = &[
    "near_degenerate_fan",
    "fan",
    "bipyramid",
    "cube",
    "uv_sphere",
    "torus",
    "offset_sphere",
    "repeated_polygon",
    "far_plane_triangle",
];

#[test]
fn regions_never_overlap_and_cover_what_the_triangles_cover() {
    let mut cases = hard_cases::all(3);
    cases.push(("random_soup", procedural::random_soup(40, 7)));
    for (name, scene) in cases {
        let s = screen(&scene, 64, 64);
        let map = visible_regions(&s, &VectorOptions::default(), ShadeMode::Ids).unwrap();
        let (overlap, differ) = overlap_and_cover(&s, &map);
        let unit2 = map.grid.units_per_pixel().powi(2);
        let (overlap_px, differ_px) = (overlap as f64 / 2.0 / unit2, differ as f64 / 2.0 / unit2);
        // Snap rounding puts every region on one arrangement: regions of
        // different primitives share no area anywhere.
        assert_eq!(overlap, 0, "{name}: regions overlap by {overlap_px} px^2");
        eprintln!("{name}: union differs from the cover by {differ_px} px^2");
        if MESHES.contains(&name) {
            // No cut lines and no crossing edges inside a face: nothing is
            // rounded, so the union is exactly the covered set.
            assert_eq!(
                differ, 0,
                "{name}: the regions' union is not the covered set"
            );
        } else {
            // Where cut points are rounded to the grid (1/16384 pixel by
            // default), the union may differ from the covered set (itself
            // rounded by the polygon library) by slivers that thin.
            assert!(
                differ_px < 1e-2,
                "{name}: union differs from the cover by {differ_px} px^2"
            );
        }
    }
}
