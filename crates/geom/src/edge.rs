//! Exact integer edge functions and GL's fill rule (top-left in GL's row order).
//!
//! For an edge from `a` to `b` the edge function is
//! `E(p) = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)`, evaluated
//! in `i64` on fixed-point coordinates (see [`crate::fixed`]), so it is exact:
//! the sign never depends on rounding. A triangle whose vertices are ordered
//! so that its doubled area [`orient2d`]`(v0, v1, v2)` is positive has
//! `E > 0` on all three edges in its interior.
//!
//! # Fill rule
//!
//! A sample exactly on an edge (`E == 0`) belongs to the triangle only if the
//! edge is a *top* or *left* edge in the rasterizer's own row order, which
//! is GL's: row 0 at the bottom of the image. That is what Mesa's llvmpipe
//! does when it draws into a framebuffer object (its top-left rule, applied
//! to rows in memory order, GL's bottom row first), and what reproduces its
//! renders on every pixel. In hider's y-down window coordinates, with the
//! positive orientation above, the owned edges are therefore:
//! - left edge: going up the screen (`dy < 0`), the interior to its right;
//! - bottom edge: horizontal (`dy == 0`) with the interior above it, i.e.
//!   `dx < 0` (the top edge of GL's frame).
//!
//! The rule is the mirror image of the usual y-down top-left rule in y
//! only: the two differ exactly on samples lying on horizontal edges.
//! Two triangles sharing an edge see it with opposite directions, so exactly
//! one of them owns samples on it; a vertex shared by a fan is owned by
//! exactly one triangle too. A closed mesh therefore covers every sample
//! exactly once.

use crate::fixed::FixedPt;

/// Twice the signed area of the triangle `a b c` in fixed-point units
/// squared: positive when `E_ab(c) > 0` (clockwise on a y-down screen).
pub fn orient2d(a: FixedPt, b: FixedPt, c: FixedPt) -> i64 {
    let (ax, ay) = (i64::from(a.x), i64::from(a.y));
    (i64::from(b.x) - ax) * (i64::from(c.y) - ay) - (i64::from(b.y) - ay) * (i64::from(c.x) - ax)
}

/// Whether the edge `a -> b` of a positively oriented triangle owns the
/// samples that lie exactly on it: a left edge, or a horizontal edge with
/// the interior above it (a top edge in GL's bottom-up row order; see the
/// module documentation).
pub fn is_top_left(a: FixedPt, b: FixedPt) -> bool {
    top_left_bias(b.x - a.x, b.y - a.y) != 0
}

/// The fill rule as the bias of an edge function: 1 for an edge of
/// direction `(dx, dy)` (`to - from`, in a positively oriented triangle)
/// that owns its samples ([`is_top_left`]: `dy < 0`, or `dy == 0` and
/// `dx < 0`), 0 otherwise. An edge function plus its bias is positive
/// exactly at the samples the edge owns. Branch-free, for loops that
/// should vectorise.
#[inline(always)]
pub const fn top_left_bias(dx: i32, dy: i32) -> i32 {
    ((dy < 0) | ((dy == 0) & (dx < 0))) as i32
}

/// [`top_left_bias`] of every lane.
#[inline(always)]
pub fn top_left_biases<const N: usize>(dx: [i32; N], dy: [i32; N]) -> [i32; N] {
    let mut out = [0; N];
    for ((o, &dx), &dy) in out.iter_mut().zip(&dx).zip(&dy) {
        *o = top_left_bias(dx, dy);
    }
    out
}

/// An edge function `E(x, y) = a*x + b*y + c` with the fill rule folded into
/// `c`, so that a sample is inside the edge's half-plane iff `E(x, y) > 0`
/// ([`EdgeFunction::contains`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EdgeFunction {
    /// Change of `E` per fixed-point unit of x.
    pub a: i64,
    /// Change of `E` per fixed-point unit of y.
    pub b: i64,
    /// Constant term, already biased by the fill rule: samples with
    /// `E(p) > 0` are inside; `c` was lowered by one for edges that are not
    /// owning (the fill rule), so that `E == 0` on such an edge tests as
    /// outside.
    pub c: i64,
}

impl EdgeFunction {
    /// The edge function of `from -> to`, for a triangle whose orientation
    /// is positive, with the fill rule's bias applied.
    #[inline]
    pub fn new(from: FixedPt, to: FixedPt) -> Self {
        let (fx, fy) = (i64::from(from.x), i64::from(from.y));
        let a = -(i64::from(to.y) - fy);
        let b = i64::from(to.x) - fx;
        // E(p) = b*(py - fy) + a*(px - fx); c collects the constant part.
        let c = -a * fx - b * fy;
        // Owning edges (fill rule) test E + 1 > 0 (i.e. E >= 0); others
        // keep E > 0.
        let bias = if is_top_left(from, to) { 1 } else { 0 };
        Self { a, b, c: c + bias }
    }

    /// The biased value at a fixed-point sample position.
    #[inline]
    pub fn eval(&self, x: i64, y: i64) -> i64 {
        self.a * x + self.b * y + self.c
    }

    /// Whether the sample at `(x, y)` (fixed point) is inside this edge
    /// under the fill rule.
    #[inline]
    pub fn contains(&self, x: i64, y: i64) -> bool {
        self.eval(x, y) > 0
    }
}

/// The three edge functions of a triangle with positive orientation
/// (`orient2d(v[0], v[1], v[2]) > 0`).
#[inline]
pub fn triangle_edges(v: &[FixedPt; 3]) -> [EdgeFunction; 3] {
    [
        EdgeFunction::new(v[0], v[1]),
        EdgeFunction::new(v[1], v[2]),
        EdgeFunction::new(v[2], v[0]),
    ]
}

/// Whether the fixed-point sample `(x, y)` is covered by the positively
/// oriented triangle `v` under the fill rule. The single coverage
/// decision every hider shares.
pub fn triangle_covers(v: &[FixedPt; 3], x: i64, y: i64) -> bool {
    triangle_edges(v).iter().all(|e| e.contains(x, y))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixed::pixel_center;

    fn p(x: i32, y: i32) -> FixedPt {
        FixedPt::new(x * 256, y * 256)
    }

    fn covered(v: &[FixedPt; 3], w: i32, h: i32) -> Vec<bool> {
        let mut out = Vec::new();
        for j in 0..h {
            for i in 0..w {
                out.push(triangle_covers(
                    v,
                    pixel_center(i).into(),
                    pixel_center(j).into(),
                ));
            }
        }
        out
    }

    #[test]
    fn orientation_sign() {
        assert!(orient2d(p(0, 0), p(1, 0), p(0, 1)) > 0);
        assert!(orient2d(p(0, 0), p(0, 1), p(1, 0)) < 0);
    }

    #[test]
    fn left_and_bottom_edges_of_the_y_down_frame() {
        // Positive triangle (0,0) (4,0) (0,4): top edge a->b (not owned: it
        // is a bottom edge in GL's row order), left edge c->a (owned).
        assert!(!is_top_left(p(0, 0), p(4, 0)));
        assert!(!is_top_left(p(4, 0), p(0, 4)));
        assert!(is_top_left(p(0, 4), p(0, 0)));
        // A bottom horizontal edge goes right-to-left in positive order.
        assert!(is_top_left(p(4, 4), p(0, 4)));
        assert_eq!(top_left_biases([1, -1, 0, 5], [0, 0, -3, 2]), [0, 1, 1, 0]);
    }

    #[test]
    fn two_triangles_sharing_an_edge_cover_each_pixel_once() {
        // A square split along a diagonal that passes exactly through pixel
        // centres, with its sides on pixel centres too: every sample on a
        // shared or outer edge is a candidate for double counting.
        let h = 128; // half pixel
        let a = FixedPt::new(h, h);
        let b = FixedPt::new(8 * 256 + h, h);
        let c = FixedPt::new(8 * 256 + h, 8 * 256 + h);
        let d = FixedPt::new(h, 8 * 256 + h);
        let t1 = [a, b, c];
        let t2 = [a, c, d];
        assert!(orient2d(a, b, c) > 0 && orient2d(a, c, d) > 0);
        let c1 = covered(&t1, 10, 10);
        let c2 = covered(&t2, 10, 10);
        let square = covered(&[a, b, c], 10, 10)
            .iter()
            .zip(&c2)
            .map(|(x, y)| x | y)
            .collect::<Vec<_>>();
        for k in 0..100 {
            assert!(!(c1[k] && c2[k]), "pixel {k} covered twice");
        }
        // The union is the half-open square: the bottom and left sides are
        // in, the top and right sides out: 8 x 8 pixels.
        assert_eq!(square.iter().filter(|&&x| x).count(), 64);
    }

    #[test]
    fn fan_around_a_vertex_on_a_pixel_centre_covers_it_once() {
        let centre = FixedPt::new(pixel_center(5), pixel_center(5));
        let ring = [p(0, 0), p(10, 0), p(10, 10), p(0, 10)];
        let mut count = 0;
        for k in 0..4 {
            let t = [centre, ring[k], ring[(k + 1) % 4]];
            assert!(orient2d(t[0], t[1], t[2]) > 0);
            if triangle_covers(&t, centre.x.into(), centre.y.into()) {
                count += 1;
            }
        }
        assert_eq!(count, 1);
    }
}
