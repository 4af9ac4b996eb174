//! How many splits the painter's ordered polygons need at least, from the
//! interpenetrating pairs: the prediction that lets the planner refuse the
//! painter up front instead of letting it run for minutes into its split
//! budget.
//!
//! Two interpenetrating triangles `A` and `B` cross along a segment of the
//! line `L = plane(A) ∩ plane(B)`. No depth order exists between them
//! until some piece of `A` or of `B` has been cut along `L`, and one split
//! cuts one piece along one line. So a split serves only pairs that share
//! both a triangle and a cutting line: the cut of `A` along its line with
//! `plane(B)` serves `(A, X)` only when `X` lies in the plane of `B` too (a
//! floor of many coplanar triangles crossing a wall needs one cut of the
//! wall). Give each pair its two possible cuts, `(A, plane(B))` and
//! `(B, plane(A))`: the splits needed are at least a vertex cover of those
//! cuts, and so at least any matching of them, which a greedy pass finds.
//!
//! The bound is conservative, far below what the painter spends: each cut
//! piece must be cut again by every other line through it, so random
//! crossing triangles cost it several splits per pair. The planner refuses
//! only when even this bound is over budget. Planes are compared after
//! rounding to `f32` (normal scaled to a unit largest component, and the
//! offset), so triangles meant to be coplanar share their cut; distinct
//! planes through one common line are counted apart (a degenerate pencil
//! of planes, where the bound may overcount).

use std::collections::HashSet;
use std::hash::BuildHasherDefault;

use glam::DVec3;
use hider_geom::star::Mix;

/// A plane, rounded: the axis of the normal's largest component and the
/// other two components and the offset, scaled so that component is 1, as
/// `f32` bits.
type PlaneKey = (u8, u32, u32, u32);

/// The rounded plane of a triangle (`None` without area).
fn plane_key(t: &[DVec3; 3]) -> Option<PlaneKey> {
    let n = (t[1] - t[0]).cross(t[2] - t[0]);
    let a = n.abs();
    let axis = if a.x >= a.y && a.x >= a.z {
        0
    } else if a.y >= a.z {
        1
    } else {
        2
    };
    let big = n[axis];
    if big == 0.0 || !big.is_finite() {
        return None;
    }
    let unit = n / big;
    let d = unit.dot(t[0]);
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    // +0.0 for -0.0, so equal planes give equal bits.
    let bits = |x: f64| ((x as f32) + 0.0).to_bits();
    Some((axis as u8, bits(unit[u]), bits(unit[v]), bits(d)))
}

/// A lower bound on the painter's splits for the interpenetrating `pairs`
/// (primitive ids) among `tris` (primitive id and world corners), see the
/// module documentation.
pub fn painter_splits_at_least(tris: &[(u32, [DVec3; 3])], pairs: &[(u32, u32)]) -> u64 {
    if pairs.is_empty() {
        return 0;
    }
    let max_id = tris.iter().map(|t| t.0).max().unwrap_or(0) as usize;
    let mut planes: Vec<Option<PlaneKey>> = vec![None; max_id + 1];
    for (id, t) in tris {
        planes[*id as usize] = plane_key(t);
    }
    let plane = |id: u32| planes.get(id as usize).copied().flatten();
    // Two cuts a matched pair. A cheap hash: SipHash here was a fifth of
    // `hider analyze` on 2,000 random triangles in a cube.
    let mut used: HashSet<(u32, PlaneKey), BuildHasherDefault<Mix>> =
        HashSet::with_capacity_and_hasher(2 * pairs.len(), BuildHasherDefault::default());
    let mut matched = 0u64;
    for &(a, b) in pairs {
        let (Some(pa), Some(pb)) = (plane(a), plane(b)) else {
            continue;
        };
        let (cut_a, cut_b) = ((a, pb), (b, pa));
        if !used.contains(&cut_a) && !used.contains(&cut_b) {
            used.insert(cut_a);
            used.insert(cut_b);
            matched += 1;
        }
    }
    matched
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(p: [[f64; 3]; 3]) -> [DVec3; 3] {
        p.map(DVec3::from_array)
    }

    #[test]
    fn pairs_in_general_position_need_a_split_each() {
        // Three triangles standing across one floor triangle, each in its
        // own plane: three pairs, three lines, three splits at least.
        let floor = (0, t([[-5.0, -5.0, 0.0], [5.0, -5.0, 0.0], [0.0, 5.0, 0.0]]));
        let mut tris = vec![floor];
        let mut pairs = Vec::new();
        for k in 1..4u32 {
            let x = f64::from(k) - 2.0;
            tris.push((k, t([[x, -1.0, -1.0], [x + 0.3, 1.0, -1.0], [x, 0.0, 1.0]])));
            pairs.push((0, k));
        }
        assert_eq!(painter_splits_at_least(&tris, &pairs), 3);
        assert_eq!(painter_splits_at_least(&tris, &[]), 0);
    }

    #[test]
    fn a_coplanar_floor_crossing_one_wall_needs_one_split() {
        // A wall in x = 0 crossed by four floor triangles in z = 0: one cut
        // of the wall along its line with the floor serves all four.
        let wall = (0, t([[0.0, -4.0, -1.0], [0.0, 4.0, -1.0], [0.0, 0.0, 1.0]]));
        let mut tris = vec![wall];
        let mut pairs = Vec::new();
        for k in 1..5u32 {
            let y = f64::from(k) * 1.5 - 4.0;
            tris.push((k, t([[-1.0, y, 0.0], [1.0, y, 0.0], [0.0, y + 1.0, 0.0]])));
            pairs.push((0, k));
        }
        assert_eq!(painter_splits_at_least(&tris, &pairs), 1);
    }
}
