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
use crate::sweep::{Segment, orient, proper_crossings};

/// The work of one snap rounding.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SnapStats {
    /// Distinct edges of the regions.
    pub segments: u64,
    /// Event points of the crossing sweep.
    pub events: u64,
    /// Neighbouring edges the sweep tested for a crossing.
    pub tests: u64,
    /// Pairs of edges crossing properly.
    pub crossings: u64,
    /// Grid cells the edges walked through to find their hot pixels.
    pub cells: u64,
}

/// Snaps the contours of every region in place. Returns, per region,
/// whether any of its edges was rerouted, and the work done.
pub fn snap_round(regions: &mut [IntShapes]) -> (Vec<bool>, SnapStats) {
    let (segments, index) = unique_segments(regions);
    let mut hot: Vec<IntPoint> = index.keys().flat_map(|&(a, b)| [a, b]).collect();
    let mut stats = SnapStats {
        segments: segments.len() as u64,
        ..SnapStats::default()
    };
    // The crossings by a sweep, whose cost follows the crossings found:
    // binning pairs of edges by area tests every pair of a dense fan of
    // edges meeting at one vertex (a disc's triangulation).
    let sweep = proper_crossings(&segments, |i, j| {
        stats.crossings += 1;
        hot.push(crossing(segments[i as usize], segments[j as usize]));
    });
    stats.events = sweep.events;
    stats.tests = sweep.tests;
    hot.sort_unstable_by_key(|p| (p.x, p.y));
    hot.dedup();
    let hot_bins = PointBins::new(&hot);
    // The chain of grid points each segment becomes (without its ends);
    // `None` when the segment is not rerouted.
    let chains: Vec<Option<Vec<IntPoint>>> = segments
        .iter()
        .map(|&(a, b)| hot_bins.chain(a, b, &mut stats.cells))
        .collect();
    let touched = regions
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
        .collect();
    (touched, stats)
}

/// An undirected segment's key: its ends in lexicographic order.
fn key(a: IntPoint, b: IntPoint) -> (IntPoint, IntPoint) {
    if (a.x, a.y) <= (b.x, b.y) {
        (a, b)
    } else {
        (b, a)
    }
}

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
    /// from `a`; `None` when there are none. Adds the cells walked to
    /// `cells`.
    fn chain(&self, a: IntPoint, b: IntPoint, cells: &mut u64) -> Option<Vec<IntPoint>> {
        let (lo, hi) = seg_box((a, b));
        // Doubled coordinates put the squares' corners on integers.
        let (a2, b2) = (double(a), double(b));
        let mut found: Vec<(i128, IntPoint)> = Vec::new();
        self.walk(a2, b2, |cell| {
            *cells += 1;
            for &h in &self.lists[cell] {
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
        });
        if found.is_empty() {
            return None;
        }
        found.sort_unstable_by_key(|&(t, h)| (t, h.x, h.y));
        Some(found.into_iter().map(|(_, h)| h).collect())
    }

    /// Calls `visit` once for every cell whose hot pixels the segment
    /// `a2 -> b2` (doubled coordinates, ends in the grid's span) can
    /// meet, walking only the cells it passes through (Amanatides and
    /// Woo, "A fast voxel traversal algorithm", 1987), exactly. A hot
    /// pixel's square lies inside its cell widened by half a unit on each
    /// side, so the walk is over those widened cells: their sides lie on
    /// odd doubled coordinates, where no end of a segment can be, so the
    /// segment crosses every side it meets, and where it passes exactly
    /// through a corner all four cells around it are visited.
    fn walk(&self, a2: IntPoint, b2: IntPoint, mut visit: impl FnMut(usize)) {
        let cell_of =
            |v: i32, o: i64, n: i64| ((i64::from(v / 2) - o) / self.cells.size).clamp(0, n - 1);
        let (cols, rows) = (self.cells.cols, self.cells.rows);
        let (mut c, mut r) = (
            cell_of(a2.x, self.cells.x0, cols),
            cell_of(a2.y, self.cells.y0, rows),
        );
        let (cb, rb) = (
            cell_of(b2.x, self.cells.x0, cols),
            cell_of(b2.y, self.cells.y0, rows),
        );
        let (dx, dy) = (
            i128::from(b2.x) - i128::from(a2.x),
            i128::from(b2.y) - i128::from(a2.y),
        );
        let (sx, sy) = (dx.signum() as i64, dy.signum() as i64);
        // The side between cell `k - 1` and cell `k`, doubled.
        let side = |k: i64, o: i64| i128::from(2 * (o + k * self.cells.size) - 1);
        visit(self.cells.at(c, r));
        for _ in 0..(cb - c).abs() + (rb - r).abs() {
            if (c, r) == (cb, rb) {
                break;
            }
            // The distances along each axis to the next side crossed,
            // compared as parameters `nx / |dx|` and `ny / |dy|`.
            let nx = (side(c + i64::from(sx > 0), self.cells.x0) - i128::from(a2.x)).abs();
            let ny = (side(r + i64::from(sy > 0), self.cells.y0) - i128::from(a2.y)).abs();
            let order = match (sx, sy) {
                (0, _) => std::cmp::Ordering::Greater,
                (_, 0) => std::cmp::Ordering::Less,
                _ => (nx * dy.abs()).cmp(&(ny * dx.abs())),
            };
            match order {
                std::cmp::Ordering::Less => c += sx,
                std::cmp::Ordering::Greater => r += sy,
                std::cmp::Ordering::Equal => {
                    visit(self.cells.at(c + sx, r));
                    visit(self.cells.at(c, r + sy));
                    c += sx;
                    r += sy;
                }
            }
            visit(self.cells.at(c, r));
        }
        debug_assert_eq!((c, r), (cb, rb), "the walk reaches the end's cell");
    }
}

/// A point with both coordinates doubled (the grid stays within 2^29, so
/// this fits in `i32`).
fn double(p: IntPoint) -> IntPoint {
    IntPoint::new(2 * p.x, 2 * p.y)
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    /// The hot pixels `a -> b` passes, by testing every hot pixel.
    fn every_pixel(hot: &[IntPoint], a: IntPoint, b: IntPoint) -> Option<Vec<IntPoint>> {
        let bins = PointBins {
            cells: Cells {
                x0: 0,
                y0: 0,
                size: i64::from(u32::MAX),
                cols: 1,
                rows: 1,
            },
            lists: vec![hot.to_vec()],
        };
        let mut cells = 0;
        bins.chain(a, b, &mut cells)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// The cell walk finds the hot pixels testing them all finds,
        /// squares touched at a side or a corner included: the points on
        /// a fine lattice put many squares' sides on cell sides.
        #[test]
        fn the_cell_walk_finds_every_hot_pixel(
            points in prop::collection::vec((0i32..40, 0i32..40), 2..120),
            ends in prop::collection::vec((0usize..1000, 0usize..1000), 1..30),
            scale in prop_oneof![Just(1), Just(2), Just(7)],
        ) {
            let mut hot: Vec<IntPoint> =
                points.iter().map(|&(x, y)| IntPoint::new(x * scale, y * scale)).collect();
            hot.sort_unstable_by_key(|p| (p.x, p.y));
            hot.dedup();
            let bins = PointBins::new(&hot);
            for (i, j) in ends {
                let (a, b) = (hot[i % hot.len()], hot[j % hot.len()]);
                if a == b {
                    continue;
                }
                let mut cells = 0;
                prop_assert_eq!(bins.chain(a, b, &mut cells), every_pixel(&hot, a, b));
            }
        }
    }

    #[test]
    fn a_long_diagonal_walks_a_line_of_cells_not_its_box() {
        // A diagonal of hot points with the whole span binned: the box of
        // the long diagonal covers every cell, the walk about `2 * side`.
        let side = 300;
        let hot: Vec<IntPoint> = (0..side)
            .flat_map(|k| [IntPoint::new(k * 10, 0), IntPoint::new(0, k * 10)])
            .collect();
        let bins = PointBins::new(&hot);
        let mut cells = 0;
        bins.chain(hot[0], IntPoint::new(10 * (side - 1), 10 * (side - 1)), &mut cells);
        let total = bins.cells.len() as u64;
        assert!(cells * 5 < total, "{cells} of {total} cells walked");
    }
}
