//! Drawing each stretch once and in plotting order: overlapping collinear
//! pieces reduced to one, and polylines ordered greedily for a pen plotter.

use super::Polyline;
use crate::chain::Piece;

/// Overlapping collinear pieces drawn once: distinct edges can project
/// onto one segment, or onto overlapping parts of one line (the long
/// edges of a sliver seen edge-on, a piece whose end was cut by one
/// occluder and whose neighbour's by another), and a plotter would draw
/// the overlap twice. Each piece keeps only what the pieces before it on
/// its line left uncovered: those found through buckets of direction
/// (1/1000 radian) and offset (2 pixels), neighbouring buckets included,
/// whose both ends lie within `ON_LINE` (1/500 pixel) of the piece's
/// line.
/// Visible pieces come first, in [`LineKind`](super::LineKind)'s order, then the hidden
/// ones, so a hidden piece under a visible one is dropped. Pieces under
/// 1/100 pixel (their direction is not known well enough) are kept as
/// they are.
pub(super) fn drop_doubles(
    mut visible: Vec<Piece>,
    mut hidden: Vec<Piece>,
) -> (Vec<Piece>, Vec<Piece>) {
    /// How far (pixels) a piece's ends may be from another's line and
    /// still count as on it: well inside any stroke.
    const ON_LINE: f64 = 2e-3;
    let order = |x: &Piece, y: &Piece| (x.2, x.3).cmp(&(y.2, y.3));
    visible.sort_by(order);
    hidden.sort_by(order);
    /// A direction and offset bucket, and the pieces in it by their ends.
    type Buckets = std::collections::HashMap<(i64, i64), Vec<([f64; 2], [f64; 2])>>;
    let mut lines = Buckets::new();
    let mut keep = |pieces: Vec<Piece>| {
        let mut out = Vec::with_capacity(pieces.len());
        for piece in pieces {
            let (a, b) = (piece.0, piece.1);
            let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
            let length = dx.hypot(dy);
            if length < 1e-2 {
                out.push(piece);
                continue;
            }
            let (ux, uy) = (dx / length, dy / length);
            // The direction folded to [0, pi), and the offset along its
            // normal, bucketed.
            let mut angle = dy.atan2(dx);
            if angle < 0.0 {
                angle += std::f64::consts::PI;
            }
            let (fx, fy) = (angle.cos(), angle.sin());
            let offset = -fy * a[0] + fx * a[1];
            // Offsets are measured from the origin: a direction known to
            // 1e-3 radian moves them by up to 1e-3 times the distance
            // from it, so their buckets are wide.
            let bucket = ((angle / 1e-3).round() as i64, (offset / 2.0).round() as i64);
            let along = |p: [f64; 2]| ux * (p[0] - a[0]) + uy * (p[1] - a[1]);
            let across = |p: [f64; 2]| (-uy * (p[0] - a[0]) + ux * (p[1] - a[1])).abs();
            // What of [0, length] no earlier piece on the line holds.
            let mut free = vec![(0.0, length)];
            let n = (std::f64::consts::PI / 1e-3).round() as i64;
            for da in -1..=1 {
                for dc in -1..=1 {
                    // Directions near 0 and near pi are the same line
                    // with opposite offsets.
                    let mut key = (bucket.0 + da, bucket.1 + dc);
                    if key.0 < 0 || key.0 >= n {
                        key = (key.0.rem_euclid(n), -bucket.1 + dc);
                    }
                    let Some(taken) = lines.get(&key) else {
                        continue;
                    };
                    for &(p, q) in taken {
                        if across(p) > ON_LINE || across(q) > ON_LINE {
                            continue;
                        }
                        let (c, d) = (along(p).min(along(q)), along(p).max(along(q)));
                        free = free
                            .into_iter()
                            .flat_map(|(x, y)| {
                                if d <= x || c >= y {
                                    vec![(x, y)]
                                } else {
                                    [(x, c.max(x)), (d.min(y), y)]
                                        .into_iter()
                                        .filter(|(p, q)| q - p > 1e-4)
                                        .collect()
                                }
                            })
                            .collect();
                    }
                }
            }
            lines
                .entry(bucket)
                .or_default()
                .push(([a[0], a[1]], [b[0], b[1]]));
            let at = |t: f64| {
                let f = t / length;
                [a[0] + f * dx, a[1] + f * dy, a[2] + f * (b[2] - a[2])]
            };
            for (x, y) in free {
                if x == 0.0 && y == length {
                    out.push(piece);
                } else {
                    out.push((at(x), at(y), piece.2, piece.3));
                }
            }
        }
        out
    };
    let visible = keep(visible);
    let hidden = keep(hidden);
    (visible, hidden)
}

/// The length of a polyline in pixels.
fn length(line: &Polyline) -> f64 {
    line.points
        .windows(2)
        .map(|w| (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1))
        .sum()
}

/// Drops polylines shorter than `min_length` and orders the rest for a
/// pen plotter, keeping each object group contiguous (the SVG's layers):
/// from the pen's position, greedily the object holding the nearest
/// polyline end, in it the nearest polyline (of any kind), reversed when
/// its last point is the nearer end (ties to the earlier polyline, then
/// to its first point). Objects are compact on the page, so
/// finishing one before the next travels less than sweeping the page once
/// per kind: on the spider at 1024 pixels, 2,727 pixels of pen-up travel
/// this way, 3,661 with each kind contiguous within its object, 5,343 with
/// each kind contiguous over the page (and 1,455 with no grouping at all).
/// The nearest end is found in a grid of the ends (see [`Ends`]), not by
/// looking at every one per step, which cost the square of the polylines
/// (48 s of the 128,000 slivers' lines).
pub(super) fn plot_order(
    lines: Vec<Polyline>,
    min_length: f64,
    start: (f64, f64),
) -> Vec<Polyline> {
    let mut left: Vec<Option<Polyline>> = lines
        .into_iter()
        .filter(|l| length(l) >= min_length)
        .map(Some)
        .collect();
    let ends: Vec<Option<[(f64, f64); 2]>> = left
        .iter()
        .map(|l| {
            let l = l.as_ref()?;
            Some([*l.points.first()?, *l.points.last()?])
        })
        .collect();
    let mut groups: std::collections::HashMap<u32, Vec<u32>> = std::collections::HashMap::new();
    for (k, l) in left.iter().enumerate() {
        if let (Some(l), Some(_)) = (l, ends[k]) {
            groups.entry(l.group).or_default().push(k as u32);
        }
    }
    let everything: Vec<u32> = (0..left.len() as u32)
        .filter(|&k| ends[k as usize].is_some())
        .collect();
    let mut all = Ends::new(&ends, &everything);
    let mut per_group: std::collections::HashMap<u32, Ends> = groups
        .into_iter()
        .map(|(g, ks)| (g, Ends::new(&ends, &ks)))
        .collect();
    let mut alive = vec![true; left.len()];
    let mut out = Vec::with_capacity(left.len());
    let mut pen = start;
    let mut object: Option<u32> = None;
    loop {
        // The nearest end in the current object, else anywhere (the
        // current object has none left then).
        let here = object
            .and_then(|g| per_group.get_mut(&g))
            .and_then(|e| e.nearest(pen, &ends, &alive));
        let Some((k, reversed)) = here.or_else(|| all.nearest(pen, &ends, &alive)) else {
            break;
        };
        let Some(mut l) = left[k].take() else { break };
        alive[k] = false;
        all.remaining -= 1;
        if let Some(e) = per_group.get_mut(&l.group) {
            e.remaining -= 1;
        }
        if reversed {
            l.points.reverse();
            l.depths.reverse();
        }
        pen = *l.points.last().unwrap_or(&pen);
        object = Some(l.group);
        out.push(l);
    }
    out
}

/// A uniform grid of polyline ends for nearest-end queries, about one
/// polyline a cell, entries of drawn polylines dropped from a cell when
/// a query looks at it.
struct Ends {
    origin: (f64, f64),
    size: f64,
    cols: i64,
    rows: i64,
    /// Per cell, (polyline, whether the end is its last point).
    cells: Vec<Vec<(u32, bool)>>,
    /// Polylines not drawn yet.
    remaining: usize,
}

impl Ends {
    fn new(ends: &[Option<[(f64, f64); 2]>], ks: &[u32]) -> Self {
        let points = || ks.iter().filter_map(|&k| ends[k as usize]).flatten();
        let (mut lo, mut hi) = (
            (f64::INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        for p in points() {
            lo = (lo.0.min(p.0), lo.1.min(p.1));
            hi = (hi.0.max(p.0), hi.1.max(p.1));
        }
        let n = ks.len().max(1) as f64;
        let (w, h) = ((hi.0 - lo.0).max(0.0), (hi.1 - lo.1).max(0.0));
        let size = ((w * h / n).sqrt()).max(w.max(h) / n).max(1e-9);
        let side = |extent: f64| {
            let cells = (extent / size).floor();
            if cells.is_finite() {
                cells as i64 + 1
            } else {
                1
            }
        };
        let (cols, rows) = (side(w), side(h));
        let mut grid = Self {
            origin: if lo.0.is_finite() { lo } else { (0.0, 0.0) },
            size,
            cols,
            rows,
            cells: vec![Vec::new(); (cols * rows) as usize],
            remaining: ks.len(),
        };
        for &k in ks {
            let Some(pair) = ends[k as usize] else {
                continue;
            };
            for (p, last) in [(pair[0], false), (pair[1], true)] {
                let (c, r) = grid.cell(p);
                grid.cells[(r * cols + c) as usize].push((k, last));
            }
        }
        grid
    }

    fn cell(&self, p: (f64, f64)) -> (i64, i64) {
        let at =
            |v: f64, o: f64, n: i64| (((v - o) / self.size).floor().max(0.0) as i64).min(n - 1);
        (
            at(p.0, self.origin.0, self.cols),
            at(p.1, self.origin.1, self.rows),
        )
    }

    /// The live polyline with the nearest end to `pen` (least squared
    /// distance, then least index, then its first point), searched ring
    /// by ring of cells around the pen's until no farther ring can hold
    /// a nearer end.
    fn nearest(
        &mut self,
        pen: (f64, f64),
        ends: &[Option<[(f64, f64); 2]>],
        alive: &[bool],
    ) -> Option<(usize, bool)> {
        if self.remaining == 0 {
            return None;
        }
        let dist = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).powi(2) + (a.1 - b.1).powi(2);
        let (pc, pr) = self.cell(pen);
        let mut best: Option<(f64, u32, bool)> = None;
        let reach = self.cols.max(self.rows);
        for ring in 0..=reach {
            for r in (pr - ring).max(0)..=(pr + ring).min(self.rows - 1) {
                let on_edge = r == pr - ring || r == pr + ring;
                let step = if on_edge { 1 } else { 2 * ring.max(1) };
                let mut c = pc - ring;
                while c <= pc + ring {
                    if (0..self.cols).contains(&c) {
                        let cell = &mut self.cells[(r * self.cols + c) as usize];
                        cell.retain(|&(k, _)| alive[k as usize]);
                        for &(k, last) in cell.iter() {
                            let Some(pair) = ends[k as usize] else {
                                continue;
                            };
                            let d = dist(pen, pair[usize::from(last)]);
                            let better = best.is_none_or(|(bd, bk, bl)| {
                                d.total_cmp(&bd).then(k.cmp(&bk)).then(last.cmp(&bl))
                                    == std::cmp::Ordering::Less
                            });
                            if better {
                                best = Some((d, k, last));
                            }
                        }
                    }
                    c += if ring == 0 { 1 } else { step };
                }
            }
            // Every cell beyond this ring is at least `ring` cells from
            // the pen's (clamped into the grid, which only brings it
            // nearer to the cells).
            let bound = ring as f64 * self.size;
            if best.is_some_and(|(d, _, _)| d <= bound * bound) {
                break;
            }
        }
        best.map(|(_, k, last)| (k as usize, last))
    }
}
