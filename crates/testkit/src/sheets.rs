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

/// A fan of `count` triangles (at least 3) around one centre vertex, the
/// triangulation CAD files make of a disc or a cylinder's cap: the rim
/// on the unit circle at `z = 0`, counter-clockwise seen from `+z`, the
/// centre at `(0, 0, lift)` (0: a flat disc; above: a cone seen from its
/// apex, a sphere's pole). Every triangle meets every other at the
/// centre, the case where binning by area lists all pairs.
pub fn fan(count: u32, lift: f64) -> Mesh {
    let n = count.max(3);
    let mut positions = vec![DVec3::new(0.0, 0.0, lift)];
    positions.extend((0..n).map(|k| {
        let a = std::f64::consts::TAU * f64::from(k) / f64::from(n);
        DVec3::new(a.cos(), a.sin(), 0.0)
    }));
    Mesh {
        name: "fan".into(),
        positions,
        indices: (0..n).map(|k| [0, 1 + k, 1 + (k + 1) % n]).collect(),
        ..Mesh::default()
    }
}

/// `count` long thin parallel triangles across `[-1, 1]^2`, each from a
/// point at `x = -1` to an edge at `x = 1` `1.5 / count` tall, spaced
/// `2 / count` apart, in seven planes `z = 0, 0.01, .., 0.06` taken in
/// turn: seen head-on, neighbours in depth overlap only near the image's
/// edges, and each plane's slivers are one face group of separate
/// pieces. With square bins, a segment along one sliver has every other
/// sliver of its row of bins as a candidate occluder, and a group's union
/// meets every sliver in each bin.
pub fn slivers(count: u32) -> Mesh {
    let n = f64::from(count.max(1));
    let mut positions = Vec::with_capacity(3 * count as usize);
    for i in 0..count {
        let y = -1.0 + 2.0 * f64::from(i) / n;
        let z = f64::from(i % 7) * 0.01;
        positions.extend([
            DVec3::new(-1.0, y, z),
            DVec3::new(1.0, y, z),
            DVec3::new(1.0, y + 1.5 / n, z),
        ]);
    }
    Mesh {
        name: "slivers".into(),
        positions,
        indices: (0..count).map(|k| [3 * k, 3 * k + 1, 3 * k + 2]).collect(),
        ..Mesh::default()
    }
}

/// Two fans of `count` triangles each on one centre vertex at the
/// origin: one flat on the unit circle, the other's rim half a step
/// round and tilted (`z = tilt x`), so that their triangles overlap
/// near the centre while no two triangles of one fan do (the shared
/// vertex is no hub: corners there overlap across the fans).
pub fn two_fans(count: u32, tilt: f64) -> Mesh {
    let n = count.max(3);
    let mut positions = vec![DVec3::ZERO];
    for (turn, lift) in [(0.0, 0.0), (0.5, tilt)] {
        positions.extend((0..n).map(|k| {
            let a = std::f64::consts::TAU * (f64::from(k) + turn) / f64::from(n);
            DVec3::new(a.cos(), a.sin(), lift * a.cos())
        }));
    }
    let fan = |first: u32| (0..n).map(move |k| [0, first + k, first + (k + 1) % n]);
    Mesh {
        name: "two fans".into(),
        positions,
        indices: fan(1).chain(fan(1 + n)).collect(),
        ..Mesh::default()
    }
}
