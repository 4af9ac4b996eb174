//! Options of the Warnock hider.

use hider_scene::ShadeMode;

/// Largest supported [`WarnockOptions::samples_per_side`].
pub(crate) const MAX_SAMPLES_PER_SIDE: u32 = 16;

/// Options of [`crate::Warnock`]. `Default` is the accurate choice: stop at
/// pixel size and resolve each pixel at its centre, exactly as the z-buffer
/// does, so the result equals the oracle on every non-tie pixel.
///
/// ```
/// use hider_warnock::WarnockOptions;
///
/// let options = WarnockOptions::default()
///     .with_samples_per_side(4)
///     .with_max_bytes(64 << 20);
/// assert!(options.is_antialiased());
/// assert_eq!(options.max_bytes, 64 << 20);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct WarnockOptions {
    /// Samples per pixel side. `1` (the default) subdivides down to pixels
    /// and samples each at its centre. A larger power of two (2, 4, 8 or
    /// 16) keeps subdividing inside a pixel down to an `n x n` grid of
    /// samples on the 1/256-pixel lattice (sample `k` at offset
    /// `(2k + 1) * 128 / n`), and writes the covered fraction to
    /// [`hider_scene::Frame::coverage`] and a box-filtered colour: the
    /// anti-aliased mode, scored against the oracle's analytic coverage.
    pub samples_per_side: u32,
    /// How the anti-aliased mode colours samples (the pixel-centre mode
    /// leaves colour to [`hider_scene::shade_frame`]).
    pub shade: ShadeMode,
    /// Record the final (leaf) regions of the subdivision, for the debug
    /// picture ([`crate::draw_region_outlines`]). Off by default:
    /// the record can hold up to one entry per pixel.
    pub record_regions: bool,
    /// Record every window of the pixel pass with each polygon's class
    /// against it and what decided it ([`crate::Warnock::window_classes`]),
    /// for teaching and debugging. Off by default: the record holds one
    /// entry per polygon per window looked at (capped at
    /// [`crate::MAX_CLASS_RECORDS`], whose worst case counts in
    /// [`Self::max_bytes`]).
    pub record_classes: bool,
    /// Budget for the working memory (triangle set-up records plus the
    /// worst-case candidate arena), in bytes; checked before anything is
    /// allocated, a larger frame is refused with
    /// [`hider_scene::Error::Limit`]. Default 1 GiB.
    pub max_bytes: u64,
    /// Stops the work from outside or at a deadline: polled per region subdivided,
    /// it then returns [`hider_scene::Error::Cancelled`]. Default: never
    /// cancelled, and free to poll.
    pub cancel: hider_scene::Cancel,
}

impl Default for WarnockOptions {
    fn default() -> Self {
        Self {
            samples_per_side: 1,
            shade: ShadeMode::Lambert,
            record_regions: false,
            record_classes: false,
            max_bytes: 1 << 30,
            cancel: hider_scene::Cancel::default(),
        }
    }
}

impl WarnockOptions {
    /// Sets [`Self::cancel`].
    pub fn with_cancel(mut self, cancel: hider_scene::Cancel) -> Self {
        self.cancel = cancel;
        self
    }

    /// Sets [`Self::samples_per_side`] (checked when rendering).
    pub fn with_samples_per_side(mut self, samples: u32) -> Self {
        self.samples_per_side = samples;
        self
    }

    /// Sets [`Self::shade`].
    pub fn with_shade(mut self, shade: ShadeMode) -> Self {
        self.shade = shade;
        self
    }

    /// Sets [`Self::record_regions`].
    pub fn with_record_regions(mut self, record: bool) -> Self {
        self.record_regions = record;
        self
    }

    /// Sets [`Self::record_classes`].
    pub fn with_record_classes(mut self, record: bool) -> Self {
        self.record_classes = record;
        self
    }

    /// Sets [`Self::max_bytes`].
    pub fn with_max_bytes(mut self, bytes: u64) -> Self {
        self.max_bytes = bytes;
        self
    }

    /// Whether the anti-aliased (sub-pixel) mode is on.
    pub fn is_antialiased(&self) -> bool {
        self.samples_per_side > 1
    }

    /// Checks the options, naming the bad value.
    pub fn validate(&self) -> hider_scene::Result<()> {
        let n = self.samples_per_side;
        if n == 0 || n > MAX_SAMPLES_PER_SIDE || !n.is_power_of_two() {
            return Err(hider_scene::Error::OutOfRange {
                what: "warnock samples per side",
                expected: "1, 2, 4, 8 or 16",
                value: n.to_string(),
            });
        }
        Ok(())
    }
}
