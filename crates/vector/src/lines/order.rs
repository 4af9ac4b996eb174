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
/// its last point is the nearer end. Objects are compact on the page, so
/// finishing one before the next travels less than sweeping the page once
/// per kind: on the spider at 1024 pixels, 2,727 pixels of pen-up travel
/// this way, 3,661 with each kind contiguous within its object, 5,343 with
/// each kind contiguous over the page (and 1,455 with no grouping at all).
/// `O(n^2)` in the polylines, small next to the visibility work.
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
    let mut out = Vec::with_capacity(left.len());
    let mut pen = start;
    let mut object: Option<u32> = None;
    // Squared: only compared, and `hypot` per end per step was most of the
    // time of a drawing with thousands of polylines.
    let dist = |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).powi(2) + (a.1 - b.1).powi(2);
    for _ in 0..left.len() {
        // The nearest end in the current object, else anywhere.
        let mut best = [(f64::INFINITY, 0, false); 2];
        for (k, l) in left.iter().enumerate() {
            let Some(l) = l else { continue };
            let (Some(&first), Some(&last)) = (l.points.first(), l.points.last()) else {
                continue;
            };
            let level = usize::from(object != Some(l.group));
            for (d, reversed) in [(dist(pen, first), false), (dist(pen, last), true)] {
                if d < best[level].0 {
                    best[level] = (d, k, reversed);
                }
            }
        }
        let Some(&(_, k, reversed)) = best.iter().find(|b| b.0.is_finite()) else {
            break;
        };
        let Some(mut l) = left[k].take() else { break };
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
