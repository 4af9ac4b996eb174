//! A triangle minus a deep pile of occluders, batch by batch.
//!
//! One boolean of a triangle against all `N` occluders over it intersects
//! the occluders with each other, and under a pile of depth `N` every one
//! of the `N` triangles would do so; cutting the triangle down by the
//! largest occluders first, a batch at a time, stops as soon as nothing is
//! left.

use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay::ShapeType;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::i_float::int::point::IntPoint;

use crate::snap::snap_round;
use crate::splitter::IntShapes;
use crate::splitter::Overlay;

/// Occluders subtracted in one boolean: past this, a triangle under a
/// deep pile of occluders (depth complexity `N` at one spot) is cut down
/// batch by batch, largest occluders first, and stops as soon as nothing
/// is left, instead of intersecting all `N` occluders with each other for
/// every one of the `N` triangles.
pub const BATCH: usize = 16;

/// `triangle` minus the union of `occluders` (reordered), by non-zero
/// fill: all occluders are positively oriented.
pub fn subtract(
    overlay: &mut Overlay,
    triangle: &[IntPoint],
    occluders: &mut [Vec<IntPoint>],
) -> IntShapes {
    if occluders.len() > BATCH {
        occluders.sort_by_key(|o| std::cmp::Reverse(area2(o)));
    }
    let mut rest: IntShapes = vec![vec![triangle.to_vec()]];
    let mut next = 0;
    let mut batch: Vec<IntShapes> = Vec::with_capacity(BATCH + 1);
    while next < occluders.len() {
        // Only occluders that still meet what is left can take anything.
        batch.clear();
        while next < occluders.len() && batch.len() < BATCH {
            let o = &occluders[next];
            next += 1;
            if next <= BATCH || rest.iter().any(|shape| meets(o, &shape[0])) {
                batch.push(vec![vec![o.clone()]]);
            }
        }
        if batch.is_empty() {
            break;
        }
        // Slivers crossing at tiny angles make the polygon library round
        // crossing after crossing, each making new ones; rounded once and
        // together beforehand, they have no crossings left to round.
        let thin = batch.iter().any(|o| is_sliver(&o[0][0]));
        batch.push(std::mem::take(&mut rest));
        if thin {
            snap_round(&mut batch);
        }
        overlay.clear();
        let (subject, clips) = batch.split_last().expect("the rest was pushed");
        overlay.add_source(subject, ShapeType::Subject);
        for o in clips {
            overlay.add_source(o, ShapeType::Clip);
        }
        rest = overlay.overlay(OverlayRule::Difference, FillRule::NonZero);
        if rest.is_empty() {
            break;
        }
    }
    rest
}

/// Whether a polygon is a sliver: narrower than 1/1024 of its longest
/// edge, as triangles seen nearly edge-on are.
pub fn is_sliver(poly: &[IntPoint]) -> bool {
    let n = poly.len();
    let longest = (0..n)
        .map(|k| {
            let (a, b) = (poly[k], poly[(k + 1) % n]);
            let (dx, dy) = (i128::from(b.x - a.x), i128::from(b.y - a.y));
            dx * dx + dy * dy
        })
        .max()
        .unwrap_or(0);
    // Width = 2 area / longest edge; compare squares to stay in integers.
    let a2 = i128::from(area2(poly));
    a2 * a2 * 1024 * 1024 < longest * longest
}

/// Whether a convex, positively oriented polygon may meet the inside of a
/// contour: false when one of its edges has the whole contour on its
/// closed outer side (a separating line), decided exactly.
fn meets(convex: &[IntPoint], contour: &[IntPoint]) -> bool {
    let n = convex.len();
    !(0..n).any(|k| {
        let (a, b) = (convex[k], convex[(k + 1) % n]);
        let (abx, aby) = (
            i64::from(b.x) - i64::from(a.x),
            i64::from(b.y) - i64::from(a.y),
        );
        contour.iter().all(|&c| {
            let (acx, acy) = (
                i64::from(c.x) - i64::from(a.x),
                i64::from(c.y) - i64::from(a.y),
            );
            i128::from(abx) * i128::from(acy) - i128::from(aby) * i128::from(acx) <= 0
        })
    })
}

/// Twice the area of a simple polygon, unsigned.
fn area2(poly: &[IntPoint]) -> i64 {
    let n = poly.len();
    (0..n)
        .map(|k| {
            let (a, b) = (poly[k], poly[(k + 1) % n]);
            i64::from(a.x) * i64::from(b.y) - i64::from(b.x) * i64::from(a.y)
        })
        .sum::<i64>()
        .abs()
}
