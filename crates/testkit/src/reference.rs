//! The pixel-centre references tests score hiders against, both from
//! `hider-oracle`: the textbook window-depth z-buffer and the ray cast.

use hider_oracle::{Agreement, RayCastOracle};
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

/// The oracle's answer for `screen` with the default options: the exact
/// order of the snapped window-depth planes, exact ties to the lower id
/// (gap 0); score exact hiders with [`compare_exact`], approximate ones
/// with [`hider_oracle::Reference::compare`].
pub fn ray_cast(screen: &ScreenScene) -> hider_oracle::Reference {
    RayCastOracle::default().evaluate(screen)
}

/// The exact hiders of the registry whose depth buffer is `f32` window
/// depth: held to [`hider_oracle::Reference::compare_exact_f32`].
pub const F32_DEPTH: [&str; 3] = ["zbuffer", "zbuffer-reversed", "zbuffer-tiled"];

/// An exact hider's ids (registry name `name`) against the oracle: equal on
/// every covered pixel, exact ties included; the `f32` buffers
/// ([`F32_DEPTH`]) are excused where two surfaces that are not tied lie
/// closer in window depth than `f32` resolves.
///
/// ```
/// use hider_scene::procedural;
/// use hider_testkit::{reference, screen};
///
/// let s = screen(&procedural::coplanar_pair(), 24, 24);
/// let r = reference::ray_cast(&s);
/// assert!(reference::compare_exact(&r, "zbuffer-f64", &r.ids).is_exact());
/// ```
pub fn compare_exact(reference: &hider_oracle::Reference, name: &str, ids: &[u32]) -> Agreement {
    compare(reference, name, ids)
}

/// Like [`compare_exact`], but accepting any id at every tie, exact ties
/// included ([`hider_oracle::Reference::compare_off_ties`]): for hostile
/// inputs (symmetric lattices, near planes at `1e-12`) where two different
/// planes meet exactly at pixel centres and `f64` plane evaluation orders
/// them by rounding rather than by the tie rule.
pub fn compare_off_ties(reference: &hider_oracle::Reference, name: &str, ids: &[u32]) -> Agreement {
    let resolution = if F32_DEPTH.contains(&name) {
        hider_oracle::WINDOW_TIE_TOLERANCE
    } else {
        0.0
    };
    reference.compare_off_ties(ids, resolution)
}

fn compare(reference: &hider_oracle::Reference, name: &str, ids: &[u32]) -> Agreement {
    if F32_DEPTH.contains(&name) {
        reference.compare_exact_f32(ids)
    } else {
        reference.compare_exact(ids)
    }
}
