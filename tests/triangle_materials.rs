//! Materials per triangle (`Mesh::triangle_materials`): one mesh whose
//! faces name different materials renders exactly as the same faces split
//! into one mesh per material, in every registered hider (ids, depth and
//! colour, translucency included), and the per-triangle materials survive
//! an OBJ round trip.

mod library_support;
use library_support::library_frame;

use hider::plan::registry;
use hider::scene::glam::DVec3;
use hider::scene::{Material, Mesh, Scene, load_obj, save_obj};

const SIZE: u32 = 40;

/// Four overlapping quads at different depths, eight triangles whose
/// materials alternate red / glass / green / default-looking grey.
fn faces() -> (Vec<DVec3>, Vec<[u32; 3]>, Vec<u32>) {
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    let mut materials = Vec::new();
    for (k, (x, y, z)) in [
        (-0.4, -0.4, 0.0),
        (0.0, 0.0, 0.3),
        (0.4, -0.2, 0.6),
        (-0.2, 0.3, 0.9),
    ]
    .into_iter()
    .enumerate()
    {
        let base = positions.len() as u32;
        for (dx, dy) in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)] {
            positions.push(DVec3::new(x + dx, y + dy, z));
        }
        indices.push([base, base + 1, base + 2]);
        indices.push([base, base + 2, base + 3]);
        // The two triangles of a quad differ, so no run of equal
        // materials covers a whole quad.
        materials.push((2 * k as u32) % 4);
        materials.push((2 * k as u32 + 1) % 4);
    }
    (positions, indices, materials)
}

fn materials() -> Vec<Material> {
    let named = |name: &str, diffuse: [f32; 3], opacity: f32| Material {
        name: name.into(),
        diffuse,
        opacity,
        ..Material::default()
    };
    vec![
        named("red", [0.9, 0.1, 0.1], 1.0),
        named("glass", [0.2, 0.5, 0.9], 0.4),
        named("green", [0.1, 0.8, 0.2], 1.0),
        Material::default(),
    ]
}

/// One mesh, a material per triangle.
fn per_triangle() -> Scene {
    let (positions, indices, triangle_materials) = faces();
    let mut scene = Scene {
        materials: materials(),
        ..Scene::default()
    };
    scene.meshes.push(Mesh {
        name: "faces".into(),
        positions,
        indices,
        triangle_materials,
        ..Mesh::default()
    });
    scene
}

/// The same triangles, in the same order, one mesh per triangle with the
/// mesh's material: what a user had to write before.
fn split() -> Scene {
    let (positions, indices, triangle_materials) = faces();
    let mut scene = Scene {
        materials: materials(),
        ..Scene::default()
    };
    for (tri, k) in indices.iter().zip(triangle_materials) {
        scene.meshes.push(Mesh {
            name: "faces".into(),
            positions: tri.iter().map(|&i| positions[i as usize]).collect(),
            indices: vec![[0, 1, 2]],
            material: Some(k as usize),
            ..Mesh::default()
        });
    }
    scene
}

#[test]
fn per_triangle_materials_render_as_one_mesh_per_material_in_every_hider() {
    let (one, many) = (per_triangle(), split());
    for entry in registry::all() {
        one.validate().unwrap();
        many.validate().unwrap();
        let (a, b) = (
            library_frame(entry.name, &one, SIZE),
            library_frame(entry.name, &many, SIZE),
        );
        assert_eq!(a.ids, b.ids, "{}: ids", entry.name);
        assert_eq!(a.depth, b.depth, "{}: depth", entry.name);
        assert_eq!(a.color, b.color, "{}: colour", entry.name);
        // The materials show: red and green pixels both appear.
        let has = |rgb: fn(&[u16; 3]) -> bool| {
            a.rgba_bytes()
                .chunks(4)
                .any(|p| rgb(&[p[0], p[1], p[2]].map(u16::from)))
        };
        assert!(
            has(|p| p[0] > p[1].max(p[2]) + 60),
            "{}: no red",
            entry.name
        );
        assert!(
            has(|p| p[1] > p[0].max(p[2]) + 60),
            "{}: no green",
            entry.name
        );
    }
}

#[test]
fn per_triangle_materials_are_checked_and_survive_an_obj_round_trip() {
    let mut bad = per_triangle();
    bad.meshes[0].triangle_materials.pop();
    let e = bad.validate().unwrap_err().to_string();
    assert!(e.contains("7 triangle materials for 8 triangles"), "{e}");
    let mut bad = per_triangle();
    bad.meshes[0].triangle_materials[5] = 9;
    let e = bad.validate().unwrap_err().to_string();
    assert!(
        e.contains("triangle 5 uses material 9, but there are 4"),
        "{e}"
    );

    let scene = per_triangle();
    let dir = std::env::temp_dir().join(format!("hider-tri-mtl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("faces.obj");
    save_obj(&scene, &path).unwrap();
    let back = load_obj(&path).unwrap();
    let colours = |s: &Scene| -> Vec<[f32; 3]> {
        s.triangles()
            .map(|(_, m, t)| s.triangle_material(m, t).map_or([-1.0; 3], |m| m.diffuse))
            .collect()
    };
    assert_eq!(colours(&back), colours(&scene));
    std::fs::remove_dir_all(&dir).unwrap();
}
