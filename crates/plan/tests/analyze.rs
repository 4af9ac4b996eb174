//! Each effect the analysis detects, on a scene with it and one without.

use glam::DVec3;
use hider_plan::{RenderOptions, analyze};
use hider_scene::geom::Camera;
use hider_scene::{Light, Mesh, Scene, procedural};
use hider_testkit::hard_cases;

fn small() -> RenderOptions {
    RenderOptions::default().with_size(64, 64)
}

#[test]
fn transparency_with_and_without() {
    let opaque = procedural::cube();
    let fx = analyze(&opaque, &small()).unwrap();
    assert!(!fx.transparency.present && fx.transparency.certain);
    let mut glass = procedural::cube();
    glass.materials[0].opacity = 0.4;
    let fx = analyze(&glass, &small()).unwrap();
    assert!(fx.transparency.present);
    assert_eq!(fx.transparency.count, 12);
    assert!(fx.transparency.detail.contains(&glass.materials[0].name));
    // Back faces show through glass: culling them is no longer exact.
    assert!(!fx.cull_back_faces_exact);
}

#[test]
fn lighting_follows_shading_with_the_head_light_when_there_are_no_lights() {
    let bare = procedural::cube();
    let fx = analyze(&bare, &small()).unwrap();
    assert!(fx.lighting.present && fx.lighting.count == 0);
    assert!(
        fx.lighting.detail.contains("head light"),
        "{}",
        fx.lighting.detail
    );
    assert!(
        !analyze(&bare, &small().with_shading(false))
            .unwrap()
            .lighting
            .present
    );
    let mut lit = procedural::cube();
    lit.lights.push(Light::Directional {
        direction: DVec3::new(-1.0, -1.0, -1.0),
        color: [1.0; 3],
    });
    assert!(analyze(&lit, &small()).unwrap().lighting.present);
    assert!(
        !analyze(&lit, &small().with_shading(false))
            .unwrap()
            .lighting
            .present
    );
    let mut normals = procedural::cube();
    let n = normals.meshes[0].positions.len();
    normals.meshes[0].normals = vec![glam::Vec3::Y; n];
    let fx = analyze(&normals, &small()).unwrap();
    assert!(
        fx.lighting.present && fx.lighting.count == 1,
        "{}",
        fx.lighting.detail
    );
}

#[test]
fn antialiasing_only_when_asked() {
    let s = procedural::cube();
    assert!(!analyze(&s, &small()).unwrap().antialiasing.present);
    assert!(
        analyze(&s, &small().with_antialiasing(true))
            .unwrap()
            .antialiasing
            .present
    );
}

#[test]
fn intersections_with_and_without() {
    let fx = analyze(&procedural::intersecting_pair(), &small()).unwrap();
    assert!(fx.intersections.present && fx.intersections.certain);
    assert_eq!(fx.intersections.count, 1);
    assert_eq!(fx.intersections.examples, vec![vec![0, 1]]);
    // A closed mesh: neighbours share edges and vertices, none crosses.
    for scene in [procedural::cube(), procedural::uv_sphere(24)] {
        let fx = analyze(&scene, &small()).unwrap();
        assert!(!fx.intersections.present, "{}", fx.intersections.detail);
        assert!(fx.intersections.certain);
    }
    let boxes = analyze(&hard_cases::interpenetrating_boxes(3, 7), &small()).unwrap();
    assert!(boxes.intersections.present && boxes.intersections.count >= 4);
    // Coplanar overlaps are ties, not intersections.
    let fx = analyze(&procedural::coplanar_pair(), &small()).unwrap();
    assert!(!fx.intersections.present);
    assert!(fx.coplanar_overlaps.present);
}

#[test]
fn cyclic_overlap_with_and_without() {
    let fx = analyze(&procedural::cyclic_triple(), &small()).unwrap();
    assert!(!fx.intersections.present, "{}", fx.intersections.detail);
    assert!(fx.cyclic_overlap.present, "{}", fx.cyclic_overlap.detail);
    assert_eq!(fx.cyclic_overlap.count, 1);
    let mut cycle = fx.cyclic_overlap.examples[0].clone();
    cycle.sort_unstable();
    assert_eq!(cycle, vec![0, 1, 2]);
    assert!(fx.naive_order_violations.present);
    let fx = analyze(&hard_cases::cyclic_overlap(5), &small()).unwrap();
    assert!(fx.cyclic_overlap.present, "{}", fx.cyclic_overlap.detail);
    // A sphere has overlaps (front over back faces) but no cycle, and the
    // naive farthest-vertex sort already orders them.
    let fx = analyze(&procedural::uv_sphere(24), &small()).unwrap();
    assert!(!fx.cyclic_overlap.present, "{}", fx.cyclic_overlap.detail);
    assert!(fx.cyclic_overlap.certain);
}

#[test]
fn back_faces_hidden_by_a_closed_mesh_visible_when_open_or_inside() {
    let cube = procedural::cube();
    let fx = analyze(&cube, &small()).unwrap();
    assert!(
        fx.back_faces.count > 0,
        "the fit camera sees some back faces"
    );
    assert!(!fx.back_faces.present, "{}", fx.back_faces.detail);
    assert!(fx.cull_back_faces_exact);
    // Open the cube: its inside shows.
    let mut open = procedural::cube();
    open.meshes[0].indices.truncate(10);
    let fx = analyze(&open, &small()).unwrap();
    assert!(fx.back_faces.present || fx.back_faces.count == 0);
    assert!(!fx.cull_back_faces_exact);
    // The eye inside the cube sees only back faces.
    let inside = Camera::perspective(DVec3::ZERO, DVec3::new(0.0, 0.0, -1.0), 0.1, 10.0);
    let fx = analyze(&cube, &small().with_camera(Some(inside))).unwrap();
    assert!(fx.back_faces.present, "{}", fx.back_faces.detail);
    // A single triangle seen from behind.
    let mut one = Scene::default();
    one.push_mesh(
        Mesh {
            positions: vec![DVec3::ZERO, DVec3::Y, DVec3::X],
            indices: vec![[0, 1, 2]],
            ..Mesh::default()
        },
        None,
    );
    let fx = analyze(&one, &small()).unwrap();
    assert!(fx.back_faces.present && fx.back_faces.examples == vec![vec![0]]);
}

#[test]
fn a_tiny_budget_makes_findings_uncertain_and_safe() {
    let soup = procedural::random_soup(300, 5);
    let fx = analyze(&soup, &small().with_pair_budget(10)).unwrap();
    assert!(!fx.intersections.certain && fx.intersections.present);
    assert!(!fx.cyclic_overlap.certain && fx.cyclic_overlap.present);
    let full = analyze(&soup, &small()).unwrap();
    assert!(full.intersections.certain && full.intersections.present);
    // The report names every effect.
    let text = full.to_string();
    for name in [
        "transparency",
        "textures",
        "intersections",
        "cyclic overlap",
        "back faces",
    ] {
        assert!(text.contains(name), "{text}");
    }
}
