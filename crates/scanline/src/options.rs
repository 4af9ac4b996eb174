//! Options of the scanline hider.

/// Options of [`crate::Scanline`]. `Default` is the accurate choice (every
/// setting here is exact; they only trade time and memory).
///
/// ```
/// use hider_scanline::ScanlineOptions;
///
/// let options = ScanlineOptions::default()
///     .with_max_splits_per_span(4)
///     .with_max_bytes(256 << 20);
/// assert_eq!(options.max_splits_per_span, 4);
/// assert_eq!(options.max_bytes, 256 << 20);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct ScanlineOptions {
    /// How many times one span may be split at depth crossings before the
    /// rest of it is resolved by the one-row depth buffer fallback.
    ///
    /// Splitting costs a pass over the span's active polygon list per split
    /// plus a short search for the crossing pixel; a span that keeps
    /// splitting lies in a knot of mutually piercing polygons, where
    /// comparing depths pixel by pixel over the remaining run is cheaper.
    /// Both paths decide every pixel with the same per-pixel depth
    /// comparison, so the setting changes cost, not the picture. `0` sends
    /// every span that would split to the fallback; `u32::MAX` never uses
    /// it. Default 16.
    pub max_splits_per_span: u32,
    /// Budget for the working tables (polygon and edge tables, bucket
    /// indices, active lists, the row buffer), in bytes. Checked before
    /// anything is allocated; a scene that would need more is refused with
    /// [`hider_scene::Error::Budget`]. Default 1 GiB.
    pub max_bytes: u64,
    /// Record the sweep ([`crate::Scanline::trace`]): the edge table, each
    /// row's active edge list, and every run of pixels with its visible
    /// primitive, its depths at both ends and how it was resolved
    /// ([`crate::Scanline::spans`]), for pictures, teaching and debugging.
    /// Off by default: the record grows with the edges' rows and the runs
    /// (at most one per pixel); its worst case counts in [`Self::max_bytes`].
    pub record_spans: bool,
    /// Stops the work from outside or at a deadline: polled per band of rows,
    /// it then returns [`hider_scene::Error::Cancelled`]. Default: never
    /// cancelled, and free to poll.
    pub cancel: hider_scene::Cancel,
}

impl Default for ScanlineOptions {
    fn default() -> Self {
        Self {
            max_splits_per_span: 16,
            max_bytes: 1 << 30,
            record_spans: false,
            cancel: hider_scene::Cancel::default(),
        }
    }
}

impl ScanlineOptions {
    /// Sets [`Self::cancel`].
    pub fn with_cancel(mut self, cancel: hider_scene::Cancel) -> Self {
        self.cancel = cancel;
        self
    }

    /// Sets [`Self::max_splits_per_span`].
    pub fn with_max_splits_per_span(mut self, splits: u32) -> Self {
        self.max_splits_per_span = splits;
        self
    }

    /// Sets [`Self::record_spans`].
    pub fn with_record_spans(mut self, record: bool) -> Self {
        self.record_spans = record;
        self
    }

    /// Sets [`Self::max_bytes`].
    pub fn with_max_bytes(mut self, bytes: u64) -> Self {
        self.max_bytes = bytes;
        self
    }
}
