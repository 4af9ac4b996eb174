//! What the registry holds about one hider: its name, what it is, how it
//! is checked, which knobs it takes, and how to build it.

use hider_scene::DynHider;

use crate::algo::AlgoName;
use crate::config::HiderConfig;
use crate::error::Knob;

/// What kind of answer a hider gives, which decides how it is checked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Decides visibility at pixel centres and must equal the exact oracle
    /// on every non-tie pixel (and have identical coverage).
    ExactPixelCentre,
    /// Decides at pixel centres but is *meant* to be wrong in documented
    /// cases (naive sort, coarse depth, linear depth): measured, not
    /// required to agree.
    ApproximatePixelCentre,
    /// Resolves several samples per pixel (anti-aliasing, transparency);
    /// scored against analytic coverage.
    MultiSample,
    /// The slow exact reference itself.
    Reference,
}

/// Which [`HiderConfig`] knobs an entry takes; a knob it does not take is
/// refused by [`Entry::build`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct Knobs {
    /// [`HiderConfig::depth_format`].
    pub depth_format: bool,
    /// [`HiderConfig::depth_source`].
    pub depth_source: bool,
    /// [`HiderConfig::threads`] (never refused: the others ignore it).
    pub threads: bool,
    /// [`HiderConfig::ordered_polygons`].
    pub ordered_polygons: bool,
    /// [`HiderConfig::max_splits`].
    pub max_splits: bool,
    /// [`HiderConfig::max_list_len`] and [`HiderConfig::overflow`].
    pub fragment_lists: bool,
}

impl Knobs {
    /// No knob.
    pub const NONE: Self = Self {
        depth_format: false,
        depth_source: false,
        threads: false,
        ordered_polygons: false,
        max_splits: false,
        fragment_lists: false,
    };

    /// Whether a depth knob (format or source) is taken.
    pub fn any_depth(&self) -> bool {
        self.depth_format || self.depth_source
    }

    /// Whether `knob` is taken.
    pub fn takes(&self, knob: Knob) -> bool {
        match knob {
            Knob::DepthFormat => self.depth_format,
            Knob::DepthSource => self.depth_source,
            Knob::OrderedPolygons => self.ordered_polygons,
            Knob::MaxSplits => self.max_splits,
            Knob::MaxListLen | Knob::Overflow => self.fragment_lists,
        }
    }
}

/// One registered hider.
#[derive(Clone, Copy, Debug)]
pub struct Entry {
    /// Name on the command line (`--algo NAME`) and in tables.
    pub name: &'static str,
    /// One line saying what it is.
    pub description: &'static str,
    /// How it is checked.
    pub kind: Kind,
    /// The [`HiderConfig`] knobs it takes.
    pub knobs: Knobs,
    /// Builds the hider from the entry's typed options with the knobs of
    /// `config` that it takes applied (already checked).
    pub(crate) with_config: fn(&HiderConfig) -> Box<dyn DynHider>,
}

impl Entry {
    /// The entry's name as a type.
    pub fn algo(&self) -> AlgoName {
        self.name
            .parse()
            .expect("every registry name is an AlgoName (checked by a test)")
    }

    /// A fresh instance with the entry's own options.
    pub fn make(&self) -> Box<dyn DynHider> {
        (self.with_config)(&HiderConfig::default())
    }
}
