//! The differential check: every pixel-centre hider of the registry on a
//! decoded case, against the ray-cast oracle.
//!
//! - every exact hider ([`Kind::ExactPixelCentre`]) gives the oracle's id
//!   on every pixel that is not a tie ([`crate::reference::compare_off_ties`]:
//!   exactly equal depths, or closer than `f64` evaluation of the two planes
//!   can tell apart, a bound proved from the rounding, see
//!   `docs/oracle.md`; these symmetric inputs put exact ties of different
//!   planes on pixel centres on purpose) nor, for the `f32` buffers, closer
//!   than `f32` resolves; and refuses only with a documented
//!   budget ([`is_budget`]); such refusals are listed in
//!   [`Outcome::budget_refusals`] for campaigns to count;
//! - coverage is identical across every pixel-centre hider (exact or
//!   approximate) and the oracle;
//! - no hider reports holding more than its default budget, [`BUDGET`].
//!
//! A case the front end or the camera refuses is not a finding: bad input
//! refused with an error is the behaviour wanted.

use hider_oracle::RayCastOracle;
use hider_plan::registry::{self, Kind};
use hider_scene::{Error, Frame, PrepareOptions, View, prepare};

use super::DiffCase;

/// The default memory budget of every hider (`max_bytes`, 1 GiB): what a
/// frame of these small cases must stay far under.
pub const BUDGET: u64 = 1 << 30;

/// Whether `e` is a refusal under a documented budget: [`Error::Limit`]
/// (checked before any work), or a hider's error saying a budget it
/// documents ran out (the painter's split budget).
pub fn is_budget(e: &Error) -> bool {
    match e {
        Error::Limit { .. } => true,
        Error::Render { message, .. } => message.contains("budget"),
        _ => false,
    }
}

/// What one case did, for tallies.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Outcome {
    /// Hiders that rendered the case and were compared.
    pub hiders: u32,
    /// Pixels the oracle covers.
    pub covered: u64,
    /// Tie pixels the oracle reports.
    pub ties: u64,
    /// Why the case was not rendered at all (camera, front end or oracle
    /// budget refused it), if it was not.
    pub refused: Option<String>,
    /// Hiders that refused the case with a documented budget, and why.
    pub budget_refusals: Vec<String>,
}

/// Renders `case` with every pixel-centre hider and compares each with the
/// oracle; the first violation, one line naming the case, the hider and
/// the first wrong pixel.
///
/// # Errors
///
/// The violation found.
pub fn check_case(case: &DiffCase) -> Result<Outcome, String> {
    let refused = |e: Error| Outcome {
        refused: Some(e.to_string()),
        ..Outcome::default()
    };
    let view = match View::new(case.camera, case.size.0, case.size.1) {
        Ok(v) => v,
        Err(e) => return Ok(refused(e)),
    };
    let screen = match prepare(&case.scene, &view, &PrepareOptions::default()) {
        Ok(s) => s,
        Err(e) => return Ok(refused(e)),
    };
    let reference = match RayCastOracle::default().try_evaluate(&screen) {
        Ok(r) => r,
        Err(e) => return Ok(refused(e)),
    };
    let mut outcome = Outcome {
        covered: reference.covered_count() as u64,
        ..Outcome::default()
    };
    let mut frame = Frame::new(case.size.0, case.size.1).map_err(|e| e.to_string())?;
    let fail = |name: &str, what: String| Err(format!("{} on [{}]: {what}", name, case.label));
    for entry in registry::all() {
        let exact = match entry.kind {
            Kind::ExactPixelCentre => true,
            Kind::ApproximatePixelCentre => false,
            Kind::MultiSample | Kind::Reference => continue,
        };
        let mut hider = entry.make();
        let stats = match hider.render(&screen, &mut frame) {
            Ok(stats) => stats,
            // A documented budget; the case is small, but a pile can be
            // deep.
            Err(e) if is_budget(&e) => {
                outcome.budget_refusals.push(format!("{}: {e}", entry.name));
                continue;
            }
            Err(e) if exact => return fail(entry.name, format!("refused: {e}")),
            // Demonstration modes refuse scenes they do not apply to.
            Err(_) => continue,
        };
        if stats.peak_bytes > BUDGET {
            return fail(entry.name, format!("held {} bytes", stats.peak_bytes));
        }
        let a = if exact {
            crate::reference::compare_off_ties(&reference, entry.name, &frame.ids)
        } else {
            // Approximate hiders: coverage only.
            reference.compare(&frame.ids, f64::INFINITY)
        };
        if a.coverage_mismatches > 0 || (exact && !a.is_exact()) {
            return fail(entry.name, a.to_string());
        }
        if exact {
            outcome.ties = outcome.ties.max(a.ties);
        }
        outcome.hiders += 1;
    }
    Ok(outcome)
}
