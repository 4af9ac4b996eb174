//! What the tile kernel reads of a triangle, for both triangle types it
//! draws: the shared front end's [`ScreenTri`] and the lean [`DepthTri`].

use hider_geom::{FixedPt, PlaneEq};
use hider_scene::ScreenTri;

use crate::depth_scene::{DepthTri, SmallSetup};

/// What the tile kernel reads of a triangle; implemented by both
/// [`ScreenTri`] and the lean [`DepthTri`].
pub(crate) trait RasterTri: Sync {
    /// Whether the list may hold triangles that cover no pixel centre
    /// (binning drops them). The lean front end drops them itself; a
    /// screen scene keeps them for the other hiders.
    const MAY_MISS_CENTRES: bool;
    /// Snapped vertices, positively ordered.
    fn v(&self) -> &[FixedPt; 3];
    /// The window-depth plane.
    fn depth(&self) -> &PlaneEq;
    /// The primitive id.
    fn prim(&self) -> u32;
    /// The small-box set-up the front end made ([`SmallSetup::NONE`] for
    /// a screen scene's triangles).
    fn setup(&self) -> &SmallSetup;
}

/// Both triangle types keep the same three fields under the same names.
macro_rules! raster_tri {
    ($($t:ty: $miss:expr, $self_:ident => $setup:expr),*) => {$(
        impl RasterTri for $t {
            const MAY_MISS_CENTRES: bool = $miss;
            #[inline]
            fn v(&self) -> &[FixedPt; 3] {
                &self.v
            }
            #[inline]
            fn depth(&self) -> &PlaneEq {
                &self.depth
            }
            #[inline]
            fn prim(&self) -> u32 {
                self.prim
            }
            #[inline]
            fn setup(&$self_) -> &SmallSetup {
                $setup
            }
        }
    )*};
}
raster_tri!(
    ScreenTri: true, self => &SmallSetup::NONE,
    DepthTri: false, self => &self.setup
);
