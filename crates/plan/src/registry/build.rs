//! Building an entry's hider for a [`HiderConfig`]: the knobs the entry
//! takes are applied; a knob set for an entry that does not take it is
//! refused, naming the knob ([`Knob`]) and the entries that take it.

use hider_scene::DynHider;

use super::entry::{Entry, Knobs};
use super::table::all;
use crate::algo::AlgoName;
use crate::config::HiderConfig;
use crate::error::{Knob, PlanError, Result};

impl Entry {
    /// A fresh instance with the entry's own options and the knobs of
    /// `config` applied, or an error naming the first knob set in `config`
    /// that this entry does not take (see [`Entry::knobs`]).
    pub fn build(&self, config: &HiderConfig) -> Result<Box<dyn DynHider>> {
        match refusal(self.algo(), self.knobs, config) {
            Some(error) => Err(error),
            None => Ok((self.with_config)(config)),
        }
    }
}

/// The error for the first knob set in `config` that a hider named `hider`
/// taking `knobs` does not take (`hider` may be a pseudo-name such as
/// `auto`).
pub(crate) fn refusal(hider: AlgoName, knobs: Knobs, config: &HiderConfig) -> Option<PlanError> {
    let refused = [
        (
            Knob::DepthFormat,
            config.depth_format.is_some(),
            knobs.depth_format,
        ),
        (
            Knob::DepthSource,
            config.depth_source.is_some(),
            knobs.depth_source,
        ),
        (
            Knob::OrderedPolygons,
            config.ordered_polygons,
            knobs.ordered_polygons,
        ),
        (
            Knob::MaxSplits,
            config.max_splits.is_some(),
            knobs.max_splits,
        ),
        (
            Knob::MaxListLen,
            config.max_list_len.is_some(),
            knobs.fragment_lists,
        ),
        (
            Knob::Overflow,
            config.overflow.is_some(),
            knobs.fragment_lists,
        ),
    ]
    .into_iter()
    .find(|&(_, set, taken)| set && !taken)?;
    let knob = refused.0;
    Some(PlanError::KnobNotApplicable {
        hider,
        knob,
        takers: takers(knob),
    })
}

/// The hiders taking `knob`, sorted by name.
pub fn takers(knob: Knob) -> Vec<AlgoName> {
    let mut names: Vec<AlgoName> = all()
        .into_iter()
        .filter(|e| e.knobs.takes(knob))
        .map(|e| e.algo())
        .collect();
    names.sort_unstable_by_key(|a| a.as_str());
    names
}
