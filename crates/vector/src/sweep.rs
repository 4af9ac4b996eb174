//! Every proper crossing of a set of integer segments, by a plane sweep:
//! Bentley and Ottmann, "Algorithms for reporting and counting geometric
//! intersections" (IEEE Trans. Computers, 1979), in the form of de Berg,
//! Cheong, van Kreveld and Overmars, *Computational Geometry* (3rd ed.),
//! ch. 2, which handles the degenerate cases: many segments through one
//! point, vertical segments, segments ending inside others.
//!
//! A vertical line sweeps the plane from left to right (ties broken
//! upward, so the event order is the lexicographic order of points). The
//! status holds the segments the line meets, bottom to top; two segments
//! can only cross after they have been neighbours in it, so only
//! neighbours are tested, and the cost is `O((n + k) log n)` for `n`
//! segments and `k` crossing pairs, where testing pairs that share a bin
//! costs the square of the segments through the densest bin (a fan's
//! spokes all meet its centre).
//!
//! Everything is exact: the coordinates are integers within `2^29` (the
//! region grid), a crossing point is a rational whose denominator is at
//! most `2^59`, and it is held as an integer part plus a fraction, so that
//! every comparison (event order, which side of a segment a crossing
//! lies on) fits in `i128`. Collinear overlapping segments never cross
//! properly; they sit side by side in the status in the order of their
//! indices.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use i_overlay::i_float::int::point::IntPoint;

/// A segment by its two ends.
pub type Segment = (IntPoint, IntPoint);

/// The work of one sweep.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SweepStats {
    /// Distinct event points handled (segment ends and crossings).
    pub events: u64,
    /// Pairs of neighbours in the status tested for a crossing.
    pub tests: u64,
}

/// Calls `report(i, j)` (with `i < j`) once for every pair of segments
/// that cross properly: each one's ends lie strictly on either side of
/// the other's line. Degenerate segments (both ends equal) cross nothing.
/// Coordinates must lie within `[-2^29, 2^29]`.
pub fn proper_crossings(segments: &[Segment], mut report: impl FnMut(u32, u32)) -> SweepStats {
    debug_assert!(
        segments
            .iter()
            .flat_map(|s| [s.0, s.1])
            .all(|p| p.x.unsigned_abs() <= 1 << 29 && p.y.unsigned_abs() <= 1 << 29),
        "sweep coordinates out of range"
    );
    // Each segment from its lexicographically lower end (its left end, or
    // its lower end when vertical).
    let segs: Vec<Segment> = segments
        .iter()
        .map(|&(a, b)| if lex(a) <= lex(b) { (a, b) } else { (b, a) })
        .collect();
    let live: Vec<u32> = (0..segs.len() as u32)
        .filter(|&k| segs[k as usize].0 != segs[k as usize].1)
        .collect();
    let mut starts = live.clone();
    starts.sort_unstable_by_key(|&k| lex(segs[k as usize].0));
    let mut ends = live;
    ends.sort_unstable_by_key(|&k| lex(segs[k as usize].1));
    let (mut si, mut ei) = (0, 0);
    let mut crossings: BinaryHeap<std::cmp::Reverse<Point>> = BinaryHeap::new();
    let mut status = Treap::new(segs.len());
    let mut root = NIL;
    let mut stats = SweepStats::default();
    let mut through: Vec<u32> = Vec::new();
    let mut fresh: Vec<u32> = Vec::new();
    loop {
        // The next event point: the least of the next start, end and
        // crossing.
        let mut next: Option<Point> = None;
        let mut offer = |p: Point| {
            if next.is_none_or(|n| p < n) {
                next = Some(p);
            }
        };
        if let Some(&k) = starts.get(si) {
            offer(Point::at(segs[k as usize].0));
        }
        if let Some(&k) = ends.get(ei) {
            offer(Point::at(segs[k as usize].1));
        }
        if let Some(std::cmp::Reverse(p)) = crossings.peek() {
            offer(*p);
        }
        let Some(p) = next else { break };
        stats.events += 1;
        fresh.clear();
        while let Some(&k) = starts.get(si) {
            if Point::at(segs[k as usize].0) != p {
                break;
            }
            fresh.push(k);
            si += 1;
        }
        while ends
            .get(ei)
            .is_some_and(|&k| Point::at(segs[k as usize].1) == p)
        {
            ei += 1;
        }
        while crossings.peek().is_some_and(|c| c.0 == p) {
            crossings.pop();
        }
        // The segments through `p` are contiguous in the status, between
        // those passing below it and those passing above.
        let (below, rest) = status.split(root, &|s| side(segs[s as usize], p) > 0);
        let (mid, above) = status.split(rest, &|s| side(segs[s as usize], p) == 0);
        through.clear();
        status.in_order(mid, &mut through);
        // Those with `p` inside (not an end) cross properly at `p` every
        // one of them not on their line.
        through.retain(|&s| Point::at(segs[s as usize].1) != p);
        let by_direction = |&a: &u32, &b: &u32| {
            direction_order(segs[a as usize], segs[b as usize]).then(a.cmp(&b))
        };
        through.sort_unstable_by(by_direction);
        report_bundle(&segs, &through, &mut report);
        // Past `p` the continuing and starting segments are ordered by
        // direction, bottom to top.
        fresh.extend_from_slice(&through);
        fresh.sort_unstable_by(by_direction);
        let mut new_mid = NIL;
        for &s in &fresh {
            status.reset(s);
            new_mid = status.merge(new_mid, s);
        }
        let (low, high) = (status.last(below), status.first(above));
        let mut test = |a: u32, b: u32| {
            if a == NIL || b == NIL {
                return;
            }
            stats.tests += 1;
            let (s, t) = (segs[a as usize], segs[b as usize]);
            if crosses(s, t) {
                let q = crossing_point(s, t);
                if q > p {
                    crossings.push(std::cmp::Reverse(q));
                }
            }
        };
        match (fresh.first(), fresh.last()) {
            (Some(&first), Some(&last)) => {
                test(low, first);
                test(last, high);
            }
            _ => test(low, high),
        }
        let left = status.merge(below, new_mid);
        root = status.merge(left, above);
    }
    stats
}

/// Reports every pair of a bundle of segments through one point (each
/// with the point inside) whose directions differ, the bundle sorted by
/// direction: pairs within one direction overlap, they do not cross.
fn report_bundle(segs: &[Segment], bundle: &[u32], report: &mut impl FnMut(u32, u32)) {
    let mut group_end = 0;
    for (i, &a) in bundle.iter().enumerate() {
        if group_end <= i {
            group_end = i + 1;
            while group_end < bundle.len()
                && direction_order(segs[a as usize], segs[bundle[group_end] as usize])
                    == Ordering::Equal
            {
                group_end += 1;
            }
        }
        for &b in &bundle[group_end..] {
            report(a.min(b), a.max(b));
        }
    }
}

fn lex(p: IntPoint) -> (i32, i32) {
    (p.x, p.y)
}

/// The order of two segments (each from its lower end) just past a point
/// both pass through: by the angle of their directions, from straight
/// down (exclusive) to straight up.
fn direction_order(s: Segment, t: Segment) -> Ordering {
    let d = |s: Segment| {
        (
            i128::from(s.1.x) - i128::from(s.0.x),
            i128::from(s.1.y) - i128::from(s.0.y),
        )
    };
    let (u, v) = (d(s), d(t));
    // `v` turned counterclockwise from `u` lies above it past the point.
    (0).cmp(&(u.0 * v.1 - u.1 * v.0))
}

/// The sign of the turn `a -> b -> c`, exact.
pub fn orient(a: IntPoint, b: IntPoint, c: IntPoint) -> i64 {
    let (abx, aby) = (
        i128::from(b.x) - i128::from(a.x),
        i128::from(b.y) - i128::from(a.y),
    );
    let (acx, acy) = (
        i128::from(c.x) - i128::from(a.x),
        i128::from(c.y) - i128::from(a.y),
    );
    (abx * acy - aby * acx).signum() as i64
}

/// Whether two segments cross properly (the predicate of the brute-force
/// test this sweep replaces).
pub fn crosses(p: Segment, q: Segment) -> bool {
    let (o1, o2) = (orient(p.0, p.1, q.0), orient(p.0, p.1, q.1));
    let (o3, o4) = (orient(q.0, q.1, p.0), orient(q.0, q.1, p.1));
    o1 * o2 < 0 && o3 * o4 < 0
}

/// An event point: `(ix + fx / d, iy + fy / d)` with `0 <= fx, fy < d`.
/// Segment ends have `d = 1`; a crossing's `d` is the cross product of
/// the two directions (at most `2^59`), so a product of a fraction and a
/// denominator stays below `2^118`.
#[derive(Clone, Copy, Debug)]
struct Point {
    ix: i64,
    fx: i128,
    iy: i64,
    fy: i128,
    d: i128,
}

impl Point {
    fn at(p: IntPoint) -> Self {
        Self {
            ix: i64::from(p.x),
            fx: 0,
            iy: i64::from(p.y),
            fy: 0,
            d: 1,
        }
    }
}

impl Ord for Point {
    fn cmp(&self, other: &Self) -> Ordering {
        self.ix
            .cmp(&other.ix)
            .then((self.fx * other.d).cmp(&(other.fx * self.d)))
            .then(self.iy.cmp(&other.iy))
            .then((self.fy * other.d).cmp(&(other.fy * self.d)))
    }
}

impl PartialOrd for Point {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl PartialEq for Point {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl Eq for Point {}

/// The exact crossing point of two properly crossing segments.
fn crossing_point(s: Segment, t: Segment) -> Point {
    let d = |a: IntPoint, b: IntPoint| {
        (
            i128::from(b.x) - i128::from(a.x),
            i128::from(b.y) - i128::from(a.y),
        )
    };
    let (r, q, w) = (d(s.0, s.1), d(t.0, t.1), d(s.0, t.0));
    let (mut den, mut num) = (r.0 * q.1 - r.1 * q.0, w.0 * q.1 - w.1 * q.0);
    if den < 0 {
        (den, num) = (-den, -num);
    }
    // `num / den` lies in (0, 1), so `num * r` stays below `2^89`.
    let (ox, oy) = (num * r.0, num * r.1);
    Point {
        ix: i64::from(s.0.x) + ox.div_euclid(den) as i64,
        fx: ox.rem_euclid(den),
        iy: i64::from(s.0.y) + oy.div_euclid(den) as i64,
        fy: oy.rem_euclid(den),
        d: den,
    }
}

/// Which side of segment `s` (from its lower end) the point `p` lies on:
/// positive above (to the left), zero on its line, negative below.
fn side(s: Segment, p: Point) -> i32 {
    let (a, b) = s;
    let (dx, dy) = (
        i128::from(b.x) - i128::from(a.x),
        i128::from(b.y) - i128::from(a.y),
    );
    // `(p - a) * d`, below `2^89`; the products below `2^118`.
    let px = i128::from(p.ix - i64::from(a.x)) * p.d + p.fx;
    let py = i128::from(p.iy - i64::from(a.y)) * p.d + p.fy;
    (dx * py - dy * px).signum() as i32
}

/// No node.
const NIL: u32 = u32::MAX;

/// The status: a treap (Seidel and Aragon, "Randomized search trees",
/// 1996) ordered by position, split and merged by monotone predicates, so
/// that its order needs no key of its own. Node `k` is segment `k`.
struct Treap {
    left: Vec<u32>,
    right: Vec<u32>,
    priority: Vec<u32>,
}

impl Treap {
    fn new(n: usize) -> Self {
        // A fixed hash of the index: random enough for balance, and the
        // same run every time.
        let priority = (0..n as u32)
            .map(|k| {
                let mut x = k.wrapping_mul(0x9E37_79B9) ^ 0x85EB_CA6B;
                x ^= x >> 15;
                x = x.wrapping_mul(0x2C1B_3C6D);
                x ^ (x >> 12)
            })
            .collect();
        Self {
            left: vec![NIL; n],
            right: vec![NIL; n],
            priority,
        }
    }

    fn reset(&mut self, k: u32) {
        self.left[k as usize] = NIL;
        self.right[k as usize] = NIL;
    }

    /// Splits `t` into the leading nodes for which `pred` holds and the
    /// rest; `pred` must hold on a prefix of the order.
    fn split(&mut self, t: u32, pred: &impl Fn(u32) -> bool) -> (u32, u32) {
        if t == NIL {
            return (NIL, NIL);
        }
        let k = t as usize;
        if pred(t) {
            let (l, r) = self.split(self.right[k], pred);
            self.right[k] = l;
            (t, r)
        } else {
            let (l, r) = self.split(self.left[k], pred);
            self.left[k] = r;
            (l, t)
        }
    }

    /// `a` followed by `b`.
    fn merge(&mut self, a: u32, b: u32) -> u32 {
        if a == NIL {
            return b;
        }
        if b == NIL {
            return a;
        }
        if self.priority[a as usize] > self.priority[b as usize] {
            let r = self.merge(self.right[a as usize], b);
            self.right[a as usize] = r;
            a
        } else {
            let l = self.merge(a, self.left[b as usize]);
            self.left[b as usize] = l;
            b
        }
    }

    fn in_order(&self, t: u32, out: &mut Vec<u32>) {
        let mut stack = Vec::new();
        let mut cur = t;
        while cur != NIL || !stack.is_empty() {
            while cur != NIL {
                stack.push(cur);
                cur = self.left[cur as usize];
            }
            let k = stack.pop().expect("the loop condition");
            out.push(k);
            cur = self.right[k as usize];
        }
    }

    fn first(&self, mut t: u32) -> u32 {
        while t != NIL && self.left[t as usize] != NIL {
            t = self.left[t as usize];
        }
        t
    }

    fn last(&self, mut t: u32) -> u32 {
        while t != NIL && self.right[t as usize] != NIL {
            t = self.right[t as usize];
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    fn brute(segments: &[Segment]) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        for i in 0..segments.len() {
            for j in i + 1..segments.len() {
                if crosses(segments[i], segments[j]) {
                    out.push((i as u32, j as u32));
                }
            }
        }
        out
    }

    fn swept(segments: &[Segment]) -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        proper_crossings(segments, |i, j| out.push((i, j)));
        out.sort_unstable();
        out
    }

    fn seg(a: (i32, i32), b: (i32, i32)) -> Segment {
        (IntPoint::new(a.0, a.1), IntPoint::new(b.0, b.1))
    }

    /// Segments on a small lattice, scaled and moved: shared ends,
    /// collinear overlaps, vertical and horizontal segments, several
    /// crossings at one point and ends on other segments are common.
    fn lattice(side: i32) -> impl Strategy<Value = Vec<Segment>> {
        let p = (0..side, 0..side);
        let scale = prop_oneof![Just(1), Just(3), Just(1 << 20), Just((1 << 29) / 16)];
        let offset = prop_oneof![Just(0), Just(-(1 << 28)), Just(12_345)];
        (prop::collection::vec((p.clone(), p), 0..40), scale, offset).prop_map(
            |(pairs, scale, offset)| {
                pairs
                    .into_iter()
                    .map(|(a, b)| {
                        let q = |(x, y): (i32, i32)| (offset + x * scale, offset + y * scale);
                        seg(q(a), q(b))
                    })
                    .collect()
            },
        )
    }

    /// Segments through a few common points (stars), plus a few others.
    fn stars() -> impl Strategy<Value = Vec<Segment>> {
        let coord = -1000..1000;
        let centre = (coord.clone(), coord.clone());
        let star = (
            centre,
            prop::collection::vec(((-30i32..30, -30i32..30), 1i32..4, 0i32..4), 1..25),
        )
            .prop_map(|((cx, cy), rays)| {
                rays.into_iter()
                    .filter(|&((dx, dy), _, _)| (dx, dy) != (0, 0))
                    .map(|((dx, dy), out, back)| {
                        // Through the centre, or ending on it (`back` 0).
                        seg(
                            (cx - back * dx, cy - back * dy),
                            (cx + out * dx, cy + out * dy),
                        )
                    })
                    .collect::<Vec<_>>()
            });
        let free = prop::collection::vec(
            ((coord.clone(), coord.clone()), (coord.clone(), coord)),
            0..10,
        )
        .prop_map(|v| v.into_iter().map(|(a, b)| seg(a, b)).collect::<Vec<_>>());
        (prop::collection::vec(star, 1..4), free)
            .prop_map(|(stars, free)| stars.into_iter().flatten().chain(free).collect())
    }

    /// Random segments anywhere in the grid's range.
    fn wide() -> impl Strategy<Value = Vec<Segment>> {
        let c = -(1i32 << 29)..=(1 << 29);
        prop::collection::vec(((c.clone(), c.clone()), (c.clone(), c)), 0..40)
            .prop_map(|v| v.into_iter().map(|(a, b)| seg(a, b)).collect())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(400))]

        #[test]
        fn the_sweep_finds_exactly_the_proper_crossings(
            segments in prop_oneof![lattice(4), lattice(9), stars(), wide()]
        ) {
            prop_assert_eq!(swept(&segments), brute(&segments));
        }
    }

    #[test]
    fn a_star_through_one_point_crosses_pairwise_there() {
        // Four lines through the origin, a fifth segment ending there.
        let s = vec![
            seg((-4, 0), (4, 0)),
            seg((0, -4), (0, 4)),
            seg((-4, -4), (4, 4)),
            seg((-4, 4), (4, -4)),
            seg((0, 0), (3, 7)),
            seg((-2, 0), (2, 0)),
        ];
        assert_eq!(swept(&s), brute(&s));
        assert_eq!(swept(&s).len(), 4 * 3 / 2 + 3);
    }

    #[test]
    fn a_fan_has_no_crossing_and_linear_work() {
        let n = 400;
        let spokes: Vec<Segment> = (0..n)
            .map(|k| {
                let a = f64::from(k) * std::f64::consts::TAU / f64::from(n);
                let r = 1e6;
                seg((0, 0), ((r * a.cos()) as i32, (r * a.sin()) as i32))
            })
            .collect();
        let mut count = 0;
        let stats = proper_crossings(&spokes, |_, _| count += 1);
        assert_eq!(count, 0);
        assert!(stats.tests < 4 * n as u64, "{stats:?}");
    }
}
