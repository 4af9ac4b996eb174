//! Closing the region map onto the covered set.
//!
//! After the snap rounding and the ownership pass the regions share no
//! area, but their union and the union of the triangles can still differ
//! by slivers narrower than one grid unit: the region contours were cut
//! and rounded by their own booleans, the triangles' outline was not. This
//! pass snap rounds the region contours and the triangles' outlines in one
//! arrangement (Hobby's "Practical segment intersection with finite
//! precision output"), so that no two edges of either cross except at grid
//! points and every boolean below is exact; it then clips the regions to
//! the covered set and hands each piece of the covered set no region holds
//! to the region it shares most vertices with.

use std::collections::{HashMap, HashSet};

use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay::ShapeType;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::i_float::int::point::IntPoint;

use crate::contact::shapes_touch;
use crate::grid::{Bins, Grid, bounds};
use crate::ownership::contours;
use crate::parts::{BooleanWork, overlay_by_parts};
use crate::splitter::IntShapes;
use crate::splitter::new_overlay;

/// The covered set's outline: the union of `polys` (the triangles on the
/// grid) that are not `hidden`, before snap rounding.
///
/// One boolean over all triangles would split every edge at every
/// crossing, and on a pile of large triangles nearly every pair crosses:
/// the arrangement is quadratic while the outline is small. So the union
/// is built up a tree instead, the triangles in Morton order of their
/// boxes' centres, `FAN_IN` sets at a time: each merge sees only the
/// outlines of its inputs, whose inner crossings earlier merges removed.
/// The crossings still on an outline are rounded to the grid as the
/// one-shot boolean rounds them. Each merge runs one boolean per part of
/// its shapes whose boxes chain together (`parts.rs`): near the root the
/// sets are the whole map, and `N` separate long slivers in one boolean
/// cost `N^1.5` in `i_overlay`'s fragment splitter.
pub fn outline(
    grid: &Grid,
    polys: &[Vec<IntPoint>],
    hidden: &[bool],
    work: &mut BooleanWork,
) -> IntShapes {
    let mut order: Vec<(u64, usize)> = polys
        .iter()
        .zip(hidden)
        .enumerate()
        .filter(|(_, (p, h))| p.len() >= 3 && !**h)
        .filter_map(|(k, (p, _))| bounds(p).map(|(lo, hi)| (morton(lo, hi), k)))
        .collect();
    order.sort_unstable();
    let mut sets: Vec<IntShapes> = order
        .chunks(FAN_IN)
        .map(|chunk| {
            let segments = chunk.iter().map(|&(_, k)| polys[k].len()).sum();
            work.add(segments);
            let mut overlay = new_overlay(segments);
            for &(_, k) in chunk {
                overlay.add_contour(&polys[k], ShapeType::Subject);
            }
            overlay.overlay(OverlayRule::Subject, FillRule::NonZero)
        })
        .collect();
    while sets.len() > 1 {
        sets = sets
            .chunks(FAN_IN)
            .map(|chunk| {
                let shapes: Vec<_> = chunk
                    .iter()
                    .flatten()
                    .map(|s| (s.as_slice(), ShapeType::Subject))
                    .collect();
                overlay_by_parts(grid, &shapes, OverlayRule::Subject, work)
            })
            .collect();
    }
    sets.pop().unwrap_or_default()
}

/// Sets merged by one boolean of [`outline`].
const FAN_IN: usize = 8;

/// The Morton code of a box's centre (grid units; the grid stays within
/// 2^29, so the centre's coordinates shifted to non-negative fit 31 bits).
fn morton(lo: IntPoint, hi: IntPoint) -> u64 {
    let spread = |v: i32| {
        let mut x = u64::from((v as u32) ^ 0x8000_0000) >> 1;
        x &= 0xffff_ffff;
        x = (x | (x << 16)) & 0x0000_ffff_0000_ffff;
        x = (x | (x << 8)) & 0x00ff_00ff_00ff_00ff;
        x = (x | (x << 4)) & 0x0f0f_0f0f_0f0f_0f0f;
        x = (x | (x << 2)) & 0x3333_3333_3333_3333;
        (x | (x << 1)) & 0x5555_5555_5555_5555
    };
    let cx = ((i64::from(lo.x) + i64::from(hi.x)) / 2) as i32;
    let cy = ((i64::from(lo.y) + i64::from(hi.y)) / 2) as i32;
    spread(cx) | (spread(cy) << 1)
}

/// Makes the union of `regions` equal `covered`, the outline snap rounded
/// in one arrangement with the regions (so every boolean here is exact).
///
/// The two map-wide booleans (what the regions hold outside the covered
/// set, and the covered set's gaps) run one per part (`parts.rs`).
pub fn close_to_cover(
    grid: &Grid,
    covered: &IntShapes,
    regions: &mut [IntShapes],
    work: &mut BooleanWork,
) {
    let mut shapes: Vec<(&[Vec<IntPoint>], ShapeType)> = regions
        .iter()
        .flatten()
        .map(|s| (s.as_slice(), ShapeType::Subject))
        .collect();
    shapes.extend(covered.iter().map(|s| (s.as_slice(), ShapeType::Clip)));
    let excess = overlay_by_parts(grid, &shapes, OverlayRule::Difference, work);
    remove_excess(grid, regions, excess);
    let mut shapes: Vec<(&[Vec<IntPoint>], ShapeType)> = covered
        .iter()
        .map(|s| (s.as_slice(), ShapeType::Subject))
        .collect();
    shapes.extend(
        regions
            .iter()
            .flatten()
            .map(|s| (s.as_slice(), ShapeType::Clip)),
    );
    let gap = overlay_by_parts(grid, &shapes, OverlayRule::Difference, work);
    if gap.is_empty() {
        return;
    }
    // Which regions have each vertex: a gap piece goes to the region it
    // shares most vertices with.
    let mut owners: HashMap<IntPoint, Vec<usize>> = HashMap::new();
    for (k, region) in regions.iter().enumerate() {
        for &p in region.iter().flatten().flatten() {
            owners.entry(p).or_default().push(k);
        }
    }
    for piece in gap {
        let mut counts: HashMap<usize, usize> = HashMap::new();
        let corners: HashSet<IntPoint> = piece.iter().flatten().copied().collect();
        for p in &corners {
            for &k in owners.get(p).into_iter().flatten() {
                *counts.entry(k).or_default() += 1;
            }
        }
        let owner = counts
            .into_iter()
            .map(|(k, c)| (c, k))
            .max()
            .map(|(_, k)| k);
        // A piece touching no region (left where a sliver's own region
        // vanished) goes to the region with the nearest vertex.
        if let Some(k) = owner.or_else(|| nearest(regions, &piece)) {
            regions[k] = boolean(&regions[k], &vec![piece], OverlayRule::Union);
        }
    }
}

/// Takes the pieces `excess` out of the regions. Every region whose box
/// meets a piece's box passes through a difference with it (which also
/// writes the region as `i_overlay` does: collinear points dropped), but
/// a piece sharing no point with a region changes nothing of that
/// difference, so only the pieces touching it run (found through the
/// bins, tested exactly), or one piece when none touches: diagonal
/// slivers' boxes all meet, and every piece against every region was
/// `pieces x regions` booleans.
fn remove_excess(grid: &Grid, regions: &mut [IntShapes], excess: IntShapes) {
    if excess.is_empty() {
        return;
    }
    let pieces: Vec<IntShapes> = excess.into_iter().map(|p| vec![p]).collect();
    let piece_boxes: Vec<_> = pieces.iter().map(|p| shapes_box(p)).collect();
    let bins = Bins::covering(grid, &pieces.iter().map(contours).collect::<Vec<_>>());
    let mut seen = vec![usize::MAX; pieces.len()];
    for (k, region) in regions.iter_mut().enumerate() {
        let Some(rb) = shapes_box(region) else {
            continue;
        };
        let Some(first) = piece_boxes
            .iter()
            .position(|pb| pb.is_some_and(|pb| meets(rb, pb)))
        else {
            continue;
        };
        let mut touching: Vec<usize> = Vec::new();
        bins.query_covering(&contours(region), |j| {
            let j = j as usize;
            if seen[j] != k {
                seen[j] = k;
                touching.push(j);
            }
        });
        touching.retain(|&j| {
            piece_boxes[j].is_some_and(|pb| meets(rb, pb))
                && region.iter().any(|s| shapes_touch(s, &pieces[j][0]))
        });
        touching.sort_unstable();
        if touching.is_empty() {
            touching.push(first);
        }
        for j in touching {
            *region = boolean(region, &pieces[j], OverlayRule::Difference);
        }
    }
}

/// The bounding box of a polygon set.
fn shapes_box(shapes: &[Vec<Vec<IntPoint>>]) -> Option<(IntPoint, IntPoint)> {
    bounds(shapes.iter().flatten().flatten())
}

/// Whether two boxes share area or boundary.
fn meets(a: (IntPoint, IntPoint), b: (IntPoint, IntPoint)) -> bool {
    a.0.x <= b.1.x && b.0.x <= a.1.x && a.0.y <= b.1.y && b.0.y <= a.1.y
}

/// The region with the vertex nearest to a vertex of `piece`.
fn nearest(regions: &[IntShapes], piece: &[Vec<IntPoint>]) -> Option<usize> {
    let far = |p: &IntPoint| {
        piece
            .iter()
            .flatten()
            .map(|q| {
                let (dx, dy) = (
                    i64::from(p.x) - i64::from(q.x),
                    i64::from(p.y) - i64::from(q.y),
                );
                dx * dx + dy * dy
            })
            .min()
            .unwrap_or(i64::MAX)
    };
    (0..regions.len())
        .filter_map(|k| {
            regions[k]
                .iter()
                .flatten()
                .flatten()
                .map(far)
                .min()
                .map(|d| (d, k))
        })
        .min()
        .map(|(_, k)| k)
}

/// One boolean of two polygon sets.
fn boolean(a: &IntShapes, b: &IntShapes, rule: OverlayRule) -> IntShapes {
    let mut overlay = new_overlay(64);
    overlay.add_source(a, ShapeType::Subject);
    overlay.add_source(b, ShapeType::Clip);
    overlay.overlay(rule, FillRule::NonZero)
}
