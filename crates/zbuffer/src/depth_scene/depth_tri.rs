//! The lean front end's output types: a triangle as a depth-only hider
//! needs it, and one pixel of a triangle too small to rasterise.

use hider_geom::{EdgeFunction, FixedPt, PlaneEq, Viewport};
use hider_scene::ScreenTri;

/// A triangle as a depth-only hider needs it: [`ScreenTri`] without the
/// per-vertex depths, `w` and the `1/w` plane.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DepthTri {
    /// Snapped vertices, ordered so that the edge functions are positive
    /// inside (as [`ScreenTri::v`]).
    pub v: [FixedPt; 3],
    /// Window depth as an affine function of window position.
    pub depth: PlaneEq,
    /// Primitive id: index of the source triangle in the scene.
    pub prim: u32,
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
#[derive(Clone, Copy, Debug, Default, PartialEq)]
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
        }
    }
}
