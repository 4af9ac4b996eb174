//! The tolerances of the approximate comparisons ([`crate::Reference::compare`]):
//! the oracle itself calls a tie only at exactly equal depths (or within
//! the proved `f64` rounding bound, [`crate::plane_rounding_bound`]).

/// Relative camera-distance gap under which [`crate::Reference::compare`]
/// counts the two nearest surfaces at a pixel centre as a tie: the
/// standard of the *approximate* hiders and of the benchmark's scores.
/// Exact hiders are held to [`crate::Reference::compare_exact`], which has
/// no tolerance.
///
/// The gap is `(d2 - d1) / d1` with `d1`, `d2` the view depths (distance in
/// front of the eye along the view axis) of the nearest and second-nearest
/// distinct primitives, or `(d2 - d1) / (far - near)` for an orthographic
/// camera.
///
/// Why `1e-5`: an `f32` window-depth buffer resolves about `2^-24` in
/// window depth near 1; with the fit camera (`far/near = 100`, scene at
/// about 25 x near) that is a relative view depth of about `1.5e-6`, and
/// fixed-point buffers and the naive painter are coarser still, while real
/// ordering errors (a wrong sort, linear-z interpolation) show gaps of
/// `1e-3` and more. It is *not* a statement about ties: under a telephoto
/// camera or a tight depth range, relative gaps far below `1e-5` are window
/// depths every buffer separates (issue 37), which is why the oracle no
/// longer uses it to decide.
pub const DEFAULT_TIE_TOLERANCE: f64 = 1e-5;

/// Window-depth difference under which the two nearest surfaces at a pixel
/// centre are a tie whatever their relative gap: `2^-22`, four `f32` steps
/// just below 1.0.
///
/// Every [`hider_scene::Frame`] stores window depth as `f32`, and the
/// exact hiders of the registry include `f32` depth buffers. Where
/// window depth has no resolution left (a far/near ratio of 1e9, geometry
/// thousands of near distances away) such a buffer cannot order two
/// surfaces whatever algorithm it runs, so that is no error of the
/// algorithm. For the fit camera (far/near = 100) this criterion is
/// weaker than the relative one and changes nothing.
/// [`Reference::compare_strict`](crate::Reference::compare_strict) leaves it out, for hiders with `f64`
/// depth.
pub const WINDOW_TIE_TOLERANCE: f64 = 1.0 / (1u64 << 22) as f64;
