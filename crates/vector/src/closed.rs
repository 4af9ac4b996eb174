//! Back faces of closed solids seen from outside, found before any pair
//! test: they are never visible.
//!
//! Along a ray from an eye outside a closed, consistently oriented
//! surface, the crossings alternate between entering and leaving it, and
//! the first one enters. A back face of an outward-oriented solid is a
//! leaving crossing, so a front face of the same solid is strictly nearer
//! at every one of its points (depth ties only along shared edges). Its
//! visible region is empty, and computing that by a boolean against the
//! front faces is most of the work on models made of closed parts.
//!
//! The argument needs every triangle of the solid on screen as it is in
//! the model, so it is used only when the front end clipped and culled
//! nothing (it may drop triangles whose snapped area is zero).

use glam::DVec3;
use hider_scene::ScreenScene;
use rustc_hash::FxHashMap;

/// A camera-space corner, exactly.
type Key = [u64; 3];

fn key(p: DVec3) -> Key {
    [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]
}

/// Per screen triangle: whether it is a back face of a closed,
/// outward-oriented solid with the eye outside.
pub fn hidden_back_faces(scene: &ScreenScene) -> Vec<bool> {
    let mut hidden = vec![false; scene.tris.len()];
    let s = scene.stats;
    // Triangles whose snapped area is zero may be dropped: their three
    // collinear edges add nothing to any winding number, so the snapped
    // solid still covers every point as often from the front as from the
    // back.
    let untouched = s.clipped == 0 && s.culled == 0 && s.back_faces == 0;
    let mut per_prim = vec![0u32; scene.prims.len()];
    for t in &scene.tris {
        per_prim[t.prim as usize] += 1;
    }
    if !untouched || per_prim.iter().any(|&n| n > 1) {
        return hidden;
    }
    let solid = closed_outward_components(scene);
    for (k, t) in scene.tris.iter().enumerate() {
        // In camera space the eye is the origin and a face of an outward
        // solid turns away from it when det(a, b, c) > 0; the front end's
        // own facing on screen must agree, and nearly edge-on faces are
        // left to the general method.
        let [a, b, c] = scene.prims[t.prim as usize].camera;
        let away = a.dot(b.cross(c)) > 1e-9 * a.length() * b.length() * c.length();
        hidden[k] = away && !t.front_facing && solid[t.prim as usize];
    }
    hidden
}

/// Per primitive: whether its edge-connected component is closed (every
/// directed edge matched by exactly one opposite edge), encloses a
/// clearly positive volume, and leaves the eye outside.
fn closed_outward_components(scene: &ScreenScene) -> Vec<bool> {
    let n = scene.prims.len();
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(parent: &mut [usize], mut k: usize) -> usize {
        while parent[k] != k {
            parent[k] = parent[parent[k]];
            k = parent[k];
        }
        k
    }
    // Per undirected edge: how often it runs each way, and a primitive
    // on each side.
    let mut edges: FxHashMap<(Key, Key), [(u32, usize); 2]> = FxHashMap::default();
    edges.reserve(3 * n);
    for (p, prim) in scene.prims.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (key(prim.camera[k]), key(prim.camera[(k + 1) % 3]));
            let (e, side) = if a <= b { ((a, b), 0) } else { ((b, a), 1) };
            let entry = edges.entry(e).or_insert([(0, p); 2]);
            entry[side] = (entry[side].0 + 1, p);
        }
    }
    let mut open = vec![false; n];
    for [(forward, p), (backward, q)] in edges.into_values() {
        if forward == 1 && backward == 1 {
            let (rp, rq) = (find(&mut parent, p), find(&mut parent, q));
            parent[rp] = rq;
        } else {
            open[p] = true;
            open[q] = true;
        }
    }
    // Per component: open at all; then, for closed ones only, signed
    // volume (times 6), winding number around the eye (solid angles, Van
    // Oosterom and Strackee) and extent.
    let roots: Vec<usize> = (0..n).map(|p| find(&mut parent, p)).collect();
    let mut any_open = vec![false; n];
    for p in 0..n {
        any_open[roots[p]] |= open[p];
    }
    let mut sums = vec![(0.0, 0.0, 0.0); n];
    for (p, prim) in scene.prims.iter().enumerate() {
        if any_open[roots[p]] {
            continue;
        }
        let [a, b, c] = prim.camera;
        let det = a.dot(b.cross(c));
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let den = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
        let extent = [a, b, c]
            .iter()
            .map(|v| v.abs().max_element())
            .fold(0.0, f64::max);
        let sum = &mut sums[roots[p]];
        sum.0 += det;
        sum.1 += 2.0 * det.atan2(den);
        sum.2 = f64::max(sum.2, extent);
    }
    (0..n)
        .map(|p| {
            let root = roots[p];
            let (volume6, angles, extent) = sums[root];
            let winding = angles / (4.0 * std::f64::consts::PI);
            // The eye in camera space is the origin: the winding number is
            // 0 outside a closed surface and +-1 inside; a volume far from
            // zero against the extent tells outward from inward.
            !any_open[root] && winding.abs() < 0.25 && volume6 > 1e-9 * extent.powi(3)
        })
        .collect()
}
