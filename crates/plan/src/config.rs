//! The knobs a caller (the `hider` command line, the Python package, the
//! benchmark) sets across hiders.

use hider_scene::ShadeMode;
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

    /// Sets [`Self::ordered_polygons`].
    pub fn with_ordered_polygons(mut self, ordered_polygons: bool) -> Self {
        self.ordered_polygons = ordered_polygons;
        self
    }
}
