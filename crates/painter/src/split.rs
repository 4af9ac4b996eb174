//! Splitting a convex polygon by a line (Sutherland & Hodgman 1974, one
//! clip plane, keeping both sides).
//!
//! The painter works in window space, where a plane of the scene is the
//! graph of an affine window-depth function (window depth `z/w` is affine
//! in the pixel position). Cutting polygon P "by the plane of Q" is then
//! cutting its screen footprint along the line where the two depth planes
//! meet, `d_P(x, y) - d_Q(x, y) = 0`: every split the algorithm makes is a
//! split of a convex 2D polygon by an affine function of `(x, y)`, which is
//! what this module does.
//!
//! The geometry here is only used to *decide* the order. Which pixel centres
//! a piece covers is decided separately and exactly by [`crate::Cut`], so
//! rounding in the intersection points computed here can never open a crack
//! or paint a pixel twice.

use glam::DVec2;
use hider_geom::PlaneEq;

use crate::sides::Tag;

/// A polygon with a [`Tag`] per vertex.
pub(crate) type Tagged = (Vec<DVec2>, Vec<Tag>);

/// Splits the convex polygon `poly` (window pixels, either orientation) by
/// the line `f(x, y) = 0`, carrying each vertex's [`Tag`]: `negative`
/// receives the part where `f <= 0`, `positive` the part where `f >= 0`.
/// Both keep the input's orientation. A side that is not a proper polygon
/// (fewer than three distinct vertices) is left empty. Both outputs are
/// cleared first.
///
/// Each crossing point is computed once and pushed to both sides, so the
/// two halves share their new edge bit for bit. A vertex kept keeps its
/// tag, a crossing on the edge `a -> b` lies on the planes both `a` and
/// `b` lie on and on `plane` (the plane whose meeting line `f` is, if
/// any).
pub(crate) fn split_tagged(
    (poly, tags): (&[DVec2], &[Tag]),
    f: &PlaneEq,
    plane: Option<u32>,
    negative: &mut Tagged,
    positive: &mut Tagged,
) {
    for side in [&mut *negative, &mut *positive] {
        side.0.clear();
        side.1.clear();
    }
    let push = |out: &mut Tagged, p: DVec2, tag: Tag| {
        if out.0.last() != Some(&p) {
            out.0.push(p);
            out.1.push(tag);
        }
    };
    let n = poly.len();
    for k in 0..n {
        let (a, b) = (poly[k], poly[(k + 1) % n]);
        let (fa, fb) = (f.eval(a.x, a.y), f.eval(b.x, b.y));
        if fa <= 0.0 {
            push(negative, a, tags[k]);
        }
        if fa >= 0.0 {
            push(positive, a, tags[k]);
        }
        if (fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0) {
            let p = a + (b - a) * (fa / (fa - fb));
            let tag = Tag::crossing(tags[k], tags[(k + 1) % n], plane);
            push(negative, p, tag);
            push(positive, p, tag);
        }
    }
    for side in [negative, positive] {
        if side.0.len() > 1 && side.0.first() == side.0.last() {
            side.0.pop();
            side.1.pop();
        }
        if side.0.len() < 3 {
            side.0.clear();
            side.1.clear();
        }
    }
}

/// Twice the signed area of a polygon (positive for the orientation the
/// screen triangles use: clockwise on the y-down screen).
#[cfg(test)]
pub(crate) fn doubled_area(poly: &[DVec2]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|k| {
            let a = poly[k];
            let b = poly[(k + 1) % n];
            // Same sign convention as `hider_geom::orient2d`.
            a.x * b.y - a.y * b.x
        })
        .sum::<f64>()
}

/// The range `(min, max)` of `f` over a polygon's vertices: for an affine
/// `f` and a convex polygon, its range over the whole polygon.
pub(crate) fn range_over(poly: &[DVec2], f: &PlaneEq) -> (f64, f64) {
    poly.iter()
        .map(|p| f.eval(p.x, p.y))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The untagged split, the plain Sutherland-Hodgman step whose
    /// vertices [`split_tagged`] must give: splits the convex polygon
    /// `poly` by the line `f(x, y) = 0` into `negative` (`f <= 0`) and
    /// `positive` (`f >= 0`), both cleared first, keeping the input's
    /// orientation and leaving a side with fewer than three distinct
    /// vertices empty; each crossing is computed once and pushed to both
    /// sides.
    fn split_convex(
        poly: &[DVec2],
        f: &PlaneEq,
        negative: &mut Vec<DVec2>,
        positive: &mut Vec<DVec2>,
    ) {
        negative.clear();
        positive.clear();
        let n = poly.len();
        for k in 0..n {
            let a = poly[k];
            let b = poly[(k + 1) % n];
            let fa = f.eval(a.x, a.y);
            let fb = f.eval(b.x, b.y);
            if fa <= 0.0 {
                push_distinct(negative, a);
            }
            if fa >= 0.0 {
                push_distinct(positive, a);
            }
            if (fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0) {
                // t in (0, 1) because fa and fb have strictly opposite signs.
                let t = fa / (fa - fb);
                let p = a + (b - a) * t;
                push_distinct(negative, p);
                push_distinct(positive, p);
            }
        }
        for side in [negative, positive] {
            if side.len() > 1 && side.first() == side.last() {
                side.pop();
            }
            if side.len() < 3 {
                side.clear();
            }
        }
    }

    fn push_distinct(out: &mut Vec<DVec2>, p: DVec2) {
        if out.last() != Some(&p) {
            out.push(p);
        }
    }

    fn line_x(c: f64) -> PlaneEq {
        // f(x, y) = x - c
        PlaneEq {
            x0: c,
            y0: 0.0,
            value: 0.0,
            dx: 1.0,
            dy: 0.0,
        }
    }

    fn square() -> Vec<DVec2> {
        // Positive orientation in y-down window coordinates.
        vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(4.0, 0.0),
            DVec2::new(4.0, 4.0),
            DVec2::new(0.0, 4.0),
        ]
    }

    #[test]
    fn square_splits_into_two_rectangles_sharing_the_cut() {
        let (mut neg, mut pos) = (Vec::new(), Vec::new());
        split_convex(&square(), &line_x(1.0), &mut neg, &mut pos);
        assert_eq!(neg.len(), 4);
        assert_eq!(pos.len(), 4);
        assert_eq!(doubled_area(&neg), 8.0);
        assert_eq!(doubled_area(&pos), 24.0);
        assert!(neg.iter().all(|p| p.x <= 1.0));
        assert!(pos.iter().all(|p| p.x >= 1.0));
        assert!(neg.contains(&DVec2::new(1.0, 0.0)) && pos.contains(&DVec2::new(1.0, 0.0)));
    }

    #[test]
    fn a_line_missing_or_touching_the_polygon_leaves_one_side_empty() {
        let (mut neg, mut pos) = (Vec::new(), Vec::new());
        split_convex(&square(), &line_x(9.0), &mut neg, &mut pos);
        assert_eq!(neg, square());
        assert!(pos.is_empty());
        // Touching along an edge: the positive side is a degenerate segment.
        split_convex(&square(), &line_x(4.0), &mut neg, &mut pos);
        assert_eq!(neg, square());
        assert!(pos.is_empty());
        // Through a vertex only.
        let diag = PlaneEq {
            x0: 0.0,
            y0: 0.0,
            value: 0.0,
            dx: 1.0,
            dy: 1.0,
        };
        split_convex(&square(), &diag, &mut neg, &mut pos);
        assert!(neg.is_empty());
        assert_eq!(pos, square());
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        #[test]
        fn halves_partition_the_area(
            c in -1.0f64..5.0, dx in -1.0f64..1.0, dy in -1.0f64..1.0,
        ) {
            prop_assume!(dx.abs() + dy.abs() > 1e-3);
            let f = PlaneEq { x0: c, y0: 2.0, value: 0.0, dx, dy };
            let (mut neg, mut pos) = (Vec::new(), Vec::new());
            split_convex(&square(), &f, &mut neg, &mut pos);
            let total = doubled_area(&neg) + doubled_area(&pos);
            prop_assert!((total - 32.0).abs() < 1e-9, "areas {} + {}", doubled_area(&neg), doubled_area(&pos));
            for p in &neg { prop_assert!(f.eval(p.x, p.y) <= 1e-12); }
            for p in &pos { prop_assert!(f.eval(p.x, p.y) >= -1e-12); }
            prop_assert!(doubled_area(&neg) >= 0.0 && doubled_area(&pos) >= 0.0);
        }

        #[test]
        fn the_tagged_split_has_the_untagged_vertices(
            c in -1.0f64..5.0, dx in -1.0f64..1.0, dy in -1.0f64..1.0,
        ) {
            let f = PlaneEq { x0: c, y0: 2.0, value: 0.0, dx, dy };
            let (mut neg, mut pos) = (Vec::new(), Vec::new());
            split_convex(&square(), &f, &mut neg, &mut pos);
            let tags: Vec<Tag> = (0..4).map(|k| Tag::corner(k % 3)).collect();
            let (mut tneg, mut tpos) = Default::default();
            split_tagged((&square(), &tags), &f, Some(1), &mut tneg, &mut tpos);
            let (tneg, tpos): (Tagged, Tagged) = (tneg, tpos);
            prop_assert_eq!(&neg, &tneg.0);
            prop_assert_eq!(&pos, &tpos.0);
            prop_assert_eq!(tneg.0.len(), tneg.1.len());
            prop_assert_eq!(tpos.0.len(), tpos.1.len());
        }
    }
}
