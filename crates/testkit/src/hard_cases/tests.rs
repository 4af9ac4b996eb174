//! The hard cases are valid, deterministic and have what they promise.

use super::*;
use hider_geom::Projection;
use std::collections::HashMap;

#[test]
fn every_case_is_valid_deterministic_and_non_empty() {
    let a = all(7);
    let b = all(7);
    assert_eq!(a, b);
    assert_ne!(all(8)[0].1, a[0].1);
    for (name, scene) in &a {
        assert!(scene.validate().is_ok(), "{name}");
        assert!(scene.triangle_count() > 0, "{name}");
    }
}

/// Every directed edge appears once and its reverse once.
fn is_closed(scene: &Scene) -> bool {
    let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
    for mesh in &scene.meshes {
        for t in &mesh.indices {
            for k in 0..3 {
                *edges.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
            }
        }
    }
    edges
        .iter()
        .all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
}

#[test]
fn closed_meshes_are_closed_and_outward() {
    for (name, scene, _) in closed_meshes(3) {
        assert!(is_closed(&scene), "{name}");
        // Outward: the signed volume is positive.
        let mut volume = 0.0;
        for (_, m, t) in scene.triangles() {
            let [a, b, c] = scene.triangle_positions(m, t);
            volume += a.dot(b.cross(c)) / 6.0;
        }
        assert!(volume > 0.0, "{name}: volume {volume}");
    }
    assert!(!is_closed(&fan(8, 1)));
}

#[test]
fn intersecting_pairs_really_intersect() {
    // Both triangles of a pair share their centroid, which lies inside
    // both: the pair has points on either side of each other's plane.
    let s = intersecting_pairs(5, 11);
    for m in &s.meshes {
        let p = &m.positions;
        let n = (p[1] - p[0]).cross(p[2] - p[0]);
        let side: Vec<f64> = p[3..].iter().map(|q| n.dot(*q - p[0])).collect();
        assert!(
            side.iter().any(|&d| d > 0.0) && side.iter().any(|&d| d < 0.0),
            "{}",
            m.name
        );
    }
}

#[test]
fn coplanar_triangles_are_exactly_coplanar() {
    let s = coplanar_overlaps(5, 1);
    assert!(
        s.meshes
            .iter()
            .flat_map(|m| &m.positions)
            .all(|p| p.z == 0.0)
    );
}

#[test]
fn huge_cases_have_what_they_promise() {
    let b = huge_coordinates(10, 1, 1e7).bounds().unwrap();
    assert!(b.0.min_element() > 1e7 - 4.0 && b.1.max_element() < 1e7 + 4.0);
    let c = huge_depth_range(10, 1e5, 1).camera.unwrap();
    assert_eq!(
        c.projection,
        Projection::Perspective {
            fovy_degrees: 60.0,
            near: 1e-3,
            far: 1e6
        }
    );
    let s = near_plane_crossing(20, 1);
    let behind = s
        .meshes
        .iter()
        .flat_map(|m| &m.positions)
        .filter(|p| p.z > 0.0)
        .count();
    assert!(behind > 0);
}

#[test]
fn pinwheels_of_order_two_and_four_are_exactly_symmetric_on_the_lattice() {
    for (order, bits) in [(4, 0), (4, 3), (2, 0), (2, 5)] {
        let s = pinwheel(order, false, bits);
        assert_eq!(s.triangle_count(), 2 * order as usize);
        let step = 2f64.powi(-(bits as i32));
        let bars: Vec<&Vec<glam::DVec3>> = s.meshes.iter().map(|m| &m.positions).collect();
        for (k, bar) in bars.iter().enumerate() {
            for p in bar.iter() {
                assert_eq!((p.x / step).fract(), 0.0, "order {order}: {p}");
                assert_eq!((p.y / step).fract(), 0.0, "order {order}: {p}");
            }
            // The next bar is this one turned by a quarter (order 4) or a
            // half (order 2) turn, exactly.
            let next = bars[(k + 1) % bars.len()];
            for (p, q) in bar.iter().zip(next.iter()) {
                let turned = if order == 4 {
                    glam::DVec3::new(-p.y, p.x, p.z)
                } else {
                    glam::DVec3::new(-p.x, -p.y, p.z)
                };
                assert_eq!(turned, *q, "order {order}, bar {k}");
            }
        }
    }
}

#[test]
fn pinwheel_bars_have_area_on_every_lattice() {
    for order in 2..=6 {
        for bits in [0, 1, 4, 8] {
            for mirrored in [false, true] {
                let s = pinwheel(order, mirrored, bits);
                for (_, m, t) in s.triangles() {
                    let [a, b, c] = s.triangle_positions(m, t);
                    let area = (b - a).cross(c - a).length();
                    assert!(area >= 1.0, "order {order} bits {bits}: area {area}");
                }
                let screen = crate::screen(&s, 64, 64);
                let covered = crate::reference::pixel_centre(&screen)
                    .ids
                    .iter()
                    .filter(|&&id| id != hider_scene::NO_ID)
                    .count();
                assert!(covered > 200, "order {order} bits {bits}: {covered} pixels");
            }
        }
    }
}

#[test]
fn pinwheel_bars_are_planar_and_mirrored_pinwheels_are_mirror_images() {
    for order in 2..=6 {
        let s = pinwheel(order, true, 8);
        assert_eq!(s.meshes.len(), 2 * order as usize);
        assert!(s.validate().is_ok());
        let (right, left) = s.meshes.split_at(order as usize);
        for (a, b) in right.iter().zip(left) {
            for (p, q) in a.positions.iter().zip(&b.positions) {
                assert_eq!(*q, glam::DVec3::new(-p.x, p.y, p.z));
            }
        }
        // Bar 0 is a parallelogram whose height depends on the position
        // along it alone: exactly planar.
        let p = &right[0].positions;
        assert_eq!(p[0] + p[2], p[1] + p[3]);
    }
}

#[test]
fn bar_cycle_has_the_near_plane_it_was_asked_for() {
    let c = bar_cycle(1e-9).camera.unwrap();
    assert!(matches!(c.projection, Projection::Perspective { near, .. } if near == 1e-9));
    assert_eq!(bar_cycle(1e-9).triangle_count(), 6);
}

#[test]
fn far_plane_triangle_lies_on_the_far_plane() {
    let s = far_plane_triangle();
    let Projection::Perspective { far, .. } = s.camera.unwrap().projection else {
        panic!("perspective expected");
    };
    assert!(s.meshes[0].positions.iter().all(|p| -p.z == far));
}

#[test]
fn one_pixel_pile_covers_exactly_one_pixel_centre() {
    // Every triangle contains the pixel centre, seen along the view axis
    // (the camera is orthographic, so screen position is world x, y).
    let s = one_pixel_pile(500, 3);
    let c = crate::cameras::ONE_PIXEL_CENTRE;
    for (_, m, t) in s.triangles() {
        let [a, b, d] = s.triangle_positions(m, t);
        let side =
            |p: glam::DVec3, q: glam::DVec3| (q.x - p.x) * (c.y - p.y) - (q.y - p.y) * (c.x - p.x);
        let e = [side(a, b), side(b, d), side(d, a)];
        assert!(e.iter().all(|&v| v > 0.0) || e.iter().all(|&v| v < 0.0));
        for p in [a, b, d] {
            assert!((p.x - c.x).abs() < 0.6 / 32.0 && (p.y - c.y).abs() < 0.6 / 32.0);
        }
    }
}

#[test]
fn repeated_polygon_is_fan_split_into_coincident_copies() {
    let s = repeated_polygon(475);
    assert_eq!(s.triangle_count(), 4 * 475 - 2);
    let m = &s.meshes[0];
    assert_eq!(m.positions.len(), 4);
    assert_eq!(
        &m.indices[..4],
        &[[0, 1, 2], [0, 2, 3], [0, 3, 0], [0, 0, 1]]
    );
    let copies = m.indices.iter().filter(|t| **t == [0, 1, 2]).count();
    assert_eq!(copies, 475);
}

#[test]
fn offset_sphere_is_a_unit_sphere_around_the_offset() {
    let (lo, hi) = offset_sphere(16, 1e6).bounds().unwrap();
    assert_eq!((lo + hi) * 0.5, glam::DVec3::splat(1e6));
    assert!(((hi - lo) - glam::DVec3::splat(2.0)).abs().max_element() < 1e-6);
}
