//! The report's summary per hider over the accuracy study: how many scenes
//! it gets exactly right, its mean and worst error, its time relative to
//! the fastest exact hider, and its memory.

use std::fmt::Write as _;

use super::format::{fmt_bytes, fmt_ms};
use super::options::ReportOptions;
use super::rows::{accuracy_rows, geometric_mean, kind_of};
use crate::record::Row;

/// The summary table, then the time-vs-error plot over all scenes.
pub(super) fn summary_section(
    s: &mut String,
    rows: &[Row],
    hiders: &[String],
    options: &ReportOptions,
) {
    let _ = writeln!(s, "## Summary per hider (accuracy study)\n");
    let reference_time = reference_time(rows, hiders);
    let _ = writeln!(
        s,
        "| hider | kind | scenes with 0 wrong ids | mean error | worst scene (error) | time, geometric mean (ms) | relative to {} | median peak memory |",
        reference_time.as_ref().map_or("-", |r| r.0.as_str())
    );
    let _ = writeln!(s, "|---|---|---:|---:|---|---:|---:|---:|");
    for h in hiders {
        summary_line(s, rows, h, reference_time.as_ref().map(|r| r.1));
    }
    s.push('\n');
    if let Some(p) = options.image_link("bench-pareto-all", "svg") {
        let _ = writeln!(s, "![time vs error over all accuracy scenes]({p})\n");
    }
}

/// The fastest exact pixel-centre hider and its geometric-mean time: the
/// unit of the summary's relative times.
fn reference_time(rows: &[Row], hiders: &[String]) -> Option<(String, f64)> {
    hiders
        .iter()
        .filter(|h| kind_of(rows, h) == "ExactPixelCentre")
        .filter_map(|h| {
            geometric_mean(accuracy_rows(rows, h).map(|r| r.render_ms)).map(|t| (h.clone(), t))
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
}

/// One hider's line of the summary table.
fn summary_line(s: &mut String, rows: &[Row], h: &str, reference_time: Option<f64>) {
    let acc: Vec<&Row> = accuracy_rows(rows, h).collect();
    let scored: Vec<&Row> = acc
        .iter()
        .copied()
        .filter(|r| r.error().is_some())
        .collect();
    // Pixel-centre ids of every kind (multi-sample hiders report the
    // surface at the pixel centre too).
    let with_ids: Vec<&Row> = acc
        .iter()
        .copied()
        .filter(|r| r.wrong_ids.is_some())
        .collect();
    let exact = with_ids
        .iter()
        .filter(|r| r.wrong_ids == Some(0) && r.coverage_mismatches == Some(0))
        .count();
    let mean = if scored.is_empty() {
        "-".into()
    } else {
        format!(
            "{:.2e}",
            scored.iter().filter_map(|r| r.error()).sum::<f64>() / scored.len() as f64
        )
    };
    let worst = scored
        .iter()
        .max_by(|a, b| {
            a.error()
                .unwrap_or(0.0)
                .total_cmp(&b.error().unwrap_or(0.0))
        })
        .filter(|r| r.error() > Some(0.0))
        .map_or("-".into(), |r| {
            format!("{} ({:.1e})", r.scene, r.error().unwrap_or(0.0))
        });
    let t = geometric_mean(acc.iter().map(|r| r.render_ms));
    let rel = match (t, reference_time) {
        (Some(t), Some(r)) => format!("{:.2}x", t / r),
        _ => "-".into(),
    };
    let mut peaks: Vec<u64> = acc.iter().map(|r| r.peak_bytes).collect();
    peaks.sort_unstable();
    let peak = peaks
        .get(peaks.len() / 2)
        .map_or("-".into(), |&p| fmt_bytes(p));
    let _ = writeln!(
        s,
        "| {h} | {} | {exact}/{} | {mean} | {worst} | {} | {rel} | {peak} |",
        kind_of(rows, h),
        with_ids.len(),
        t.map_or("-".into(), fmt_ms),
    );
}
