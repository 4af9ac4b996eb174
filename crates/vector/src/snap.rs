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

use crate::grid::div_round;
use crate::hot::HotPixels;
use crate::splitter::IntShapes;
use crate::sweep::{Segment, proper_crossings};

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
    /// Hot pixel quadtree nodes the edges visited to find the hot pixels
    /// they pass.
    pub nodes: u64,
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
    let hot_bins = HotPixels::new(&hot);
    // The chain of grid points each segment becomes (without its ends);
    // `None` when the segment is not rerouted.
    let chains: Vec<Option<Vec<IntPoint>>> = segments
        .iter()
        .map(|&(a, b)| hot_bins.chain(a, b, &mut stats.nodes))
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
