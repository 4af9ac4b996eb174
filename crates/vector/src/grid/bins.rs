//! A uniform grid of bins over the image, shaped and turned like the
//! items it holds, listing each item in the bins its polygons meet.

use i_overlay::i_float::int::point::IntPoint;

use super::Grid;

/// A uniform grid of bins over the image, each listing the items whose
/// polygons meet it: the candidates for overlap with a given polygon or box.
pub struct Bins {
    /// The bins' frame: a grid point `(x, y)` is at `(a x + b y, a y - b
    /// x)` minus `origin` in it, for `frame = (a, b)`: the grid turned by
    /// the items' common direction (when they have one) and scaled by
    /// `|(a, b)|`, so that the bins' rows run along it. Integer, so that
    /// a polygon's bins are found exactly there.
    frame: (i64, i64),
    /// The least corner of the image in the frame.
    origin: (i64, i64),
    /// A bin's width and height, frame units.
    size: (i64, i64),
    cols: i64,
    rows: i64,
    cells: Vec<Vec<u32>>,
    /// Each item's group ([`crate::stars::NONE`] for none), when set.
    groups: Vec<u32>,
}

/// An item counts as long and thin, and votes for the bins' direction,
/// when its longest side is this many times the width across it.
const ELONGATED: f64 = 8.0;

/// Largest component of a turned frame ([`Bins::covering`]): directions
/// to within about 2 degrees, and frame coordinates within `2^35` of a
/// grid of `2^29`.
const FRAME_STEPS: f64 = 16.0;

impl Bins {
    /// A grid point in the frame.
    fn to_frame(&self, p: IntPoint) -> (i64, i64) {
        let (a, b) = self.frame;
        let (x, y) = (i64::from(p.x), i64::from(p.y));
        (a * x + b * y - self.origin.0, a * y - b * x - self.origin.1)
    }

    /// The bin (column, row) of a point in the frame, clamped to the bins.
    fn cell(&self, p: (i64, i64)) -> (i64, i64) {
        (
            p.0.div_euclid(self.size.0).clamp(0, self.cols - 1),
            p.1.div_euclid(self.size.1).clamp(0, self.rows - 1),
        )
    }

    /// Bins over `grid` of one polygon per triangle, `polys[k]` where
    /// `live[k]` is some (culled and clipped-away triangles hold none):
    /// [`Bins::covering`] of those, each in the
    /// bins its closed polygons meet (each polygon's bins row by row,
    /// between its leftmost and rightmost bin in the row: exact for a
    /// convex polygon, more for others), not in every bin of its box: the
    /// box of a long thin triangle (a spoke of a fan, a sliver seen
    /// edge-on) covers bins in proportion to its area, so that binning
    /// by boxes costs the square of the input on a fan.
    pub fn covering_live<T>(grid: &Grid, live: &[Option<T>], polys: &[Vec<IntPoint>]) -> Self {
        let items: Vec<Vec<&[IntPoint]>> = live
            .iter()
            .zip(polys)
            .map(|(b, p)| match b {
                Some(_) => vec![p.as_slice()],
                None => Vec::new(),
            })
            .collect();
        Self::covering(grid, &items)
    }

    /// Bins of about one item each over `grid`, holding each item in the
    /// bins its closed polygons meet (see [`Bins::covering_live`]).
    ///
    /// The bins are shaped like the items: with square bins, `N` long
    /// parallel slivers lie `sqrt(N)` to a row of bins and each meets the
    /// `sqrt(N)` bins of its row, so every sliver met every other of its
    /// row in every bin (`N^2` visits); bins as long as the slivers hold
    /// one or two. When most items are long and thin along one direction
    /// (by the mean of their longest sides' doubled angles) the bins are
    /// turned to it (an integer frame, `Bins::frame`): slivers laid along a diagonal have
    /// square boxes, and bins shaped by boxes stayed square. The bins
    /// are then stretched by the items' boxes in that frame (their
    /// geometric-mean width over height), keeping their area.
    pub fn covering(grid: &Grid, items: &[Vec<&[IntPoint]>]) -> Self {
        Self::covering_within(grid, items, usize::MAX).expect("no limit on the entries")
    }

    /// [`Bins::covering`], or `None` as soon as the bins would hold more
    /// than `max_entries` entries (items counted once per bin): big
    /// overlapping shapes each fill the bins of their area.
    pub fn covering_within(
        grid: &Grid,
        items: &[Vec<&[IntPoint]>],
        max_entries: usize,
    ) -> Option<Self> {
        let frame = common_direction(items);
        let (a, b) = frame;
        let corners = [
            (0, 0),
            (grid.width, 0),
            (0, grid.height),
            (grid.width, grid.height),
        ]
        .map(|(x, y)| (a * x + b * y, a * y - b * x));
        let origin = (
            corners.iter().map(|c| c.0).min().unwrap_or(0),
            corners.iter().map(|c| c.1).min().unwrap_or(0),
        );
        let extent = (
            corners.iter().map(|c| c.0).max().unwrap_or(0) - origin.0,
            corners.iter().map(|c| c.1).max().unwrap_or(0) - origin.1,
        );
        let mut bins = Self {
            frame,
            origin,
            size: (1, 1),
            cols: 1,
            rows: 1,
            cells: Vec::new(),
            groups: Vec::new(),
        };
        let mut count = 0usize;
        let mut log_aspect = 0.0;
        for contours in items {
            if let Some((lo, hi)) = bins.frame_bounds(contours) {
                count += 1;
                let extent = |a: i64, b: i64| ((b - a) as f64).max(1.0);
                log_aspect += extent(lo.0, hi.0).ln() - extent(lo.1, hi.1).ln();
            }
        }
        let scale = ((a * a + b * b) as f64).sqrt();
        let area = (grid.width as f64) * (grid.height as f64) * scale * scale;
        let side = (area / count.max(1) as f64)
            .sqrt()
            .max(grid.units_per_pixel() * scale);
        let stretch = (log_aspect / count.max(1) as f64 / 2.0).exp();
        // A bin keeps the area `side^2` (about one item each) and fits in
        // the frame's image box both ways.
        let (w, h) = (extent.0.max(1) as f64, extent.1.max(1) as f64);
        let sx = (side * stretch).min(w).max(side * side / h);
        bins.size = ((sx as i64).max(1), ((side * side / sx) as i64).max(1));
        bins.cols = extent.0 / bins.size.0 + 1;
        bins.rows = extent.1 / bins.size.1 + 1;
        bins.cells = vec![Vec::new(); (bins.cols * bins.rows) as usize];
        let mut cells = Vec::new();
        let mut entries = 0usize;
        for (k, contours) in items.iter().enumerate() {
            cells.clear();
            bins.cover(contours, |cell| cells.push(cell));
            cells.sort_unstable();
            cells.dedup();
            entries += cells.len();
            if entries > max_entries {
                return None;
            }
            for &cell in &cells {
                bins.cells[cell].push(k as u32);
            }
        }
        Some(bins)
    }

    /// The inclusive box of closed polygons in the frame.
    fn frame_bounds(&self, contours: &[&[IntPoint]]) -> Option<((i64, i64), (i64, i64))> {
        let mut points = contours
            .iter()
            .copied()
            .flatten()
            .map(|&p| self.to_frame(p));
        let first = points.next()?;
        Some(points.fold((first, first), |(lo, hi), p| {
            (
                (lo.0.min(p.0), lo.1.min(p.1)),
                (hi.0.max(p.0), hi.1.max(p.1)),
            )
        }))
    }

    /// Calls `visit` with every bin the closed polygons `contours` meet
    /// (a bin may come more than once).
    fn cover(&self, contours: &[&[IntPoint]], visit: impl FnMut(usize)) {
        self.cover_near(contours, 0, visit);
    }

    /// [`Bins::cover`] of the points within `near` grid units of the
    /// closed polygons (with the bins around them: every covered row's
    /// span widened, and taken over by the rows next to it, by as many
    /// bins as `near` reaches in the frame).
    fn cover_near(&self, contours: &[&[IntPoint]], near: i64, mut visit: impl FnMut(usize)) {
        let Some((lo, hi)) = self.frame_bounds(contours) else {
            return;
        };
        let (r0, r1) = (self.cell(lo).1, self.cell(hi).1);
        // Per row of bins, the least and greatest column the edges reach.
        let mut span = vec![(i64::MAX, i64::MIN); (r1 - r0 + 1) as usize];
        let col =
            |x: i128| ((x.div_euclid(i128::from(self.size.0))) as i64).clamp(0, self.cols - 1);
        for contour in contours {
            let n = contour.len();
            for k in 0..n {
                let (p, q) = (
                    self.to_frame(contour[k]),
                    self.to_frame(contour[(k + 1) % n]),
                );
                let (p, q) = if p.1 <= q.1 { (p, q) } else { (q, p) };
                let (er0, er1) = (self.cell(p).1, self.cell(q).1);
                let (dx, dy) = (
                    i128::from(q.0) - i128::from(p.0),
                    i128::from(q.1) - i128::from(p.1),
                );
                for r in er0..=er1 {
                    // The edge's part within the row's closed band, by
                    // its ends' x (floor and ceiling of the exact values).
                    let y0 = i128::from(p.1).max(i128::from(r * self.size.1));
                    let y1 = i128::from(q.1).min(i128::from((r + 1) * self.size.1));
                    let (xa, xb) = if dy == 0 {
                        (i128::from(p.0.min(q.0)), i128::from(p.0.max(q.0)))
                    } else {
                        let at = |y: i128| {
                            let num = i128::from(p.0) * dy + (y - i128::from(p.1)) * dx;
                            (num.div_euclid(dy), -(-num).div_euclid(dy))
                        };
                        let ((f0, c0), (f1, c1)) = (at(y0.min(y1)), at(y1.max(y0)));
                        (f0.min(f1), c0.max(c1))
                    };
                    let slot = &mut span[(r.clamp(r0, r1) - r0) as usize];
                    slot.0 = slot.0.min(col(xa));
                    slot.1 = slot.1.max(col(xb));
                }
            }
        }
        if near == 0 {
            for (i, &(c0, c1)) in span.iter().enumerate() {
                let r = r0 + i as i64;
                for c in c0..=c1 {
                    visit((r * self.cols + c) as usize);
                }
            }
            return;
        }
        // A displacement of `near` grid units is at most `near |frame|`
        // frame units along either frame axis.
        let reach = near.saturating_mul(self.frame.0.abs() + self.frame.1.abs());
        let (dc, dr) = (
            (reach + self.size.0 - 1) / self.size.0,
            (reach + self.size.1 - 1) / self.size.1,
        );
        for r in (r0 - dr).max(0)..=(r1 + dr).min(self.rows - 1) {
            let (c0, c1) = span
                [((r - dr).max(r0) - r0) as usize..=((r + dr).min(r1) - r0) as usize]
                .iter()
                .fold((i64::MAX, i64::MIN), |(a, b), &(c0, c1)| {
                    (a.min(c0), b.max(c1))
                });
            if c0 > c1 {
                continue;
            }
            for c in (c0 - dc).max(0)..=(c1 + dc).min(self.cols - 1) {
                visit((r * self.cols + c) as usize);
            }
        }
    }

    /// [`Bins::query_covering`] of the points within `near` grid units of
    /// the closed polygons `contours`.
    pub fn query_near(&self, contours: &[&[IntPoint]], near: i64, mut visit: impl FnMut(u32)) {
        self.cover_near(contours, near, |cell| {
            for &k in &self.cells[cell] {
                visit(k);
            }
        });
    }

    /// Gives the items groups (one per item, [`crate::stars::NONE`] for
    /// none), each bin's items of one group kept together (grouped items
    /// first, the rest after in their order), so that a query can skip a
    /// group it needs none of without looking at its items.
    pub fn with_groups(mut self, groups: Vec<u32>) -> Self {
        for cell in &mut self.cells {
            cell.sort_by_key(|&k| (groups[k as usize], k));
        }
        self.groups = groups;
        self
    }

    /// [`Bins::query_covering`], leaving out every item whose group (see
    /// [`Bins::with_groups`]) is in `skip`.
    pub fn query_covering_skipping(
        &self,
        contours: &[&[IntPoint]],
        skip: &[u32],
        mut visit: impl FnMut(u32),
    ) {
        let group = |k: u32| {
            self.groups
                .get(k as usize)
                .copied()
                .unwrap_or(crate::stars::NONE)
        };
        self.cover(contours, |cell| {
            let list = &self.cells[cell];
            let mut i = 0;
            while i < list.len() {
                let g = group(list[i]);
                if g != crate::stars::NONE && skip.contains(&g) {
                    i += list[i..].partition_point(|&k| group(k) == g);
                    continue;
                }
                visit(list[i]);
                i += 1;
            }
        });
    }

    /// Calls `visit` with every item of a [`Bins::covering`] that shares a
    /// bin with the closed polygons `contours` (an item may come more than
    /// once).
    pub fn query_covering(&self, contours: &[&[IntPoint]], mut visit: impl FnMut(u32)) {
        self.cover(contours, |cell| {
            for &k in &self.cells[cell] {
                visit(k);
            }
        });
    }
}

/// The frame `(a, b)` of [`Bins`] for `items`: the identity `(1, 0)`
/// unless at least a quarter of them, net, are long and thin
/// ([`ELONGATED`]) along one direction that is not an axis (the bins'
/// stretch serves those), else that direction to within
/// [`FRAME_STEPS`] steps. Votes are the longest sides' doubled angles,
/// so that opposite directions agree and crossing ones cancel.
fn common_direction(items: &[Vec<&[IntPoint]>]) -> (i64, i64) {
    let (mut cx, mut cy, mut count) = (0.0f64, 0.0f64, 0usize);
    for contours in items {
        // (squared length, dx, dy) of the longest side; twice the area.
        let mut longest = (0.0f64, 0.0f64, 0.0f64);
        let mut area2 = 0.0f64;
        for c in contours {
            for k in 0..c.len() {
                let (p, q) = (c[k], c[(k + 1) % c.len()]);
                let (px, py, qx, qy) = (
                    f64::from(p.x),
                    f64::from(p.y),
                    f64::from(q.x),
                    f64::from(q.y),
                );
                let (dx, dy) = (qx - px, qy - py);
                let l2 = dx * dx + dy * dy;
                if l2 > longest.0 {
                    longest = (l2, dx, dy);
                }
                area2 += px * qy - qx * py;
            }
        }
        if contours.iter().all(|c| c.is_empty()) {
            continue;
        }
        count += 1;
        // Longest side over the width across it: `L^2 / (2 A)`.
        let (l2, dx, dy) = longest;
        if l2 > 0.0 && l2 >= ELONGATED * area2.abs() {
            cx += (dx * dx - dy * dy) / l2;
            cy += 2.0 * dx * dy / l2;
        }
    }
    if cx.hypot(cy) < count as f64 / 4.0 {
        return (1, 0);
    }
    let angle = cy.atan2(cx) / 2.0;
    let (a, b) = (
        (FRAME_STEPS * angle.cos()).round() as i64,
        (FRAME_STEPS * angle.sin()).round() as i64,
    );
    if a == 0 || b == 0 {
        return (1, 0);
    }
    let g = gcd(a.abs(), b.abs());
    (a / g, b / g)
}

fn gcd(a: i64, b: i64) -> i64 {
    if b == 0 { a } else { gcd(b, a % b) }
}

#[cfg(test)]
pub(crate) mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::grid::bounds;
    use crate::sweep::orient;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        /// Every point of a closed triangle lies in a bin the triangle
        /// is binned in, so two triangles whose interiors overlap share
        /// a bin: long thin ones, ones along bin sides, points on them.
        #[test]
        fn a_triangle_is_binned_wherever_it_reaches(
            tris in prop::collection::vec(
                prop::array::uniform3((0i32..6_000, 0i32..6_000)), 1..12),
        ) {
            let grid = Grid { shift: 0, width: 6_000, height: 6_000 };
            let polys: Vec<Vec<IntPoint>> = tris
                .iter()
                .map(|t| t.iter().map(|&(x, y)| IntPoint::new(x, y)).collect())
                .collect();
            let items: Vec<Vec<&[IntPoint]>> = polys.iter().map(|p| vec![p.as_slice()]).collect();
            let bins = Bins::covering(&grid, &items);
            for (k, p) in polys.iter().enumerate() {
                let (lo, hi) = bounds(p).expect("three points");
                let inside = |q: IntPoint| {
                    let o = |a: IntPoint, b: IntPoint| {
                        i64::from(b.x - a.x) * i64::from(q.y - a.y)
                            - i64::from(b.y - a.y) * i64::from(q.x - a.x)
                    };
                    let s = [o(p[0], p[1]), o(p[1], p[2]), o(p[2], p[0])];
                    s.iter().all(|&v| v >= 0) || s.iter().all(|&v| v <= 0)
                };
                let step = ((hi.x - lo.x).max(hi.y - lo.y) / 60).max(1);
                let mut points: Vec<IntPoint> = p.clone();
                for x in (lo.x..=hi.x).step_by(step as usize) {
                    for y in (lo.y..=hi.y).step_by(step as usize) {
                        points.push(IntPoint::new(x, y));
                    }
                }
                for q in points.into_iter().filter(|&q| inside(q)) {
                    let (c, r) = bins.cell(bins.to_frame(q));
                    prop_assert!(
                        bins.cells[(r * bins.cols + c) as usize].contains(&(k as u32)),
                        "triangle {k} {p:?} not binned at {q:?}"
                    );
                }
            }
        }

        /// Two triangles that share a point share a bin, whatever the
        /// shape of the bins: long thin ones side by side or crossing,
        /// which stretch the bins, all turned by 45 degrees or by the
        /// angle of (4, 3), which turns them (`Bins::covering`).
        #[test]
        fn slivers_that_meet_share_a_bin(
            tris in prop::collection::vec(
                (0i32..60_000, 0i32..60_000, 1i32..30_000, 1i32..400, 0i32..3, 0u8..8), 2..200),
            all_turned in 0u8..3,
        ) {
            let grid = Grid { shift: 0, width: 500_000, height: 500_000 };
            let (c, s) = [(1, 0), (1, 1), (4, 3)][usize::from(all_turned)];
            // A corner, a long side, a short one; most along x, some
            // along y; then all turned (and moved into the image).
            let polys: Vec<Vec<IntPoint>> = tris
                .iter()
                .map(|&(x, y, len, thick, lean, turn)| {
                    let pts = [(x, y), (x + len, y + lean), (x + len, y + thick)];
                    pts.iter()
                        .map(|&(a, b)| if turn == 0 { (b, a) } else { (a, b) })
                        .map(|(a, b)| IntPoint::new(c * a - s * b + 250_000, s * a + c * b))
                        .collect()
                })
                .filter(|p: &Vec<IntPoint>| orient(p[0], p[1], p[2]) != 0)
                .collect();
            let live: Vec<Option<()>> = polys.iter().map(|_| Some(())).collect();
            let bins = Bins::covering_live(&grid, &live, &polys);
            for (i, p) in polys.iter().enumerate() {
                let mut found = vec![false; polys.len()];
                bins.query_covering(&[p.as_slice()], |k| found[k as usize] = true);
                for (j, q) in polys.iter().enumerate() {
                    prop_assert!(!meet(p, q) || found[j], "{i} {p:?} misses {j} {q:?}");
                }
            }
        }
    }

    /// Whether two convex polygons (either orientation) share a point: no
    /// edge of either separates them.
    pub(crate) fn meet(a: &[IntPoint], b: &[IntPoint]) -> bool {
        let separates = |p: &[IntPoint], q: &[IntPoint]| {
            let s = orient(p[0], p[1], p[2]).signum();
            (0..p.len()).any(|k| {
                let (e0, e1) = (p[k], p[(k + 1) % p.len()]);
                q.iter().all(|&x| orient(e0, e1, x) * s < 0)
            })
        };
        !separates(a, b) && !separates(b, a)
    }
}
