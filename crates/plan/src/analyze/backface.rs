//! Can back faces be seen? Closed, outward-facing meshes wholly inside the
//! depth range hide every back face behind a front face of their own.
//!
//! Back-face culling is the oldest visibility shortcut: a closed solid seen
//! from outside shows only faces turned toward the eye, so the ones turned
//! away can be dropped before rasterisation, about half of the triangles.
//! It is exact only under three conditions, checked here per mesh:
//! - *closed*: every edge (vertices welded by position, so the split
//!   vertices of OBJ files with uvs or normals count as one) is used
//!   exactly twice, once in each direction — which also makes the
//!   orientation consistent;
//! - *outward*: the signed volume is positive, so counter-clockwise (GL's
//!   front) faces look out of the solid;
//! - *not cut open*: every vertex lies strictly between the near and far
//!   planes, so clipping opens no window into the inside (and, for a
//!   perspective camera, the eye cannot be inside: it would lie in the
//!   convex hull of vertices that are all in front of it).

use glam::DVec3;
use hider_geom::Projection;

use hider_scene::{Scene, View};

/// Whether each mesh of the scene certainly hides its back faces from this
/// view (see the module documentation), indexed like `scene.meshes`.
pub fn hidden_back_faces(scene: &Scene, view: &View) -> Vec<bool> {
    // Eye-relative, as the front end transforms: subtracting the eye
    // before the rotation keeps the depths of a scene 1e17 from the origin
    // as accurate as at the origin.
    let mut eye_to_camera = view.camera.view_matrix();
    eye_to_camera.w_axis = glam::DVec4::W;
    let eye = view.camera.eye;
    let (near, far) = match view.camera.projection {
        Projection::Perspective { near, far, .. } | Projection::Orthographic { near, far, .. } => {
            (near, far)
        }
    };
    scene
        .meshes
        .iter()
        .map(|mesh| {
            let in_range = mesh.indices.iter().flatten().all(|&i| {
                let d = -eye_to_camera
                    .transform_point3(mesh.positions[i as usize] - eye)
                    .z;
                d > near && d < far
            });
            in_range && closed_outward(&mesh.positions, &mesh.indices)
        })
        .collect()
}

/// Whether the triangles form a closed, consistently and outwardly
/// oriented surface.
///
/// Edges are checked by sorting rather than hashing: every undirected
/// edge (between welded vertices) must occur exactly twice, once in each
/// direction. On a 2-million-triangle mesh this is one sort of 64-bit keys
/// instead of millions of hash-map updates.
pub fn closed_outward(positions: &[DVec3], indices: &[[u32; 3]]) -> bool {
    if indices.is_empty() {
        return false;
    }
    let (ids, welded) = weld(positions);
    if welded >= 1 << 31 {
        return false; // the keys below need ids below 2^31
    }
    let mut edges: Vec<u64> = Vec::with_capacity(indices.len() * 3);
    let (origin, scale) = volume_frame(positions, indices);
    let mut volume = 0.0;
    for t in indices {
        let w = t.map(|i| ids[i as usize]);
        if w[0] == w[1] || w[1] == w[2] || w[0] == w[2] {
            continue; // no area, no edges
        }
        let p = t.map(|i| (positions[i as usize] - origin) * scale);
        volume += p[0].dot(p[1].cross(p[2]));
        for k in 0..3 {
            let (a, b) = (w[k], w[(k + 1) % 3]);
            // The undirected edge in the high bits, its direction in the
            // lowest: sorted, the two uses of an edge are neighbours.
            edges.push(u64::from(a.min(b)) << 33 | u64::from(a.max(b)) << 1 | u64::from(a > b));
        }
    }
    // A NaN volume is not positive either.
    if edges.is_empty() || volume.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return false;
    }
    edges.sort_unstable();
    // Closed and consistently oriented: the keys come in pairs of one edge
    // in both directions (direction bit 0 then 1), and no edge is used a
    // third time (which would start a pair with the previous pair's edge).
    edges
        .chunks(2)
        .all(|pair| pair.len() == 2 && pair[0] ^ pair[1] == 1 && pair[0] & 1 == 0)
}

/// Where and at what scale to sum the signed volume: the corner of the
/// mesh's bounding box, and a power of two (exact) that brings its extent
/// near 1. The sign of a closed mesh's volume does not depend on the
/// origin, but its rounding does: summed about the world origin, a mesh
/// 1e17 away cancels terms of 1e51 down to its true volume, and one of
/// extent 1e200 overflows to infinity (or NaN).
fn volume_frame(positions: &[DVec3], indices: &[[u32; 3]]) -> (DVec3, f64) {
    let mut lo = DVec3::splat(f64::INFINITY);
    let mut hi = DVec3::splat(f64::NEG_INFINITY);
    for &i in indices.iter().flatten() {
        let p = positions[i as usize];
        lo = lo.min(p);
        hi = hi.max(p);
    }
    // Half of each bound first, so the extent of coordinates near the
    // largest f64 does not overflow.
    let extent = (hi * 0.5 - lo * 0.5).max_element();
    let scale = hider_geom::camera::rescaled(DVec3::new(extent, 0.0, 0.0)).x / extent;
    if scale.is_finite() && scale > 0.0 {
        (lo, scale)
    } else {
        (lo, 1.0)
    }
}

/// One id per distinct position (-0.0 and 0.0 alike), so that the split
/// vertices of OBJ files with uvs or normals count as one; and the number
/// of distinct positions.
fn weld(positions: &[DVec3]) -> (Vec<u32>, u32) {
    let key = |i: u32| {
        let p = positions[i as usize];
        [p.x, p.y, p.z].map(|v| (v + 0.0).to_bits())
    };
    let mut order: Vec<u32> = (0..positions.len() as u32).collect();
    order.sort_unstable_by_key(|&i| key(i));
    let mut ids = vec![0; positions.len()];
    let mut next = 0;
    for (k, &i) in order.iter().enumerate() {
        if k > 0 && key(order[k - 1]) != key(i) {
            next += 1;
        }
        ids[i as usize] = next;
    }
    (ids, next + 1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_scene::procedural;

    #[test]
    fn cube_is_closed_and_outward_a_flipped_or_open_one_is_not() {
        let cube = procedural::cube();
        let m = &cube.meshes[0];
        assert!(closed_outward(&m.positions, &m.indices));
        let flipped: Vec<[u32; 3]> = m.indices.iter().map(|t| [t[0], t[2], t[1]]).collect();
        assert!(!closed_outward(&m.positions, &flipped));
        assert!(!closed_outward(&m.positions, &m.indices[1..]));
        // Splitting vertices (as OBJ files with uvs do) keeps it closed.
        let mut positions = Vec::new();
        let mut indices = Vec::new();
        for t in &m.indices {
            let base = positions.len() as u32;
            positions.extend(t.map(|i| m.positions[i as usize]));
            indices.push([base, base + 1, base + 2]);
        }
        assert!(closed_outward(&positions, &indices));
        // A face given twice uses its edges twice in one direction.
        let mut twice = m.indices.clone();
        twice.push(m.indices[0]);
        assert!(!closed_outward(&m.positions, &twice));
        let sphere = procedural::uv_sphere(12);
        let s = &sphere.meshes[0];
        assert!(closed_outward(&s.positions, &s.indices));
    }

    #[test]
    fn huge_and_far_away_solids_are_still_closed_and_outward() {
        let sphere = procedural::uv_sphere(12);
        let s = &sphere.meshes[0];
        // 2^664 ~ 1e200: the volume about the world origin overflowed.
        let huge: Vec<DVec3> = s.positions.iter().map(|&p| p * 2f64.powi(664)).collect();
        assert!(closed_outward(&huge, &s.indices));
        // 2^40 away: summed about the world origin, the terms of 1e36
        // cancel and the rounding error outweighs the true volume.
        let offset = DVec3::splat(2f64.powi(40));
        let far: Vec<DVec3> = s.positions.iter().map(|&p| p + offset).collect();
        assert!(closed_outward(&far, &s.indices));
        let flipped: Vec<[u32; 3]> = s.indices.iter().map(|t| [t[0], t[2], t[1]]).collect();
        assert!(!closed_outward(&huge, &flipped));
        assert!(!closed_outward(&far, &flipped));
    }

    #[test]
    fn a_solid_far_from_the_origin_hides_its_back_faces_as_at_the_origin() {
        let offset = DVec3::new(2f64.powi(50), -(2f64.powi(50)), 2f64.powi(49));
        let mut scene = procedural::uv_sphere(12);
        let at_origin = View::for_scene(&scene, 64, 64).unwrap();
        assert_eq!(hidden_back_faces(&scene, &at_origin), vec![true]);
        for p in &mut scene.meshes[0].positions {
            *p += offset;
        }
        let mut moved = at_origin;
        moved.camera.eye += offset;
        moved.camera.target += offset;
        assert_eq!(hidden_back_faces(&scene, &moved), vec![true]);
    }
}
