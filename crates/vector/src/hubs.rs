//! Hubs: screen vertices shared by many triangles whose corners there do
//! not overlap (the centre of a fan, a disc's or a cylinder cap's
//! triangulation, a sphere's pole seen end on), so that the pair phase can
//! skip every pair of them without looking at it.
//!
//! A triangle lies inside the wedge its corner spans at any of its
//! vertices, so two triangles sharing a vertex whose wedges there have no
//! interior point in common have no interior point in common either. Bins
//! cannot tell such pairs apart: all `N` triangles of a fan meet the bin
//! of its centre at any bin size, and looking at every pair costs `N^2`.
//! When all the corners at a vertex are pairwise disjoint (checked exactly
//! by sorting them by angle), every pair of its triangles is disjoint.

use std::cmp::Ordering;
use std::collections::HashMap;

use hider_geom::fixed::FixedPt;

/// No hub.
pub const NONE: u32 = u32::MAX;

/// Triangles a vertex must have to be a hub: below it the pairs are few.
const LEAST: usize = 16;

/// The hubs of the triangles (screen vertices, positively oriented) that
/// `on` marks: per triangle, the hub ids of
/// its vertices that are hubs ([`NONE`] elsewhere), the one with the most
/// triangles first.
pub fn hubs(tris: &[[FixedPt; 3]], on: &[bool]) -> Vec<[u32; 3]> {
    let mut at: HashMap<(i32, i32), Vec<(u32, u8)>> = HashMap::new();
    for (k, t) in tris.iter().enumerate().filter(|(k, _)| on[*k]) {
        for (i, v) in t.iter().enumerate() {
            at.entry((v.x, v.y)).or_default().push((k as u32, i as u8));
        }
    }
    let mut out = vec![[NONE; 3]; tris.len()];
    let mut sizes: Vec<usize> = Vec::new();
    for corners in at.into_values() {
        if corners.len() < LEAST || !disjoint(tris, &corners) {
            continue;
        }
        let id = sizes.len() as u32;
        sizes.push(corners.len());
        for (k, _) in corners {
            let slot = out[k as usize]
                .iter_mut()
                .find(|h| **h == NONE)
                .expect("three vertices");
            *slot = id;
        }
    }
    for ids in &mut out {
        ids.sort_by_key(|&h| std::cmp::Reverse(sizes.get(h as usize).copied().unwrap_or(0)));
    }
    out
}

/// Whether the corners `(triangle, vertex)` at one point are pairwise
/// disjoint: sorted by the angle of their first side, each one's second
/// side comes no later than the next one's first (counterclockwise).
fn disjoint(tris: &[[FixedPt; 3]], corners: &[(u32, u8)]) -> bool {
    let sides = |&(k, i): &(u32, u8)| {
        let t = &tris[k as usize];
        let i = usize::from(i);
        let v = t[i];
        let d = |p: FixedPt| {
            (
                i64::from(p.x) - i64::from(v.x),
                i64::from(p.y) - i64::from(v.y),
            )
        };
        (d(t[(i + 1) % 3]), d(t[(i + 2) % 3]))
    };
    let mut wedges: Vec<((i64, i64), (i64, i64))> = corners.iter().map(sides).collect();
    // A corner without area (a zero-area triangle) makes no claim either
    // way: keep the rule simple and leave the vertex alone.
    if wedges.iter().any(|&(a, b)| cross(a, b) <= 0) {
        return false;
    }
    wedges.sort_by(|x, y| ccw_order((1, 0), x.0, y.0));
    let n = wedges.len();
    (0..n).all(|i| {
        let (start, end) = wedges[i];
        let next = wedges[(i + 1) % n].0;
        // The next corner starts at angle 0 from this one when both start
        // along one ray: they overlap.
        ccw_order(start, end, next) != Ordering::Greater && same_ray(start, next) == (n == 1)
    })
}

fn cross(a: (i64, i64), b: (i64, i64)) -> i128 {
    i128::from(a.0) * i128::from(b.1) - i128::from(a.1) * i128::from(b.0)
}

fn same_ray(a: (i64, i64), b: (i64, i64)) -> bool {
    cross(a, b) == 0 && i128::from(a.0) * i128::from(b.0) + i128::from(a.1) * i128::from(b.1) > 0
}

/// The order of the counterclockwise angles from `s` to `a` and to `b`,
/// each in `[0, 360)` degrees, exact.
fn ccw_order(s: (i64, i64), a: (i64, i64), b: (i64, i64)) -> Ordering {
    // Half 0: angles in [0, 180); half 1: [180, 360).
    let half = |x: (i64, i64)| {
        let c = cross(s, x);
        u8::from(!(c > 0 || same_ray(s, x)))
    };
    half(a).cmp(&half(b)).then_with(|| 0.cmp(&cross(a, b)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri(p: [(i32, i32); 3]) -> [FixedPt; 3] {
        p.map(|(x, y)| FixedPt { x, y })
    }

    /// `n` triangles around the origin, corner `k` spanning the angles
    /// `[k, k + 1 + overlap]` of `n` steps.
    fn fan(n: u32, overlap: u32) -> Vec<[FixedPt; 3]> {
        let at = |k: u32| {
            let a = std::f64::consts::TAU * f64::from(k % n) / f64::from(n);
            ((1e5 * a.cos()) as i32, (1e5 * a.sin()) as i32)
        };
        (0..n)
            .map(|k| tri([(0, 0), at(k), at(k + 1 + overlap)]))
            .collect()
    }

    #[test]
    fn a_fan_is_a_hub_and_an_overlapping_one_is_not() {
        let plain = fan(40, 0);
        let h = hubs(&plain, &[true; 40]);
        assert!(h.iter().all(|ids| ids[0] == 0 && ids[1] == NONE), "{h:?}");
        let doubled = fan(40, 1);
        let h = hubs(&doubled, &[true; 40]);
        assert!(h.iter().all(|ids| ids[0] == NONE), "{h:?}");
        // One triangle twice: two corners on one ray.
        let mut twice = fan(40, 0);
        twice.push(twice[3]);
        let h = hubs(&twice, &[true; 41]);
        assert!(h.iter().all(|ids| ids[0] == NONE), "{h:?}");
        // A half fan is a hub too.
        let half: Vec<_> = fan(80, 0).into_iter().take(40).collect();
        let h = hubs(&half, &[true; 40]);
        assert!(h.iter().all(|ids| ids[0] == 0), "{h:?}");
    }
}
