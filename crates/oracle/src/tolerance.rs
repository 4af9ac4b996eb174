//! When two surfaces at a pixel centre count as a tie.

/// Relative camera-distance gap under which the two nearest surfaces at a
/// pixel centre count as a tie.
///
/// The gap is `(d2 - d1) / d1` with `d1`, `d2` the view depths (distance in
/// front of the eye along the view axis) of the nearest and second-nearest
/// distinct primitives, or `(d2 - d1) / (far - near)` for an orthographic
/// camera.
///
/// Why `1e-5`: two things separate a correct hider from this oracle even
/// when both are right about their own inputs.
/// - *Snapping*: hiders interpolate the window-depth plane of the snapped
///   triangle (corners moved by up to 1/512 pixel); the oracle uses the
///   plane of the unsnapped source triangle. Near a crossing of two
///   surfaces, or between two nearly parallel ones, the two depth orders can
///   differ where the surfaces are closer than the depth change that 1/512
///   pixel of snapping causes.
/// - *Depth-buffer resolution*: an `f32` window-depth buffer resolves
///   about `2^-24` in window depth near 1; with the fit camera
///   (`far/near = 100`, scene at about 25 x near) that is a relative view
///   depth of about `1.5e-6`.
///
/// `1e-5` sits above both for the scenes the tests use (the suite reports
/// the largest gap at which any hider disagrees, see `docs/oracle.md`),
/// while real ordering errors (a wrong sort, linear-z interpolation) show
/// gaps of `1e-3` and more. Scenes built to defeat depth precision (huge
/// depth ranges) are expected to produce tie pixels; that is the point of
/// counting them.
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
