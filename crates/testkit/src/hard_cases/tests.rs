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
