//! The knobs a caller (the `hider` command line) sets across hiders.

use hider_zbuffer::{DepthFormat, DepthSource};

/// Cross-cutting knobs for building a registered hider: each
/// [`Entry`](crate::registry::Entry) applies the ones its hider has and
/// refuses, naming the knob and the hider, the ones it does not.
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
    /// Depth buffer storage format (`--depth-format`), for the entries
    /// whose format is not part of their name (`zbuffer`,
    /// `zbuffer-tiled`).
    pub depth_format: Option<DepthFormat>,
    /// What the depth test compares (`--depth-source`), for `zbuffer`.
    pub depth_source: Option<DepthSource>,
    /// Worker threads (`--threads`) for the hiders that render in
    /// parallel; the others ignore it (it also drives the front end, so it
    /// is never refused).
    pub threads: Option<usize>,
    /// Whether vector output will be asked of the hider (`--svg`): only
    /// entries whose hider has [`vector_output`] accept it.
    ///
    /// [`vector_output`]: hider_scene::DynHider::vector_output
    pub vector_output: bool,
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

    /// Sets [`Self::vector_output`].
    pub fn with_vector_output(mut self, vector_output: bool) -> Self {
        self.vector_output = vector_output;
        self
    }
}
