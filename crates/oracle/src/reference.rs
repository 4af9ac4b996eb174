//! The oracle's answer for one frame.

/// The oracle's answer for one frame: per pixel centre, the visible
/// primitive, its depth, and how far the runner-up was.
///
/// Score an exact hider's ids against it with [`Reference::compare_exact`]
/// (or [`Reference::compare_exact_f32`] for an `f32` depth buffer), an
/// approximate one with [`Reference::compare`] (see [`crate::Agreement`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Reference {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Visible primitive per pixel ([`hider_scene::NO_ID`] for background),
    /// row-major.
    pub ids: Vec<u32>,
    /// Window depth of the visible surface (1.0 for background): always
    /// the depth of the surface [`Self::ids`] reports.
    pub depth: Vec<f32>,
    /// Relative view-depth gap between the nearest and the second-nearest
    /// distinct primitive at each pixel centre (`f64::INFINITY` when fewer
    /// than two primitives cover it; see [`crate::DEFAULT_TIE_TOLERANCE`]
    /// for the measure). Exactly 0 at a tie, exact or rounding
    /// ([`Self::is_tie`]), and positive everywhere else.
    pub gap: Vec<f64>,
    /// Window-depth difference between the same two surfaces
    /// (`f64::INFINITY` when fewer than two cover the centre): exactly 0 at
    /// an exact tie ([`Self::is_exact_tie`]), positive elsewhere; below
    /// [`crate::WINDOW_TIE_TOLERANCE`] an `f32` depth buffer cannot order
    /// them.
    pub window_gap: Vec<f64>,
}
