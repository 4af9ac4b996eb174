//! Building an entry's hider for a [`HiderConfig`]: the knobs the entry
//! takes are applied; a knob set for an entry that does not take it is
//! refused, naming the knob and the entries that take it.

use hider_scene::DynHider;

use super::entry::{Entry, Knobs};
use super::table::all;
use crate::config::HiderConfig;
use crate::error::{PlanError, Result};

impl Entry {
    /// A fresh instance with the entry's own options and the knobs of
    /// `config` applied, or an error naming the first knob set in `config`
    /// that this entry does not take (see [`Entry::knobs`]).
    pub fn build(&self, config: &HiderConfig) -> Result<Box<dyn DynHider>> {
        match refusal(self.name, self.knobs, config) {
            Some(error) => Err(error),
            None => Ok((self.with_config)(config)),
        }
    }
}

/// The error for the first knob set in `config` that a hider named `hider`
/// taking `knobs` does not take (`hider` may be a pseudo-name such as
/// `auto`).
pub(crate) fn refusal(
    hider: &'static str,
    knobs: Knobs,
    config: &HiderConfig,
) -> Option<PlanError> {
    let refuse = |knob: &'static str, message: String| {
        Some(PlanError::KnobNotApplicable {
            hider,
            knob,
            message,
        })
    };
    let (format, source) = (config.depth_format.is_some(), config.depth_source.is_some());
    if (format || source) && !knobs.any_depth() {
        let knob = if format {
            "--depth-format"
        } else {
            "--depth-source"
        };
        return refuse(
            knob,
            format!(
                "--depth-format and --depth-source apply to --algo {} only",
                takers(Knobs::any_depth, "and")
            ),
        );
    }
    if format && !knobs.depth_format {
        return refuse(
            "--depth-format",
            format!(
                "--depth-format applies to --algo {} only ({hider} has a fixed depth format)",
                takers(|k| k.depth_format, "and")
            ),
        );
    }
    if source && !knobs.depth_source {
        return refuse(
            "--depth-source",
            format!(
                "--depth-source applies to --algo {} only ({hider} compares window depth)",
                takers(|k| k.depth_source, "and")
            ),
        );
    }
    if config.vector_output && !knobs.vector_output {
        return refuse(
            "--svg",
            format!(
                "--svg needs --algo {} (vector output comes from the depth order)",
                takers(|k| k.vector_output, "or")
            ),
        );
    }
    None
}

/// The names of the entries taking a knob, in alphabetical order, joined
/// as in a sentence: `a`, `a and b`, `a, b and c`.
fn takers(takes: fn(&Knobs) -> bool, conjunction: &str) -> String {
    let mut names: Vec<&str> = all()
        .into_iter()
        .filter(|e| takes(&e.knobs))
        .map(|e| e.name)
        .collect();
    names.sort_unstable();
    match names.split_last() {
        None => "none".to_owned(),
        Some((last, [])) => (*last).to_owned(),
        Some((last, rest)) => format!("{} {conjunction} {last}", rest.join(", ")),
    }
}
