//! Big face groups: a flat sheet of thousands of coplanar triangles of
//! one colour is one group, and its path is one boolean over all of their
//! regions, past the sizes at which `i_overlay` leaves its list splitter
//! for its tree (2,000 segments) and fragment (32,000) splitters, whose
//! contour walk failed to close in `i_overlay` 4.5.2 (see `splitter.rs`).
//! The union must keep every region's area and drop the seams between
//! them.

mod common;

use common::area2;
use hider_scene::{Scene, ShadeMode, procedural};
use hider_testkit::{screen, sheets};
use hider_vector::{RegionMap, VectorOptions, visible_regions};

/// A `cells x cells` grid sheet seen at a slant by the fit camera, one
/// material under one directional light.
fn sheet(cells: u32) -> Scene {
    sheets::lit(vec![sheets::grid(cells, |p| p)])
}

fn regions(scene: &Scene) -> RegionMap {
    let s = screen(scene, 128, 128);
    visible_regions(&s, &VectorOptions::default(), ShadeMode::Lambert).unwrap()
}

/// Asserts that the groups' paths hold exactly the regions' area and
/// the covered set's: the unions lost and added nothing.
fn unions_keep_the_area(map: &RegionMap) {
    let regions: i128 = map.prims.iter().map(|r| area2(&r.shapes)).sum();
    let groups: i128 = map.groups.iter().map(|g| area2(&g.shapes)).sum();
    assert_eq!(groups, regions);
    assert_eq!(groups, area2(&map.covered));
}

#[test]
fn a_flat_sheet_is_one_group_with_one_outline() {
    // 20,000 triangles: the union gets 60,000 segments, past the
    // switch to the fragment splitter (32,000) too.
    let map = regions(&sheet(100));
    assert_eq!(map.prims.len(), 20_000);
    assert_eq!(map.groups.len(), 1, "{:?}", map.stats);
    let shapes = &map.groups[0].shapes;
    assert_eq!(shapes.len(), 1, "one piece");
    assert_eq!(shapes[0].len(), 1, "no hole");
    unions_keep_the_area(&map);
}

#[test]
fn a_pierced_sheet_is_one_group_with_holes() {
    let mut scene = sheet(100);
    let soup = procedural::random_soup(300, 1);
    let material = soup.materials.into_iter().next();
    for mut mesh in soup.meshes {
        mesh.material = None;
        scene.push_mesh(mesh, material.clone());
    }
    let map = regions(&scene);
    // The soup's triangles lie in 300 distinct planes: at most one group
    // each, and the sheet's visible triangles one more.
    assert!(map.groups.len() <= 301, "{} groups", map.groups.len());
    let sheet_group = map
        .groups
        .iter()
        .max_by_key(|g| g.prims.len())
        .expect("a group");
    assert!(
        sheet_group.prims.len() > 15_000,
        "{}",
        sheet_group.prims.len()
    );
    assert!(
        sheet_group.shapes.iter().any(|s| s.len() > 1),
        "the soup cuts holes in the sheet's path"
    );
    unions_keep_the_area(&map);
}
