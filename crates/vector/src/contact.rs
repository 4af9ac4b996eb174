//! Shapes split into the sets that share points, exactly.
//!
//! `parts.rs` splits a map-wide boolean by chained boxes, which is cheap
//! but coarse: slivers laid along a diagonal have square boxes, every one
//! meeting its neighbours', so `N` separate slivers chained into one part
//! and one boolean whose splitter (an axis-aligned tree, then a grid of
//! fragments) costs more than linearly in long diagonal segments. Here a
//! box part is refined by actual contact: two shapes are in one set when
//! an edge of one meets (closed) an edge of the other, or when either's
//! rightmost vertex lies inside the other (non-zero winding). The
//! candidates are the shapes sharing a bin ([`Bins`], turned and stretched
//! like the shapes), so a sliver meets only its few neighbours.
//!
//! Why the rightmost vertex is enough: let `A` and `B` share a point while
//! their boundaries do not meet, and let `A` have the lesser greatest `x`
//! (with equal ones neither can lie inside the other, so they would
//! touch). Each contour of `A` lies wholly inside or outside `B`. If `A`'s
//! outer contour were outside `B`, then `B`, sharing a point with `A` and
//! not crossing its boundary, would lie within `A`'s outer contour, and
//! its greatest `x` would be less than `A`'s. So `A`'s outer contour, and
//! its rightmost vertex with it, lies inside `B`.

use std::collections::HashMap;

use i_overlay::i_float::int::point::IntPoint;

use crate::grid::{Bins, Grid, bounds};
use crate::sweep::orient;

/// Candidate pairs and edge pairs tested, per shape and segment, before
/// a refinement gives up (the caller keeps the coarse part): the bins of
/// a fan's centre hold every spoke, and those spokes touch anyway.
const WORK_PER_ITEM: usize = 64;

/// Segments of a shape above which it joins every shape it shares a bin
/// and a box with, untested (coarser sets are still right): testing it
/// is a pass over its edges per candidate, and the covered set around a
/// pile's regions is one such shape touching most of them.
const BIG_SHAPE: usize = 256;

/// Bin entries per shape before a refinement gives up: a fan's spokes
/// cross about `sqrt(N)` bins each (40 each at 16,000 spokes), slivers
/// along the bins' rows one or two.
const BINS_PER_SHAPE: usize = 8;

/// The shapes `shapes` (each an outer contour and its holes) in sets that
/// share no point with each other: every two shapes sharing a point are in
/// one set (sets may be coarser). Sets ordered by their first shape,
/// shapes ascending. `None` when the bins or the tests would cost more
/// than [`BINS_PER_SHAPE`] and [`WORK_PER_ITEM`] allow, or as soon as one
/// set holds more than `max_set` segments.
pub fn contact_sets(
    grid: &Grid,
    shapes: &[&[Vec<IntPoint>]],
    max_set: usize,
) -> Option<Vec<Vec<usize>>> {
    let segments: usize = shapes.iter().flat_map(|s| s.iter()).map(Vec::len).sum();
    let budget = WORK_PER_ITEM * (shapes.len() + segments);
    let items: Vec<Vec<&[IntPoint]>> = shapes
        .iter()
        .map(|s| s.iter().map(Vec::as_slice).collect())
        .collect();
    let boxes: Vec<_> = shapes.iter().map(|s| bounds(s.iter().flatten())).collect();
    let sizes: Vec<usize> = shapes
        .iter()
        .map(|s| s.iter().map(Vec::len).sum())
        .collect();
    let rightmost: Vec<Option<IntPoint>> = shapes
        .iter()
        .map(|s| s.iter().flatten().max_by_key(|p| (p.x, p.y)).copied())
        .collect();
    let mut parent: Vec<usize> = (0..shapes.len()).collect();
    // Segments per set (at its root).
    let mut held = sizes.clone();
    fn root(parent: &mut [usize], mut k: usize) -> usize {
        while parent[k] != k {
            parent[k] = parent[parent[k]];
            k = parent[k];
        }
        k
    }
    // Shapes sharing a vertex touch: found by hashing before any bin is
    // built, so that a mesh's regions (all touching) give up at once.
    let mut first_at: HashMap<IntPoint, usize> = HashMap::with_capacity(segments);
    for (a, shape) in shapes.iter().enumerate() {
        for &p in shape.iter().flatten() {
            let b = *first_at.entry(p).or_insert(a);
            let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
            if ra != rb {
                let (keep, gone) = (ra.min(rb), ra.max(rb));
                parent[gone] = keep;
                held[keep] += held[gone];
                if held[keep] > max_set {
                    return None;
                }
            }
        }
    }
    let bins = Bins::covering_within(grid, &items, BINS_PER_SHAPE * shapes.len())?;
    let mut work = 0usize;
    let mut seen = vec![usize::MAX; shapes.len()];
    for (a, contours) in items.iter().enumerate() {
        let Some(abox) = boxes[a] else { continue };
        let mut candidates = Vec::new();
        bins.query_near(contours, NEAR as i64, |b| {
            let b = b as usize;
            if b > a && seen[b] != a {
                seen[b] = a;
                candidates.push(b);
            }
        });
        work += candidates.len();
        // Small shapes first: once those join `a`'s set, a big one (the
        // covered set around many regions) is often in it already and
        // needs no pass over its edges.
        candidates.sort_unstable_by_key(|&b| (sizes[b], b));
        for b in candidates {
            if work > budget {
                return None;
            }
            let Some(bbox) = boxes[b] else { continue };
            if !boxes_meet(abox, bbox) || root(&mut parent, a) == root(&mut parent, b) {
                continue;
            }
            let big = sizes[a].max(sizes[b]) > BIG_SHAPE;
            if big
                || touch(
                    (shapes[a], shapes[b]),
                    (abox, bbox),
                    (rightmost[a], rightmost[b]),
                    &mut work,
                )
            {
                let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
                let (keep, gone) = (ra.min(rb), ra.max(rb));
                parent[gone] = keep;
                held[keep] += held[gone];
                if held[keep] > max_set {
                    return None;
                }
            }
        }
    }
    let mut index_of_root = vec![usize::MAX; shapes.len()];
    let mut out: Vec<Vec<usize>> = Vec::new();
    for k in 0..shapes.len() {
        let r = root(&mut parent, k);
        if index_of_root[r] == usize::MAX {
            index_of_root[r] = out.len();
            out.push(Vec::new());
        }
        out[index_of_root[r]].push(k);
    }
    Some(out)
}

/// A box: lowest and highest corner, closed.
type Box2 = (IntPoint, IntPoint);

/// Whether two closed boxes come within [`NEAR`] of each other.
fn boxes_meet(a: Box2, b: Box2) -> bool {
    let n = NEAR as i64;
    let (a0x, a0y, a1x, a1y) = (
        i64::from(a.0.x),
        i64::from(a.0.y),
        i64::from(a.1.x),
        i64::from(a.1.y),
    );
    let (b0x, b0y, b1x, b1y) = (
        i64::from(b.0.x),
        i64::from(b.0.y),
        i64::from(b.1.x),
        i64::from(b.1.y),
    );
    a0x <= b1x + n && b0x <= a1x + n && a0y <= b1y + n && b0y <= a1y + n
}

/// Whether the closed shapes `a` and `b` share a point (see the module
/// documentation), adding the edge pairs tested to `work`.
fn touch(
    (a, b): (&[Vec<IntPoint>], &[Vec<IntPoint>]),
    boxes: (Box2, Box2),
    rightmost: (Option<IntPoint>, Option<IntPoint>),
    work: &mut usize,
) -> bool {
    let edges_within = |s: &[Vec<IntPoint>], within: Box2| -> Vec<(IntPoint, IntPoint)> {
        s.iter()
            .flat_map(|c| (0..c.len()).map(move |k| (c[k], c[(k + 1) % c.len()])))
            .filter(|&(p, q)| {
                boxes_meet(
                    (
                        IntPoint::new(p.x.min(q.x), p.y.min(q.y)),
                        IntPoint::new(p.x.max(q.x), p.y.max(q.y)),
                    ),
                    within,
                )
            })
            .collect()
    };
    let (ea, eb) = (edges_within(a, boxes.1), edges_within(b, boxes.0));
    *work += ea.len() * eb.len();
    if ea
        .iter()
        .any(|&(p, q)| eb.iter().any(|&(r, s)| segments_near(p, q, r, s)))
    {
        return true;
    }
    rightmost.0.is_some_and(|p| winding(b, p) != 0)
        || rightmost.1.is_some_and(|p| winding(a, p) != 0)
}

/// Whether the closed shapes `a` and `b` (each an outer contour and its
/// holes) share a point, exactly (see the module documentation).
pub fn shapes_touch(a: &[Vec<IntPoint>], b: &[Vec<IntPoint>]) -> bool {
    let (Some(abox), Some(bbox)) = (bounds(a.iter().flatten()), bounds(b.iter().flatten())) else {
        return false;
    };
    let rightmost = |s: &[Vec<IntPoint>]| s.iter().flatten().max_by_key(|p| (p.x, p.y)).copied();
    boxes_meet(abox, bbox) && touch((a, b), (abox, bbox), (rightmost(a), rightmost(b)), &mut 0)
}

/// Grid units within which two segments count as touching: where the
/// inputs cross off the grid (the outline's merges), `i_overlay` rounds
/// the crossings, moving a segment by up to `sqrt(2) / 2` units, so two
/// shapes closer than that could come to touch in one boolean and not in
/// two.
const NEAR: i128 = 2;

/// Whether the closed segments `p q` and `r s` come within [`NEAR`]
/// (exact): they meet, or an end of one is that near the other.
fn segments_near(p: IntPoint, q: IntPoint, r: IntPoint, s: IntPoint) -> bool {
    segments_meet(p, q, r, s)
        || point_near(p, r, s)
        || point_near(q, r, s)
        || point_near(r, p, q)
        || point_near(s, p, q)
}

/// Whether `p` lies within [`NEAR`] of the closed segment `a b` (exact).
fn point_near(p: IntPoint, a: IntPoint, b: IntPoint) -> bool {
    let d = |u: IntPoint, v: IntPoint| {
        (
            i128::from(v.x) - i128::from(u.x),
            i128::from(v.y) - i128::from(u.y),
        )
    };
    let ((abx, aby), (apx, apy), (bpx, bpy)) = (d(a, b), d(a, p), d(b, p));
    let (t, len2) = (apx * abx + apy * aby, abx * abx + aby * aby);
    let near2 = NEAR * NEAR;
    if t <= 0 || len2 == 0 {
        apx * apx + apy * apy <= near2
    } else if t >= len2 {
        bpx * bpx + bpy * bpy <= near2
    } else {
        let cross = abx * apy - aby * apx;
        cross * cross <= near2 * len2
    }
}

/// Whether the closed segments `p q` and `r s` share a point (exact).
fn segments_meet(p: IntPoint, q: IntPoint, r: IntPoint, s: IntPoint) -> bool {
    let (d1, d2) = (orient(p, q, r), orient(p, q, s));
    let (d3, d4) = (orient(r, s, p), orient(r, s, q));
    if d1 * d2 < 0 && d3 * d4 < 0 {
        return true;
    }
    let on = |a: IntPoint, b: IntPoint, c: IntPoint| {
        a.x.min(b.x) <= c.x && c.x <= a.x.max(b.x) && a.y.min(b.y) <= c.y && c.y <= a.y.max(b.y)
    };
    (d1 == 0 && on(p, q, r))
        || (d2 == 0 && on(p, q, s))
        || (d3 == 0 && on(r, s, p))
        || (d4 == 0 && on(r, s, q))
}

/// The winding number of the contours `shape` around `p` (not on them).
fn winding(shape: &[Vec<IntPoint>], p: IntPoint) -> i64 {
    let mut w = 0;
    for c in shape {
        for k in 0..c.len() {
            let (a, b) = (c[k], c[(k + 1) % c.len()]);
            if a.y <= p.y {
                if b.y > p.y && orient(a, b, p) > 0 {
                    w += 1;
                }
            } else if b.y <= p.y && orient(a, b, p) < 0 {
                w -= 1;
            }
        }
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: i32, y: i32, s: i32) -> Vec<Vec<IntPoint>> {
        vec![vec![
            IntPoint::new(x, y),
            IntPoint::new(x + s, y),
            IntPoint::new(x + s, y + s),
            IntPoint::new(x, y + s),
        ]]
    }

    #[test]
    fn touching_nested_and_apart_shapes() {
        let grid = Grid {
            shift: 0,
            width: 100,
            height: 100,
        };
        // A ring (square with a square hole) and shapes around it.
        let mut ring = square(10, 10, 40);
        let mut hole = square(20, 20, 20).remove(0);
        hole.reverse();
        ring.push(hole);
        let shapes = [
            ring,
            // In the hole, apart from the ring.
            square(25, 25, 5),
            // Inside the ring's body.
            square(12, 12, 3),
            // Touching the ring's outside at a corner.
            square(50, 50, 5),
            // Apart from all.
            square(60, 0, 5),
            // Covering the hole: its rightmost vertex lies in the ring.
            square(15, 15, 30),
        ];
        let refs: Vec<&[Vec<IntPoint>]> = shapes.iter().map(Vec::as_slice).collect();
        assert_eq!(
            contact_sets(&grid, &refs, usize::MAX),
            Some(vec![vec![0, 1, 2, 3, 5], vec![4]])
        );
        // One set would hold more than 20 segments (it holds 24).
        assert_eq!(contact_sets(&grid, &refs, 20), None);
        // Without the covering square the hole's square is apart.
        assert_eq!(
            contact_sets(&grid, &refs[..5], usize::MAX),
            Some(vec![vec![0, 2, 3], vec![1], vec![4]])
        );
    }

    #[test]
    fn segments_meet_at_ends_and_along_lines_only() {
        let p = IntPoint::new;
        assert!(segments_meet(p(0, 0), p(4, 4), p(4, 4), p(9, 0)));
        assert!(segments_meet(p(0, 0), p(4, 4), p(2, 2), p(9, 9)));
        assert!(segments_meet(p(0, 0), p(4, 4), p(0, 4), p(4, 0)));
        assert!(!segments_meet(p(0, 0), p(4, 4), p(5, 5), p(9, 9)));
        assert!(!segments_meet(p(0, 0), p(4, 4), p(1, 0), p(5, 4)));
    }
}
