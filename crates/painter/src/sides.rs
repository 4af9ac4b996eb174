//! Which side of another triangle's plane a piece lies on: the sign
//! questions behind Newell, Newell & Sancha's tests 4 and 5 and behind
//! choosing a split.
//!
//! Window space (x, y in pixels, z the window depth) keeps planes planar,
//! so "is this vertex nearer than the plane of Q" is the sign of
//! `z - d_Q(x, y)`. A corner of a front-end triangle is exactly the point
//! the front end produced: x and y on the 1/256 pixel lattice (exact in
//! `f64`) and z its `f64` window depth; the plane of Q passes through
//! three such points. The side is then the sign of Shewchuk's `orient3d`
//! ("Adaptive Precision Floating-Point Arithmetic and Fast Robust
//! Geometric Predicates", the `robust` crate), exact and without any
//! tolerance. So the answer cannot depend on the scene's scale, on the
//! near plane (which squeezes every depth difference into the last bits of
//! window depth) or on symmetry, and a corner shared with Q is on Q's
//! plane exactly: mesh neighbours are ordered without slack.
//!
//! A vertex made by a split is rounded. It carries a [`Tag`]: the planes
//! whose meeting lines made it, on which it lies by construction (sign
//! zero, exactly). Against any other plane its sign is taken on the
//! rounded position with a tolerance ([`rounded_sign`]) of [`TOUCH`]
//! pixels along the depth difference's gradient plus a bound on the
//! rounding of the two plane evaluations: both scale with the depth
//! differences themselves, whatever the near plane. An order decided from
//! such a sign can only be wrong at pixel centres where the two planes are
//! that close (a tie).

use glam::DVec2;
use hider_geom::PlaneEq;
use hider_scene::ScreenTri;
use robust::{Coord3D, orient3d};

use crate::newell::TOUCH;
use crate::piece::Piece;

/// No plane, in a [`Tag`].
const NO_PLANE: u32 = u32::MAX;

/// No corner, in a [`Tag`].
const NO_CORNER: u8 = u8::MAX;

/// Where a polygon vertex of a piece comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Tag {
    /// The corner of the source triangle it is (exact), or [`NO_CORNER`].
    corner: u8,
    /// Triangles (indices into the scene's list) on whose planes it lies
    /// by construction, [`NO_PLANE`] for none.
    planes: [u32; 2],
}

impl Tag {
    /// Corner `k` of the source triangle.
    pub fn corner(k: usize) -> Self {
        Self {
            corner: k as u8,
            planes: [NO_PLANE; 2],
        }
    }

    /// The crossing of a cut line with the polygon edge `a -> b`: on the
    /// planes both ends lie on (the edge lies on them), and on `plane`
    /// when the cut is the meeting line with that triangle's plane.
    pub fn crossing(a: Tag, b: Tag, plane: Option<u32>) -> Self {
        let mut planes = [NO_PLANE; 2];
        let shared = a
            .planes
            .into_iter()
            .filter(|&t| t != NO_PLANE && b.planes.contains(&t));
        for (slot, t) in planes.iter_mut().zip(plane.into_iter().chain(shared)) {
            *slot = t;
        }
        if planes[0] == planes[1] {
            planes[1] = NO_PLANE;
        }
        Self {
            corner: NO_CORNER,
            planes,
        }
    }
}

/// Whether a piece has vertices strictly in front of (nearer than) and
/// strictly behind (farther than) another triangle's plane.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Sides {
    /// Some vertex is nearer than the plane.
    pub front: bool,
    /// Some vertex is farther than the plane.
    pub behind: bool,
}

impl Sides {
    /// The plane really cuts the piece: vertices on both sides.
    pub fn cut(&self) -> bool {
        self.front && self.behind
    }
}

/// The sides of the plane of `q`'s source triangle that `p`'s vertices lie
/// on. Pieces of one triangle share their plane: no side.
pub(crate) fn sides(p: &Piece, q: &Piece, tris: &[ScreenTri]) -> Sides {
    let mut s = Sides::default();
    if p.source == q.source {
        return s;
    }
    let (pt, qt) = (&tris[p.source as usize], &tris[q.source as usize]);
    for (v, tag) in p.polygon.iter().zip(&p.tags) {
        let sign = if tag.corner != NO_CORNER {
            corner_sign(pt, usize::from(tag.corner), qt)
        } else if tag.planes.contains(&q.source) {
            0
        } else {
            rounded_sign(*v, &p.depth, &q.depth)
        };
        s.front |= sign < 0;
        s.behind |= sign > 0;
    }
    s
}

/// The point the front end produced for corner `k` of `t`.
fn corner(t: &ScreenTri, k: usize) -> Coord3D<f64> {
    let (x, y) = t.v[k].to_pixels();
    Coord3D { x, y, z: t.z[k] }
}

/// Exactly: 1 when corner `k` of `p` is farther than the plane of `q`, -1
/// when nearer, 0 when on it.
pub(crate) fn corner_sign(p: &ScreenTri, k: usize, q: &ScreenTri) -> i8 {
    // A corner that is one of the three points spanning Q's plane lies on
    // it. Mesh neighbours share corners, and for those `orient3d` is
    // exactly zero, which its adaptive stages confirm only after
    // computing the whole exact expansion: the dearest case by far.
    if (0..3).any(|m| q.v[m] == p.v[k] && q.z[m].to_bits() == p.z[k].to_bits()) {
        return 0;
    }
    // `orient3d(a, b, c, d)` is `-(d.z - plane(d.x, d.y))` times twice the
    // signed area of `a, b, c` in (x, y), which is positive for the
    // front end's triangles.
    let o = orient3d(corner(q, 0), corner(q, 1), corner(q, 2), corner(p, k));
    if o < 0.0 {
        1
    } else if o > 0.0 {
        -1
    } else {
        0
    }
}

/// The sum of the magnitudes of the slope terms of `plane` at `v`: the
/// scale of the rounding of its evaluation there, beyond that of its
/// value (the front end's window depth at its reference corner, exact).
fn slope_terms(plane: &PlaneEq, v: DVec2) -> f64 {
    (plane.dx * (v.x - plane.x0)).abs() + (plane.dy * (v.y - plane.y0)).abs()
}

/// Rounding bound of an evaluation, in units of the magnitudes of the
/// terms it adds: the evaluation itself and the rounding of the planes'
/// slopes (set up from the corners with a few roundings each).
const ROUNDING: f64 = 8.0 * f64::EPSILON;

/// The sign of `d_P - d_Q` at a rounded vertex `v`: 0 within [`TOUCH`]
/// pixels (along the gradient of the difference) plus the rounding of the
/// evaluation, else the sign of the evaluated difference.
///
/// The two reference values are subtracted first: they are window depths
/// that agree in their leading bits (exactly so behind a tiny near plane,
/// where every depth is close to 1), so their difference is exact and the
/// rounding bound scales with the depth differences, not with the depths.
pub(crate) fn rounded_sign(v: DVec2, p: &PlaneEq, q: &PlaneEq) -> i8 {
    let slope = |e: &PlaneEq| e.dx * (v.x - e.x0) + e.dy * (v.y - e.y0);
    let base = p.value - q.value;
    let diff = base + (slope(p) - slope(q));
    let gradient = (p.dx - q.dx).abs() + (p.dy - q.dy).abs();
    let tolerance =
        TOUCH * gradient + ROUNDING * (base.abs() + slope_terms(p, v) + slope_terms(q, v));
    if diff > tolerance {
        1
    } else if diff < -tolerance {
        -1
    } else {
        0
    }
}

/// The range of `depth` over a cut piece's rounded polygon, widened by
/// [`TOUCH`] pixels along its gradient and by the rounding of its
/// evaluation, so that it holds the depth of every point the piece covers.
pub(crate) fn padded_range(poly: &[DVec2], depth: &PlaneEq) -> (f64, f64) {
    let gradient = depth.dx.abs() + depth.dy.abs();
    poly.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            let z = depth.eval(v.x, v.y);
            let pad = TOUCH * gradient + ROUNDING * (z.abs() + slope_terms(depth, *v));
            (lo.min(z - pad), hi.max(z + pad))
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_geom::FixedPt;

    fn tri(v: [(i32, i32); 3], z: [f64; 3]) -> ScreenTri {
        let v = v.map(|(x, y)| FixedPt::new(x * 256, y * 256));
        ScreenTri {
            v,
            z,
            w: [1.0; 3],
            depth: PlaneEq::from_points(&v, z).unwrap(),
            inv_w: PlaneEq::constant(1.0),
            prim: 0,
            front_facing: true,
        }
    }

    #[test]
    fn corner_signs_say_farther_nearer_or_on() {
        let q = tri([(0, 0), (10, 0), (0, 10)], [0.5; 3]);
        assert!(hider_geom::orient2d(q.v[0], q.v[1], q.v[2]) > 0);
        let p = tri([(1, 1), (20, 1), (1, 20)], [0.7, 0.3, 0.5]);
        assert_eq!(corner_sign(&p, 0, &q), 1);
        assert_eq!(corner_sign(&p, 1, &q), -1);
        assert_eq!(corner_sign(&p, 2, &q), 0);
    }

    /// Depths one unit in the last place apart, near window depth 1 (a
    /// near plane of `1e-12`): any fixed tolerance above that calls them
    /// equal; the exact predicate does not.
    #[test]
    fn corner_signs_are_exact_at_the_last_bit() {
        let z: f64 = 1.0 - 1e-12;
        let next = f64::from_bits(z.to_bits() + 1);
        let q = tri([(0, 0), (10, 0), (0, 10)], [z; 3]);
        let p = tri(
            [(1, 1), (20, 1), (1, 20)],
            [next, z, f64::from_bits(z.to_bits() - 1)],
        );
        assert_eq!(corner_sign(&p, 0, &q), 1);
        assert_eq!(corner_sign(&p, 1, &q), 0);
        assert_eq!(corner_sign(&p, 2, &q), -1);
    }

    #[test]
    fn crossings_keep_the_planes_their_edge_lies_on() {
        let (a, b) = (Tag::corner(0), Tag::corner(1));
        let on_7 = Tag::crossing(a, b, Some(7));
        assert_eq!(on_7.planes, [7, NO_PLANE]);
        let on_7_too = Tag::crossing(on_7, a, Some(7));
        assert_eq!(on_7_too.planes, [7, NO_PLANE]);
        let both = Tag::crossing(on_7, on_7_too, Some(9));
        assert_eq!(both.planes, [9, 7]);
        assert_eq!(Tag::crossing(a, b, None).planes, [NO_PLANE; 2]);
    }
}
