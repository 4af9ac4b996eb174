//! The ownership pass: the snapped regions made disjoint.
//!
//! After the map-wide snap rounding each region, in ascending primitive
//! order, loses what the regions before it already own. Only regions the
//! snapping rerouted, or that meet one it rerouted, are differenced (two
//! regions the snapping left alone meet, as a rule, only along common
//! edges). Which earlier regions such a difference takes as clips used to
//! be every one whose box met it: on a fan or a cone every spoke's box
//! holds the centre, so 16 rerouted regions near a cone's apex made
//! 96,572 differences of 3.5 billion segments at 128,000 triangles.
//!
//! A region that shares no interior with the subject changes nothing of
//! the difference (its edges touching the subject's only split them at
//! points the output's collinear simplification removes again), so the
//! clips are now only the regions that overlap *some* other region: the
//! set covered at least twice is one boolean over the map (winding number
//! of the regions, outer contours counter-clockwise, plus the reversed
//! union, kept where positive), and the regions meeting its pieces are
//! found through the bins, each tested exactly. The differences still run
//! for the same regions, so the map is the same, byte for byte.

use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay::ShapeType;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::i_float::int::point::IntPoint;

use crate::cover::signed_area2;
use crate::grid::{Bins, Grid, bounds};
use crate::parts::{BooleanWork, overlay_by_parts, overlay_by_parts_filled};
use crate::splitter::{IntShapes, new_overlay};

/// A box: lowest and highest corner, closed.
type Box2 = (IntPoint, IntPoint);

/// What [`settle_ownership`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Ownership {
    /// Differences run.
    pub differences: u64,
    /// Segments sent into them, summed.
    pub segments: u64,
    /// Regions overlapping some other region after the snapping.
    pub overlapping: u64,
}

/// Makes the snapped regions disjoint: each region in ascending primitive
/// order that the snapping rerouted, or whose closed box meets (and
/// shares a bin with) an earlier non-empty rerouted one, loses what the
/// earlier regions overlapping it own. After snap rounding no two region
/// edges cross except at grid points, so these differences have nothing
/// to round and the result is exact.
pub fn settle_ownership(
    grid: &Grid,
    shapes: &mut [IntShapes],
    touched: &[bool],
    work: &mut BooleanWork,
) -> Ownership {
    let mut done = Ownership::default();
    if !touched.iter().any(|&t| t) {
        return done;
    }
    let boxes: Vec<_> = shapes
        .iter()
        .map(|s| bounds(s.iter().flatten().flatten()))
        .collect();
    let bins = Bins::covering(grid, &shapes.iter().map(contours).collect::<Vec<_>>());
    // Per region, the earlier rerouted regions it shares a bin and a box
    // with, found from the rerouted side, so that a map the snapping
    // barely touched (a fan, whose every region meets all the others at
    // its centre) queries few regions.
    let mut partners: Vec<Vec<u32>> = vec![Vec::new(); shapes.len()];
    for (j, _) in touched.iter().enumerate().filter(|(_, t)| **t) {
        let Some(jbox) = boxes[j] else { continue };
        bins.query_covering(&contours(&shapes[j]), |k| {
            let k = k as usize;
            if k > j
                && boxes[k].is_some_and(|kbox| !apart(kbox, jbox))
                && partners[k].last() != Some(&(j as u32))
            {
                partners[k].push(j as u32);
            }
        });
    }
    let overlapping = overlapping_regions(grid, shapes, touched, &boxes, &bins, work);
    done.overlapping = overlapping.iter().filter(|&&o| o).count() as u64;
    let clips = Bins::covering(
        grid,
        &shapes
            .iter()
            .zip(&overlapping)
            .map(|(s, &o)| if o { contours(s) } else { Vec::new() })
            .collect::<Vec<_>>(),
    );
    let mut seen = vec![usize::MAX; shapes.len()];
    for k in 0..shapes.len() {
        let Some(kbox) = boxes[k] else { continue };
        let earlier_touched = partners[k].iter().any(|&j| !shapes[j as usize].is_empty());
        if !touched[k] && !earlier_touched {
            continue;
        }
        let mut earlier = Vec::new();
        if overlapping[k] {
            clips.query_covering(&contours(&shapes[k]), |j| {
                let j = j as usize;
                if j >= k || seen[j] == k {
                    return;
                }
                seen[j] = k;
                if boxes[j].is_some_and(|jbox| !apart(kbox, jbox)) && !shapes[j].is_empty() {
                    earlier.push(j);
                }
            });
        }
        done.differences += 1;
        let segments =
            points(&shapes[k]) + earlier.iter().map(|&j| points(&shapes[j])).sum::<usize>();
        done.segments += segments as u64;
        work.add(segments);
        let mut overlay = new_overlay(segments);
        overlay.add_source(&shapes[k], ShapeType::Subject);
        for &j in &earlier {
            overlay.add_source(&shapes[j], ShapeType::Clip);
        }
        shapes[k] = overlay.overlay(OverlayRule::Difference, FillRule::NonZero);
    }
    done
}

/// Whether two closed boxes share no interior point.
fn apart(a: Box2, b: Box2) -> bool {
    b.1.x <= a.0.x || b.0.x >= a.1.x || b.1.y <= a.0.y || b.0.y >= a.1.y
}

/// The contours of a polygon set, as slices.
pub fn contours(shapes: &IntShapes) -> Vec<&[IntPoint]> {
    shapes.iter().flatten().map(Vec::as_slice).collect()
}

/// The points (segments) of a polygon set.
fn points(shapes: &IntShapes) -> usize {
    shapes.iter().flatten().map(Vec::len).sum()
}

/// Per region, whether it shares interior with some other region.
///
/// The set covered twice or more is one boolean over the map: every
/// region with its outer contours counter-clockwise (winding +1 inside,
/// holes -1), the regions' union reversed (-1 over all of it), kept where
/// the winding is positive. The regions meeting one of its pieces are
/// those of the bins the piece covers that share interior with it. A
/// region whose own shapes overlap each other shows up too: it only
/// gains clips that change nothing.
fn overlapping_regions(
    grid: &Grid,
    shapes: &[IntShapes],
    touched: &[bool],
    boxes: &[Option<Box2>],
    bins: &Bins,
    work: &mut BooleanWork,
) -> Vec<bool> {
    // The rerouted regions' contours may fold over themselves: their
    // boolean with nothing gives them as the fill rule reads them.
    let oriented: Vec<IntShapes> = shapes
        .iter()
        .zip(touched)
        .map(|(s, &t)| {
            if t {
                let mut overlay = new_overlay(points(s));
                overlay.add_source(s, ShapeType::Subject);
                overlay.overlay(OverlayRule::Subject, FillRule::NonZero)
            } else {
                counter_clockwise(s)
            }
        })
        .collect();
    let mut all: Vec<(&[Vec<IntPoint>], ShapeType)> = oriented
        .iter()
        .flatten()
        .map(|s| (s.as_slice(), ShapeType::Subject))
        .collect();
    let union = overlay_by_parts(grid, &all, OverlayRule::Subject, work);
    let reversed: IntShapes = union
        .into_iter()
        .map(|s| {
            s.into_iter()
                .map(|mut c| {
                    c.reverse();
                    c
                })
                .collect()
        })
        .collect();
    all.extend(reversed.iter().map(|s| (s.as_slice(), ShapeType::Subject)));
    let twice = overlay_by_parts_filled(grid, &all, OverlayRule::Subject, FillRule::Positive, work);
    let mut overlapping = vec![false; shapes.len()];
    for piece in &twice {
        let Some(pbox) = bounds(piece.iter().flatten()) else {
            continue;
        };
        let piece_contours: Vec<&[IntPoint]> = piece.iter().map(Vec::as_slice).collect();
        bins.query_covering(&piece_contours, |k| {
            let k = k as usize;
            if overlapping[k] || boxes[k].is_none_or(|kbox| apart(kbox, pbox)) {
                return;
            }
            overlapping[k] = shares_interior(&shapes[k], piece);
        });
    }
    overlapping
}

/// `shapes` with every shape's contours reversed where its outer contour
/// runs clockwise (a triangle no boolean has made runs either way).
fn counter_clockwise(shapes: &IntShapes) -> IntShapes {
    shapes
        .iter()
        .map(|shape| {
            let mut shape = shape.clone();
            if shape.first().is_some_and(|outer| signed_area2(outer) < 0) {
                shape.iter_mut().for_each(|c| c.reverse());
            }
            shape
        })
        .collect()
}

/// Whether `region` and the shape `piece` share interior (exact): a
/// separating edge when either is one convex contour, else their
/// intersection by a boolean (exact too: after the snapping their edges
/// cross only at grid points).
fn shares_interior(region: &IntShapes, piece: &[Vec<IntPoint>]) -> bool {
    let single = |s: &[Vec<Vec<IntPoint>>]| match s {
        [shape] => match shape.as_slice() {
            [outer] => Some(outer.clone()),
            _ => None,
        },
        _ => None,
    };
    let piece_set = vec![piece.to_vec()];
    for (a, b) in [(region, &piece_set), (&piece_set, region)] {
        if let Some(outer) = single(a)
            && separated(&outer, b.iter().flatten().flatten())
        {
            return false;
        }
    }
    let mut overlay = new_overlay(points(region) + points(&piece_set));
    overlay.add_source(region, ShapeType::Subject);
    overlay.add_source(&piece_set, ShapeType::Clip);
    !overlay
        .overlay(OverlayRule::Intersect, FillRule::NonZero)
        .is_empty()
}

/// Whether the convex contour `outer` has an edge with every point of
/// `others` on its closed outer side (then their interiors are apart).
/// A contour that is not convex separates nothing.
fn separated<'a>(outer: &[IntPoint], others: impl Iterator<Item = &'a IntPoint> + Clone) -> bool {
    let n = outer.len();
    let sign = signed_area2(outer).signum();
    if n < 3 || sign == 0 {
        return false;
    }
    let cross = |a: IntPoint, b: IntPoint, c: IntPoint| {
        (i128::from(b.x) - i128::from(a.x)) * (i128::from(c.y) - i128::from(a.y))
            - (i128::from(b.y) - i128::from(a.y)) * (i128::from(c.x) - i128::from(a.x))
    };
    let convex =
        (0..n).all(|k| cross(outer[k], outer[(k + 1) % n], outer[(k + 2) % n]) * sign >= 0);
    convex
        && (0..n).any(|k| {
            let (a, b) = (outer[k], outer[(k + 1) % n]);
            others.clone().all(|&p| cross(a, b, p) * sign <= 0)
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: i32, y: i32, s: i32) -> Vec<IntPoint> {
        vec![
            IntPoint::new(x, y),
            IntPoint::new(x + s, y),
            IntPoint::new(x + s, y + s),
            IntPoint::new(x, y + s),
        ]
    }

    #[test]
    fn the_library_writes_outer_contours_with_positive_area() {
        let mut overlay = new_overlay(8);
        let mut clockwise = square(0, 0, 10);
        clockwise.reverse();
        overlay.add_contour(&clockwise, ShapeType::Subject);
        let out = overlay.overlay(OverlayRule::Subject, FillRule::NonZero);
        assert!(signed_area2(&out[0][0]) > 0);
    }

    #[test]
    fn touching_squares_share_no_interior_and_nested_ones_do() {
        let a: IntShapes = vec![vec![square(0, 0, 10)]];
        assert!(!shares_interior(&a, &[square(10, 0, 10)]));
        assert!(shares_interior(&a, &[square(2, 2, 3)]));
        assert!(shares_interior(&a, &[square(5, 5, 10)]));
        // Not convex: the boolean decides.
        let l = vec![
            IntPoint::new(0, 0),
            IntPoint::new(20, 0),
            IntPoint::new(20, 5),
            IntPoint::new(5, 5),
            IntPoint::new(5, 20),
            IntPoint::new(0, 20),
        ];
        let ell: IntShapes = vec![vec![l]];
        assert!(!shares_interior(&ell, &[square(10, 10, 5)]));
        assert!(shares_interior(&ell, &[square(1, 1, 2)]));
    }
}
