//! Pairs of triangles around a shared vertex whose angular sectors meet.
//!
//! Two triangles sharing a vertex `v` are convex sets containing `v`, so
//! their intersection is a convex set containing `v`: if they meet
//! anywhere other than at `v`, they meet arbitrarily close to it, inside
//! both of their *sectors* (the angle each spans at `v`). In the plane,
//! two triangles sharing a vertex therefore overlap (interiors) exactly
//! when their sectors at it overlap by a positive angle. A flat fan, a cone
//! seen along its axis, or the pole of a UV sphere is a *star* of `n`
//! triangles around one vertex whose bounding boxes all meet there, so a
//! bin grid lists all `n^2 / 2` pairs; their sectors tile the circle, and
//! only neighbours meet. [`sector_pairs`] finds every pair of sectors
//! whose closures meet in `O(n log n + k)` for `k` such pairs: sorted by
//! starting direction, the sectors that start inside another form one
//! circular run of that order, and two closed arcs of a circle meet
//! exactly when one of them contains the other's start.
//!
//! Directions are compared exactly: by half-plane (coordinate
//! comparisons) and then by the sign of an orientation predicate, so the
//! caller's exact `orient2d` decides every tie.

use std::cmp::Ordering;

use crate::FixedPt;

/// A point type whose directions around an apex can be ordered exactly.
pub trait AngularPoint: Copy + PartialEq {
    /// The sign of the orientation of `a, b, c` (positive when `c` is
    /// counter-clockwise of `b` seen from `a`, in the frame where the `x`
    /// axis turns to the `y` axis counter-clockwise), computed exactly.
    fn orient(a: Self, b: Self, c: Self) -> i8;
    /// Whether `self` lies at an angle in `[0, pi)` around `apex`: above it,
    /// or at its height and to its right.
    fn upper_of(self, apex: Self) -> bool;
}

impl AngularPoint for FixedPt {
    fn orient(a: Self, b: Self, c: Self) -> i8 {
        crate::edge::orient2d(a, b, c).signum() as i8
    }

    fn upper_of(self, apex: Self) -> bool {
        self.y > apex.y || (self.y == apex.y && self.x > apex.x)
    }
}

/// The directions a triangle spans at its vertex `apex`: from the
/// direction of `start` counter-clockwise to that of `end`, at most a half
/// turn (a whole half turn when the triangle is flat with `apex` between
/// its other corners, which covers both of their directions).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sector<P> {
    /// A point in the first direction.
    pub start: P,
    /// A point in the last direction.
    pub end: P,
}

impl<P: AngularPoint> Sector<P> {
    /// The sector of the triangle `apex, p, q` at `apex`; `None` when both
    /// other corners coincide with `apex` (no direction at all).
    pub fn around(apex: P, p: P, q: P) -> Option<Self> {
        let one = |d: P| Some(Self { start: d, end: d });
        match (p == apex, q == apex) {
            (true, true) => return None,
            (true, false) => return one(q),
            (false, true) => return one(p),
            _ => {}
        }
        match P::orient(apex, p, q) {
            1.. => Some(Self { start: p, end: q }),
            ..0 => Some(Self { start: q, end: p }),
            0 if compare(apex, p, q) == Ordering::Equal => one(p),
            // Opposite directions: the half turn from p to q holds both.
            0 => Some(Self { start: p, end: q }),
        }
    }
}

/// The order of the directions of `a` and `b` around `apex` by angle in
/// `[0, 2 pi)` from the `x` axis; `Equal` for the same direction.
pub fn compare<P: AngularPoint>(apex: P, a: P, b: P) -> Ordering {
    match (a.upper_of(apex), b.upper_of(apex)) {
        (true, false) => Ordering::Less,
        (false, true) => Ordering::Greater,
        _ => match P::orient(apex, a, b) {
            1.. => Ordering::Less,
            ..0 => Ordering::Greater,
            0 => Ordering::Equal,
        },
    }
}

/// Every pair `(i, j)`, `i < j`, of `sectors` around `apex` whose closed
/// sectors share a direction, with at least one of the two in `query`
/// (`query(i)`); sorted, each once. `O(n log n + k)` for `n` sectors and
/// `k` pairs whose closures meet (see the module documentation).
pub fn sector_pairs<P: AngularPoint>(
    apex: P,
    sectors: &[Sector<P>],
    query: impl Fn(usize) -> bool,
) -> Vec<(u32, u32)> {
    sector_pairs_within(apex, sectors, query, usize::MAX).unwrap_or_default()
}

/// [`sector_pairs`], or `None` as soon as more than `most` pairs (counted
/// before removing the pairs found twice) are in sight: a *dense* star,
/// whose sectors overlap so much that they do not save the caller any
/// work, found without listing its pairs.
pub fn sector_pairs_within<P: AngularPoint>(
    apex: P,
    sectors: &[Sector<P>],
    query: impl Fn(usize) -> bool,
    most: usize,
) -> Option<Vec<(u32, u32)>> {
    let mut all: Vec<u32> = (0..sectors.len() as u32).collect();
    all.sort_by(|&a, &b| compare(apex, sectors[a as usize].start, sectors[b as usize].start));
    // Sorted too: `all` is.
    let asked: Vec<u32> = all.iter().copied().filter(|&i| query(i as usize)).collect();
    let mut out = Vec::new();
    // Pairs where the asked sector holds the other's start, then pairs
    // where any sector holds an asked one's start.
    for (holders, starts) in [(&asked, &all), (&all, &asked)] {
        for &h in holders {
            let (first, second) = starts_within(apex, sectors, starts, sectors[h as usize]);
            if out.len() + first.len() + second.len() > most {
                return None;
            }
            for &k in first.iter().chain(second) {
                if k != h {
                    out.push((h.min(k), h.max(k)));
                }
            }
        }
    }
    out.sort_unstable();
    out.dedup();
    Some(out)
}

/// The entries of `ids` (sorted by start) whose start lies in the closed
/// sector `s`: one circular run of the order, as at most two slices.
fn starts_within<'a, P: AngularPoint>(
    apex: P,
    sectors: &[Sector<P>],
    ids: &'a [u32],
    s: Sector<P>,
) -> (&'a [u32], &'a [u32]) {
    let start_of = |k: &u32| sectors[*k as usize].start;
    let lo = ids.partition_point(|k| compare(apex, start_of(k), s.start) == Ordering::Less);
    let hi = ids.partition_point(|k| compare(apex, start_of(k), s.end) != Ordering::Greater);
    if compare(apex, s.start, s.end) != Ordering::Greater {
        (&ids[lo..hi.max(lo)], &[])
    } else {
        // The sector crosses the x axis: the end of the order, then its
        // beginning.
        (&ids[lo..], &ids[..hi])
    }
}

/// Fewest triangles sharing a vertex for the callers here to handle it as
/// a star rather than by their bins: below that, the bins' pairs at the
/// vertex are few anyway (a regular mesh has six triangles at a vertex).
pub const MIN_STAR: usize = 12;

/// The stars of snapped screen triangles (corners the same vertex when
/// their fixed-point positions are equal), of at least [`MIN_STAR`]
/// triangles. `corners(k)` is `None` for a triangle to leave out; one
/// without area belongs to none (its "interior" is a segment, which the
/// sector argument does not cover).
pub fn fixed_stars(n: usize, corners: impl Fn(usize) -> Option<[FixedPt; 3]>) -> Stars {
    Stars::new(n, fixed_keys(corners), MIN_STAR)
}

/// [`fixed_stars`] when they pay for a search over the pairs of the `n`
/// triangles ([`Stars::paying`]), else none.
pub fn fixed_stars_paying(n: usize, corners: impl Fn(usize) -> Option<[FixedPt; 3]>) -> Stars {
    Stars::paying(n, fixed_keys(corners), MIN_STAR)
}

/// The corner keys of [`fixed_stars`]: none for a triangle without area.
fn fixed_keys(
    corners: impl Fn(usize) -> Option<[FixedPt; 3]>,
) -> impl Fn(usize) -> Option<[(i32, i32); 3]> {
    move |k| {
        let v = corners(k)?;
        (crate::edge::orient2d(v[0], v[1], v[2]) != 0).then(|| v.map(|p| (p.x, p.y)))
    }
}

/// Most candidate pairs per member a star may yield before it counts as
/// dense and is dissolved ([`Stars::retain`]): sectors that overlap that
/// much (a pleated fan seen edge-on, random triangles around one vertex)
/// save nothing over the caller's bins, which then take the star's pairs
/// as they did without stars.
pub const DENSE_PAIRS_PER_MEMBER: usize = 8;

/// The pair budget of a star of `members` triangles (see
/// [`DENSE_PAIRS_PER_MEMBER`]).
pub fn dense_limit(members: usize) -> usize {
    DENSE_PAIRS_PER_MEMBER * members + 64
}

/// Every pair `(i, j)`, `i < j`, of snapped triangles (corners
/// `corners(t)`) sharing a star of `stars` whose closed sectors meet
/// there: a superset of the pairs sharing a star whose interiors overlap.
/// Sorted, each once. Dense stars are dissolved first (their triangles
/// leave `stars`, see [`DENSE_PAIRS_PER_MEMBER`]).
pub fn fixed_star_pairs(
    stars: &mut Stars,
    corners: impl Fn(u32) -> [FixedPt; 3],
) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    let mut dense = Vec::new();
    for h in 0..stars.len() {
        let members = stars.members(h);
        let (t, i) = members[0];
        let apex = corners(t)[usize::from(i)];
        let sectors: Vec<Sector<FixedPt>> = members
            .iter()
            .filter_map(|&(t, i)| {
                let (v, i) = (corners(t), usize::from(i));
                Sector::around(v[i], v[(i + 1) % 3], v[(i + 2) % 3])
            })
            .collect();
        // Members have area, so none was left out and `sectors` lines up
        // with `members`.
        debug_assert_eq!(sectors.len(), members.len());
        match sector_pairs_within(apex, &sectors, |_| true, dense_limit(members.len())) {
            Some(pairs) => out.extend(pairs.into_iter().map(|(x, y)| {
                let (a, b) = (members[x as usize].0, members[y as usize].0);
                (a.min(b), a.max(b))
            })),
            None => dense.push(h),
        }
    }
    if !dense.is_empty() {
        stars.retain(|h| dense.binary_search(&h).is_err());
        // A pair of a dissolved star that also shares a kept one stays.
        out.retain(|&(a, b)| stars.share(a as usize, b as usize));
    }
    out.sort_unstable();
    out.dedup();
    out
}

mod hubs;

pub use hubs::{Mix, NO_STAR, Stars};

#[cfg(test)]
mod tests;
