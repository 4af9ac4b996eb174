//! The knobs a caller (the `hider` command line, the Python package, the
//! benchmark) sets across hiders.

use hider_abuffer::OverflowPolicy;
use hider_scene::{Cancel, ShadeMode};
use hider_zbuffer::{DepthFormat, DepthSource};

/// Cross-cutting knobs for building a registered hider: each
/// [`Entry`](crate::registry::Entry) applies the ones its hider has and
/// refuses, naming the [`Knob`](crate::Knob) and the hider, the ones it
/// does not.
///
/// `Default` sets nothing: every entry is built with its own options.
///
/// ```
/// use hider_plan::{HiderConfig, registry};
/// use hider_zbuffer::DepthFormat;
///
/// let config = HiderConfig::default().with_depth_format(DepthFormat::F64);
/// assert!(registry::by_name("zbuffer-tiled").unwrap().build(&config).is_ok());
/// let refused = registry::by_name("painter").unwrap().build(&config);
/// assert!(refused.is_err());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct HiderConfig {
    /// Depth buffer storage format, for the entries whose format is not
    /// part of their name (`zbuffer`, `zbuffer-tiled`).
    pub depth_format: Option<DepthFormat>,
    /// What the depth test compares, for `zbuffer`.
    pub depth_source: Option<DepthSource>,
    /// Worker threads for the hiders that render in parallel; the others
    /// ignore it (it also drives the front end, so it is never refused).
    pub threads: Option<usize>,
    /// Whether the depth-ordered polygons will be asked of the hider: only
    /// entries whose hider has [`ordered_polygons`] accept it.
    ///
    /// [`ordered_polygons`]: hider_scene::DynHider::ordered_polygons
    pub ordered_polygons: bool,
    /// How the hiders that resolve colour themselves colour primitives
    /// (their options' `shade`); never refused: for the others the colour
    /// pass over the ids applies it.
    pub shade: Option<ShadeMode>,
    /// The painter's split budget, exactly this many splits
    /// (`PainterOptions::max_splits`; `None` keeps its automatic budget).
    /// A budget: under `auto` it applies when the plan picks the painter.
    pub max_splits: Option<u64>,
    /// The A-buffers' bound on one pixel's fragment list
    /// (`ABufferOptions::max_list_len`). A budget, as `max_splits`.
    pub max_list_len: Option<u32>,
    /// What the A-buffers do with a full fragment list
    /// (`ABufferOptions::overflow`). A budget, as `max_splits`.
    pub overflow: Option<OverflowPolicy>,
    /// The token that stops the hider (every entry's options' `cancel`);
    /// never refused. Default: never cancelled.
    pub cancel: Cancel,
}

impl HiderConfig {
    /// Sets [`Self::depth_format`].
    pub fn with_depth_format(mut self, format: DepthFormat) -> Self {
        self.depth_format = Some(format);
        self
    }

    /// Sets [`Self::depth_source`].
    pub fn with_depth_source(mut self, source: DepthSource) -> Self {
        self.depth_source = Some(source);
        self
    }

    /// Sets [`Self::threads`].
    pub fn with_threads(mut self, threads: usize) -> Self {
        self.threads = Some(threads);
        self
    }

    /// Sets [`Self::shade`].
    pub fn with_shade(mut self, shade: ShadeMode) -> Self {
        self.shade = Some(shade);
        self
    }

    /// Sets [`Self::max_splits`].
    pub fn with_max_splits(mut self, splits: u64) -> Self {
        self.max_splits = Some(splits);
        self
    }

    /// Sets [`Self::max_list_len`].
    pub fn with_max_list_len(mut self, len: u32) -> Self {
        self.max_list_len = Some(len);
        self
    }

    /// Sets [`Self::overflow`].
    pub fn with_overflow(mut self, overflow: OverflowPolicy) -> Self {
        self.overflow = Some(overflow);
        self
    }

    /// This config without the budgets a hider taking `knobs` does not
    /// have: under `auto`, a budget is a limit for the hider the plan
    /// picks, if it has one, not a request that only some hiders accept.
    pub(crate) fn budgets_for(mut self, knobs: crate::registry::Knobs) -> Self {
        if !knobs.max_splits {
            self.max_splits = None;
        }
        if !knobs.fragment_lists {
            self.max_list_len = None;
            self.overflow = None;
        }
        self
    }

    /// Sets [`Self::cancel`].
    pub fn with_cancel(mut self, cancel: Cancel) -> Self {
        self.cancel = cancel;
        self
    }

    /// Sets [`Self::ordered_polygons`].
    pub fn with_ordered_polygons(mut self, ordered_polygons: bool) -> Self {
        self.ordered_polygons = ordered_polygons;
        self
    }
}
