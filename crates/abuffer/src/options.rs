//! Options of the hiders of this crate. `Default` is the accurate choice.

use hider_scene::{Error, Result, ShadeMode};

use crate::pattern::SamplePattern;

/// How fragments are ordered and composited at resolve time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum DepthMode {
    /// Every sample is composited in its own depth order, by the window
    /// depth of each covered sample: exact where surfaces intersect inside
    /// a pixel. With 32 samples the result equals a 32-sample supersampled
    /// z-buffer sample for sample. The sample depths are not stored: they
    /// are the triangle's depth plane at the samples, recomputed (same
    /// expression, same `f32` values) for the pixels where two fragments
    /// overlap in mask and depth range; only a fragment that two triangles
    /// were merged into keeps its 32 depths (`128` bytes more). The
    /// default.
    #[default]
    PerSample,
    /// Carpenter's fragments: only `zmin` and `zmax` per fragment; the list
    /// is composited in `zmin` order, and where the next fragment overlaps
    /// this one in depth the paper's approximation estimates the visible
    /// fraction from the two depth ranges, as if two planes crossed the
    /// pixel with opposite slopes:
    /// `vis = (zmax' - zmin) / ((zmax - zmin) + (zmax' - zmin'))`.
    MinMax,
    /// Like [`DepthMode::MinMax`] but ignoring interpenetration: fragments
    /// are composited strictly in `zmin` order. Kept to show what the
    /// paper's approximation buys.
    ZminOrder,
}

/// When two fragments of one pixel are merged into one (Carpenter's merge
/// of adjacent fragments of the same surface).
///
/// A candidate pair always has disjoint masks (the centre counting as a
/// sample), triangles that share a snapped vertex (they are neighbours in a
/// mesh), the same facing and the same material.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum MergePolicy {
    /// Never merge.
    Off,
    /// Merge only when the two colours and opacities agree (each colour
    /// channel within `1e-5`, far below one 8-bit step): the merged fragment then shades
    /// every sample as the separate ones would, so merging is exact (in
    /// [`DepthMode::PerSample`] the per-sample depths are kept). Typical
    /// hit: the two triangles of a planar quad. The default.
    #[default]
    SameColor,
    /// Carpenter's rule: merge neighbours of the same surface whatever their
    /// shading, averaging colour by covered samples. Saves the most memory;
    /// a merged fragment that is partly hidden shows the average colour of
    /// its parts in the visible samples.
    SameSurface,
}

/// What happens when a fragment would make a pixel's list longer than
/// [`ABufferOptions::max_list_len`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum OverflowPolicy {
    /// First drop the fragments provably hidden in every sample and at the
    /// centre by nearer opaque fragments (exact); if the list is still
    /// full, drop the fragment with the farthest `zmin` (the new one or an
    /// old one) and count it in [`crate::ABufferStats::dropped`]. The
    /// default: a pixel with hundreds of surfaces degrades instead of
    /// failing the frame.
    #[default]
    DropFarthest,
    /// Drop provably hidden fragments; if the list is still full, fail the
    /// frame with a [`hider_scene::Error::Render`] naming the pixel.
    Error,
}

/// Default bound on one pixel's fragment list.
pub(crate) const DEFAULT_MAX_LIST_LEN: u32 = 128;
/// Default bound on the A-buffer's working memory: 1 GiB.
pub(crate) const DEFAULT_MAX_BYTES: u64 = 1 << 30;

/// Options of [`crate::ABuffer`]: every knob that changes what it does or
/// how much work it takes. `Default` is the accurate choice; set fields
/// with the `with_*` methods:
///
/// ```
/// use hider_abuffer::{ABufferOptions, DepthMode, MergePolicy};
///
/// let options = ABufferOptions::default()
///     .with_depth(DepthMode::MinMax)
///     .with_merge(MergePolicy::Off)
///     .with_max_bytes(64 << 20);
/// assert_eq!(options.depth, DepthMode::MinMax);
/// assert!(options.occlusion_culling);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct ABufferOptions {
    /// Sample positions of the coverage masks (default: the 8 x 4 grid).
    pub pattern: SamplePattern,
    /// Depth handling at resolve time (default: exact per-sample depth).
    pub depth: DepthMode,
    /// Fragment merging (default: exact, same-colour merges only).
    pub merge: MergePolicy,
    /// Longest fragment list a pixel may hold (default 128).
    pub max_list_len: u32,
    /// What to do when a list would be longer.
    pub overflow: OverflowPolicy,
    /// Bound on working memory (pixel table plus fragment pool), in bytes
    /// (default 1 GiB). The pixel table is checked before it is allocated; the pool stops
    /// with [`hider_scene::Error::Budget`] when the next fragment would pass
    /// the bound.
    pub max_bytes: u64,
    /// How primitives are coloured before compositing.
    pub shade: ShadeMode,
    /// Exact occlusion culling (default on): per pixel, per 8 x 8 block,
    /// and pruning of lists behind a pixel's opaque bound.
    ///
    /// A tuning knob, set only by tests and the profiling bins: it trades
    /// the bookkeeping of opaque bounds for fragments never inserted. The
    /// output does not change (below), and the default, on, is the fast
    /// exact choice. Off, no pixel gets an opaque bound, so nothing is
    /// culled on arrival, no block is skipped and nothing is pruned behind
    /// a bound: every fragment reaches its list (the overflow policy still
    /// applies). The image, coverage,
    /// ids and sample ids are the same either way (culling only drops
    /// fragments that lose every sample and the centre; colours may differ
    /// in the last bit of rounding, within one 8-bit step); only the work
    /// counters and the time differ. Off is the reference the culling is
    /// tested against, and measures what it saves.
    pub occlusion_culling: bool,
    /// Whether each tile takes its triangles front to back (the default:
    /// sorted by nearest vertex depth) or in submission order.
    ///
    /// A tuning knob, set only by tests and the profiling bins: it trades a
    /// sort per tile for more culling. The output does not change: the exact
    /// answer (samples, coverage, ids) is the same either way, since lists
    /// are ordered by depth at resolve; front to back, the nearest surfaces
    /// set the opaque bounds first, so far more of what lies behind is
    /// culled (per pixel or per block) instead of inserted and pruned.
    /// Merging decisions, which look at the latest fragments of a list,
    /// and colour rounding may differ (within one 8-bit step). The default,
    /// front to back, is the fast exact choice.
    pub front_to_back: bool,
    /// Threads rendering bands of tiles: `1` renders on the calling
    /// thread, `0` (the default) uses every core the machine reports. The
    /// caller's rayon pool is used when it has exactly this many threads
    /// (a command line with `--threads T` builds one), a pool of the
    /// hider's own otherwise. Tiles are independent (their lists,
    /// culling and resolve), so the image, the sample ids and the work
    /// counters are the same at every thread count; each thread keeps a
    /// pixel table and fragment pool of its own, and
    /// [`Self::max_bytes`] is shared evenly among them (fewer threads
    /// run when the bound does not hold two pixel tables per thread).
    pub threads: usize,
    /// Whether tiles whose triangles are all opaque are resolved from a
    /// sample buffer instead of fragment lists (the default: on).
    ///
    /// A tuning knob, set only by tests and the profiling bins: it trades
    /// a sample buffer's memory for a much cheaper pass than lists. The
    /// output does not change (below), and the default, on, is the fast
    /// exact choice. The lists of such a tile only decide which surface is in front at each
    /// sample and at the centre; a depth and a primitive per sample answer
    /// the same, so the image, coverage, ids and sample ids are those of
    /// the lists (property-tested, bit for bit with merging off; merging
    /// averages colours within one 8-bit step), for a fraction of the
    /// cost. Used in [`DepthMode::PerSample`] without
    /// [`MergePolicy::SameSurface`] (whose averaged colours show), when
    /// [`Self::max_bytes`] holds the buffer (half a megabyte per thread)
    /// beside the pixel table. Off, every tile keeps lists: the reference
    /// the sample buffer is tested against.
    pub sample_tiles: bool,
    /// Stops the work from outside or at a deadline: polled per tile and every few thousand triangles,
    /// it then returns [`hider_scene::Error::Cancelled`]. Default: never
    /// cancelled, and free to poll.
    pub cancel: hider_scene::Cancel,
}

impl Default for ABufferOptions {
    fn default() -> Self {
        Self {
            pattern: SamplePattern::Grid32,
            depth: DepthMode::PerSample,
            merge: MergePolicy::SameColor,
            max_list_len: DEFAULT_MAX_LIST_LEN,
            overflow: OverflowPolicy::DropFarthest,
            max_bytes: DEFAULT_MAX_BYTES,
            shade: ShadeMode::Lambert,
            occlusion_culling: true,
            front_to_back: true,
            threads: 0,
            sample_tiles: true,
            cancel: hider_scene::Cancel::default(),
        }
    }
}

impl ABufferOptions {
    /// Sets [`Self::cancel`].
    pub fn with_cancel(mut self, cancel: hider_scene::Cancel) -> Self {
        self.cancel = cancel;
        self
    }

    /// Carpenter's own configuration: 8 x 4 masks, `zmin`/`zmax` fragments
    /// with the interpenetration approximation, same-surface merging.
    pub fn carpenter() -> Self {
        Self::default()
            .with_depth(DepthMode::MinMax)
            .with_merge(MergePolicy::SameSurface)
    }

    /// Sets [`Self::pattern`].
    pub fn with_pattern(mut self, pattern: SamplePattern) -> Self {
        self.pattern = pattern;
        self
    }

    /// Sets [`Self::depth`].
    pub fn with_depth(mut self, depth: DepthMode) -> Self {
        self.depth = depth;
        self
    }

    /// Sets [`Self::merge`].
    pub fn with_merge(mut self, merge: MergePolicy) -> Self {
        self.merge = merge;
        self
    }

    /// Sets [`Self::max_list_len`] (at least 1).
    pub fn with_max_list_len(mut self, len: u32) -> Self {
        self.max_list_len = len.max(1);
        self
    }

    /// Sets [`Self::overflow`].
    pub fn with_overflow(mut self, overflow: OverflowPolicy) -> Self {
        self.overflow = overflow;
        self
    }

    /// Sets [`Self::max_bytes`].
    pub fn with_max_bytes(mut self, bytes: u64) -> Self {
        self.max_bytes = bytes;
        self
    }

    /// Sets [`Self::shade`].
    pub fn with_shade(mut self, shade: ShadeMode) -> Self {
        self.shade = shade;
        self
    }

    /// Sets [`Self::occlusion_culling`].
    pub fn with_occlusion_culling(mut self, on: bool) -> Self {
        self.occlusion_culling = on;
        self
    }

    /// Sets [`Self::front_to_back`].
    pub fn with_front_to_back(mut self, on: bool) -> Self {
        self.front_to_back = on;
        self
    }

    /// Sets [`Self::threads`].
    pub fn with_threads(mut self, threads: usize) -> Self {
        self.threads = threads;
        self
    }

    /// Sets [`Self::sample_tiles`].
    pub fn with_sample_tiles(mut self, on: bool) -> Self {
        self.sample_tiles = on;
        self
    }

    /// Largest accepted [`Self::threads`].
    pub const MAX_THREADS: usize = 256;

    /// Whether these are [`Self::carpenter`]'s options, whatever the
    /// thread count (which changes no output).
    pub fn is_carpenter(&self) -> bool {
        self.with_threads(0) == Self::carpenter().with_threads(0)
    }
}

/// Options of the supersampling baselines ([`crate::SupersampledZBuffer`]
/// and [`crate::SortedTransparencyZBuffer`]). `Default` is the accurate
/// choice (all 32 samples):
///
/// ```
/// use hider_abuffer::{SamplePattern, SsaaOptions};
///
/// let options = SsaaOptions::default().with_pattern(SamplePattern::Grid4);
/// assert_eq!(options.pattern.count(), 4);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct SsaaOptions {
    /// Sample positions (default: all 32 cells of the 8 x 4 grid).
    pub pattern: SamplePattern,
    /// How primitives are coloured.
    pub shade: ShadeMode,
    /// Bound on the sample buffers, in bytes, checked before allocating.
    pub max_bytes: u64,
    /// Stops the work from outside or at a deadline: polled every few thousand triangles,
    /// it then returns [`hider_scene::Error::Cancelled`]. Default: never
    /// cancelled, and free to poll.
    pub cancel: hider_scene::Cancel,
}

impl Default for SsaaOptions {
    fn default() -> Self {
        Self {
            pattern: SamplePattern::Grid32,
            shade: ShadeMode::Lambert,
            max_bytes: DEFAULT_MAX_BYTES,
            cancel: hider_scene::Cancel::default(),
        }
    }
}

impl SsaaOptions {
    /// Sets [`Self::cancel`].
    pub fn with_cancel(mut self, cancel: hider_scene::Cancel) -> Self {
        self.cancel = cancel;
        self
    }

    /// Sets [`Self::pattern`].
    pub fn with_pattern(mut self, pattern: SamplePattern) -> Self {
        self.pattern = pattern;
        self
    }

    /// Sets [`Self::shade`].
    pub fn with_shade(mut self, shade: ShadeMode) -> Self {
        self.shade = shade;
        self
    }

    /// Sets [`Self::max_bytes`].
    pub fn with_max_bytes(mut self, bytes: u64) -> Self {
        self.max_bytes = bytes;
        self
    }

    /// Checks that `pixels` pixels of `per_sample` bytes per sample (plus
    /// the centre buffer) fit in [`Self::max_bytes`]; returns the bytes.
    pub(crate) fn check_budget(
        &self,
        hider: &'static str,
        pixels: usize,
        per_sample: u64,
    ) -> Result<u64> {
        let bytes = pixels as u64 * (self.pattern.count() as u64 * per_sample + 12);
        if bytes > self.max_bytes {
            return Err(Error::Budget {
                what: hider,
                value: bytes,
                limit: self.max_bytes,
            });
        }
        Ok(bytes)
    }
}
