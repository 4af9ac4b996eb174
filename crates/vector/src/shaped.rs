//! Bins shaped like the triangles they hold.
//!
//! Square bins cost the square of the input on long parallel slivers: a
//! query along one sliver (its own polygon, or a segment on it) crosses
//! `W / s` bins of side `s`, each holding the `s / d` slivers of its row
//! (`d` their spacing), so it visits `W / d` entries, which grows with
//! `N` whatever `s` is. Bins as elongated as the triangles hold about one
//! sliver per row, so a query visits about as many entries as the
//! polygon has neighbours.
//!
//! [`ShapedBins`] are [`Bins`] in a frame shrunk along the triangles'
//! long axis (by their summed box widths over their summed box heights,
//! rounded down to an integer): a grid point `(x, y)` goes to
//! `(floor(x / a), floor(y / b))` with one of `a`, `b` equal to 1. A
//! shrunk polygon's corners are each within one unit of the exact image,
//! so every point of the exact image of a convex polygon lies within one
//! unit (along each axis) of the shrunk polygon; two polygons that meet
//! at a point therefore have shrunk polygons within two units of each
//! other. A query covers its convex polygons moved by `(+-2, +-2)` (four
//! copies): with bins at least 256 units tall, the row spans of the
//! copies hold the polygon's two-unit neighbourhood in every row, so an
//! item meeting the query shares a bin with it, as in [`Bins`].

use i_overlay::i_float::int::point::IntPoint;

use crate::grid::{Bins, Grid, bounds};

/// Largest elongation of the bins (either way).
const MAX_STRETCH: f64 = (1u64 << 20) as f64;

/// How far (shrunk units) a query reaches beyond its polygons: the
/// rounding of both its corners and the items' (see the module
/// documentation).
const REACH: i32 = 2;

/// [`Bins`] shaped like their items (see the module documentation).
pub struct ShapedBins {
    bins: Bins,
    /// Grid units per shrunk unit, along x and y (one of them 1).
    shrink: (i64, i64),
}

impl ShapedBins {
    /// [`Bins::covering_live`], shaped: bins of about one triangle each,
    /// holding `polys[k]` where `live[k]` is some.
    pub fn covering_live<T>(grid: &Grid, live: &[Option<T>], polys: &[Vec<IntPoint>]) -> Self {
        let kept = || {
            polys
                .iter()
                .zip(live)
                .filter(|(p, l)| l.is_some() && !p.is_empty())
                .map(|(p, _)| p)
        };
        let (mut wide, mut tall) = (0.0f64, 0.0f64);
        for (lo, hi) in kept().filter_map(|p| bounds(p)) {
            wide += f64::from(hi.x) - f64::from(lo.x) + 1.0;
            tall += f64::from(hi.y) - f64::from(lo.y) + 1.0;
        }
        let stretch = if tall > 0.0 { wide / tall } else { 1.0 };
        let stretch = stretch.clamp(1.0 / MAX_STRETCH, MAX_STRETCH);
        let shrink = if stretch >= 1.0 {
            (stretch as i64, 1)
        } else {
            (1, (1.0 / stretch) as i64)
        };
        let shrunk_grid = Grid {
            // Bins as fine as the count asks for, at least 256 units
            // (the copies of a query need four): the pixel floor of
            // `Bins::covering` would keep a sliver's row a pixel tall.
            shift: 0,
            width: grid.width / shrink.0 + 1,
            height: grid.height / shrink.1 + 1,
        };
        let shrunk: Vec<Vec<IntPoint>> = polys
            .iter()
            .zip(live)
            .map(|(p, l)| match l {
                Some(_) => p.iter().map(|&q| shrink_point(q, shrink)).collect(),
                None => Vec::new(),
            })
            .collect();
        let items: Vec<Vec<&[IntPoint]>> = shrunk
            .iter()
            .map(|p| match p.is_empty() {
                true => Vec::new(),
                false => vec![p.as_slice()],
            })
            .collect();
        Self {
            bins: Bins::covering(&shrunk_grid, &items),
            shrink,
        }
    }

    /// See [`Bins::with_groups`].
    #[allow(
        dead_code,
        reason = "for the pair phase in regions.rs (a hook its owner makes)"
    )]
    pub fn with_groups(self, groups: Vec<u32>) -> Self {
        Self {
            bins: self.bins.with_groups(groups),
            ..self
        }
    }

    /// Calls `visit` with every item sharing a bin with the convex
    /// polygons `contours` (grid units; an item may come more than once):
    /// every item whose polygon meets one of them among others.
    pub fn query_covering(&self, contours: &[&[IntPoint]], visit: impl FnMut(u32)) {
        let copies = self.copies(contours);
        let refs: Vec<&[IntPoint]> = copies.iter().map(Vec::as_slice).collect();
        self.bins.query_covering(&refs, visit);
    }

    /// [`ShapedBins::query_covering`], leaving out every item whose group
    /// is in `skip` (see [`Bins::query_covering_skipping`]).
    #[allow(
        dead_code,
        reason = "for the pair phase in regions.rs (a hook its owner makes)"
    )]
    pub fn query_covering_skipping(
        &self,
        contours: &[&[IntPoint]],
        skip: &[u32],
        visit: impl FnMut(u32),
    ) {
        let copies = self.copies(contours);
        let refs: Vec<&[IntPoint]> = copies.iter().map(Vec::as_slice).collect();
        self.bins.query_covering_skipping(&refs, skip, visit);
    }

    /// Each contour shrunk and moved by `(+-REACH, +-REACH)`.
    fn copies(&self, contours: &[&[IntPoint]]) -> Vec<Vec<IntPoint>> {
        let mut out = Vec::with_capacity(4 * contours.len());
        for c in contours {
            let shrunk: Vec<IntPoint> = c.iter().map(|&p| shrink_point(p, self.shrink)).collect();
            for (dx, dy) in [
                (-REACH, -REACH),
                (REACH, -REACH),
                (REACH, REACH),
                (-REACH, REACH),
            ] {
                out.push(
                    shrunk
                        .iter()
                        .map(|p| IntPoint::new(p.x + dx, p.y + dy))
                        .collect(),
                );
            }
        }
        out
    }
}

/// A grid point in the shrunk frame (rounded down).
fn shrink_point(p: IntPoint, (sx, sy): (i64, i64)) -> IntPoint {
    IntPoint::new(
        i64::from(p.x).div_euclid(sx) as i32,
        i64::from(p.y).div_euclid(sy) as i32,
    )
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::sweep::orient;

    /// Whether two convex polygons (counter-clockwise or clockwise) share
    /// a point: no edge of either separates them.
    fn meet(a: &[IntPoint], b: &[IntPoint]) -> bool {
        let separates = |p: &[IntPoint], q: &[IntPoint]| {
            let s = orient(p[0], p[1], p[2]).signum();
            (0..p.len()).any(|k| {
                let (e0, e1) = (p[k], p[(k + 1) % p.len()]);
                q.iter().all(|&x| orient(e0, e1, x) * s < 0)
            })
        };
        !separates(a, b) && !separates(b, a)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        /// Two triangles that share a point share a bin, whatever the
        /// shape of the bins: long thin ones side by side or crossing.
        #[test]
        fn triangles_that_meet_share_a_bin(
            tris in prop::collection::vec(
                (0i32..60_000, 0i32..60_000, 1i32..30_000, 1i32..400, 0i32..3, 0u8..8), 2..200),
        ) {
            let grid = Grid { shift: 0, width: 100_000, height: 100_000 };
            // Slivers: a corner, a long side, a short one, most along x,
            // some along y.
            let polys: Vec<Vec<IntPoint>> = tris
                .iter()
                .map(|&(x, y, len, thick, lean, turn)| {
                    let tall = turn == 0;
                    let pts = [(x, y), (x + len, y + lean), (x + len, y + thick)];
                    pts.iter()
                        .map(|&(a, b)| if tall { IntPoint::new(b, a) } else { IntPoint::new(a, b) })
                        .collect()
                })
                .filter(|p: &Vec<IntPoint>| orient(p[0], p[1], p[2]) != 0)
                .collect();
            let live: Vec<Option<()>> = polys.iter().map(|_| Some(())).collect();
            let bins = ShapedBins::covering_live(&grid, &live, &polys);
            for (i, p) in polys.iter().enumerate() {
                let mut found = vec![false; polys.len()];
                bins.query_covering(&[p.as_slice()], |k| found[k as usize] = true);
                for (j, q) in polys.iter().enumerate() {
                    prop_assert!(!meet(p, q) || found[j], "{i} {p:?} misses {j} {q:?}");
                }
            }
        }
    }
}
