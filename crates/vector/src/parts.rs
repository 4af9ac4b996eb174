//! Map-wide booleans split into independent parts.
//!
//! A boolean over the whole map (the covered set's outline, the closing
//! pass, a face group's union) is one `i_overlay` call, whose splitter
//! past 32,000 segments cuts every segment at the columns of a grid about
//! `sqrt(segments)` wide: a long segment becomes `sqrt` fragments, and a
//! face group of `N` long parallel slivers cost `N^1.5` time and memory
//! (859 MB at 32,000 slivers). Shapes whose closed bounding boxes do not
//! meet share no point, so the boolean of the whole is the concatenation
//! of the booleans of the parts the boxes chain into: each call then sees
//! only its own part, and the slivers' calls stay small.

use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap};

use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay::ShapeType;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::i_float::int::point::IntPoint;

use crate::contact::contact_sets;
use crate::grid::{Grid, bounds};
use crate::splitter::{IntShapes, new_overlay};

/// The work of the map-wide booleans.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BooleanWork {
    /// Booleans run.
    pub booleans: u64,
    /// Segments (contour points) sent into them, summed.
    pub segments: u64,
    /// The most segments sent into one of them.
    pub largest: u64,
}

impl BooleanWork {
    /// Counts one boolean of `segments` segments.
    pub fn add(&mut self, segments: usize) {
        self.booleans += 1;
        self.segments += segments as u64;
        self.largest = self.largest.max(segments as u64);
    }
}

/// Segments above which a part of chained boxes is split further by
/// contact ([`contact_sets`]): below, `i_overlay`'s sweep list handles
/// it at once.
const REFINE_ABOVE: usize = 2_000;

/// Mean segments per shape above which a part is not refined: few big
/// shapes (the outline's merges near the root on a pile) overlap as a
/// rule, and testing their contact costs the product of their edges.
const MEAN_SEGMENTS: usize = 16;

/// A box: lowest and highest corner, closed.
type Box2 = (IntPoint, IntPoint);

/// The items (by index) in parts whose closed boxes chain together:
/// two items with meeting boxes are in one part. Items without a box are
/// left out. Parts are ordered by their first item, items ascending.
///
/// A sweep in y keeps the live parts (those whose box reaches the sweep
/// line) in a map by their boxes' x intervals, which it keeps disjoint:
/// an item merges with the run of live parts its x interval meets, and
/// the merged box meets no other live part (their intervals lay outside
/// the run). Every live box spans the sweep line, so an item's box meets
/// a live part's exactly when their x intervals meet. A part's box
/// over-covers its items, so parts can come out coarser than the meeting
/// relation makes them, never finer: `O(n log n)` whatever the overlap
/// (the spokes of a fan make one part without testing their pairs).
pub fn parts(boxes: &[Option<Box2>]) -> Vec<Vec<usize>> {
    let mut order: Vec<usize> = (0..boxes.len()).filter(|&k| boxes[k].is_some()).collect();
    order.sort_unstable_by_key(|&k| (boxes[k].map(|b| b.0.y), k));
    // Union-find over the items; a part's box is held by its root, which
    // is always the item whose arrival made it.
    let mut parent: Vec<usize> = (0..boxes.len()).collect();
    let mut part_box: Vec<Option<Box2>> = boxes.to_vec();
    let mut live: BTreeMap<i32, usize> = BTreeMap::new();
    let mut expiry: BinaryHeap<Reverse<(i32, usize)>> = BinaryHeap::new();
    for &k in &order {
        let (mut lo, mut hi) = boxes[k].expect("ordered items have boxes");
        while let Some(&Reverse((top, r))) = expiry.peek() {
            if top >= lo.y {
                break;
            }
            expiry.pop();
            if parent[r] == r {
                let (rlo, _) = part_box[r].expect("a root has a box");
                live.remove(&rlo.x);
            }
        }
        // The live parts whose x intervals meet [lo.x, hi.x]: the last
        // starting at or before lo.x (if it reaches it), then all
        // starting within.
        let mut run: Vec<usize> = Vec::new();
        if let Some((_, &r)) = live.range(..=lo.x).next_back()
            && part_box[r].is_some_and(|(_, rhi)| rhi.x >= lo.x)
        {
            run.push(r);
        }
        run.extend(live.range(lo.x..=hi.x).map(|(_, &r)| r));
        run.dedup();
        for r in run {
            let (rlo, rhi) = part_box[r].expect("a root has a box");
            live.remove(&rlo.x);
            parent[r] = k;
            lo = IntPoint::new(lo.x.min(rlo.x), lo.y.min(rlo.y));
            hi = IntPoint::new(hi.x.max(rhi.x), hi.y.max(rhi.y));
        }
        part_box[k] = Some((lo, hi));
        live.insert(lo.x, k);
        expiry.push(Reverse((hi.y, k)));
    }
    let mut index_of_root = vec![usize::MAX; boxes.len()];
    let mut out: Vec<Vec<usize>> = Vec::new();
    for (k, b) in boxes.iter().enumerate() {
        if b.is_none() {
            continue;
        }
        // With path halving: the merges of a fan chain every spoke.
        let mut r = k;
        while parent[r] != r {
            parent[r] = parent[parent[r]];
            r = parent[r];
        }
        if index_of_root[r] == usize::MAX {
            index_of_root[r] = out.len();
            out.push(Vec::new());
        }
        out[index_of_root[r]].push(k);
    }
    out
}

/// The box of a shape (all its contours' points).
pub fn shape_box(contours: &[Vec<IntPoint>]) -> Option<Box2> {
    bounds(contours.iter().flatten())
}

/// `rule` (by non-zero fill) over `shapes`, each a shape (outer contour
/// and holes) that is a subject or a clip, one boolean per part of
/// [`parts`]; a part without a subject is skipped (every rule this crate
/// uses gives nothing there). The result is the one boolean's, in its
/// order.
pub fn overlay_by_parts(
    grid: &Grid,
    shapes: &[(&[Vec<IntPoint>], ShapeType)],
    rule: OverlayRule,
    work: &mut BooleanWork,
) -> IntShapes {
    overlay_by_parts_filled(grid, shapes, rule, FillRule::NonZero, work)
}

/// [`overlay_by_parts`] under the fill rule `fill`.
pub fn overlay_by_parts_filled(
    grid: &Grid,
    shapes: &[(&[Vec<IntPoint>], ShapeType)],
    rule: OverlayRule,
    fill: FillRule,
    work: &mut BooleanWork,
) -> IntShapes {
    let boxes: Vec<Option<Box2>> = shapes.iter().map(|(s, _)| shape_box(s)).collect();
    let mut out = IntShapes::new();
    let mut finer: Vec<Vec<usize>> = Vec::new();
    for part in parts(&boxes) {
        let segments: usize = part.iter().flat_map(|&k| shapes[k].0).map(Vec::len).sum();
        if segments <= REFINE_ABOVE || segments > MEAN_SEGMENTS * part.len() {
            finer.push(part);
            continue;
        }
        let members: Vec<&[Vec<IntPoint>]> = part.iter().map(|&k| shapes[k].0).collect();
        // A set holding half the segments would at best halve the
        // largest boolean (the regions of a mesh or a pile all touch).
        match contact_sets(grid, &members, segments / 2) {
            Some(sets) => finer.extend(
                sets.into_iter()
                    .map(|set| set.into_iter().map(|i| part[i]).collect()),
            ),
            None => finer.push(part),
        }
    }
    for part in finer {
        if !part.iter().any(|&k| shapes[k].1 == ShapeType::Subject) {
            continue;
        }
        let segments: usize = part.iter().flat_map(|&k| shapes[k].0).map(Vec::len).sum();
        work.add(segments);
        let mut overlay = new_overlay(segments);
        for &k in &part {
            overlay.add_source(shapes[k].0, shapes[k].1);
        }
        out.extend(overlay.overlay(rule, fill));
    }
    // In the order one boolean gives them: by the least point (x, then
    // y) of the outer contour, so that a drawing's bytes do not depend on
    // how the map fell into parts.
    out.sort_by_cached_key(|shape| {
        shape
            .first()
            .and_then(|outer| outer.iter().min_by_key(|p| (p.x, p.y)).map(|p| (p.x, p.y)))
    });
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(12))]

        /// Split by contact, a union of 700 thin diagonal triangles on a
        /// coarse lattice, whose boxes chain into one part while most
        /// are apart (some touching at corners or along edges, some
        /// overlapping), is the one boolean's, shape for shape.
        #[test]
        fn parts_split_by_contact_give_the_one_boolean(
            tris in prop::collection::vec(
                ((0i32..160, 0i32..160), 4i32..24, 1i32..3, any::<bool>()),
                700..701),
        ) {
            let grid = Grid { shift: 0, width: 1_100, height: 1_100 };
            let shapes: Vec<Vec<Vec<IntPoint>>> = tris
                .iter()
                .map(|&((x, y), long, wide, up)| {
                    let far = if up { (x + long + wide, y + long) } else { (x + long, y + long + wide) };
                    vec![[(x, y), (x + long, y + long), far]
                        .iter()
                        .map(|&(px, py)| IntPoint::new(5 * px, 5 * py))
                        .collect()]
                })
                .collect();
            let input: Vec<_> = shapes
                .iter()
                .map(|s| (s.as_slice(), ShapeType::Subject))
                .collect();
            let mut work = BooleanWork::default();
            let split = overlay_by_parts(&grid, &input, OverlayRule::Subject, &mut work);
            let mut overlay = new_overlay(2_100);
            for s in &shapes {
                overlay.add_source(s, ShapeType::Subject);
            }
            let mut one = overlay.overlay(OverlayRule::Subject, FillRule::NonZero);
            one.sort_by_cached_key(|shape| {
                shape[0].iter().min_by_key(|p| (p.x, p.y)).map(|p| (p.x, p.y))
            });
            // Contact split the chained boxes further.
            let boxes: Vec<_> = shapes.iter().map(|s| shape_box(s)).collect();
            prop_assert!(work.booleans > parts(&boxes).len() as u64, "{work:?}");
            prop_assert_eq!(split, one);
        }
    }

    fn b(x0: i32, y0: i32, x1: i32, y1: i32) -> Option<Box2> {
        Some((IntPoint::new(x0, y0), IntPoint::new(x1, y1)))
    }

    #[test]
    fn meeting_boxes_chain_into_parts() {
        let boxes = [
            b(0, 0, 10, 1),
            b(0, 5, 10, 6),
            // Touches the first at its corner: one part.
            b(10, 1, 12, 3),
            None,
            // Overlaps the second only.
            b(9, 6, 20, 30),
            // Apart from all.
            b(30, 0, 31, 40),
            // Under the fourth's x range but below everything else.
            b(15, -10, 16, -1),
        ];
        assert_eq!(
            parts(&boxes),
            vec![vec![0, 2], vec![1, 4], vec![5], vec![6]]
        );
    }

    #[test]
    fn a_part_growing_wider_takes_in_the_live_parts_it_meets() {
        // The third box spans the first two, which are live.
        let boxes = [b(0, 0, 1, 10), b(5, 0, 6, 10), b(0, 2, 6, 3), b(8, 4, 9, 5)];
        assert_eq!(parts(&boxes), vec![vec![0, 1, 2], vec![3]]);
    }
}
