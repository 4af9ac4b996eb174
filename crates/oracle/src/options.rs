//! The oracle's options: which plane depth is taken from and the work
//! budget.

/// Which camera-space plane the oracle intersects the pixel rays with.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DepthPlane {
    /// The window-depth plane through the screen triangle's *snapped*
    /// corners (the front end's fixed-point positions and `f64` window
    /// depths), evaluated and compared *exactly* at each pixel centre.
    /// Projection maps planes to planes, so this is exactly the surface
    /// every hider is asked to render, and window depth orders surfaces as
    /// view depth does. A tie is an exactly equal depth; the lower id wins
    /// it. The referee for cross-validating hiders (the default).
    #[default]
    Snapped,
    /// The plane of the *source* triangle (`PrimInfo::camera`, before
    /// clipping and snapping). Measures what the front end's 1/256-pixel
    /// snapping does to visibility: where two surfaces cross or nearly
    /// touch, moving corners by up to 1/512 pixel can flip the order.
    /// Near the near plane, where screen-space depth gradients are steep,
    /// such flips appear at relative gaps above `1e-5`, so hiders are not
    /// scored against this plane. Depth is the `f64` intersection of the
    /// pixel's camera ray with the plane; the nearest wins, a tie is an
    /// equal `f64` depth.
    Source,
}

/// Options of the [`RayCastOracle`](crate::RayCastOracle). `Default` is the
/// accurate choice.
///
/// ```
/// use hider_oracle::{DepthPlane, OracleOptions};
///
/// let options = OracleOptions::default()
///     .with_depth_plane(DepthPlane::Source)
///     .with_max_pixel_tests(1 << 20)
///     .with_max_bytes(64 << 20);
/// assert_eq!(options.depth_plane, DepthPlane::Source);
/// assert_eq!(options.max_bytes, 64 << 20);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct OracleOptions {
    /// The plane each triangle's depth is taken from.
    pub depth_plane: DepthPlane,
    /// Most (triangle, pixel) candidate tests one frame may cost, checked
    /// before any work in
    /// [`RayCastOracle::try_evaluate`](crate::RayCastOracle::try_evaluate)
    /// and `render`: the oracle is slow on purpose and should refuse rather
    /// than run for hours.
    pub max_pixel_tests: u64,
    /// Budget for the per-pixel working arrays (nearest surfaces, camera
    /// rays of the source-plane mode and the reference's ids, depths and
    /// gaps: about 100 bytes a pixel, [`RayCastOracle::bytes_needed`](crate::RayCastOracle::bytes_needed)),
    /// checked before anything is allocated: an image that would need more
    /// is refused with [`hider_scene::Error::Limit`] instead of exhausting
    /// the machine's memory (16384 x 16384 pixels would need about 28 GB).
    /// Default 2 GiB, enough for 4096 x 4096.
    pub max_bytes: u64,
    /// Stops the work from outside or at a deadline: polled per row of pixels,
    /// it then returns [`hider_scene::Error::Cancelled`]. Default: never
    /// cancelled, and free to poll.
    pub cancel: hider_scene::Cancel,
}

/// The default [`OracleOptions::max_bytes`]: 2 GiB.
pub const DEFAULT_MAX_BYTES: u64 = 1 << 31;

impl Default for OracleOptions {
    fn default() -> Self {
        Self {
            depth_plane: DepthPlane::Snapped,
            max_pixel_tests: 1 << 34,
            max_bytes: DEFAULT_MAX_BYTES,
            cancel: hider_scene::Cancel::default(),
        }
    }
}

impl OracleOptions {
    /// Sets [`Self::cancel`].
    pub fn with_cancel(mut self, cancel: hider_scene::Cancel) -> Self {
        self.cancel = cancel;
        self
    }

    /// Sets [`Self::depth_plane`].
    pub fn with_depth_plane(mut self, plane: DepthPlane) -> Self {
        self.depth_plane = plane;
        self
    }

    /// Sets [`Self::max_pixel_tests`].
    pub fn with_max_pixel_tests(mut self, tests: u64) -> Self {
        self.max_pixel_tests = tests;
        self
    }

    /// Sets [`Self::max_bytes`].
    pub fn with_max_bytes(mut self, bytes: u64) -> Self {
        self.max_bytes = bytes;
        self
    }
}
