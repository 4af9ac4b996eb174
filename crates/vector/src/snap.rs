//! Snap rounding of the whole region map, so that its regions form one
//! consistent arrangement.
//!
//! Each region is computed by its own boolean difference, and each
//! difference rounds its own cut points to the grid: two regions meeting
//! along a cut line or a crossing of edges see two slightly different
//! roundings of it, and slivers of overlap or gap appear between them.
//! This pass rounds every cut point of the map once, for all regions
//! together, as in Hobby's "Practical segment intersection with finite
//! precision output" (snap rounding): every vertex and every proper
//! crossing of two region edges is a *hot pixel* (the unit square of the
//! grid around it), and every edge is rerouted through the centre of every
//! hot pixel it passes through. Two rerouted edges then never cross except
//! at their common grid points, so the later booleans on the snapped
//! regions have nothing left to round: they are exact.

use std::collections::HashMap;

use i_overlay::i_float::int::point::IntPoint;
use i_overlay::i_shape::int::shape::IntShapes;

use crate::grid::div_round;

/// Snaps the contours of every region in place. Returns, per region,
/// whether any of its edges was rerouted.
pub fn snap_round(regions: &mut [IntShapes]) -> Vec<bool> {
    let (segments, index) = unique_segments(regions);
    let mut hot: Vec<IntPoint> = index.keys().flat_map(|&(a, b)| [a, b]).collect();
    let seg_bins = SegmentBins::new(&segments);
    seg_bins.crossings(&segments, &mut hot);
    hot.sort_unstable_by_key(|p| (p.x, p.y));
    hot.dedup();
    let hot_bins = PointBins::new(&hot);
    // The chain of grid points each segment becomes (without its ends);
    // `None` when the segment is not rerouted.
    let chains: Vec<Option<Vec<IntPoint>>> = segments
        .iter()
        .map(|&(a, b)| hot_bins.chain(a, b))
        .collect();
    regions
        .iter_mut()
        .map(|shapes| {
            let mut touched = false;
            for contour in shapes.iter_mut().flatten() {
                let n = contour.len();
                let mut out = Vec::with_capacity(n);
                for k in 0..n {
                    let (a, b) = (contour[k], contour[(k + 1) % n]);
                    out.push(a);
                    if a == b {
                        continue;
                    }
                    let forward = key(a, b) == (a, b);
                    if let Some(chain) = &chains[index[&key(a, b)] as usize] {
                        touched = true;
                        if forward {
                            out.extend(chain.iter().copied());
                        } else {
                            out.extend(chain.iter().rev().copied());
                        }
                    }
                }
                out.dedup();
                while out.len() > 1 && out.first() == out.last() {
                    out.pop();
                }
                *contour = out;
            }
            touched
        })
        .collect()
}

/// An undirected segment's key: its ends in lexicographic order.
fn key(a: IntPoint, b: IntPoint) -> (IntPoint, IntPoint) {
    if (a.x, a.y) <= (b.x, b.y) {
        (a, b)
    } else {
        (b, a)
    }
}

type Segment = (IntPoint, IntPoint);

/// Every distinct non-degenerate edge of the regions, and the index from
/// an edge's key to its position.
fn unique_segments(regions: &[IntShapes]) -> (Vec<Segment>, HashMap<Segment, u32>) {
    let mut segments = Vec::new();
    let mut index = HashMap::new();
    for contour in regions.iter().flatten().flatten() {
        let n = contour.len();
        for k in 0..n {
            let (a, b) = (contour[k], contour[(k + 1) % n]);
            if a != b {
                index.entry(key(a, b)).or_insert_with(|| {
                    segments.push(key(a, b));
                    (segments.len() - 1) as u32
                });
            }
        }
    }
    (segments, index)
}

/// The sign of the turn `a -> b -> c`, exact.
fn orient(a: IntPoint, b: IntPoint, c: IntPoint) -> i64 {
    let (abx, aby) = (
        i64::from(b.x) - i64::from(a.x),
        i64::from(b.y) - i64::from(a.y),
    );
    let (acx, acy) = (
        i64::from(c.x) - i64::from(a.x),
        i64::from(c.y) - i64::from(a.y),
    );
    (i128::from(abx) * i128::from(acy) - i128::from(aby) * i128::from(acx)).signum() as i64
}

/// The crossing point of two properly crossing segments, rounded to the
/// nearest grid point (halves away from zero), exact in `i128`.
fn crossing(p: Segment, q: Segment) -> IntPoint {
    let d = |a: IntPoint, b: IntPoint| {
        (
            i128::from(b.x) - i128::from(a.x),
            i128::from(b.y) - i128::from(a.y),
        )
    };
    let (r, s, w) = (d(p.0, p.1), d(q.0, q.1), d(p.0, q.0));
    let den = r.0 * s.1 - r.1 * s.0;
    let num = w.0 * s.1 - w.1 * s.0;
    let at = |base: i32, step: i128| {
        let v = div_round(num * step, den);
        (i128::from(base) + v) as i32
    };
    IntPoint::new(at(p.0.x, r.0), at(p.0.y, r.1))
}

/// A uniform grid of square cells over a set of boxes.
struct Cells {
    x0: i64,
    y0: i64,
    size: i64,
    cols: i64,
    rows: i64,
}

impl Cells {
    /// Cells of about one item each over the box `(lo, hi)`.
    fn new(lo: IntPoint, hi: IntPoint, count: usize) -> Self {
        let (w, h) = (
            i64::from(hi.x) - i64::from(lo.x) + 1,
            i64::from(hi.y) - i64::from(lo.y) + 1,
        );
        let size = (((w as f64) * (h as f64) / count.max(1) as f64).sqrt() as i64).max(1);
        // Bound the cell count whatever the spread of the items.
        let size = size.max(w.max(h) / 2048 + 1);
        Self {
            x0: i64::from(lo.x),
            y0: i64::from(lo.y),
            size,
            cols: w / size + 1,
            rows: h / size + 1,
        }
    }

    /// The inclusive cell range `(c0, r0, c1, r1)` of a box.
    fn range(&self, lo: IntPoint, hi: IntPoint) -> (i64, i64, i64, i64) {
        let c = |v: i32, o: i64, n: i64| ((i64::from(v) - o) / self.size).clamp(0, n - 1);
        (
            c(lo.x, self.x0, self.cols),
            c(lo.y, self.y0, self.rows),
            c(hi.x, self.x0, self.cols),
            c(hi.y, self.y0, self.rows),
        )
    }

    fn len(&self) -> usize {
        (self.cols * self.rows) as usize
    }

    fn at(&self, c: i64, r: i64) -> usize {
        (r * self.cols + c) as usize
    }
}

fn seg_box(s: Segment) -> (IntPoint, IntPoint) {
    (
        IntPoint::new(s.0.x.min(s.1.x), s.0.y.min(s.1.y)),
        IntPoint::new(s.0.x.max(s.1.x), s.0.y.max(s.1.y)),
    )
}

fn span<'a>(points: impl Iterator<Item = &'a IntPoint>) -> (IntPoint, IntPoint) {
    points.fold(
        (
            IntPoint::new(i32::MAX, i32::MAX),
            IntPoint::new(i32::MIN, i32::MIN),
        ),
        |(lo, hi), p| {
            (
                IntPoint::new(lo.x.min(p.x), lo.y.min(p.y)),
                IntPoint::new(hi.x.max(p.x), hi.y.max(p.y)),
            )
        },
    )
}

/// Segments binned by their boxes, to find the crossing pairs.
struct SegmentBins {
    cells: Cells,
    lists: Vec<Vec<u32>>,
}

impl SegmentBins {
    fn new(segments: &[Segment]) -> Self {
        let (lo, hi) = span(segments.iter().flat_map(|s| [&s.0, &s.1]));
        let cells = Cells::new(lo, hi, segments.len());
        let mut lists = vec![Vec::new(); cells.len()];
        for (k, &s) in segments.iter().enumerate() {
            let (a, b) = seg_box(s);
            let (c0, r0, c1, r1) = cells.range(a, b);
            for r in r0..=r1 {
                for c in c0..=c1 {
                    lists[cells.at(c, r)].push(k as u32);
                }
            }
        }
        Self { cells, lists }
    }

    /// Pushes the rounded point of every proper crossing to `hot`. A pair
    /// is tested only in the cell holding the low corner of the overlap of
    /// its boxes, so once.
    fn crossings(&self, segments: &[Segment], hot: &mut Vec<IntPoint>) {
        for r in 0..self.cells.rows {
            for c in 0..self.cells.cols {
                let list = &self.lists[self.cells.at(c, r)];
                for (i, &si) in list.iter().enumerate() {
                    let p = segments[si as usize];
                    let (plo, phi) = seg_box(p);
                    for &sj in &list[i + 1..] {
                        let q = segments[sj as usize];
                        let (qlo, qhi) = seg_box(q);
                        let lo = IntPoint::new(plo.x.max(qlo.x), plo.y.max(qlo.y));
                        let hi = IntPoint::new(phi.x.min(qhi.x), phi.y.min(qhi.y));
                        if lo.x > hi.x || lo.y > hi.y {
                            continue;
                        }
                        let (c0, r0, _, _) = self.cells.range(lo, lo);
                        if (c0, r0) != (c, r) {
                            continue;
                        }
                        let (o1, o2) = (orient(p.0, p.1, q.0), orient(p.0, p.1, q.1));
                        let (o3, o4) = (orient(q.0, q.1, p.0), orient(q.0, q.1, p.1));
                        if o1 * o2 < 0 && o3 * o4 < 0 {
                            hot.push(crossing(p, q));
                        }
                    }
                }
            }
        }
    }
}

/// Hot pixel centres, binned.
struct PointBins {
    cells: Cells,
    lists: Vec<Vec<IntPoint>>,
}

impl PointBins {
    fn new(points: &[IntPoint]) -> Self {
        let (lo, hi) = span(points.iter());
        let cells = Cells::new(lo, hi, points.len());
        let mut lists = vec![Vec::new(); cells.len()];
        for &p in points {
            let (c, r, _, _) = cells.range(p, p);
            lists[cells.at(c, r)].push(p);
        }
        Self { cells, lists }
    }

    /// The hot pixel centres strictly between `a` and `b` that the segment
    /// passes through (closed unit square around each centre), in order
    /// from `a`; `None` when there are none.
    fn chain(&self, a: IntPoint, b: IntPoint) -> Option<Vec<IntPoint>> {
        let (lo, hi) = seg_box((a, b));
        let (c0, r0, c1, r1) = self.cells.range(lo, hi);
        // Doubled coordinates put the squares' corners on integers.
        let (a2, b2) = (double(a), double(b));
        let mut found: Vec<(i128, IntPoint)> = Vec::new();
        for r in r0..=r1 {
            for c in c0..=c1 {
                for &h in &self.lists[self.cells.at(c, r)] {
                    // A square meets the segment's box only if its centre
                    // lies in the box: the ends are grid points.
                    if h == a || h == b || h.x < lo.x || h.x > hi.x || h.y < lo.y || h.y > hi.y {
                        continue;
                    }
                    let h2 = double(h);
                    let sides = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
                        .map(|(dx, dy)| orient(a2, b2, IntPoint::new(h2.x + dx, h2.y + dy)));
                    let all_left = sides.iter().all(|&s| s > 0);
                    let all_right = sides.iter().all(|&s| s < 0);
                    if !all_left && !all_right {
                        let t = i128::from(h.x - a.x) * i128::from(b.x - a.x)
                            + i128::from(h.y - a.y) * i128::from(b.y - a.y);
                        found.push((t, h));
                    }
                }
            }
        }
        if found.is_empty() {
            return None;
        }
        found.sort_unstable_by_key(|&(t, h)| (t, h.x, h.y));
        Some(found.into_iter().map(|(_, h)| h).collect())
    }
}

/// A point with both coordinates doubled (the grid stays within 2^29, so
/// this fits in `i32`).
fn double(p: IntPoint) -> IntPoint {
    IntPoint::new(2 * p.x, 2 * p.y)
}
