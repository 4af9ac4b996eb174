//! Work counters, not times: the hidden half of a closed solid costs no
//! boolean, either skipped as the back faces of a solid seen from outside
//! or decided by the cover test when the solid is open; and the back-face
//! shortcut never hides what is seen.

mod common;

use common::area2;
use hider_scene::{Scene, ShadeMode, procedural};
use hider_testkit::screen;
use hider_vector::{RegionMap, VectorOptions, visible_regions};

fn regions(scene: &Scene) -> RegionMap {
    let s = screen(scene, 256, 256);
    visible_regions(&s, &VectorOptions::default(), ShadeMode::Lambert).unwrap()
}

#[test]
fn a_closed_sphere_skips_its_back_faces() {
    let map = regions(&procedural::uv_sphere(48));
    let stats = map.stats;
    // About half the triangles face away; all but the nearly edge-on ones
    // at the silhouette are skipped before any pair test.
    assert!(
        stats.hidden_back_faces * 5 > stats.triangles * 2,
        "{stats:?}"
    );
    assert_eq!(stats.differences, 0, "{stats:?}");
}

#[test]
fn an_open_sphere_decides_its_hidden_half_without_booleans() {
    let mut scene = procedural::uv_sphere(48);
    // One triangle fewer: not closed, so no back face may be skipped.
    scene.meshes[0].indices.pop();
    let stats = regions(&scene).stats;
    assert_eq!(stats.hidden_back_faces, 0, "{stats:?}");
    assert!(stats.decided * 3 > stats.triangles, "{stats:?}");
    assert!(stats.differences * 20 < stats.triangles, "{stats:?}");
}

#[test]
fn an_inside_out_sphere_keeps_its_near_faces() {
    let closed = regions(&procedural::uv_sphere(48));
    let mut scene = procedural::uv_sphere(48);
    // Inward normals: the near half is back-facing but is what is seen.
    for t in &mut scene.meshes[0].indices {
        t.swap(1, 2);
    }
    let flipped = regions(&scene);
    assert_eq!(flipped.stats.hidden_back_faces, 0);
    let area = |map: &RegionMap| map.prims.iter().map(|r| area2(&r.shapes)).sum::<i128>();
    // The same disc is covered either way.
    assert!(area(&flipped) > 0);
    assert_eq!(area(&flipped), area(&closed));
}
