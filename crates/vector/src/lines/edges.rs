//! Feature edges of the meshes: silhouettes from the front/back change
//! over the adjacency, boundaries, creases and material boundaries,
//! projected and snapped like the front end's corners.

use glam::{DVec3, DVec4};
use hider_geom::fixed::SUBPIXEL_SCALE;
use hider_scene::ScreenScene;

use super::{Feature, LineKind};

/// Fixed-point units per pixel.
const SCALE: f64 = SUBPIXEL_SCALE as f64;

/// An edge of a mesh: the keys of its two vertices, in ascending order.
type EdgeKey = ([u64; 3], [u64; 3]);
/// A mesh vertex identified by its exact camera-space coordinates.
fn vertex_key(p: DVec3) -> [u64; 3] {
    [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]
}

/// The feature edges of the scene's meshes, projected and clipped to the
/// near and far planes.
pub(super) fn edge_features(scene: &ScreenScene, crease_degrees: f64) -> Vec<Feature> {
    // (edge as sorted vertex keys, prim, edge runs forward), sorted so the
    // users of one edge are adjacent: cheaper than hashing 48-byte keys.
    let mut uses: Vec<(EdgeKey, u32, bool)> = Vec::with_capacity(3 * scene.prims.len());
    for (prim, info) in scene.prims.iter().enumerate() {
        let c = info.camera;
        if (c[1] - c[0]).cross(c[2] - c[0]).length_squared() == 0.0 {
            continue;
        }
        for k in 0..3 {
            let (a, b) = (vertex_key(c[k]), vertex_key(c[(k + 1) % 3]));
            let key = if a < b { (a, b) } else { (b, a) };
            uses.push((key, prim as u32, a < b));
        }
    }
    uses.sort_unstable();
    let edges = uses.chunk_by(|x, y| x.0 == y.0).map(|run| {
        let users: Vec<(u32, bool)> = run.iter().map(|u| (u.1, u.2)).collect();
        (run[0].0, users)
    });
    let cos_crease = crease_degrees.to_radians().cos();
    let normal = |prim: u32| {
        let c = scene.prims[prim as usize].camera;
        (c[1] - c[0]).cross(c[2] - c[0]).normalize()
    };
    let facing = |prim: u32| {
        let c = scene.prims[prim as usize].camera;
        let n = (c[1] - c[0]).cross(c[2] - c[0]);
        if scene.is_perspective() {
            n.dot(-c[0]) > 0.0
        } else {
            n.z > 0.0
        }
    };
    let mut out = Vec::new();
    for (key, users) in edges {
        let kind = match users.as_slice() {
            [(a, fa), (b, fb)] => {
                let material =
                    scene.prims[*a as usize].material != scene.prims[*b as usize].material;
                // Consistent winding runs a shared edge in opposite
                // directions; otherwise one normal is flipped.
                let cos = normal(*a).dot(normal(*b)) * if fa != fb { 1.0 } else { -1.0 };
                let facing_differs = (facing(*a) != facing(*b)) == (fa != fb);
                if facing_differs {
                    Some(LineKind::Silhouette)
                } else if material {
                    Some(LineKind::Material)
                } else if cos < cos_crease {
                    Some(LineKind::Crease)
                } else {
                    None
                }
            }
            _ => Some(LineKind::Boundary),
        };
        let Some(kind) = kind else { continue };
        let from_bits = |k: [u64; 3]| {
            DVec3::new(
                f64::from_bits(k[0]),
                f64::from_bits(k[1]),
                f64::from_bits(k[2]),
            )
        };
        let own = [users[0].0, users.get(1).map_or(users[0].0, |u| u.0)];
        if let Some((ends, camera)) = project_segment(scene, from_bits(key.0), from_bits(key.1)) {
            out.push(Feature {
                ends,
                camera,
                own,
                kind,
            });
        }
    }
    // A stable order, whatever the hash map's.
    out.sort_by(|a, b| {
        (a.ends[0].x, a.ends[0].y, a.ends[1].x, a.ends[1].y)
            .partial_cmp(&(b.ends[0].x, b.ends[0].y, b.ends[1].x, b.ends[1].y))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    out
}

/// A camera-space segment in window space `(x, y, depth)`, clipped to the
/// near and far planes in clip space, and its clipped camera-space ends;
/// `None` when nothing is left.
fn project_segment(scene: &ScreenScene, a: DVec3, b: DVec3) -> Option<([DVec3; 2], [DVec3; 2])> {
    let m = scene.projection_matrix;
    let (mut ca, mut cb) = (m * a.extend(1.0), m * b.extend(1.0));
    let (mut a, mut b) = (a, b);
    // GL clip space: near is w + z >= 0, far is w - z >= 0.
    for plane in [
        DVec4::new(0.0, 0.0, 1.0, 1.0),
        DVec4::new(0.0, 0.0, -1.0, 1.0),
    ] {
        let (da, db) = (plane.dot(ca), plane.dot(cb));
        if da < 0.0 && db < 0.0 {
            return None;
        }
        // Clip space is linear in camera space: the same parameter cuts
        // both.
        if da < 0.0 {
            let t = da / (da - db);
            (ca, a) = (ca.lerp(cb, t), a.lerp(b, t));
        } else if db < 0.0 {
            let t = da / (da - db);
            (cb, b) = (ca.lerp(cb, t), a.lerp(b, t));
        }
    }
    if ca.w <= 0.0 || cb.w <= 0.0 {
        return None;
    }
    // Snapped to 1/256 pixel like the front end's vertices, so an edge
    // ends exactly where its triangles' corners are and the faces meeting
    // there do not hide a sliver of it.
    let snap = |v: f64| (v * SCALE).round() / SCALE;
    let win = |c: DVec4| {
        let w = scene.viewport.ndc_to_window(c.truncate() / c.w);
        DVec3::new(snap(w.x), snap(w.y), w.z)
    };
    Some(([win(ca), win(cb)], [a, b]))
}

/// The camera-space point of window position `(x, y, depth)`.
pub(super) fn unproject(scene: &ScreenScene, w: DVec3) -> DVec3 {
    let vp = scene.viewport;
    let ndc = DVec4::new(
        2.0 * w.x / f64::from(vp.width) - 1.0,
        1.0 - 2.0 * w.y / f64::from(vp.height),
        2.0 * w.z - 1.0,
        1.0,
    );
    let c = scene.projection_matrix.inverse() * ndc;
    c.truncate() / c.w
}
