//! The pair tests of Newell, Newell & Sancha (1972), in window space.
//!
//! The list is sorted far to near; P is the candidate to paint next and Q
//! another polygon still in the list. P may be painted before Q when any of
//! these holds, tried from cheapest to dearest:
//!
//! 1. their depth extents do not overlap (Q is entirely nearer);
//! 2. their x extents do not overlap;
//! 3. their y extents do not overlap;
//! 4. P lies entirely behind Q's plane (on the far side from the eye);
//! 5. Q lies entirely in front of P's plane;
//! 6. their projections on the screen do not overlap.
//!
//! Window space (x, y in pixels, z the window depth `z/w`) is a projective
//! image of camera space in which the viewing rays are parallel to the z
//! axis, so planes stay planes and "behind the plane of Q as seen from the
//! eye" becomes "larger window depth than Q's depth plane at the same
//! pixel": the plane tests compare affine depth functions at the
//! polygon's vertices (an affine function is extreme at the vertices of a
//! convex polygon).
//!
//! Tests 2, 3 and 6 are exact for uncut triangles, whose vertices are
//! fixed-point (every product below fits an `f64` mantissa), and touching
//! is allowed there: under the top-left rule a pixel centre on a shared
//! boundary belongs to at most one of two polygons with disjoint
//! interiors. Cut pieces have rounded vertices, and splitting makes them
//! touch all the time (the pieces around the point where three planes
//! meet touch at that point); counting such contacts as overlaps would
//! report cycles that no split can break. So for cut pieces an overlap
//! thinner than [`TOUCH`] counts as touching. A pixel centre that close to
//! both pieces lies on a line where they were cut by each other's planes
//! (a depth tie there), or on a shared triangle edge (owned by one side
//! under the top-left rule). Tests 4 and 5 allow `depth_epsilon` of slack,
//! so orders they decide are exact up to that depth difference.

use glam::DVec2;

use crate::piece::{Piece, depth_difference, edge_line};
use crate::split::range_over;

/// Overlap (pixels) under which bounding boxes and projections of cut
/// pieces count as touching: many orders of magnitude above the rounding
/// of their vertices (about 1e-14 pixel), far below pixel spacing.
pub const TOUCH: f64 = 1e-9;

/// Margin (pixels) by which the rasteriser widens a cut piece's box, so
/// that no centre it covers is skipped.
pub const CUT_MARGIN: f64 = 1e-6;

/// Which test settled a pair.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Decided {
    /// Test 1: disjoint depth extents.
    Depth,
    /// Test 2: disjoint x extents.
    X,
    /// Test 3: disjoint y extents.
    Y,
    /// Test 4: P behind Q's plane.
    PBehind,
    /// Test 5: Q in front of P's plane.
    QInFront,
    /// Test 6: projections do not overlap.
    Projection,
}

/// The outcome of testing whether P may be painted before Q.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Outcome {
    /// P may be painted before Q.
    Ok(Decided),
    /// Every test failed: painting P first might cover part of Q wrongly.
    Blocked(Blocked),
}

/// What the plane tests found for a blocked pair, for choosing between
/// moving Q and splitting.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Blocked {
    /// Range of `d_P - d_Q` over P's vertices (negative: P in front of
    /// Q's plane there).
    pub pq: (f64, f64),
    /// Range of `d_Q - d_P` over Q's vertices.
    pub qp: (f64, f64),
}

impl Blocked {
    /// Whether Q may be painted before P instead (tests 4 and 5 with the
    /// roles swapped): Q behind P's plane, or P in front of Q's plane.
    pub fn reverse_ok(&self, eps: f64) -> bool {
        self.qp.0 >= -eps || self.pq.1 <= eps
    }

    /// Whether Q's plane really cuts P (vertices beyond `eps` on both sides).
    pub fn q_plane_cuts_p(&self, eps: f64) -> bool {
        self.pq.0 < -eps && self.pq.1 > eps
    }

    /// Whether P's plane really cuts Q.
    pub fn p_plane_cuts_q(&self, eps: f64) -> bool {
        self.qp.0 < -eps && self.qp.1 > eps
    }
}

/// What tests 1 to 3 look at, small enough to keep inline in the sorted
/// list so that most pairs are settled without touching the pieces.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Extent {
    /// Nearest window depth.
    pub zmin: f64,
    /// Farthest window depth.
    pub zmax: f64,
    /// Bounding box, smallest corner.
    pub min: DVec2,
    /// Bounding box, largest corner.
    pub max: DVec2,
    /// Whether the piece is an uncut triangle (exact vertices).
    pub uncut: bool,
}

impl Extent {
    /// The extents of a piece.
    pub fn of(p: &Piece) -> Self {
        Self {
            zmin: p.zmin,
            zmax: p.zmax,
            min: p.min,
            max: p.max,
            uncut: p.is_uncut(),
        }
    }
}

/// Tests 1 to 3: whether disjoint depth, x or y extents let P be painted
/// before Q.
#[inline]
pub(crate) fn extents_decide(p: &Extent, q: &Extent, eps: f64) -> Option<Decided> {
    if q.zmax <= p.zmin + eps {
        return Some(Decided::Depth);
    }
    let touch = if p.uncut && q.uncut { 0.0 } else { TOUCH };
    if p.max.x <= q.min.x + touch || q.max.x <= p.min.x + touch {
        return Some(Decided::X);
    }
    if p.max.y <= q.min.y + touch || q.max.y <= p.min.y + touch {
        return Some(Decided::Y);
    }
    None
}

/// Runs tests 1 to 6 on the pair (P, Q). (The ordering loop runs tests 1
/// to 3 on its inline [`Extent`]s and calls [`may_precede_by_planes`].)
#[cfg(test)]
pub(crate) fn may_precede(p: &Piece, q: &Piece, eps: f64) -> Outcome {
    if let Some(d) = extents_decide(&Extent::of(p), &Extent::of(q), eps) {
        return Outcome::Ok(d);
    }
    may_precede_by_planes(p, q, eps)
}

/// Tests 4 to 6, for a pair whose extents overlap.
pub(crate) fn may_precede_by_planes(p: &Piece, q: &Piece, eps: f64) -> Outcome {
    let pq = range_over(&p.polygon, &depth_difference(&p.depth, &q.depth));
    if pq.0 >= -eps {
        return Outcome::Ok(Decided::PBehind);
    }
    let qp = range_over(&q.polygon, &depth_difference(&q.depth, &p.depth));
    if qp.1 <= eps {
        return Outcome::Ok(Decided::QInFront);
    }
    if !projections_overlap(p, q) {
        return Outcome::Ok(Decided::Projection);
    }
    Outcome::Blocked(Blocked { pq, qp })
}

/// Whether the interiors of the two pieces' screen projections may share a
/// pixel centre: false only when a separating line is found (one of the
/// polygons' edges, the separating-axis theorem for convex polygons) or
/// both are pieces of one triangle (whose cuts partition its centres).
pub(crate) fn projections_overlap(a: &Piece, b: &Piece) -> bool {
    if a.source == b.source {
        return false;
    }
    let exact = a.is_uncut() && b.is_uncut();
    !(separated_by_an_edge_of(a, b, exact) || separated_by_an_edge_of(b, a, exact))
}

fn separated_by_an_edge_of(a: &Piece, b: &Piece, exact: bool) -> bool {
    let n = a.polygon.len();
    for k in 0..n {
        let (p0, p1) = (a.polygon[k], a.polygon[(k + 1) % n]);
        let length = (p1 - p0).length();
        if length == 0.0 {
            continue;
        }
        // Any line with A on one side and B on the other separates them,
        // so a rounded edge direction does no harm: both polygons are
        // measured against the same computed line.
        let line = edge_line(p0, p1);
        let inner = min_over(&a.polygon, |v| line.eval(v.x, v.y));
        let outer = -min_over(&b.polygon, |v| -line.eval(v.x, v.y));
        // The line's values are distances times `length`.
        let touch = if exact { 0.0 } else { TOUCH * length };
        if outer <= inner + touch {
            return true;
        }
    }
    false
}

fn min_over(poly: &[DVec2], f: impl Fn(DVec2) -> f64) -> f64 {
    poly.iter().map(|v| f(*v)).fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_geom::{FixedPt, PlaneEq};
    use hider_scene::ScreenTri;

    fn tri(v: [(i32, i32); 3], z: [f64; 3], source: u32) -> Piece {
        let v = v.map(|(x, y)| FixedPt::new(x * 256, y * 256));
        let t = ScreenTri {
            v,
            z,
            w: [1.0; 3],
            depth: PlaneEq::from_points(&v, z).unwrap(),
            inv_w: PlaneEq::constant(1.0),
            prim: source,
            front_facing: true,
        };
        Piece::from_tri(&t, source)
    }

    #[test]
    fn disjoint_depths_decide_first() {
        let far = tri([(0, 0), (10, 0), (0, 10)], [0.8; 3], 0);
        let near = tri([(0, 0), (10, 0), (0, 10)], [0.2; 3], 1);
        assert!(matches!(
            may_precede(&far, &near, 1e-10),
            Outcome::Ok(Decided::Depth)
        ));
        // The near one overlaps the far one in depth and on screen, lies in
        // front of its plane, so the far one blocks it.
        let Outcome::Blocked(b) = may_precede(&near, &far, 1e-10) else {
            panic!("near before far must be blocked");
        };
        assert!(b.reverse_ok(1e-10));
        assert!(!b.q_plane_cuts_p(1e-10));
    }

    #[test]
    fn plane_tests_order_overlapping_depth_ranges() {
        // P is steep (0.1 .. 0.9), Q flat at 0.5 but entirely off P's
        // plane on the near side where they overlap on screen.
        let p = tri([(0, 0), (10, 0), (0, 10)], [0.9, 0.9, 0.1], 0);
        let q = tri([(0, 0), (4, 0), (0, 1)], [0.5; 3], 1);
        // P's plane at Q's vertices: 0.9, 0.9, 0.82 -> Q in front.
        assert!(matches!(
            may_precede(&p, &q, 1e-10),
            Outcome::Ok(Decided::QInFront)
        ));
        // Q first would need Q behind P's plane or P in front of Q's
        // plane: neither holds, so P blocks Q.
        assert!(matches!(may_precede(&q, &p, 1e-10), Outcome::Blocked(_)));
    }

    #[test]
    fn touching_triangles_are_separated_exactly() {
        // Share the edge (10,0)-(0,10); opposite sides.
        let a = tri([(0, 0), (10, 0), (0, 10)], [0.5; 3], 0);
        let b = tri([(10, 0), (10, 10), (0, 10)], [0.4; 3], 1);
        assert!(!projections_overlap(&a, &b));
        // Overlapping by one fixed-point unit is not separated.
        let mut c = b.clone();
        c.polygon[0].x -= 1.0 / 256.0;
        assert!(projections_overlap(&a, &c));
    }

    #[test]
    fn intersecting_triangles_block_both_ways_and_cut_each_other() {
        let p = tri([(0, 0), (10, 0), (0, 10)], [0.2, 0.8, 0.5], 0);
        let q = tri([(0, 0), (10, 0), (0, 10)], [0.8, 0.2, 0.5], 1);
        let Outcome::Blocked(b) = may_precede(&p, &q, 1e-10) else {
            panic!("intersecting triangles must block");
        };
        assert!(!b.reverse_ok(1e-10));
        assert!(b.q_plane_cuts_p(1e-10) && b.p_plane_cuts_q(1e-10));
    }
}
