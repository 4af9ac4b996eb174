//! Occlusion culling: pieces that no point of the picture can show.
//!
//! Before ordering, every input triangle is laid over a grid of pixel
//! squares (the hi-z idea of hierarchical z-buffers, at one level): a
//! square the triangle covers *entirely* (all four corners inside its
//! closed outline) records the triangle's farthest depth over the square,
//! and each square keeps the nearest such value, its **occluder depth**.
//! A piece whose nearest depth over every square its outline meets is
//! strictly farther than that square's occluder depth is hidden at every
//! point of its polygon, not only at pixel centres: something opaque
//! covers each of those squares entirely and is nearer everywhere on it.
//! Such a piece is dropped before it is ordered (counted in
//! [`crate::PainterStats::culled`]), which keeps both outputs exact: the
//! raster, since a nearer surface covers every centre of the piece, and
//! the vector drawing, which it could only have been painted over.
//!
//! Both bounds are conservative: a depth plane's extremes over a square
//! are at its corners, each evaluation is widened by a bound on its
//! rounding, outlines are widened (pieces) or narrowed (occluders) by
//! [`PAD`], and a piece reaching outside the viewport is never culled. So
//! a piece is only culled where the gap is far larger than any rounding,
//! never at a depth tie.
//!
//! On random triangles overlapping in a cube, most pieces that splitting
//! makes lie under many layers and are culled as they are made, so the
//! pieces left to order are those near the visible surface (the
//! `painter_cube` benchmark).

use hider_geom::PlaneEq;
use hider_scene::{ScreenScene, ScreenTri};

use crate::piece::Piece;

/// Pixels by which an outline is widened (a piece's) or narrowed (an
/// occluder's) before squares are counted: far above the rounding of
/// split vertices (~1e-13 pixel) and of the crossings computed here.
const PAD: f64 = 1e-6;

/// Relative bound on the rounding of one depth-plane evaluation, taken
/// far above the few ulps it costs.
const ROUNDING: f64 = 1e-12;

/// The occluder depth of every pixel square of the viewport.
#[derive(Clone, Debug, Default)]
pub(crate) struct HiZ {
    width: usize,
    height: usize,
    /// Per square (row-major), the nearest farthest-depth of a triangle
    /// covering it entirely; infinity where none does.
    occluder: Vec<f64>,
    /// Whether any square has an occluder (else nothing is culled).
    any: bool,
}

/// The x range where the closed convex polygon `poly` meets the horizontal
/// line `y = c`, if it does.
fn span_at(poly: &[[f64; 2]], c: f64) -> Option<(f64, f64)> {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for k in 0..poly.len() {
        let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
        if a[1] == c {
            lo = lo.min(a[0]);
            hi = hi.max(a[0]);
        }
        if (a[1] < c && c < b[1]) || (b[1] < c && c < a[1]) {
            let x = a[0] + (c - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
            lo = lo.min(x);
            hi = hi.max(x);
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// The x range where `poly` meets the slab `c0 <= y <= c1`: its vertices
/// inside the slab and its crossings of the slab's two sides.
fn span_over(poly: &[[f64; 2]], c0: f64, c1: f64) -> Option<(f64, f64)> {
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for v in poly {
        if c0 <= v[1] && v[1] <= c1 {
            lo = lo.min(v[0]);
            hi = hi.max(v[0]);
        }
    }
    for c in [c0, c1] {
        if let Some((a, b)) = span_at(poly, c) {
            lo = lo.min(a);
            hi = hi.max(b);
        }
    }
    (lo <= hi).then_some((lo, hi))
}

/// The depth plane's value at the centre of square `(i, j)` and a bound
/// on how far it moves over the square plus the evaluation's rounding.
#[inline]
fn over_square(plane: &PlaneEq, i: usize, j: usize) -> (f64, f64) {
    let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
    let centre = plane.eval(x, y);
    let reach = 0.5 * (plane.dx.abs() + plane.dy.abs());
    let rounding = ROUNDING
        * (plane.value.abs()
            + plane.dx.abs() * ((x - plane.x0).abs() + 1.0)
            + plane.dy.abs() * ((y - plane.y0).abs() + 1.0));
    (centre, reach + rounding)
}

impl HiZ {
    /// Builds the occluder depths of `scene`'s triangles.
    pub fn build(&mut self, scene: &ScreenScene) {
        self.width = scene.viewport.width as usize;
        self.height = scene.viewport.height as usize;
        self.occluder.clear();
        self.occluder
            .resize(self.width * self.height, f64::INFINITY);
        self.any = false;
        for tri in &scene.tris {
            self.add(tri);
        }
    }

    /// Lays one triangle over the squares it covers entirely.
    fn add(&mut self, tri: &ScreenTri) {
        let poly: Vec<[f64; 2]> = tri
            .v
            .iter()
            .map(|p| {
                let (x, y) = p.to_pixels();
                [x, y]
            })
            .collect();
        let ymin = poly.iter().map(|v| v[1]).fold(f64::INFINITY, f64::min);
        let ymax = poly.iter().map(|v| v[1]).fold(f64::NEG_INFINITY, f64::max);
        if !(ymin.is_finite() && ymax.is_finite()) || !tri.depth.value.is_finite() {
            return;
        }
        let j0 = ymin.ceil().max(0.0) as usize;
        let j1 = (ymax.floor().min(self.height as f64)) as usize;
        for j in j0..j1 {
            let (Some(top), Some(bottom)) =
                (span_at(&poly, j as f64), span_at(&poly, j as f64 + 1.0))
            else {
                continue;
            };
            let lo = (top.0.max(bottom.0) + PAD).ceil().max(0.0);
            let hi = (top.1.min(bottom.1) - PAD).floor().min(self.width as f64);
            if !(lo < hi) {
                continue;
            }
            for i in lo as usize..hi as usize {
                let (centre, reach) = over_square(&tri.depth, i, j);
                let far = centre + reach;
                let slot = &mut self.occluder[j * self.width + i];
                if far < *slot {
                    *slot = far;
                    self.any = true;
                }
            }
        }
    }

    /// Whether every point of `piece` is strictly farther than the
    /// occluder of each square it meets.
    pub fn hides(&self, piece: &Piece) -> bool {
        if !self.any
            || !(piece.min.x - PAD >= 0.0
                && piece.min.y - PAD >= 0.0
                && piece.max.x + PAD <= self.width as f64
                && piece.max.y + PAD <= self.height as f64)
        {
            return false;
        }
        let poly: Vec<[f64; 2]> = piece.polygon.iter().map(|p| [p.x, p.y]).collect();
        let j0 = (piece.min.y - PAD).floor() as usize;
        let j1 = ((piece.max.y + PAD).floor() as usize).min(self.height - 1);
        for j in j0..=j1 {
            let (c0, c1) = (j as f64 - PAD, j as f64 + 1.0 + PAD);
            let Some((lo, hi)) = span_over(&poly, c0, c1) else {
                continue;
            };
            let i0 = (lo - PAD).floor().max(0.0) as usize;
            let i1 = ((hi + PAD).floor() as usize).min(self.width - 1);
            for i in i0..=i1 {
                let (centre, reach) = over_square(&piece.depth, i, j);
                let near = (centre - reach).max(piece.zmin);
                if !(near > self.occluder[j * self.width + i]) {
                    return false;
                }
            }
        }
        true
    }
}
