//! The error type of the plan crate: a hider that is not registered, a
//! knob that does not apply to the chosen hider, and the scene crate's
//! errors.
//!
//! The errors are typed and speak of hiders and knobs, not of any front
//! end's spelling: the `hider` command line names its flags (`--algo`,
//! `--depth-format`), the Python package its keywords (`algo=`), each from
//! the fields.

use crate::algo::AlgoName;

/// A cross-cutting knob of [`HiderConfig`](crate::HiderConfig) that only
/// some hiders take.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Knob {
    /// [`HiderConfig::depth_format`](crate::HiderConfig::depth_format).
    DepthFormat,
    /// [`HiderConfig::depth_source`](crate::HiderConfig::depth_source).
    DepthSource,
    /// [`HiderConfig::ordered_polygons`](crate::HiderConfig::ordered_polygons).
    OrderedPolygons,
    /// [`HiderConfig::max_splits`](crate::HiderConfig::max_splits).
    MaxSplits,
    /// [`HiderConfig::max_list_len`](crate::HiderConfig::max_list_len).
    MaxListLen,
    /// [`HiderConfig::overflow`](crate::HiderConfig::overflow).
    Overflow,
}

impl Knob {
    /// The knob in words (`"depth format"`).
    pub fn describe(self) -> &'static str {
        match self {
            Knob::DepthFormat => "depth format",
            Knob::DepthSource => "depth source",
            Knob::OrderedPolygons => "ordered polygons",
            Knob::MaxSplits => "split budget",
            Knob::MaxListLen => "fragment list length",
            Knob::Overflow => "fragment list overflow policy",
        }
    }

    /// Why only some hiders take it, for `hider` (a name or `auto`).
    pub fn reason(self, hider: &str) -> String {
        match self {
            Knob::DepthFormat => format!("{hider} has a fixed depth format"),
            Knob::DepthSource => format!("{hider} compares window depth"),
            Knob::OrderedPolygons => {
                "the ordered polygons come from a painter's depth order".into()
            }
            Knob::MaxSplits => format!("{hider} splits no polygons"),
            Knob::MaxListLen | Knob::Overflow => format!("{hider} keeps no fragment lists"),
        }
    }
}

impl std::fmt::Display for Knob {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.describe())
    }
}

/// Everything that can go wrong choosing, building or feeding a hider.
#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    /// No registered hider has this name.
    #[error("no hider named '{name}' (registered: {})", names(known))]
    UnknownHider {
        /// The name asked for.
        name: String,
        /// Every registered name, in registry order.
        known: Vec<AlgoName>,
    },
    /// A [`HiderConfig`](crate::HiderConfig) knob was set for a hider that
    /// does not take it.
    #[error("the {knob} applies to {} only, not to {hider} ({})", names(takers), knob.reason(hider.as_str()))]
    KnobNotApplicable {
        /// The hider asked for ([`AlgoName::Auto`] for the planner).
        hider: AlgoName,
        /// The knob.
        knob: Knob,
        /// The hiders that take it, sorted by name.
        takers: Vec<AlgoName>,
    },
    /// Ordered polygons were asked, and the analysis predicts that the
    /// painter would run out of its split budget
    /// ([`hider_painter::PainterOptions::max_splits`], capped per triangle)
    /// before ordering them: refused before it runs.
    #[error(
        "ordered polygons refused: the painter needs at least {needed} splits for the \
         {pairs} interpenetrating pairs in view, over its split budget of {budget} for \
         {triangles} triangles (PainterOptions::max_splits, HiderConfig::max_splits); raise \
         it, or ask for the exact visible regions or a raster image instead, which need no \
         splits"
    )]
    PainterBudget {
        /// The conservative prediction
        /// ([`Effects::painter_splits_at_least`](crate::Effects::painter_splits_at_least)).
        needed: u64,
        /// The interpenetrating pairs found.
        pairs: u64,
        /// The split budget the painter would have
        /// ([`painter_split_budget`](crate::planner::painter_split_budget)).
        budget: u64,
        /// Triangles in view.
        triangles: u64,
    },
    /// The scene crate's error (loading, preparing, analysing, rendering).
    #[error(transparent)]
    Scene(#[from] hider_scene::Error),
}

/// Names joined by ", ".
pub(crate) fn names(algos: &[AlgoName]) -> String {
    algos
        .iter()
        .map(|a| a.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}

/// `Result` with [`PlanError`].
pub type Result<T, E = PlanError> = std::result::Result<T, E>;

/// An error and its chain of causes as the one line the `hider` and
/// `hider-bench` tools print: the messages joined by `": "`, leaving out a
/// cause whose message its parent already ends with (errors that print
/// their source themselves).
///
/// ```
/// use std::error::Error;
/// use std::fmt;
///
/// #[derive(Debug)]
/// struct Write(std::io::Error);
/// impl fmt::Display for Write {
///     fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
///         f.write_str("cannot write out.png")
///     }
/// }
/// impl Error for Write {
///     fn source(&self) -> Option<&(dyn Error + 'static)> {
///         Some(&self.0)
///     }
/// }
///
/// let e = Write(std::io::Error::other("disk full"));
/// assert_eq!(hider_plan::error_line(&e), "cannot write out.png: disk full");
/// ```
pub fn error_line(error: &(dyn std::error::Error + 'static)) -> String {
    let mut chain: Vec<String> = Vec::new();
    let mut cause = Some(error);
    while let Some(e) = cause {
        let message = e.to_string();
        if !chain.last().is_some_and(|prev| prev.ends_with(&message)) {
            chain.push(message);
        }
        cause = e.source();
    }
    chain.join(": ")
}
