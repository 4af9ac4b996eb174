//! Every hider of the workspace by name: one list that the command line,
//! the benchmark and the property tests read, so adding an algorithm is
//! one entry here.
//!
//! Each [`Entry`] builds its hider from the algorithm crate's typed options
//! ([`Entry::make`]); [`Entry::build`] also applies the cross-cutting knobs
//! of a [`HiderConfig`](crate::HiderConfig) the entry takes (depth format,
//! depth source, threads, ordered polygons, shade mode) and refuses the
//! others with a typed error naming the knob
//! ([`PlanError::KnobNotApplicable`]), so a caller never matches on hider
//! names.
//!
//! ```
//! use hider_plan::registry::{self, Kind};
//!
//! let entry = registry::by_name("warnock").unwrap();
//! assert_eq!(entry.kind, Kind::ExactPixelCentre);
//! assert_eq!(entry.make().name(), "warnock");
//! assert!(matches!(
//!     registry::find("nonesuch"),
//!     Err(hider_plan::PlanError::UnknownHider { .. })
//! ));
//! ```

mod build;
mod entry;
mod table;

#[cfg(test)]
mod tests;

use hider_scene::DynHider;

pub(crate) use build::refusal;
pub use build::takers;
pub use entry::{Entry, Kind, Knobs};
pub use table::all;

use crate::algo::AlgoName;
use crate::error::{PlanError, Result};

/// The entry with this name.
pub fn by_name(name: &str) -> Option<Entry> {
    all().into_iter().find(|e| e.name == name)
}

/// The entry with this name, or an error listing every registered name
/// (`auto` names no entry: it is the planner's).
pub fn find(name: &str) -> Result<Entry> {
    by_name(name).ok_or_else(|| PlanError::UnknownHider {
        name: name.to_owned(),
        known: AlgoName::REGISTERED.to_vec(),
    })
}

/// The entry of `algo` (`None` for [`AlgoName::Auto`]).
pub fn entry(algo: AlgoName) -> Option<Entry> {
    by_name(algo.as_str())
}

/// Every registered name, in registry order.
pub fn names() -> Vec<&'static str> {
    all().iter().map(|e| e.name).collect()
}

/// Fresh instances of every hider that must equal the oracle on non-tie
/// pixels ([`Kind::ExactPixelCentre`]).
pub fn pixel_centre_hiders() -> Vec<Box<dyn DynHider>> {
    all()
        .into_iter()
        .filter(|e| e.kind == Kind::ExactPixelCentre)
        .map(|e| e.make())
        .collect()
}
