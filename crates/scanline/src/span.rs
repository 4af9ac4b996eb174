//! Visible-surface resolution along one span.
//!
//! A span is a run of pixels on a row between two consecutive edge
//! crossings, so the same set of polygons covers every pixel of it. Watkins
//! (1970) resolves a span as a whole: order the polygons in it by depth at
//! its left end; the nearest one is visible over the whole span unless some
//! other polygon's depth crosses it inside the span (the two polygons
//! interpenetrate), in which case the span is split at the crossing and the
//! rest is resolved the same way.
//!
//! Window depth is affine in the window position (scratchapixel's
//! depth-buffer lesson: `z/w`, not `z`, is what interpolates linearly on
//! screen), so along a row the depth
//! difference of two polygons is affine too and changes sign at most once:
//! "does `p` come in front of the head anywhere in the span" is the same
//! question as "is `p` in front at the span's right end". Every comparison
//! is the one a z-buffer makes at a pixel centre — the depth planes
//! evaluated there, smaller wins, equal depths go to the earlier triangle
//! (a LESS test drawing in primitive order) — and the crossing pixel is
//! pinned down by evaluating that comparison on both sides of it, so a
//! split lands exactly where a z-buffer would switch.
//!
//! No per-pixel depth buffer is used. A span that keeps splitting (a knot
//! of mutually piercing polygons) is finished by the documented fallback: a
//! z-buffer over one row segment, with the same comparison.

use hider_geom::PlaneEq;

use crate::stats::ScanlineStats;
use crate::trace::{Resolution, ScanlineTrace, SpanRecord};

/// What the span step needs of a polygon: its depth plane and its id.
/// Kept in a table by polygon slot, so that the active polygon list moves
/// only small entries when it is reordered.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Surface {
    /// Its window depth plane.
    pub plane: PlaneEq,
    /// The primitive id written for it.
    pub prim: u32,
}

/// A polygon in a span's active polygon list.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Active {
    /// Its window depth at the span position being resolved.
    pub depth: f64,
    /// Its polygon-table slot: triangle order, the tie-breaker, and the
    /// index of its [`Surface`].
    pub slot: u32,
}

/// Whether depth `dp` of slot `sp` wins over depth `dh` of slot `sh`: the
/// z-buffer's LESS test with ties to the earlier triangle.
#[inline]
fn beats(dp: f64, sp: u32, dh: f64, sh: u32) -> bool {
    dp < dh || (dp == dh && sp < sh)
}

/// The output row being written.
pub(crate) struct RowOut<'a> {
    /// The row index.
    pub row: u32,
    /// The frame's ids on this row.
    pub ids: &'a mut [u32],
    /// The frame's depths on this row.
    pub depth: &'a mut [f32],
    /// The surfaces, by polygon slot.
    pub surfaces: &'a [Surface],
    /// Where to record the runs, when recording.
    pub trace: Option<&'a mut ScanlineTrace>,
    /// The span being resolved (first, last column) and how many polygons
    /// cover it, for the record.
    pub span: (u32, u32, u32),
}

impl RowOut<'_> {
    /// Records a run when tracing: columns `x0..=x1`, primitive `prim`
    /// at depths `depth` at its two ends.
    fn record(&mut self, x0: u32, x1: u32, prim: u32, how: Resolution, depth: (f64, f64)) {
        let (span0, span1, polygons) = self.span;
        if let Some(t) = self.trace.as_deref_mut() {
            t.spans.push(SpanRecord {
                row: self.row,
                x0,
                x1,
                prim,
                how,
                depth0: depth.0,
                depth1: depth.1,
                span: (span0, span1),
                polygons,
            });
        }
    }

    /// Writes polygon `a` over columns `x0..=x1`.
    fn fill(&mut self, a: &Active, x0: u32, x1: u32, how: Resolution) {
        let surface = self.surfaces[a.slot as usize];
        let row = self.row;
        if self.trace.is_some() {
            let ends = (
                surface.plane.at_pixel(x0, row),
                surface.plane.at_pixel(x1, row),
            );
            self.record(x0, x1, surface.prim, how, ends);
        }
        let (ids, depth) = (
            &mut self.ids[x0 as usize..=x1 as usize],
            &mut self.depth[x0 as usize..=x1 as usize],
        );
        for ((id, d), i) in ids.iter_mut().zip(depth.iter_mut()).zip(x0..) {
            *id = surface.prim;
            *d = surface.plane.at_pixel(i, row) as f32;
        }
    }
}

/// Sorts the active polygon list nearest first, ties to the earlier
/// triangle ([`beats`]'s order). Between two spans the order changes only
/// where polygons entered or crossed, so the list is nearly sorted (depth
/// coherence); the standard library's stable sort finds the sorted runs
/// and merges them, close to linear then, and `N log N` when a span is
/// entered by thousands of polygons in no depth order at once (a pile of
/// tiny triangles over one pixel), where an insertion sort was quadratic.
/// Returns the comparisons made.
fn sort_by_depth(apl: &mut [Active]) -> u64 {
    let mut comparisons = 0;
    // `+ 0.0` turns -0 into +0, so that the total order agrees with `<`
    // (and `==`) on every depth a finite plane gives.
    apl.sort_by(|a, b| {
        comparisons += 1;
        (a.depth + 0.0)
            .total_cmp(&(b.depth + 0.0))
            .then(a.slot.cmp(&b.slot))
    });
    comparisons
}

/// The first column in `(lo, hi]` where `p` beats `h`, given that it does
/// not at `lo` and does at `hi` (`g_lo`, `g_hi`: depth of `p` minus depth
/// of `h` there). Guesses from the planes' crossing, then confirms or
/// narrows by bisection on the per-pixel comparison itself.
fn first_win(
    h: (&PlaneEq, u32),
    p: (&PlaneEq, u32),
    lo: u32,
    hi: u32,
    g: (f64, f64),
    row: u32,
    evals: &mut u64,
) -> u32 {
    let mut wins = |i: u32| {
        *evals += 2;
        beats(p.0.at_pixel(i, row), p.1, h.0.at_pixel(i, row), h.1)
    };
    // Invariant: p loses at a, wins at b.
    let (mut a, mut b) = (lo, hi);
    let denom = g.0 - g.1;
    if denom > 0.0 && denom.is_finite() && b - a > 1 {
        let t = (g.0 / denom).clamp(0.0, 1.0);
        let guess = (f64::from(lo) + (t * f64::from(hi - lo)).ceil())
            .clamp(f64::from(lo + 1), f64::from(hi)) as u32;
        if wins(guess) {
            b = guess;
            if b - 1 > a {
                if wins(b - 1) {
                    b -= 1;
                } else {
                    a = b - 1;
                }
            }
        } else {
            a = guess;
        }
    }
    while b - a > 1 {
        let mid = a + (b - a) / 2;
        if wins(mid) {
            b = mid;
        } else {
            a = mid;
        }
    }
    b
}

/// Resolves spans; holds the fallback's one-row buffer between frames.
#[derive(Clone, Debug, Default)]
pub(crate) struct SpanResolver {
    /// Fallback: nearest depth per column of the segment.
    row_depth: Vec<f64>,
    /// Fallback: index into the active polygon list of the nearest polygon.
    row_who: Vec<u32>,
}

impl SpanResolver {
    /// Makes the row buffer `width` long (the budget was checked before).
    pub fn prepare(&mut self, width: u32) {
        self.row_depth.resize(width as usize, f64::INFINITY);
        self.row_who.resize(width as usize, u32::MAX);
    }

    /// Bytes held (capacity).
    pub fn bytes(&self) -> u64 {
        (self.row_depth.capacity() * 8 + self.row_who.capacity() * 4) as u64
    }

    /// Resolves the span `x0..=x1` covered by the polygons of `apl`
    /// (non-empty) and writes the visible one at each pixel.
    pub fn resolve(
        &mut self,
        apl: &mut [Active],
        x0: u32,
        x1: u32,
        out: &mut RowOut<'_>,
        max_splits: u32,
        stats: &mut ScanlineStats,
    ) {
        stats.spans += 1;
        stats.span_polygons_max = stats.span_polygons_max.max(apl.len() as u64);
        out.span = (x0, x1, apl.len() as u32);
        if let [only] = apl {
            out.fill(only, x0, x1, Resolution::Whole);
            return;
        }
        let row = out.row;
        let surfaces = out.surfaces;
        let plane = |a: &Active| &surfaces[a.slot as usize].plane;
        let mut x0 = x0;
        let mut splits = 0;
        loop {
            for a in apl.iter_mut() {
                a.depth = surfaces[a.slot as usize].plane.at_pixel(x0, row);
            }
            stats.depth_evaluations += apl.len() as u64;
            stats.sort_comparisons += sort_by_depth(apl);
            let Some((head, rest)) = apl.split_first() else {
                return;
            };
            // Shrink `end` to the last column where `head` stays in front.
            let mut end = x1;
            let mut head_end = plane(head).at_pixel(end, row);
            stats.depth_evaluations += 1;
            for p in rest {
                if end == x0 {
                    break;
                }
                let p_end = plane(p).at_pixel(end, row);
                stats.depth_evaluations += 1;
                if beats(p_end, p.slot, head_end, head.slot) {
                    let g = (p.depth - head.depth, p_end - head_end);
                    let h = (plane(head), head.slot);
                    let q = (plane(p), p.slot);
                    end = first_win(h, q, x0, end, g, row, &mut stats.depth_evaluations) - 1;
                    head_end = plane(head).at_pixel(end, row);
                    stats.depth_evaluations += 1;
                }
            }
            if end == x1 {
                let how = if splits == 0 {
                    Resolution::Whole
                } else {
                    Resolution::Split
                };
                out.fill(head, x0, x1, how);
                break;
            }
            if splits >= max_splits {
                self.fallback(apl, x0, x1, out, stats);
                break;
            }
            out.fill(head, x0, end, Resolution::Split);
            splits += 1;
            x0 = end + 1;
        }
        if splits > 0 {
            stats.split_spans += 1;
            stats.splits += u64::from(splits);
        }
    }

    /// The fallback: a z-buffer over the row segment `x0..=x1` only, drawing
    /// the span's polygons with the same comparison.
    fn fallback(
        &mut self,
        apl: &[Active],
        x0: u32,
        x1: u32,
        out: &mut RowOut<'_>,
        stats: &mut ScanlineStats,
    ) {
        let n = (x1 - x0 + 1) as usize;
        let (depth, who) = (&mut self.row_depth[..n], &mut self.row_who[..n]);
        depth.fill(f64::INFINITY);
        who.fill(u32::MAX);
        let surfaces = out.surfaces;
        for (k, a) in apl.iter().enumerate() {
            let plane = surfaces[a.slot as usize].plane;
            for ((d, w), i) in depth.iter_mut().zip(who.iter_mut()).zip(x0..) {
                let z = plane.at_pixel(i, out.row);
                if *w == u32::MAX || beats(z, a.slot, *d, apl[*w as usize].slot) {
                    *d = z;
                    *w = k as u32;
                }
            }
        }
        let mut run_start = x0;
        for ((&d, &w), x) in depth.iter().zip(who.iter()).zip(x0..) {
            let prim_of = |w: u32| surfaces[apl[w as usize].slot as usize].prim;
            let prim = prim_of(w);
            out.ids[x as usize] = prim;
            out.depth[x as usize] = d as f32;
            if x == x1 || prim_of(who[(x + 1 - x0) as usize]) != prim {
                let start = depth[(run_start - x0) as usize];
                out.record(run_start, x, prim, Resolution::Fallback, (start, d));
                run_start = x + 1;
            }
        }
        stats.fallback_spans += 1;
        stats.fallback_pixels += n as u64;
        stats.depth_evaluations += (n * apl.len()) as u64;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Surfaces with depth `value + dx * x` on row 0; slot = prim = index.
    fn surfaces(lines: &[(f64, f64)]) -> Vec<Surface> {
        lines
            .iter()
            .zip(0..)
            .map(|(&(value, dx), prim)| Surface {
                plane: PlaneEq {
                    value,
                    dx,
                    ..PlaneEq::default()
                },
                prim,
            })
            .collect()
    }

    /// Resolves one span over the whole row with the polygons of `slots`.
    fn run(
        lines: &[(f64, f64)],
        slots: &[u32],
        width: u32,
        max_splits: u32,
    ) -> (Vec<u32>, ScanlineStats) {
        let surfaces = surfaces(lines);
        let mut apl: Vec<Active> = slots
            .iter()
            .map(|&slot| Active { depth: 0.0, slot })
            .collect();
        let mut ids = vec![u32::MAX; width as usize];
        let mut depth = vec![1.0; width as usize];
        let mut out = RowOut {
            row: 0,
            ids: &mut ids,
            depth: &mut depth,
            surfaces: &surfaces,
            trace: None,
            span: (0, 0, 0),
        };
        let mut r = SpanResolver::default();
        r.prepare(width);
        let mut stats = ScanlineStats::default();
        r.resolve(&mut apl, 0, width - 1, &mut out, max_splits, &mut stats);
        (ids, stats)
    }

    /// The per-pixel answer for the same planes.
    fn brute(lines: &[(f64, f64)], width: u32) -> Vec<u32> {
        let surfaces = surfaces(lines);
        (0..width)
            .map(|i| {
                let best = surfaces
                    .iter()
                    .min_by(|a, b| {
                        let (da, db) = (a.plane.at_pixel(i, 0), b.plane.at_pixel(i, 0));
                        da.total_cmp(&db).then(a.prim.cmp(&b.prim))
                    })
                    .unwrap();
                best.prim
            })
            .collect()
    }

    #[test]
    fn crossing_planes_split_exactly_where_the_comparison_flips() {
        // Depth 0.5 - 0.01 x vs 0.3: they cross at x = 20, the centre of
        // column 19.5 (between columns 19 and 20).
        let lines = [(0.5, -0.01), (0.3, 0.0)];
        let (ids, stats) = run(&lines, &[0, 1], 64, 16);
        assert_eq!(ids, brute(&lines, 64));
        assert_eq!(ids[0], 1);
        assert_eq!(ids[63], 0);
        assert_eq!((stats.spans, stats.split_spans, stats.splits), (1, 1, 1));
        assert_eq!(stats.fallback_spans, 0);
    }

    #[test]
    fn exact_ties_go_to_the_earlier_triangle() {
        let lines = [(0.9, 0.0), (0.9, 0.0), (0.4, 0.0), (0.4, 0.0)];
        let (ids, stats) = run(&lines, &[3, 2], 8, 16);
        assert!(ids.iter().all(|&id| id == 2));
        assert_eq!(stats.splits, 0);
    }

    #[test]
    fn many_crossings_fall_back_after_the_limit_and_agree() {
        // A fan of lines through different points: every one is in front
        // somewhere, so the span splits several times.
        let lines: Vec<(f64, f64)> = (0..6)
            .map(|k| (0.5 + 0.01 * f64::from(k * k), -0.001 * f64::from(k * 7)))
            .collect();
        let slots = [0, 1, 2, 3, 4, 5];
        let want = brute(&lines, 200);
        let (ids, free) = run(&lines, &slots, 200, u32::MAX);
        assert_eq!(ids, want);
        assert!(free.splits >= 2, "{free:?}");
        assert_eq!(free.fallback_spans, 0);
        let (ids, capped) = run(&lines, &slots, 200, 1);
        assert_eq!(ids, want);
        assert_eq!((capped.splits, capped.fallback_spans), (1, 1));
        assert!(capped.fallback_pixels > 0);
        let (ids, never) = run(&lines, &slots, 200, 0);
        assert_eq!(ids, want);
        assert_eq!((never.splits, never.fallback_pixels), (0, 200));
    }

    #[test]
    fn depth_order_is_the_comparison_order() {
        let mut apl = [(0.9, 0), (0.1, 1), (0.5, 3), (0.5, 2), (0.0, 5), (-0.0, 4)]
            .map(|(depth, slot)| Active { depth, slot });
        sort_by_depth(&mut apl);
        assert_eq!(apl.map(|a| a.slot), [4, 5, 1, 2, 3, 0]);
        for w in apl.windows(2) {
            assert!(beats(w[0].depth, w[0].slot, w[1].depth, w[1].slot));
        }
    }
}
