//! The pixel-centre references tests score hiders against, both from
//! `hider-oracle`: the textbook window-depth z-buffer and the ray cast.

use hider_oracle::RayCastOracle;
use hider_scene::ScreenScene;

/// Per pixel centre: the nearest primitive on the window-depth planes, its
/// `f64` depth and the window-depth gap to the runner-up primitive
/// ([`hider_oracle::WindowDepthReference`]).
pub use hider_oracle::WindowDepthReference as Reference;

/// The brute-force pixel-centre z-buffer of `screen`: coverage by the
/// shared edge functions, depth from each triangle's window-depth plane in
/// `f64`, the nearest kept with the lower id on exact ties (what a LESS
/// z-buffer drawing in primitive order keeps). A hider with `f64` depth
/// matches its ids and depths bit for bit away from ties.
///
/// ```
/// use hider_scene::{NO_ID, procedural};
/// use hider_testkit::{reference, screen};
///
/// let s = screen(&procedural::cube(), 16, 16);
/// let r = reference::pixel_centre(&s);
/// assert!(r.ids.iter().any(|&id| id != NO_ID));
/// assert!(r.ids.iter().zip(&r.depth).all(|(&id, &d)| (id == NO_ID) == (d == 1.0)));
/// ```
pub fn pixel_centre(screen: &ScreenScene) -> Reference {
    hider_oracle::window_depth_reference(screen)
}

/// The ray-cast oracle's answer for `screen` with the default options:
/// depths from camera-space planes, ties by relative gap
/// ([`hider_oracle::DEFAULT_TIE_TOLERANCE`]), scored with
/// [`hider_oracle::Reference::compare`].
pub fn ray_cast(screen: &ScreenScene) -> hider_oracle::Reference {
    RayCastOracle::default().evaluate(screen)
}
