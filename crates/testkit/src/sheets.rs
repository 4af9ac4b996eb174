//! Big flat faces: grids of many coplanar triangles of one colour, the
//! scenes where the vector output's face groups are largest (one boolean
//! over all of a face's regions).

use glam::DVec3;
use hider_scene::{Light, Material, Mesh, Scene};

/// A `cells x cells` grid of squares (two triangles each) over
/// `[-1, 1]^2` in the plane `z = 0.4 x + 0.3 y` (seen at a slant by the
/// fit camera), each position mapped by `place`.
pub fn grid(cells: u32, place: impl Fn(DVec3) -> DVec3) -> Mesh {
    let n = cells + 1;
    let mut positions = Vec::with_capacity((n * n) as usize);
    for j in 0..n {
        for i in 0..n {
            let x = -1.0 + 2.0 * f64::from(i) / f64::from(cells);
            let y = -1.0 + 2.0 * f64::from(j) / f64::from(cells);
            positions.push(place(DVec3::new(x, y, 0.4 * x + 0.3 * y)));
        }
    }
    let mut indices = Vec::with_capacity(2 * (cells * cells) as usize);
    for j in 0..cells {
        for i in 0..cells {
            let k = j * n + i;
            indices.push([k, k + 1, k + n + 1]);
            indices.push([k, k + n + 1, k + n]);
        }
    }
    Mesh {
        name: "grid".into(),
        positions,
        indices,
        ..Mesh::default()
    }
}

/// `meshes` in one material under one directional light: coplanar
/// triangles of a mesh share a colour, so each flat face is one group.
pub fn lit(meshes: Vec<Mesh>) -> Scene {
    let mut scene = Scene::default();
    for mesh in meshes {
        scene.push_mesh(
            mesh,
            Some(Material {
                name: "flat".into(),
                diffuse: [0.7, 0.6, 0.5],
                ..Material::default()
            }),
        );
    }
    scene.lights.push(Light::Directional {
        direction: DVec3::new(-0.3, -0.5, -1.0),
        color: [1.0; 3],
    });
    scene
}
