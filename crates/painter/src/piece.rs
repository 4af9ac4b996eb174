//! Pieces: the polygons the painter orders, and their exact coverage.
//!
//! A piece is a screen triangle from the front end, possibly cut by a
//! sequence of lines. It carries two descriptions of itself:
//!
//! - its **polygon** (window pixels, `f64`), used only to *decide the
//!   order*: depth extents, bounding boxes, plane sides, projected overlap;
//! - its **coverage rule**: a pixel centre belongs to the piece iff the
//!   original [`ScreenTri`] covers it (the shared exact integer edge
//!   functions and fill rule) *and* every [`Cut`] keeps it.
//!
//! A cut is one affine function evaluated the same way for both pieces it
//! creates: one keeps the centres where `f < 0`, the other those where
//! `!(f < 0)`. So the two halves of a split partition the original
//! triangle's pixel centres exactly — no crack, no double hit — however
//! the polygon vertices were rounded, and a piece never covers a centre
//! its triangle does not. This is what lets split pieces be re-rasterised
//! and still give the z-buffer's coverage bit for bit.

use glam::DVec2;
use hider_geom::PlaneEq;
use hider_scene::ScreenTri;

use crate::sides::{Tag, padded_range};
use crate::split::split_tagged;

/// One side of a splitting line, as a coverage rule.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cut {
    /// The line `f(x, y) = 0` in window pixels.
    pub line: PlaneEq,
    /// Which side this piece keeps: `f < 0` when true, `f >= 0` (or not
    /// a number) when false.
    pub keep_negative: bool,
}

impl Cut {
    /// Whether the cut keeps the window position `(x, y)` (pixels).
    #[inline]
    pub fn keeps(&self, x: f64, y: f64) -> bool {
        (self.line.eval(x, y) < 0.0) == self.keep_negative
    }
}

/// A convex piece of one screen triangle, as the painter orders and paints
/// it. Pieces keep the primitive id of their triangle.
#[derive(Clone, Debug, PartialEq)]
pub struct Piece {
    /// Primitive id of the source triangle.
    pub prim: u32,
    /// Index of the source triangle in [`hider_scene::ScreenScene::tris`].
    pub source: u32,
    /// The piece's outline in window pixels, positively oriented like the
    /// screen triangles (clockwise on the y-down screen). For an uncut
    /// piece these are the triangle's snapped vertices, exactly.
    pub polygon: Vec<DVec2>,
    /// The cuts this piece went through, outermost first.
    pub cuts: Vec<Cut>,
    /// Per polygon vertex, where it comes from: a corner of the source
    /// triangle (exact) or a crossing on the planes of other triangles.
    pub(crate) tags: Vec<Tag>,
    /// Window depth of the source triangle's plane.
    pub depth: PlaneEq,
    /// Smallest window depth over the piece (nearest point): exact for a
    /// whole triangle (its nearest vertex), and for a cut piece widened by
    /// a bound on the rounding of its polygon, so that no point the piece
    /// covers is nearer.
    pub zmin: f64,
    /// Largest window depth over the piece (farthest point), exact or
    /// widened like [`Self::zmin`].
    pub zmax: f64,
    /// Bounding box corner with the smallest coordinates, pixels.
    pub min: DVec2,
    /// Bounding box corner with the largest coordinates, pixels.
    pub max: DVec2,
    /// Moved to the head of the list once already (Newell's cycle mark).
    pub(crate) moved: bool,
}

impl Piece {
    /// The whole triangle `tri`, which is `scene.tris[source]`.
    pub fn from_tri(tri: &ScreenTri, source: u32) -> Self {
        let polygon = tri
            .v
            .iter()
            .map(|p| {
                let (x, y) = p.to_pixels();
                DVec2::new(x, y)
            })
            .collect();
        let tags = (0..3).map(Tag::corner).collect();
        let mut piece = Self::with_polygon(tri.prim, source, polygon, tags, Vec::new(), tri.depth);
        // The corners' window depths are the front end's own numbers.
        piece.zmin = tri.z.iter().copied().fold(f64::INFINITY, f64::min);
        piece.zmax = tri.z.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        piece
    }

    fn with_polygon(
        prim: u32,
        source: u32,
        polygon: Vec<DVec2>,
        tags: Vec<Tag>,
        cuts: Vec<Cut>,
        depth: PlaneEq,
    ) -> Self {
        let (zmin, zmax) = padded_range(&polygon, &depth);
        let (min, max) = polygon.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        Self {
            prim,
            source,
            polygon,
            cuts,
            tags,
            depth,
            zmin,
            zmax,
            min,
            max,
            moved: false,
        }
    }

    /// Whether the piece is still its whole triangle: its polygon vertices
    /// are then exact fixed-point positions.
    pub fn is_uncut(&self) -> bool {
        self.cuts.is_empty()
    }

    /// Splits the piece along `line`: `(negative side, non-negative side)`,
    /// or `None` when the line leaves one side without area (it does not
    /// really cut the polygon).
    pub fn split(&self, line: PlaneEq) -> Option<(Piece, Piece)> {
        self.split_on(line, None)
    }

    /// [`Self::split`], where `line` is the meeting line of this piece's
    /// plane with the plane of triangle `plane` (when given): the new
    /// vertices are then known to lie on that plane.
    pub(crate) fn split_on(&self, line: PlaneEq, plane: Option<u32>) -> Option<(Piece, Piece)> {
        let (mut neg, mut pos) = ((Vec::new(), Vec::new()), (Vec::new(), Vec::new()));
        split_tagged(
            (&self.polygon, &self.tags),
            &line,
            plane,
            &mut neg,
            &mut pos,
        );
        if neg.0.is_empty() || pos.0.is_empty() {
            return None;
        }
        let half = |(polygon, tags): (Vec<DVec2>, Vec<Tag>), keep_negative: bool| {
            let mut cuts = Vec::with_capacity(self.cuts.len() + 1);
            cuts.extend_from_slice(&self.cuts);
            cuts.push(Cut {
                line,
                keep_negative,
            });
            Piece::with_polygon(self.prim, self.source, polygon, tags, cuts, self.depth)
        };
        Some((half(neg, true), half(pos, false)))
    }

    /// Whether the piece covers the fixed-point sample `(x, y)`, given its
    /// source triangle: the shared edge test with its fill rule on the triangle, then
    /// every cut at the same position in pixels.
    #[inline]
    pub fn covers(&self, tri: &ScreenTri, x: i64, y: i64) -> bool {
        if !tri.edges().iter().all(|e| e.contains(x, y)) {
            return false;
        }
        let scale = f64::from(hider_geom::fixed::SUBPIXEL_SCALE);
        // Fixed-point values are below 2^24, so the conversion is exact.
        let (px, py) = (x as f64 / scale, y as f64 / scale);
        self.cuts.iter().all(|c| c.keeps(px, py))
    }

    /// Heap and inline bytes held by the piece, for the peak-memory count.
    pub fn bytes(&self) -> usize {
        std::mem::size_of::<Self>()
            + self.polygon.capacity() * std::mem::size_of::<DVec2>()
            + self.cuts.capacity() * std::mem::size_of::<Cut>()
            + self.tags.capacity() * std::mem::size_of::<Tag>()
    }
}

/// The affine function `d_a - d_b` of two depth planes, anchored at `a`'s
/// reference point: negative where plane `a` is nearer than plane `b`. Its
/// zero line is where the two planes meet on screen — "the plane of b"
/// seen inside a.
pub(crate) fn depth_difference(a: &PlaneEq, b: &PlaneEq) -> PlaneEq {
    PlaneEq {
        x0: a.x0,
        y0: a.y0,
        // The reference values are subtracted first, as in
        // `sides::rounded_sign`: they are window depths that agree in their
        // leading bits (all but equal behind a tiny near plane), so their
        // difference is exact, and the line's offset is rounded relative to
        // the depth differences rather than to the depths. Evaluating `b`
        // at `a`'s reference point first would round at the scale of the
        // depths, about one unit in the last place of 1, which behind a
        // near plane of 1e-6 or less moves the line by micro-pixels to
        // pixels: vertices the side test calls strictly in front then land
        // on the far side of the cut, the cut only shaves a sliver off, and
        // the same pair is cut again and again until the split budget runs
        // out.
        value: (a.value - b.value) - (b.dx * (a.x0 - b.x0) + b.dy * (a.y0 - b.y0)),
        dx: a.dx - b.dx,
        dy: a.dy - b.dy,
    }
}

/// The edge function of the directed segment `a -> b` as an affine function
/// in pixels, positive on the interior side of a positively oriented
/// polygon (same sign convention as [`hider_geom::EdgeFunction`], without
/// the fill-rule bias). For fixed-point end points every product is exact.
pub(crate) fn edge_line(a: DVec2, b: DVec2) -> PlaneEq {
    PlaneEq {
        x0: a.x,
        y0: a.y,
        value: 0.0,
        dx: -(b.y - a.y),
        dy: b.x - a.x,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_geom::FixedPt;
    use hider_geom::fixed::pixel_center;

    fn tri(v: [(i32, i32); 3], z: [f64; 3]) -> ScreenTri {
        let v = v.map(|(x, y)| FixedPt::new(x, y));
        ScreenTri {
            v,
            z,
            w: [1.0; 3],
            depth: PlaneEq::from_points(&v, z).unwrap(),
            inv_w: PlaneEq::constant(1.0),
            prim: 7,
            front_facing: true,
        }
    }

    #[test]
    fn halves_partition_the_triangles_pixels_exactly() {
        // A cut through pixel centres: the rounding-sensitive case.
        let t = tri([(0, 0), (20 * 256, 0), (0, 20 * 256)], [0.2, 0.5, 0.8]);
        let whole = Piece::from_tri(&t, 0);
        let line = PlaneEq {
            x0: 5.5,
            y0: 0.5,
            value: 0.0,
            dx: 1.0,
            dy: -0.25,
        };
        let (a, b) = whole.split(line).unwrap();
        assert_eq!((a.prim, b.prim), (7, 7));
        let (mut na, mut nb, mut nw) = (0, 0, 0);
        for j in 0..24 {
            for i in 0..24 {
                let (x, y) = (i64::from(pixel_center(i)), i64::from(pixel_center(j)));
                let (ia, ib, iw) = (
                    a.covers(&t, x, y),
                    b.covers(&t, x, y),
                    whole.covers(&t, x, y),
                );
                assert!(!(ia && ib), "pixel ({i}, {j}) in both halves");
                assert_eq!(ia || ib, iw, "pixel ({i}, {j})");
                na += usize::from(ia);
                nb += usize::from(ib);
                nw += usize::from(iw);
            }
        }
        assert!(na > 0 && nb > 0);
        assert_eq!(na + nb, nw);
        // A cut piece's range is padded by at most a TOUCH along the gradient.
        assert!(a.zmin >= whole.zmin - 1e-9 && a.zmax <= whole.zmax + 1e-9);
        assert!(a.zmin <= a.zmax && whole.zmin == 0.2 && whole.zmax == 0.8);
    }

    #[test]
    fn a_line_outside_does_not_split() {
        let t = tri([(0, 0), (2560, 0), (0, 2560)], [0.5; 3]);
        let p = Piece::from_tri(&t, 0);
        let far = PlaneEq {
            x0: 50.0,
            y0: 0.0,
            value: 0.0,
            dx: 1.0,
            dy: 0.0,
        };
        assert!(p.split(far).is_none());
    }

    #[test]
    fn depth_difference_vanishes_where_the_planes_meet() {
        let a = PlaneEq {
            x0: 1.0,
            y0: 2.0,
            value: 0.5,
            dx: 0.01,
            dy: 0.0,
        };
        let b = PlaneEq {
            x0: -3.0,
            y0: 4.0,
            value: 0.3,
            dx: -0.01,
            dy: 0.02,
        };
        let d = depth_difference(&a, &b);
        for (x, y) in [(0.0, 0.0), (10.0, -3.0), (7.5, 100.0)] {
            assert!((d.eval(x, y) - (a.eval(x, y) - b.eval(x, y))).abs() < 1e-12);
        }
    }

    #[test]
    fn edge_line_is_positive_inside() {
        let t = tri([(0, 0), (2560, 0), (0, 2560)], [0.5; 3]);
        let p = Piece::from_tri(&t, 0);
        let inside = DVec2::new(2.0, 2.0);
        for k in 0..3 {
            let e = edge_line(p.polygon[k], p.polygon[(k + 1) % 3]);
            assert!(e.eval(inside.x, inside.y) > 0.0);
        }
    }
}
