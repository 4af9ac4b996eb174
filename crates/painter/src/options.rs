//! Options of the two painters. `Default` is the accurate choice.

/// Which depth a naive painter sorts by (farthest first).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SortKey {
    /// The farthest vertex of each triangle (largest window depth): the
    /// classic key, and the one Newell, Newell & Sancha start from.
    #[default]
    FarthestVertex,
    /// The centroid's depth (mean of the three window depths), as many
    /// plotting libraries do.
    Centroid,
}

/// Options of [`crate::NaivePainter`]. `Default` sorts by the farthest
/// vertex, the classic key.
///
/// ```
/// use hider_painter::{NaivePainterOptions, SortKey};
///
/// let options = NaivePainterOptions::default().with_sort_key(SortKey::Centroid);
/// assert_eq!(options.sort_key, SortKey::Centroid);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct NaivePainterOptions {
    /// The depth each triangle is sorted by.
    pub sort_key: SortKey,
    /// Stops the work from outside or at a deadline: polled while sorting and drawing,
    /// it then returns [`hider_scene::Error::Cancelled`]. Default: never
    /// cancelled, and free to poll.
    pub cancel: hider_scene::Cancel,
}

impl NaivePainterOptions {
    /// Sets [`Self::cancel`].
    pub fn with_cancel(mut self, cancel: hider_scene::Cancel) -> Self {
        self.cancel = cancel;
        self
    }

    /// Sets [`Self::sort_key`].
    pub fn with_sort_key(mut self, sort_key: SortKey) -> Self {
        self.sort_key = sort_key;
        self
    }
}

/// Most splits the automatic budget ever allows (a scene of about 62,000
/// triangles reaches it).
pub(crate) const DEFAULT_MAX_SPLITS: u64 = 4_000_000;

/// What a refusal of the split budget names ([`hider_scene::Error::Limit`]'s
/// `what`): the option that sets it, so that a caller can tell this limit
/// from others by comparing with this constant and word it in its own
/// terms (a command-line flag, a keyword).
///
/// ```
/// use hider_painter::{Painter, PainterOptions, SPLIT_BUDGET};
/// use hider_scene::{prepare, procedural, Error, Frame, Hider, PrepareOptions, View};
///
/// let scene = procedural::intersecting_pair();
/// let screen = prepare(&scene, &View::for_scene(&scene, 32, 32)?, &PrepareOptions::default())?;
/// let mut painter = Painter::new(PainterOptions::default().with_max_splits(0));
/// match painter.render(&screen, &mut Frame::new(32, 32)?) {
///     Err(Error::Limit { what, limit, .. }) if what == SPLIT_BUDGET => assert_eq!(limit, 0),
///     other => panic!("expected the split budget's refusal, got {other:?}"),
/// }
/// # Ok::<(), hider_scene::Error>(())
/// ```
pub const SPLIT_BUDGET: &str = "painter splits (the split budget, PainterOptions::max_splits)";

/// Splits allowed per input triangle, whatever [`PainterOptions::max_splits`]
/// says.
pub(crate) const SPLITS_PER_TRIANGLE: u64 = 64;

/// Splits allowed on top of [`SPLITS_PER_TRIANGLE`] per triangle.
pub(crate) const SPLITS_BASE: u64 = 4096;

/// Splits allowed per pair of input triangles, for scenes of up to
/// [`SPLITS_PAIRS_UP_TO`] triangles. Triangles that all cut one another
/// need far more than a few splits each: every one is cut along the line
/// where each other plane meets it, so its pieces grow with the square of
/// their number. The differential fuzzing found 36 triangles (a mirrored
/// order-6 pinwheel of three lattice triangles, all pairwise intersecting)
/// that need 6,587 splits, past the 6,400 that the per-triangle cap
/// alone allowed; no runaway is involved (each split cuts a real
/// intersection). Eight per pair gives them 16,768.
pub(crate) const SPLITS_PER_PAIR: u64 = 8;

/// The pair allowance counts pairs among at most this many triangles, so
/// that it adds at most 131,072 splits: large scenes keep the per-triangle
/// cap, which is what stops a degenerate cascade early.
pub(crate) const SPLITS_PAIRS_UP_TO: u64 = 128;

/// The automatic split budget of a scene of `triangles` input triangles
/// (when [`PainterOptions::max_splits`] is `None`): [`SPLITS_BASE`], plus
/// [`SPLITS_PER_TRIANGLE`] per triangle, plus [`SPLITS_PER_PAIR`] per pair
/// among up to [`SPLITS_PAIRS_UP_TO`] of them, at most
/// [`DEFAULT_MAX_SPLITS`].
pub(crate) fn split_cap(triangles: u64) -> u64 {
    let paired = triangles.min(SPLITS_PAIRS_UP_TO);
    (SPLITS_BASE + SPLITS_PER_TRIANGLE * triangles + SPLITS_PER_PAIR * paired * paired)
        .min(DEFAULT_MAX_SPLITS)
}

/// Default of [`PainterOptions::max_bytes`]: 1 GiB.
pub(crate) const DEFAULT_MAX_BYTES: u64 = 1 << 30;

/// Options of [`crate::Painter`] (Newell, Newell & Sancha with splitting).
/// `Default` is the accurate choice: exact orders, a budget no real scene
/// reaches, and vector output with every piece and no seam stroke.
///
/// ```
/// use hider_painter::PainterOptions;
///
/// let options = PainterOptions::default()
///     .with_max_splits(10_000)
///     .with_svg_drop_hidden(true);
/// assert_eq!(options.max_splits, Some(10_000));
/// assert!(options.svg_drop_hidden);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct PainterOptions {
    /// Most polygon splits allowed in one frame. Intersections and cyclic
    /// overlaps each cost at least one split; when the budget runs out
    /// `render` stops with a [`hider_scene::Error::Limit`] whose `what` is
    /// [`SPLIT_BUDGET`] rather than run (or allocate) without bound.
    ///
    /// `None` (the default) is an automatic budget for a scene of `n`
    /// triangles: `4096 + 64 n + 8 m^2` with `m = min(n, 128)`, at most
    /// 4,000,000 (a base, an allowance per input triangle and one per pair
    /// among small scenes; `split_cap` in `options.rs`). Real scenes need a
    /// few splits per triangle once hidden pieces are culled (10 on 500
    /// random triangles overlapping in a cube, 4.3 on 8,000, 1.4 on a 10k
    /// random soup), so a frame past that budget is degenerate input that
    /// would otherwise split until memory runs out (found by fuzzing).
    /// `Some(k)` allows exactly `k` splits, more or fewer than that.
    pub max_splits: Option<u64>,
    /// Most bytes the piece arena may hold (default 1 GiB); checked after
    /// every split, the frame stops with [`hider_scene::Error::Limit`]
    /// beyond it.
    pub max_bytes: u64,
    /// SVG output only: leave out pieces that own no pixel centre in the
    /// raster. Smaller files, but sub-pixel slivers that would show in a
    /// zoomed vector view are dropped, so off by default. When on, `render`
    /// also records which piece painted each pixel (one `u32` per pixel).
    pub svg_drop_hidden: bool,
    /// SVG output only: stroke each path with its own colour at this width
    /// (pixels) to hide the hairline seams vector renderers draw between
    /// abutting polygons. 0 (the exact geometry) by default.
    pub svg_seam_stroke: f64,
    /// Drop pieces hidden at every point of their polygon before ordering
    /// them (`cull.rs`): behind opaque triangles (material opacity 1)
    /// that cover every pixel square they meet. On (the default), which
    /// keeps the raster and the SVG exact and makes deep overlapping
    /// scenes cost what they show. Turn it off only when drawing the
    /// pieces in colours of one's own that may be translucent (the scene's
    /// materials say opaque, but what is behind would show through).
    pub cull_hidden: bool,
    /// Record every step of the ordering as a [`crate::PainterTrace`]
    /// ([`crate::Painter::trace`]): off by default, and free when off.
    pub trace: bool,
    /// Stops the work from outside or at a deadline: polled in the ordering loop (every few hundred polygons placed or split),
    /// it then returns [`hider_scene::Error::Cancelled`]. Default: never
    /// cancelled, and free to poll.
    pub cancel: hider_scene::Cancel,
}

impl Default for PainterOptions {
    fn default() -> Self {
        Self {
            max_splits: None,
            max_bytes: DEFAULT_MAX_BYTES,
            svg_drop_hidden: false,
            svg_seam_stroke: 0.0,
            cull_hidden: true,
            trace: false,
            cancel: hider_scene::Cancel::default(),
        }
    }
}

impl PainterOptions {
    /// Sets [`Self::cancel`].
    pub fn with_cancel(mut self, cancel: hider_scene::Cancel) -> Self {
        self.cancel = cancel;
        self
    }

    /// Sets [`Self::max_bytes`].
    pub fn with_max_bytes(mut self, max_bytes: u64) -> Self {
        self.max_bytes = max_bytes;
        self
    }

    /// The split budget a frame of `triangles` input triangles gets:
    /// [`Self::max_splits`] when set, else the automatic budget that
    /// field's documentation gives.
    pub fn split_budget(&self, triangles: u64) -> u64 {
        self.max_splits.unwrap_or_else(|| split_cap(triangles))
    }

    /// Sets [`Self::max_splits`] to exactly `max_splits` (no automatic
    /// budget).
    pub fn with_max_splits(mut self, max_splits: u64) -> Self {
        self.max_splits = Some(max_splits);
        self
    }

    /// Sets [`Self::svg_drop_hidden`].
    pub fn with_svg_drop_hidden(mut self, drop: bool) -> Self {
        self.svg_drop_hidden = drop;
        self
    }

    /// Sets [`Self::cull_hidden`].
    pub fn with_cull_hidden(mut self, cull: bool) -> Self {
        self.cull_hidden = cull;
        self
    }

    /// Sets [`Self::trace`].
    pub fn with_trace(mut self, trace: bool) -> Self {
        self.trace = trace;
        self
    }

    /// Sets [`Self::svg_seam_stroke`].
    pub fn with_svg_seam_stroke(mut self, width: f64) -> Self {
        self.svg_seam_stroke = width;
        self
    }
}
