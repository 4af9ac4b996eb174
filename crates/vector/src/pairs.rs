//! How one triangle hides another: the exact test whether two screen
//! triangles' interiors overlap, and, where they do, which part of the
//! nearer one covers the other.
//!
//! Window depth is an affine function of window position on every
//! triangle (scratchapixel's depth-buffer lesson), so the difference of
//! two depth planes is affine too, and the set where one triangle is
//! nearer than another is a half-plane: the pair's cut line is straight.
//! That is what makes the object-space answer exact up to rounding the
//! cut points to the grid.

use hider_geom::edge::orient2d;
use hider_geom::fixed::FixedPt;
use hider_scene::ScreenTri;
use i_overlay::i_float::int::point::IntPoint;

use crate::grid::Grid;

/// Whether two positively oriented triangles' interiors overlap, decided
/// exactly on their fixed-point vertices: by the separating axis theorem,
/// two convex polygons have disjoint interiors exactly when one of their
/// edges has the other polygon entirely on its closed outer side.
pub fn interiors_overlap(a: &ScreenTri, b: &ScreenTri) -> bool {
    corners_overlap(&a.v, &b.v)
}

/// [`interiors_overlap`] on the vertices alone.
pub fn corners_overlap(a: &[FixedPt; 3], b: &[FixedPt; 3]) -> bool {
    let separated = |p: &[FixedPt; 3], q: &[FixedPt; 3]| {
        (0..3).any(|k| {
            let (e0, e1) = (p[k], p[(k + 1) % 3]);
            q.iter().all(|&c| orient2d(e0, e1, c) <= 0)
        })
    };
    !separated(a, b) && !separated(b, a)
}

/// What an overlapping triangle `U` does to a triangle `T` over their
/// common area.
#[derive(Clone, Debug, PartialEq)]
pub enum Relation {
    /// `U` is behind `T` wherever both are (or ties and loses).
    Behind,
    /// `U` is in front of `T` wherever both are (or ties and wins).
    Front,
    /// The depth planes cross inside the common area: this part of `U`
    /// (a convex polygon on the grid) is in front.
    Cut(Vec<IntPoint>),
}

/// The difference `depth_hi - depth_lo` of two triangles' depth planes,
/// always formed in the same order for a pair, so that both triangles'
/// views of their cut line are computed bit for bit alike.
#[derive(Clone, Copy, Debug)]
struct DepthDiff<'a> {
    lo: &'a ScreenTri,
    hi: &'a ScreenTri,
}

impl DepthDiff<'_> {
    fn eval(&self, x: f64, y: f64) -> f64 {
        self.hi.depth.eval(x, y) - self.lo.depth.eval(x, y)
    }
}

/// The relation of `u` to `t` (indices `ti`, `ui` into the scene's
/// triangles, `u_poly` the image-clipped polygon of `u` on the grid),
/// with `tolerance` the window-depth difference that counts as a tie.
/// Exact ties go to the lower primitive id, like a LESS depth test drawing
/// in primitive order.
pub fn relation(
    grid: &Grid,
    (ti, t): (usize, &ScreenTri),
    (ui, u): (usize, &ScreenTri),
    u_poly: &[IntPoint],
    tolerance: f64,
) -> Relation {
    // Depth ranges apart by more than the tolerance decide at once: a
    // plane over a triangle stays within its corners' depths.
    let range = |x: &ScreenTri| {
        (
            x.z[0].min(x.z[1]).min(x.z[2]),
            x.z[0].max(x.z[1]).max(x.z[2]),
        )
    };
    let ((t_min, t_max), (u_min, u_max)) = (range(t), range(u));
    if u_max + tolerance < t_min {
        return Relation::Front;
    }
    if u_min > t_max + tolerance {
        return Relation::Behind;
    }
    let (lo, hi, sign) = if ti < ui { (t, u, 1.0) } else { (u, t, -1.0) };
    let diff = DepthDiff { lo, hi };
    // The common area, always clipped in the same order for the pair.
    let common = common_area(lo, hi);
    if common.is_empty() {
        return Relation::Behind;
    }
    let (mut dmin, mut dmax) = (f64::INFINITY, f64::NEG_INFINITY);
    for &(x, y) in &common {
        // d > 0 where `u` is behind `t`.
        let d = sign * diff.eval(x, y);
        dmin = dmin.min(d);
        dmax = dmax.max(d);
    }
    if dmin >= -tolerance && dmax <= tolerance {
        return if u.prim < t.prim {
            Relation::Front
        } else {
            Relation::Behind
        };
    }
    if dmin >= -tolerance {
        return Relation::Behind;
    }
    if dmax <= tolerance {
        return Relation::Front;
    }
    // Keep the part of `u` where it is nearer: d < 0.
    let cut = clip_by_plane(grid, u_poly, |x, y| sign * diff.eval(x, y));
    if cut.len() < 3 {
        Relation::Behind
    } else {
        Relation::Cut(cut)
    }
}

/// `lo` clipped by `hi`'s three edges, in pixels (f64).
fn common_area(lo: &ScreenTri, hi: &ScreenTri) -> Vec<(f64, f64)> {
    let mut poly: Vec<(f64, f64)> = lo.v.iter().map(|p| p.to_pixels()).collect();
    let hv: Vec<(f64, f64)> = hi.v.iter().map(|p| p.to_pixels()).collect();
    for k in 0..3 {
        let (a, b) = (hv[k], hv[(k + 1) % 3]);
        // Positive inside (the triangles are positively oriented).
        let side = |p: (f64, f64)| (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0);
        poly = clip_convex(&poly, side);
        if poly.len() < 3 {
            return Vec::new();
        }
    }
    poly
}

/// Sutherland-Hodgman: the part of `poly` where `side >= 0`.
pub fn clip_convex(poly: &[(f64, f64)], side: impl Fn((f64, f64)) -> f64) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(poly.len() + 1);
    for k in 0..poly.len() {
        let a = poly[k];
        let b = poly[(k + 1) % poly.len()];
        let (sa, sb) = (side(a), side(b));
        if sa >= 0.0 {
            out.push(a);
        }
        if (sa >= 0.0) != (sb >= 0.0) {
            let s = sa / (sa - sb);
            out.push((a.0 + s * (b.0 - a.0), a.1 + s * (b.1 - a.1)));
        }
    }
    out
}

/// The part of an integer polygon where `d(x, y) < 0` (`d` in pixels),
/// cut points rounded to the grid.
fn clip_by_plane(grid: &Grid, poly: &[IntPoint], d: impl Fn(f64, f64) -> f64) -> Vec<IntPoint> {
    let px: Vec<(f64, f64)> = poly.iter().map(|&p| grid.to_pixels(p)).collect();
    let kept = clip_convex(&px, |(x, y)| -d(x, y));
    let mut out: Vec<IntPoint> = kept
        .iter()
        .map(|&(x, y)| {
            let (gx, gy) = grid.from_pixels(x, y);
            IntPoint::new(gx.round() as i32, gy.round() as i32)
        })
        .collect();
    out.dedup();
    while out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    out
}

/// The segment where two triangles' depth planes cross inside their
/// common area, in pixels, with its window depth at both ends; `None`
/// when they do not cross there.
pub fn intersection_segment(
    a: &ScreenTri,
    b: &ScreenTri,
    ai: usize,
    bi: usize,
) -> Option<[(f64, f64, f64); 2]> {
    let (lo, hi) = if ai < bi { (a, b) } else { (b, a) };
    let diff = DepthDiff { lo, hi };
    let common = common_area(lo, hi);
    let n = common.len();
    let mut ends = Vec::with_capacity(2);
    for k in 0..n {
        let (p, q) = (common[k], common[(k + 1) % n]);
        let (dp, dq) = (diff.eval(p.0, p.1), diff.eval(q.0, q.1));
        if (dp < 0.0) != (dq < 0.0) && dp != dq {
            let s = dp / (dp - dq);
            let (x, y) = (p.0 + s * (q.0 - p.0), p.1 + s * (q.1 - p.1));
            ends.push((x, y, lo.depth.eval(x, y)));
        }
    }
    (ends.len() == 2).then(|| [ends[0], ends[1]])
}
