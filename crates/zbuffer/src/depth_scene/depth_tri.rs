//! The lean front end's output types: a triangle as a depth-only hider
//! needs it, and one pixel of a triangle too small to rasterise.

#[cfg(test)]
use hider_geom::edge::top_left_bias;
#[cfg(test)]
use hider_geom::fixed::{SUBPIXEL_SCALE, pixel_center};
use hider_geom::{EdgeFunction, FixedPt, PlaneEq, Viewport};
use hider_scene::ScreenTri;

use crate::tiled::SMALL_AREA;

/// A triangle as a depth-only hider needs it: [`ScreenTri`] without the
/// per-vertex depths, `w` and the `1/w` plane.
///
/// The lean front end also stores what the tiled z-buffer's small-triangle
/// kernel would set up per tile (the pixel box and the edge functions at
/// its first block column), computed eight triangles at a time where the
/// triangles are classified. It is a cache derived from the corners and
/// the viewport, so equality compares the three fields above only.
// `repr(C)`: the triangle pass writes it by its fields' offsets
// (`simd::emit`).
#[derive(Clone, Copy, Debug, Default)]
#[repr(C)]
pub struct DepthTri {
    /// Snapped vertices, ordered so that the edge functions are positive
    /// inside (as [`ScreenTri::v`]).
    pub v: [FixedPt; 3],
    /// Window depth as an affine function of window position.
    pub depth: PlaneEq,
    /// Primitive id: index of the source triangle in the scene.
    pub prim: u32,
    /// The small-box set-up, when the triangle has one.
    pub(crate) setup: SmallSetup,
}

impl PartialEq for DepthTri {
    fn eq(&self, other: &Self) -> bool {
        (self.v, self.depth, self.prim) == (other.v, other.depth, other.prim)
    }
}

impl DepthTri {
    /// The edge functions of this triangle (GL's fill rule applied, `hider_geom::edge`).
    #[inline]
    pub fn edges(&self) -> [EdgeFunction; 3] {
        hider_geom::edge::triangle_edges(&self.v)
    }

    /// The inclusive pixel rectangle whose centres may be covered (see
    /// [`Viewport::pixel_bounds`]).
    #[inline]
    pub fn pixel_bounds(&self, viewport: Viewport) -> Option<(u32, u32, u32, u32)> {
        viewport.pixel_bounds(&self.v)
    }
}

/// One pixel of a triangle too small to rasterise: the lean front end
/// hands a triangle whose box holds at most four pixel centres over as the
/// centres it covers (see [`Viewport::covered_centres`]), with the depth a
/// hider would compute there.
///
/// A fragment stands for a write of its triangle in primitive order. A
/// hider that applies fragments after the triangles gets the same answer
/// if it compares `(depth, prim)` lexicographically: the LESS depth test
/// in primitive order keeps the smallest depth and, among equal depths,
/// the first primitive.
// `repr(C)`: the triangle pass writes it by its fields' offsets
// (`simd::fragments`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[repr(C)]
pub struct DepthFragment {
    /// Window depth at the pixel centre: the triangle's
    /// [`PlaneEq::at_pixel`], the expression every pixel-centre hider
    /// evaluates.
    pub depth: f64,
    /// Pixel column.
    pub x: u16,
    /// Pixel row.
    pub y: u16,
    /// Primitive id of the triangle.
    pub prim: u32,
}

impl From<&ScreenTri> for DepthTri {
    fn from(t: &ScreenTri) -> Self {
        Self {
            v: t.v,
            depth: t.depth,
            prim: t.prim,
            setup: SmallSetup::NONE,
        }
    }
}

/// What the tiled z-buffer's small-triangle kernel sets up for a triangle
/// whose pixel box lies in one tile, computed once in the front end: the
/// box, and the three edge functions (fill rule applied) at the centre of
/// the box's first row and its first *block* column (the column rounded
/// down to a multiple of 8, where the kernel's 8-lane rows start), biased
/// by -1 so that a centre is inside iff all three are non-negative.
///
/// Tiles are multiples of 8 pixels wide, so the block columns of the
/// image are those of every tile, and when the box lies in one tile these
/// are exactly the values the kernel would compute there. A triangle has
/// a set-up when its box holds at most [`SMALL_AREA`] pixels and its
/// corners lie in the image, `[0, width) x [0, height)` (otherwise
/// [`Self::NONE`]). Then its box is not clamped to the image, so each
/// corner is less than a pixel outside the box, whose sides are at most
/// 32 pixels: every edge's extent, and every distance from a corner to a
/// centre of the box's block rows (at most 7 pixels beyond the box on
/// either side), is below 48 pixels, 12,288 in fixed point, and every
/// edge value there is below `2 * 12288^2 + 1 < 2^29` in magnitude. So
/// the values fit the kernel's `i32` lanes without the per-tile check,
/// and the set-up itself is `i32` arithmetic (`edge_values_match_i64`
/// checks it against the `i64` edge functions).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub(crate) struct SmallSetup {
    /// The pixel box (`Viewport::pixel_bounds`): first column, first row,
    /// last column, last row; empty (first after last) for none.
    pub(crate) bbox: [u16; 4],
    /// The biased edge values at the box's first block column and row.
    pub(crate) e: [i32; 3],
}

impl Default for SmallSetup {
    fn default() -> Self {
        Self::NONE
    }
}

// The bound above is for boxes of at most 32 pixels a side.
const _: () = assert!(SMALL_AREA <= 32);

impl SmallSetup {
    /// No set-up: the kernel computes its own.
    pub(crate) const NONE: Self = Self {
        bbox: [1, 0, 0, 0],
        e: [0; 3],
    };

    /// The set-up of the positively ordered triangle `v` in `viewport`:
    /// the scalar definition of what the front end's lanes compute
    /// (`simd::classify::setups`), which the tests compare them with.
    #[cfg(test)]
    pub(crate) fn new(v: &[FixedPt; 3], viewport: Viewport) -> Self {
        let Some((x0, y0, x1, y1)) = viewport.pixel_bounds(v) else {
            return Self::NONE;
        };
        // Images are at most 16384 pixels, so these fit i32; a negative
        // coordinate is above both as u32.
        let (w, h) = (
            viewport.width * SUBPIXEL_SCALE as u32,
            viewport.height * SUBPIXEL_SCALE as u32,
        );
        let inside = v.iter().all(|p| ((p.x as u32) < w) & ((p.y as u32) < h));
        if !inside || (x1 - x0 + 1) * (y1 - y0 + 1) > SMALL_AREA {
            return Self::NONE;
        }
        let (px, py) = (pixel_center((x0 & !7) as i32), pixel_center(y0 as i32));
        // `EdgeFunction::new(from, to).eval(px, py) - 1` in i32: exact,
        // by the bound above (`edge_values_match_i64`).
        let edge = |from: FixedPt, to: FixedPt| {
            let (dx, dy) = (to.x - from.x, to.y - from.y);
            dx * (py - from.y) - dy * (px - from.x) + top_left_bias(dx, dy) - 1
        };
        Self {
            // Images are at most 16384 pixels wide and high.
            bbox: [x0, y0, x1, y1].map(|c| c as u16),
            e: [edge(v[0], v[1]), edge(v[1], v[2]), edge(v[2], v[0])],
        }
    }

    /// The box, when the triangle has a set-up.
    #[inline(always)]
    pub(crate) fn ready(&self) -> Option<(u32, u32, u32, u32)> {
        let [x0, y0, x1, y1] = self.bbox.map(u32::from);
        (x0 <= x1).then_some((x0, y0, x1, y1))
    }
}

#[cfg(test)]
mod tests {
    use hider_geom::edge::triangle_edges;
    use proptest::prelude::*;

    use super::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4000))]

        /// The `i32` edge values are the `i64` edge functions' (the ones
        /// the tile kernel evaluates) wherever a set-up exists, the
        /// corners reaching the image's edges.
        #[test]
        fn edge_values_match_i64(
            at in (0i32..40 * 256, 0i32..40 * 256),
            d in proptest::array::uniform3((-9 * 256i32..9 * 256, -9 * 256i32..9 * 256)),
            size in (1u32..48, 1u32..48),
        ) {
            let mut v = d.map(|(dx, dy)| FixedPt::new(at.0 + dx, at.1 + dy));
            if hider_geom::orient2d(v[0], v[1], v[2]) < 0 {
                v.swap(1, 2);
            }
            let viewport = Viewport::new(size.0, size.1);
            let s = SmallSetup::new(&v, viewport);
            let Some((x0, y0, ..)) = s.ready() else { return Ok(()) };
            let (px, py) = (
                i64::from(pixel_center((x0 & !7) as i32)),
                i64::from(pixel_center(y0 as i32)),
            );
            let want = triangle_edges(&v).map(|e| e.eval(px, py) - 1);
            prop_assert_eq!(s.e.map(i64::from), want);
        }
    }
}
