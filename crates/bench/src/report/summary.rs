//! The report's summary per hider: its time on real-size work relative to
//! the fastest exact hider, then what the accuracy study at small sizes
//! found it getting wrong (wrong ids and coverage mismatches counted
//! apart, coverage error for the anti-aliasing hiders), and its memory.

use std::fmt::Write as _;

use super::answer::REAL;
use super::format::{fmt_bytes, fmt_count, fmt_error, fmt_ms, fmt_ratio};
use super::options::ReportOptions;
use super::rows::{accuracy_rows, geometric_mean, kind_label, kind_of, study_cases, study_rows};
use crate::record::Row;

/// The summary table, then the time-vs-error plot over all scenes.
pub(super) fn summary_section(
    s: &mut String,
    rows: &[Row],
    hiders: &[String],
    options: &ReportOptions,
) {
    let _ = writeln!(s, "## Summary per hider\n");
    let real_cases = study_cases(rows, REAL).len();
    let time_of = |h: &str| {
        if real_cases > 0 {
            geometric_mean(study_rows(rows, REAL, h).map(|r| r.render_ms))
        } else {
            geometric_mean(accuracy_rows(rows, h).map(|r| r.render_ms))
        }
    };
    let reference = hiders
        .iter()
        .filter(|h| kind_of(rows, h) == "ExactPixelCentre")
        .filter_map(|h| time_of(h).map(|t| (h.clone(), t)))
        .min_by(|a, b| a.1.total_cmp(&b.1));
    let time_what = if real_cases > 0 {
        format!("real-size time, geometric mean over {real_cases} scenes (ms)")
    } else {
        "accuracy-study time, geometric mean (ms)".to_owned()
    };
    let _ = writeln!(
        s,
        "Time: {time_what}. The other columns are the accuracy study's (small sizes): scenes whose every pixel centre has the oracle's surface (no wrong id) and whose every effect the hider simulates (a scene with translucent surfaces is not exact for a hider that draws them opaque: the count says on how many scenes it ignored an effect), scenes whose covered pixel centres are the oracle's (no coverage mismatch; anti-aliasing hiders may differ here by design), their sums, and the mean coverage error against exact analytic coverage.\n"
    );
    let _ = writeln!(
        s,
        "| hider | kind | time (ms) | relative to {} | scenes with no wrong id | scenes with no coverage mismatch | wrong ids (sum) | coverage mismatches (sum) | mean coverage error | worst scene (error) | median peak memory |",
        reference.as_ref().map_or("-", |r| r.0.as_str())
    );
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|---:|---:|---|---:|");
    for h in hiders {
        let t = time_of(h);
        let rel = match (t, &reference) {
            (Some(t), Some((_, r))) => fmt_ratio(t / r),
            _ => "-".into(),
        };
        let _ = write!(
            s,
            "| {h} | {} | {} | {rel} |",
            kind_label(&kind_of(rows, h)),
            t.map_or("-".into(), fmt_ms)
        );
        accuracy_cells(s, rows, h);
    }
    s.push('\n');
    if let Some(p) = options.image_link("bench-pareto-all", "svg") {
        let _ = writeln!(s, "![time against error over all accuracy scenes]({p})\n");
    }
}

/// The accuracy study's cells of one hider's line.
fn accuracy_cells(s: &mut String, rows: &[Row], h: &str) {
    let acc: Vec<&Row> = accuracy_rows(rows, h).collect();
    let with_ids: Vec<&Row> = acc
        .iter()
        .copied()
        .filter(|r| r.wrong_ids.is_some())
        .collect();
    let no_wrong = with_ids
        .iter()
        .filter(|r| r.wrong_ids == Some(0) && r.simulates_all_effects())
        .count();
    let ignored = with_ids
        .iter()
        .filter(|r| !r.simulates_all_effects())
        .count();
    let no_mismatch = with_ids
        .iter()
        .filter(|r| r.coverage_mismatches == Some(0))
        .count();
    let n = with_ids.len();
    let wrong: u64 = with_ids.iter().filter_map(|r| r.wrong_ids).sum();
    let mismatches: u64 = with_ids.iter().filter_map(|r| r.coverage_mismatches).sum();
    let errors: Vec<f64> = acc.iter().filter_map(|r| r.coverage_error).collect();
    let mean_coverage = if errors.is_empty() {
        "-".into()
    } else {
        fmt_error(errors.iter().sum::<f64>() / errors.len() as f64)
    };
    let worst = acc
        .iter()
        .filter_map(|r| Some((r, r.error()?)))
        .filter(|(_, e)| *e > 1e-12)
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .map_or("-".into(), |(r, e)| {
            format!("{}@{} ({})", r.scene, r.width, fmt_error(e))
        });
    let mut peaks: Vec<u64> = acc.iter().map(|r| r.peak_bytes).collect();
    peaks.sort_unstable();
    let peak = peaks
        .get(peaks.len() / 2)
        .map_or("-".into(), |&p| fmt_bytes(p));
    let (a, b, c, d) = if n == 0 {
        ("-".into(), "-".into(), "-".into(), "-".into())
    } else {
        (
            if ignored > 0 {
                format!("{no_wrong}/{n} (ignores an effect on {ignored})")
            } else {
                format!("{no_wrong}/{n}")
            },
            format!("{no_mismatch}/{n}"),
            fmt_count(wrong),
            fmt_count(mismatches),
        )
    };
    let _ = writeln!(
        s,
        " {a} | {b} | {c} | {d} | {mean_coverage} | {worst} | {peak} |"
    );
}
