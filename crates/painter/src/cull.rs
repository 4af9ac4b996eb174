//! Occlusion culling: pieces that no point of the picture can show.
//!
//! Before ordering, every input triangle is laid over a grid of squares
//! (the hi-z idea of hierarchical z-buffers, at one level; one pixel
//! wide, or a few pixels when the viewport or the overdraw is huge): a
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
//! Only triangles whose material is opaque are occluders, since the SVG
//! composites translucent ones over what lies behind
//! ([`crate::PainterOptions::cull_hidden`] turns culling off for callers
//! that draw the pieces in colours of their own).
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
    /// Viewport size, pixels.
    width: f64,
    height: f64,
    /// Side of a square, pixels (a power of two).
    side: f64,
    /// Squares per row and per column.
    cols: usize,
    rows: usize,
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

/// Most squares in the grid (8 MiB of depths).
const MAX_SQUARES: f64 = (1u64 << 20) as f64;

/// Most square visits when the triangles are laid over the grid, counted
/// on their bounding boxes: the grid gets coarser (squares of 2, 4, ...
/// pixels) until the build costs at most this, which keeps it a small part
/// of a frame whatever the overdraw.
const MAX_VISITS: f64 = (1u64 << 28) as f64;

/// The depth plane's value at the centre of the square of side `side`
/// at `(i, j)`, and a bound on how far it moves over the square plus the
/// evaluation's rounding.
#[inline]
fn over_square(plane: &PlaneEq, side: f64, i: usize, j: usize) -> (f64, f64) {
    let (x, y) = ((i as f64 + 0.5) * side, (j as f64 + 0.5) * side);
    let centre = plane.eval(x, y);
    let reach = 0.5 * side * (plane.dx.abs() + plane.dy.abs());
    let rounding = ROUNDING
        * (plane.value.abs()
            + plane.dx.abs() * ((x - plane.x0).abs() + side)
            + plane.dy.abs() * ((y - plane.y0).abs() + side));
    (centre, reach + rounding)
}

impl HiZ {
    /// Builds the occluder depths of `scene`'s opaque triangles, on
    /// squares as small as [`MAX_SQUARES`] and [`MAX_VISITS`] allow; with
    /// `enabled` false, an empty grid that culls nothing. A stopped
    /// `cancel` leaves the rest out (the caller returns its error).
    pub fn build(&mut self, scene: &ScreenScene, enabled: bool, cancel: hider_scene::Cancel) {
        self.any = false;
        self.occluder.clear();
        if !enabled {
            return;
        }
        self.width = f64::from(scene.viewport.width);
        self.height = f64::from(scene.viewport.height);
        let visits: f64 = scene
            .tris
            .iter()
            .map(|t| {
                let (lo, hi) = t.v.iter().fold(
                    ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
                    |(lo, hi), p| {
                        let (x, y) = p.to_pixels();
                        ([lo[0].min(x), lo[1].min(y)], [hi[0].max(x), hi[1].max(y)])
                    },
                );
                let w = (hi[0].min(self.width) - lo[0].max(0.0)).max(0.0);
                let h = (hi[1].min(self.height) - lo[1].max(0.0)).max(0.0);
                w * h
            })
            .sum();
        self.side = 1.0;
        while (self.width / self.side).ceil() * (self.height / self.side).ceil() > MAX_SQUARES
            || visits / (self.side * self.side) > MAX_VISITS
        {
            self.side *= 2.0;
        }
        self.cols = (self.width / self.side).ceil() as usize;
        self.rows = (self.height / self.side).ceil() as usize;
        self.occluder.clear();
        self.occluder.resize(self.cols * self.rows, f64::INFINITY);
        self.any = false;
        // A translucent triangle (its material's opacity below 1, or not
        // a number) shows what lies behind it: it hides nothing.
        for (k, tri) in scene
            .tris
            .iter()
            .filter(|t| scene.material(t.prim).opacity >= 1.0)
            .enumerate()
        {
            // Up to `MAX_VISITS` squares in all: seconds on large
            // crossing triangles; every 16, the clock costs nothing.
            if k % 16 == 0 && cancel.check().is_err() {
                return;
            }
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
        if !(ymin.is_finite() && ymax.is_finite() && tri.depth.value.is_finite()) {
            return;
        }
        let side = self.side;
        let j0 = (ymin / side).ceil().max(0.0) as usize;
        let j1 = ((ymax / side).floor().min(self.rows as f64)) as usize;
        for j in j0..j1 {
            let (Some(top), Some(bottom)) = (
                span_at(&poly, j as f64 * side),
                span_at(&poly, (j + 1) as f64 * side),
            ) else {
                continue;
            };
            let lo = ((top.0.max(bottom.0) + PAD) / side).ceil().max(0.0);
            let hi = ((top.1.min(bottom.1) - PAD) / side)
                .floor()
                .min(self.cols as f64);
            if lo.partial_cmp(&hi) != Some(std::cmp::Ordering::Less) {
                continue;
            }
            for i in lo as usize..hi as usize {
                let (centre, reach) = over_square(&tri.depth, side, i, j);
                let far = centre + reach;
                let slot = &mut self.occluder[j * self.cols + i];
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
        let inside = piece.min.x - PAD >= 0.0
            && piece.min.y - PAD >= 0.0
            && piece.max.x + PAD <= self.width
            && piece.max.y + PAD <= self.height;
        if !(self.any && inside) {
            return false;
        }
        let side = self.side;
        let poly: Vec<[f64; 2]> = piece.polygon.iter().map(|p| [p.x, p.y]).collect();
        let j0 = ((piece.min.y - PAD) / side).floor() as usize;
        let j1 = (((piece.max.y + PAD) / side).floor() as usize).min(self.rows - 1);
        for j in j0..=j1 {
            let (c0, c1) = (j as f64 * side - PAD, (j + 1) as f64 * side + PAD);
            let Some((lo, hi)) = span_over(&poly, c0, c1) else {
                continue;
            };
            let i0 = ((lo - PAD) / side).floor().max(0.0) as usize;
            let i1 = (((hi + PAD) / side).floor() as usize).min(self.cols - 1);
            for i in i0..=i1 {
                let (centre, reach) = over_square(&piece.depth, side, i, j);
                let near = (centre - reach).max(piece.zmin);
                // Not strictly farther (or not a number): it may show.
                if near.partial_cmp(&self.occluder[j * self.cols + i])
                    != Some(std::cmp::Ordering::Greater)
                {
                    return false;
                }
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use hider_scene::{Scene, procedural};
    use hider_testkit::{reference, render, screen};

    use crate::{Painter, PainterStats};

    fn run(scene: &Scene, size: u32) -> PainterStats {
        let s = screen(scene, size, size);
        let (frame, stats) = render(&mut Painter::default(), &s);
        assert_eq!(reference::pixel_centre(&s).ids, frame.ids);
        stats
    }

    fn tri(c: [f64; 2], r: f64, z: f64) -> [DVec3; 3] {
        [
            DVec3::new(c[0] - r, c[1] - r, z),
            DVec3::new(c[0] + r, c[1] - r, z),
            DVec3::new(c[0], c[1] + r, z),
        ]
    }

    fn scene(tris: &[[DVec3; 3]]) -> Scene {
        Scene::from_triangles(tris.iter().flatten().copied().collect())
    }

    /// A small triangle behind a large one is culled; one that peeks out
    /// from behind it, one in front and one in its plane are not.
    #[test]
    fn only_pieces_hidden_everywhere_are_culled() {
        let big = tri([0.0, 0.0], 2.0, 0.0);
        let frame = tri([0.0, 0.0], 2.6, -3.0);
        assert_eq!(
            run(&scene(&[big, tri([0.0, 0.0], 0.5, -1.0), frame]), 64).culled,
            1
        );
        // Sticking out past the big triangle's right edge.
        assert_eq!(
            run(&scene(&[big, tri([1.2, -1.0], 0.9, -1.0), frame]), 64).culled,
            0
        );
        assert_eq!(
            run(&scene(&[big, tri([0.0, 0.0], 0.5, 1.0), frame]), 64).culled,
            0
        );
        assert_eq!(
            run(&scene(&[big, tri([0.0, 0.0], 0.5, 0.0), frame]), 64).culled,
            0
        );
        assert_eq!(run(&procedural::coplanar_pair(), 48).culled, 0);
    }

    /// A translucent triangle hides nothing (the SVG composites it over
    /// what lies behind), and culling can be turned off.
    #[test]
    fn translucent_triangles_and_the_option_cull_nothing() {
        use hider_scene::{Material, Mesh};
        let mut s = Scene::default();
        for (t, opacity) in [
            (tri([0.0, 0.0], 2.0, 0.0), 0.5),
            (tri([0.0, 0.0], 0.5, -1.0), 1.0),
        ] {
            let mesh = Mesh {
                positions: t.to_vec(),
                indices: vec![[0, 1, 2]],
                ..Mesh::default()
            };
            let material = Material {
                opacity,
                ..Material::default()
            };
            s.push_mesh(mesh, Some(material));
        }
        assert_eq!(run(&s, 64).culled, 0);
        let hidden = scene(&[tri([0.0, 0.0], 2.0, 0.0), tri([0.0, 0.0], 0.5, -1.0)]);
        assert_eq!(run(&hidden, 64).culled, 1);
        let options = crate::PainterOptions::default().with_cull_hidden(false);
        let s = screen(&hidden, 64, 64);
        let (frame, stats) = render(&mut <Painter as hider_scene::Hider>::new(options), &s);
        assert_eq!(stats.culled, 0);
        assert_eq!(reference::pixel_centre(&s).ids, frame.ids);
    }

    /// B pierces A along x = 0.5; C, nearer than both, covers x < 0.9.
    /// Neither triangle is hidden whole, but the piece of B behind A's
    /// plane lies under C and is culled as the split makes it.
    #[test]
    fn split_pieces_under_another_triangle_are_culled() {
        let a = tri([0.0, 0.0], 2.0, 0.0);
        let b = [
            DVec3::new(-1.5, -1.5, -2.0),
            DVec3::new(1.5, -1.5, 1.0),
            DVec3::new(1.5, 1.5, 1.0),
        ];
        let c = [
            DVec3::new(0.9, -6.0, 2.0),
            DVec3::new(0.9, 6.0, 2.0),
            DVec3::new(-6.0, 0.0, 2.0),
        ];
        let stats = run(&scene(&[a, b]), 128);
        assert_eq!((stats.splits, stats.culled), (1, 0), "{stats:?}");
        let stats = run(&scene(&[a, b, c]), 128);
        assert!(stats.splits >= 1, "{stats:?}");
        assert!(stats.culled >= 1, "{stats:?}");
    }
}
