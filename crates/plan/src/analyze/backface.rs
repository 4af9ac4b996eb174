//! Can back faces be seen? A closed shell of consistently outward-facing
//! triangles wholly inside the depth range hides every back face behind a
//! front face of its own.
//!
//! Back-face culling is the oldest visibility shortcut: a closed solid seen
//! from outside shows only faces turned toward the eye, so the ones turned
//! away can be dropped before rasterisation, about half of the triangles.
//! It is exact only under three conditions, checked here per *shell*, a
//! set of triangles connected through shared edges (one mesh, one material,
//! may hold several, as an OBJ object holding two boxes does):
//! - *closed*: every edge of the mesh (vertices welded by position, so the
//!   split vertices of OBJ files with uvs or normals count as one) is used
//!   exactly twice, once in each direction, which also makes each shell's
//!   orientation consistent;
//! - *outward*: the shell's signed volume is positive, so counter-clockwise
//!   (GL's front) faces look out of it. Summed over a whole mesh the sign
//!   says nothing about a small inside-out shell beside a big outward one,
//!   whose back faces are exactly the ones that show;
//! - *not cut open*: every vertex of the shell lies strictly between the
//!   near and far planes, so clipping opens no window into the inside
//!   (and, for a perspective camera, the eye cannot be inside: it would
//!   lie in the convex hull of vertices that are all in front of it).
//!
//! Why that is enough: the ray from the eye to a point of a back face
//! leaves the solid there, and the eye is outside, so the ray entered the
//! solid through a front face of the same shell nearer the eye.
//!
//! The edge check sorts every edge, the dearest step of the analysis on
//! large scenes, so a cheap pass comes first: an odd count of triangles
//! with area, or a non-zero sum of an antisymmetric hash over the directed
//! edges, proves a mesh open without welding or sorting (a soup of 10^6
//! triangles is turned down in one pass over its vertices).

use glam::DVec3;
use hider_geom::Projection;

use hider_scene::{Scene, View};

/// Which triangles' back faces are certainly hidden, and the shells found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct HiddenBackFaces {
    /// Per primitive id: whether the triangle belongs to a shell that
    /// hides its back faces from this view.
    pub hidden: Vec<bool>,
    /// Shells (edge-connected components) of the meshes that passed the
    /// closed-mesh test.
    pub closed_shells: u64,
    /// Of those, the shells that are outward and uncut.
    pub hiding_shells: u64,
    /// Meshes turned down by the cheap hash pass (certainly open), the
    /// edge sort skipped.
    pub open_by_hash: u64,
}

/// Whether each triangle of the scene certainly hides its back face from
/// this view (see the module documentation), indexed by primitive id.
pub fn hidden_back_faces(scene: &Scene, view: &View) -> HiddenBackFaces {
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
    let in_range = |p: DVec3| {
        let d = -eye_to_camera.transform_point3(p - eye).z;
        d > near && d < far
    };
    let mut out = HiddenBackFaces {
        hidden: Vec::with_capacity(scene.triangle_count()),
        ..HiddenBackFaces::default()
    };
    for mesh in &scene.meshes {
        let start = out.hidden.len();
        out.hidden.resize(start + mesh.indices.len(), false);
        if !maybe_closed(&mesh.positions, &mesh.indices) {
            out.open_by_hash += 1;
            continue;
        }
        let Some(shells) = shells(&mesh.positions, &mesh.indices) else {
            continue;
        };
        out.closed_shells += shells.count as u64;
        let mut uncut = vec![true; shells.count];
        for (t, &s) in mesh.indices.iter().zip(&shells.of) {
            if s != NO_SHELL && uncut[s as usize] {
                uncut[s as usize] = t.iter().all(|&i| in_range(mesh.positions[i as usize]));
            }
        }
        for (k, &s) in shells.of.iter().enumerate() {
            let s = s as usize;
            if s < shells.count && uncut[s] && shells.outward[s] {
                out.hidden[start + k] = true;
            }
        }
        out.hiding_shells += (0..shells.count)
            .filter(|&s| uncut[s] && shells.outward[s])
            .count() as u64;
    }
    out
}

/// Shell of a triangle without area (it has no edges).
const NO_SHELL: u32 = u32::MAX;

/// The shells of a closed mesh.
struct Shells {
    /// Number of shells.
    count: usize,
    /// Per triangle, its shell, or [`NO_SHELL`].
    of: Vec<u32>,
    /// Per shell, whether its signed volume is positive.
    outward: Vec<bool>,
}

/// A cheap necessary condition for a closed, consistently oriented mesh,
/// without welding or sorting: the triangles with area come in an even
/// number (three edge uses each, two per edge), and an antisymmetric hash
/// `F(a, b) - F(b, a)` of every directed edge sums to zero (each edge's two
/// opposite uses cancel). Positions are hashed by their bits (-0.0 as
/// 0.0), as the welding of vertices identifies them. False means certainly open or
/// inconsistently oriented; true means "sort and see".
pub fn maybe_closed(positions: &[DVec3], indices: &[[u32; 3]]) -> bool {
    if indices.is_empty() {
        return false;
    }
    // Any hash keeps the test sound (a closed mesh's sum cancels exactly
    // whatever the values), so a cheap one will do: two rotations and
    // one mix per position. Meshes that share vertices
    // hash each once; a soup, whose vertices are used once each anyway,
    // hashes per use and allocates nothing.
    let hash = |p: DVec3| {
        let [x, y, z] = [p.x, p.y, p.z].map(|v| (v + 0.0).to_bits());
        // Rotated apart so that the sign and exponent bits of the three
        // coordinates land on different bits (a multiply alone never moves
        // a bit down: +-1 coordinates then hashed alike).
        mix(x ^ y.rotate_left(21) ^ z.rotate_left(42))
    };
    let shared: Option<Vec<u64>> =
        (positions.len() < indices.len()).then(|| positions.iter().map(|&p| hash(p)).collect());
    let mut sum = 0u64;
    let mut with_area = 0u64;
    for t in indices {
        let p = t.map(|i| positions.get(i as usize).copied().unwrap_or(DVec3::NAN));
        if p[0] == p[1] || p[1] == p[2] || p[0] == p[2] {
            continue; // no area, no edges (as the edge check skips it)
        }
        with_area += 1;
        let h = match &shared {
            Some(h) => t.map(|i| h[i as usize]),
            None => p.map(hash),
        };
        for k in 0..3 {
            let (a, b) = (h[k], h[(k + 1) % 3]);
            sum = sum
                .wrapping_add(directed(a, b))
                .wrapping_sub(directed(b, a));
        }
    }
    with_area > 0 && with_area.is_multiple_of(2) && sum == 0
}

/// A hash of the directed edge `a -> b` (not symmetric in its arguments).
/// It must be far from linear: the unmatched edges of a hole form a cycle,
/// and the linear part of any sum around a cycle cancels (XOR and a
/// multiply alone left a cube with one face removed "closed").
fn directed(a: u64, b: u64) -> u64 {
    mix(a.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ b.rotate_left(29))
}

/// SplitMix64's finaliser: every input bit moves every output bit.
fn mix(mut x: u64) -> u64 {
    x ^= x >> 30;
    x = x.wrapping_mul(0xbf58_476d_1ce4_e5b9);
    x ^= x >> 27;
    x = x.wrapping_mul(0x94d0_49bb_1331_11eb);
    x ^ (x >> 31)
}

/// Whether the triangles form one closed, consistently and outwardly
/// oriented surface, or several (every shell outward).
pub fn closed_outward(positions: &[DVec3], indices: &[[u32; 3]]) -> bool {
    maybe_closed(positions, indices)
        && shells(positions, indices).is_some_and(|s| s.count > 0 && s.outward.iter().all(|&o| o))
}

/// The shells of a closed, consistently oriented mesh (every welded edge
/// used exactly twice, once in each direction), with each one's
/// orientation; `None` when the mesh is not closed.
///
/// Edges are checked by sorting rather than hashing: on a
/// 2-million-triangle mesh a counting sort of the edge uses by their lower
/// vertex costs less than millions of hash-map updates. The two uses of an
/// edge, neighbours once sorted, join their triangles' shells.
fn shells(positions: &[DVec3], indices: &[[u32; 3]]) -> Option<Shells> {
    // The mesh's own vertex indices first: when its edges pair up by
    // index, the surface is closed whatever welding would add (a shared
    // index is a shared position), and the sort of every position that
    // welding costs is saved. Split vertices (OBJ files with uvs or
    // normals) need the welded ids.
    if positions.len() < 1 << 31 {
        let own: Vec<u32> = (0..positions.len() as u32).collect();
        if let Some(shells) = shells_by(&own, positions, indices) {
            return Some(shells);
        }
    }
    let (ids, welded) = weld(positions);
    if welded >= 1 << 31 {
        return None; // the keys below need ids below 2^31
    }
    shells_by(&ids, positions, indices)
}

/// [`shells`] with the vertex ids `ids` (indexed like `positions`, below
/// 2^31).
fn shells_by(ids: &[u32], positions: &[DVec3], indices: &[[u32; 3]]) -> Option<Shells> {
    if indices.len() >= u32::MAX as usize {
        return None; // triangle numbers are u32 below
    }
    // Every edge use, bucketed by its lower vertex id (a counting sort:
    // two passes and a scatter, cheaper than sorting 6 * 10^6 keys), as
    // `(higher id << 1 | direction) << 32 | triangle`; sorted within
    // their small buckets, the two uses of an edge are neighbours.
    let area = |t: &[u32; 3]| {
        let w = t.map(|i| ids[i as usize]);
        (w[0] != w[1] && w[1] != w[2] && w[0] != w[2]).then_some(w)
    };
    let mut start = vec![0usize; ids.len() + 1];
    for w in indices.iter().filter_map(area) {
        for j in 0..3 {
            start[w[j].min(w[(j + 1) % 3]) as usize + 1] += 1;
        }
    }
    for v in 0..ids.len() {
        start[v + 1] += start[v];
    }
    if start[ids.len()] == 0 {
        return None;
    }
    let mut fill = start.clone();
    let mut uses = vec![0u64; start[ids.len()]];
    for (k, t) in indices.iter().enumerate() {
        let Some(w) = area(t) else {
            continue; // no area, no edges
        };
        for j in 0..3 {
            let (a, b) = (w[j], w[(j + 1) % 3]);
            let slot = &mut fill[a.min(b) as usize];
            uses[*slot] = (u64::from(a.max(b)) << 1 | u64::from(a > b)) << 32 | k as u64;
            *slot += 1;
        }
    }
    drop(fill);
    // Closed and consistently oriented: in every bucket the uses come in
    // pairs of one edge in both directions (direction bit 0 then 1), and
    // no edge is used a third time (which would start a pair with the
    // previous pair's edge).
    let mut parent: Vec<u32> = (0..indices.len() as u32).collect();
    for v in 0..ids.len() {
        let bucket = &mut uses[start[v]..start[v + 1]];
        bucket.sort_unstable();
        for pair in bucket.chunks(2) {
            let (e0, e1) = (pair[0] >> 32, pair.get(1).map_or(u64::MAX, |e| e >> 32));
            if e0 ^ e1 != 1 || e0 & 1 != 0 {
                return None;
            }
            union(&mut parent, pair[0] as u32, pair[1] as u32);
        }
    }
    drop(uses);
    // Dense shell numbers, then each shell's signed volume in its own
    // frame (see `volume_frame`).
    let mut of = vec![NO_SHELL; indices.len()];
    let mut number = vec![NO_SHELL; indices.len()];
    let mut count = 0usize;
    for (k, t) in indices.iter().enumerate() {
        let w = t.map(|i| ids[i as usize]);
        if w[0] == w[1] || w[1] == w[2] || w[0] == w[2] {
            continue;
        }
        let root = find(&mut parent, k as u32) as usize;
        if number[root] == NO_SHELL {
            number[root] = count as u32;
            count += 1;
        }
        of[k] = number[root];
    }
    let mut lo = vec![DVec3::splat(f64::INFINITY); count];
    let mut hi = vec![DVec3::splat(f64::NEG_INFINITY); count];
    for (t, &s) in indices.iter().zip(&of) {
        if s == NO_SHELL {
            continue;
        }
        for &i in t {
            let p = positions[i as usize];
            lo[s as usize] = lo[s as usize].min(p);
            hi[s as usize] = hi[s as usize].max(p);
        }
    }
    let frames: Vec<(DVec3, f64)> = lo
        .iter()
        .zip(&hi)
        .map(|(&l, &h)| volume_frame(l, h))
        .collect();
    let mut volume = vec![0.0f64; count];
    for (t, &s) in indices.iter().zip(&of) {
        if s == NO_SHELL {
            continue;
        }
        let (origin, scale) = frames[s as usize];
        let p = t.map(|i| (positions[i as usize] - origin) * scale);
        volume[s as usize] += p[0].dot(p[1].cross(p[2]));
    }
    // A NaN volume is not positive either.
    let outward = volume
        .iter()
        .map(|v| v.partial_cmp(&0.0) == Some(std::cmp::Ordering::Greater))
        .collect();
    Some(Shells { count, of, outward })
}

/// The root of `x`'s set (path halving).
fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let up = parent[parent[x as usize] as usize];
        parent[x as usize] = up;
        x = up;
    }
    x
}

/// Joins the sets of `a` and `b`.
fn union(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        parent[ra.max(rb) as usize] = ra.min(rb);
    }
}

/// Where and at what scale to sum a shell's signed volume, from its
/// bounding box `lo..hi`: the box's corner, and a power of two (exact)
/// that brings its extent near 1. The sign of a closed surface's volume
/// does not depend on the origin, but its rounding does: summed about the
/// world origin, a shell 1e17 away cancels terms of 1e51 down to its true
/// volume, and one of extent 1e200 overflows to infinity (or NaN).
fn volume_frame(lo: DVec3, hi: DVec3) -> (DVec3, f64) {
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
        let all = vec![true; scene.triangle_count()];
        assert_eq!(hidden_back_faces(&scene, &at_origin).hidden, all);
        for p in &mut scene.meshes[0].positions {
            *p += offset;
        }
        let mut moved = at_origin;
        moved.camera.eye += offset;
        moved.camera.target += offset;
        assert_eq!(hidden_back_faces(&scene, &moved).hidden, all);
    }

    #[test]
    fn the_hash_pass_turns_down_open_meshes_and_soups() {
        let cube = procedural::cube();
        let m = &cube.meshes[0];
        assert!(maybe_closed(&m.positions, &m.indices));
        assert!(!maybe_closed(&m.positions, &m.indices[1..]), "odd count");
        assert!(!maybe_closed(&m.positions, &m.indices[2..]), "a hole");
        let soup = procedural::random_soup(1000, 7);
        let s = &soup.meshes[0];
        assert!(!maybe_closed(&s.positions, &s.indices));
        // One face turned over: the same edges, one pair now one-way.
        let mut turned = m.indices.clone();
        turned[0] = [turned[0][0], turned[0][2], turned[0][1]];
        turned[1] = [turned[1][0], turned[1][2], turned[1][1]];
        assert!(!maybe_closed(&m.positions, &turned));
    }
}
