//! Checking command-line values the way the rest of the tool reports
//! errors: one line naming the flag and the value, exit status 2.
//!
//! clap's own messages for a bad value span several lines (the error, a
//! tip, the usage, a pointer to `--help`), and a negative number after a
//! flag is taken for another flag. The value parsers here give the reason
//! in words, and [`usage_error_line`] folds any clap error into one line
//! (with [`hider_cli::cli_error`], which `hider-bench` shares).

use clap::error::ErrorKind;
use hider::plan::{Knob, PlanError};

/// Largest image side in pixels (the scene crate's limit).
const MAX_SIDE: u64 = hider::geom::fixed::MAX_IMAGE_SIDE as u64;

/// A whole number from `lo` to `hi`, or the reason it is not.
fn whole(s: &str, lo: u64, hi: u64, what: &str) -> Result<u64, String> {
    let range = || format!("must be a whole number of {what} from {lo} to {hi}");
    match s.trim().parse::<i128>() {
        Ok(n) if n >= i128::from(lo) && n <= i128::from(hi) => Ok(n as u64),
        _ => Err(range()),
    }
}

/// `--size`, `--width`, `--height`: 1 to 16384 pixels.
pub fn side(s: &str) -> Result<u32, String> {
    whole(s, 1, MAX_SIDE, "pixels").map(|n| n as u32)
}

/// `--threads`: 1 to 1024.
pub fn threads(s: &str) -> Result<usize, String> {
    whole(s, 1, 1024, "threads").map(|n| n as usize)
}

/// `--repeat`: 0 to 1 000 000 timed renders.
pub fn repeat(s: &str) -> Result<u32, String> {
    whole(s, 0, 1_000_000, "renders").map(|n| n as u32)
}

/// `--pair-budget`: 0 to 10^12 candidate pairs.
pub fn pair_budget(s: &str) -> Result<u64, String> {
    whole(s, 0, 1_000_000_000_000, "pairs")
}

/// A finite number.
fn finite(s: &str) -> Result<f64, String> {
    s.trim()
        .parse::<f64>()
        .ok()
        .filter(|x| x.is_finite())
        .ok_or_else(|| "must be a finite number".to_owned())
}

/// `--timeout`: a number of seconds, 0 or more (up to a year).
pub fn seconds(s: &str) -> Result<f64, String> {
    let x = finite(s)?;
    if (0.0..=365.0 * 86_400.0).contains(&x) {
        Ok(x)
    } else {
        Err("must be a number of seconds from 0 to 31536000".to_owned())
    }
}

/// `--fovy`: strictly between 0 and 180 degrees.
pub fn fovy(s: &str) -> Result<f64, String> {
    let x = finite(s)?;
    if x > 0.0 && x < 180.0 {
        Ok(x)
    } else {
        Err("must be more than 0 and less than 180 degrees".to_owned())
    }
}

/// `--near`, `--far`: a distance in front of the eye, more than 0.
pub fn distance(s: &str) -> Result<f64, String> {
    let x = finite(s)?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err("must be a distance more than 0".to_owned())
    }
}

/// Parses a byte count with an optional binary suffix: `1000`, `512K`,
/// `64M`, `2G` (`KiB`, `MiB`, `GiB` too).
pub fn bytes(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let split = t.find(|c: char| !c.is_ascii_digit()).unwrap_or(t.len());
    let (digits, suffix) = t.split_at(split);
    let shift = match suffix.trim().to_ascii_uppercase().as_str() {
        "" | "B" => 0,
        "K" | "KIB" => 10,
        "M" | "MIB" => 20,
        "G" | "GIB" => 30,
        _ => return Err(format!("'{s}' is not a byte count (e.g. 1000, 512M, 2G)")),
    };
    digits
        .parse::<u64>()
        .ok()
        .and_then(|n| n.checked_mul(1 << shift))
        .ok_or_else(|| format!("'{s}' is not a byte count (e.g. 1000, 512M, 2G)"))
}

/// Parses `x,y,z` of finite numbers (`--eye`, `--target`, `--up`).
pub fn vec3(s: &str) -> Result<glam::DVec3, String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 3 {
        return Err(format!(
            "must be three numbers x,y,z, got {} number{}",
            parts.len(),
            if parts.len() == 1 { "" } else { "s" }
        ));
    }
    let mut v = [0.0; 3];
    for (slot, p) in v.iter_mut().zip(&parts) {
        *slot = finite(p).map_err(|_| format!("'{}' is not a finite number", p.trim()))?;
    }
    Ok(glam::DVec3::from_array(v))
}

/// A clap usage error as the one line `hider` prints after `hider:
/// error: ` ([`hider_cli::cli_error::usage_error_line`], with the
/// subcommands named when none was given).
pub fn usage_error_line(e: &clap::Error) -> String {
    match e.kind() {
        ErrorKind::MissingSubcommand | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            "no subcommand given: render, analyze, list or bench (see hider --help)".to_owned()
        }
        _ => hider_cli::cli_error::usage_error_line(e),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_checked_with_reasons() {
        assert_eq!(side("512"), Ok(512));
        assert!(side("-5").unwrap_err().contains("from 1 to 16384"));
        assert!(side("0").is_err() && side("16385").is_err() && side("x").is_err());
        assert_eq!(bytes("1000"), Ok(1000));
        assert_eq!(bytes("512M"), Ok(512 << 20));
        assert_eq!(bytes("2GiB"), Ok(2 << 30));
        assert!(bytes("-1").is_err() && bytes("1.5G").is_err() && bytes("9T").is_err());
        assert!(bytes("99999999999999999999G").is_err());
        assert_eq!(threads("2"), Ok(2));
        assert!(threads("-1").is_err() && threads("0").is_err());
        assert_eq!(fovy("45"), Ok(45.0));
        assert!(fovy("-30").is_err() && fovy("180").is_err() && fovy("nan").is_err());
        assert!(distance("-1").is_err() && distance("0").is_err() && distance("inf").is_err());
        assert_eq!(vec3("1, -2,3e0"), Ok(glam::DVec3::new(1.0, -2.0, 3.0)));
        assert_eq!(
            vec3("1,2").unwrap_err(),
            "must be three numbers x,y,z, got 2 numbers"
        );
        assert!(vec3("1,2,nan").unwrap_err().contains("'nan'"));
    }
}

/// The command line's flag for a knob of the library.
fn knob_flag(knob: Knob) -> &'static str {
    match knob {
        Knob::DepthFormat => "--depth-format",
        Knob::DepthSource => "--depth-source",
        Knob::OrderedPolygons => "--svg-mode painter",
        Knob::MaxSplits => "--max-splits",
        Knob::MaxListLen => "--max-list-len",
        Knob::Overflow => "--overflow",
    }
}

/// A plan error in the command line's words: the flags a user set, not the
/// library's knobs (`hider-plan`'s messages name no front end's flags).
pub fn flag_error(error: PlanError) -> anyhow::Error {
    match error {
        PlanError::UnknownHider { name, known } => {
            let known: Vec<&str> = known.iter().map(|a| a.as_str()).collect();
            anyhow::anyhow!("unknown --algo '{name}' (one of: {})", known.join(", "))
        }
        PlanError::KnobNotApplicable {
            hider,
            knob,
            takers,
        } => {
            let flag = knob_flag(knob);
            let takers: Vec<&str> = takers.iter().map(|a| a.as_str()).collect();
            let algos = match takers.split_last() {
                None => "none".to_owned(),
                Some((last, [])) => (*last).to_owned(),
                Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
            };
            anyhow::anyhow!(
                "{flag} applies to --algo {algos} only, not to --algo {hider} ({})",
                knob.reason(hider.as_str())
            )
        }
        PlanError::PainterBudget {
            needed,
            pairs,
            budget,
            triangles,
        } => anyhow::anyhow!(
            "--svg-mode painter refused: the painter needs at least {needed} splits for the \
             {pairs} interpenetrating pairs in view, over its split budget of {budget} for \
             {triangles} triangles; raise it with --max-splits, or use --svg-mode regions or \
             lines, which need no splits"
        ),
        PlanError::Scene(e @ hider::scene::Error::Cancelled(_)) => {
            anyhow::anyhow!("{e}; raise it with --timeout")
        }
        other => other.into(),
    }
}

/// A render's error in the command line's words: a budget the flags can
/// raise names its flag (the libraries name their option fields).
pub fn budget_error(error: anyhow::Error) -> anyhow::Error {
    let flag =
        error
            .chain()
            .find_map(|cause| match cause.downcast_ref::<hider::scene::Error>()? {
                hider::scene::Error::Limit { what, .. }
                    if *what == hider::painter::SPLIT_BUDGET =>
                {
                    Some("--max-splits")
                }
                hider::scene::Error::Limit { what, .. } if *what == hider::vector::PAIRS_LIMIT => {
                    Some("--max-pairs")
                }
                hider::scene::Error::Cancelled(hider::scene::Cancelled::TimedOut { .. }) => {
                    Some("--timeout")
                }
                hider::scene::Error::Limit { what, .. }
                    if *what == hider::vector::REGION_POINTS_LIMIT =>
                {
                    Some("--max-region-points")
                }
                _ => None,
            });
    match flag {
        Some(flag) => anyhow::anyhow!(
            "{}; raise it with {flag}",
            hider_plan::error_line(error.as_ref())
        ),
        None => error,
    }
}

#[cfg(test)]
mod flag_tests {
    use super::*;

    /// Every typed plan error the CLI can meet is spelled with its flags.
    #[test]
    fn plan_errors_name_the_flags() {
        let unknown = hider::registry::find("nonesuch").unwrap_err();
        let line = flag_error(unknown).to_string();
        assert!(
            line.starts_with("unknown --algo 'nonesuch' (one of: zbuffer,"),
            "{line}"
        );
        let config =
            hider::plan::HiderConfig::default().with_depth_format(hider::zbuffer::DepthFormat::F64);
        let refused = hider::registry::find("painter").unwrap().build(&config);
        let line = flag_error(refused.err().unwrap()).to_string();
        assert_eq!(
            line,
            "--depth-format applies to --algo zbuffer or zbuffer-tiled only, not to --algo painter \
             (painter has a fixed depth format)"
        );
        let painter = hider::plan::HiderConfig::default().with_ordered_polygons(true);
        let refused = hider::registry::find("zbuffer").unwrap().build(&painter);
        let line = flag_error(refused.err().unwrap()).to_string();
        assert!(
            line.starts_with("--svg-mode painter applies to --algo painter or painter-naive only"),
            "{line}"
        );
    }
}
