//! The report's tables of the accuracy study, one line per scene and size,
//! one column per hider: the wrong pixels, then the median times, then the
//! links to the per-scene time-vs-error plots.

use std::fmt::Write as _;

use super::format::{fmt_count, fmt_error, fmt_ms};
use super::options::ReportOptions;
use crate::record::Row;

/// The accuracy and time tables (nothing without accuracy cases).
pub(super) fn scene_tables(
    s: &mut String,
    rows: &[Row],
    hiders: &[String],
    cases: &[(String, u32)],
    options: &ReportOptions,
) {
    if cases.is_empty() {
        return;
    }
    accuracy_table(s, rows, hiders, cases);
    time_table(s, rows, hiders, cases);
    let pareto: Vec<String> = cases
        .iter()
        .filter_map(|(scene, w)| {
            options
                .image_link(&format!("bench-pareto-{scene}-{w}"), "svg")
                .map(|p| format!("[{scene}@{w}]({p})"))
        })
        .collect();
    if !pareto.is_empty() {
        let _ = writeln!(
            s,
            "Time vs error per scene (Pareto fronts): {}.\n",
            pareto.join(", ")
        );
    }
}

/// The table's header line and rule: `first`, then one column per hider.
fn header(s: &mut String, first: &str, hiders: &[String]) {
    let _ = write!(s, "| {first} |");
    for h in hiders {
        let _ = write!(s, " {h} |");
    }
    let _ = writeln!(s, "\n|---|{}", "---:|".repeat(hiders.len()));
}

/// The accuracy row of hider `h` on `scene` at width `w`.
fn cell<'a>(rows: &'a [Row], scene: &str, w: u32, h: &str) -> Option<&'a Row> {
    rows.iter()
        .find(|r| r.study == "accuracy" && r.scene == scene && r.width == w && r.hider == h)
}

/// Wrong pixels per scene and hider.
fn accuracy_table(s: &mut String, rows: &[Row], hiders: &[String], cases: &[(String, u32)]) {
    let _ = writeln!(s, "## Accuracy: wrong pixels per scene\n");
    let _ = writeln!(
        s,
        "Pixel-centre hiders: wrong ids on non-tie pixels, then `+ N cov.` for coverage mismatches (pixel centres covered in one image and not the other), `0` when both are none; `ties` is the oracle's tie count for the scene. Anti-aliasing hiders: `c` and their mean coverage error against exact analytic coverage. *ignores EFFECT*: the scene calls for an effect the hider does not simulate (translucent surfaces drawn opaque): not exact for that scene, whatever its ids score.\n"
    );
    header(s, "scene (triangles, ties)", hiders);
    for (scene, w) in cases {
        let first = rows
            .iter()
            .find(|r| r.study == "accuracy" && &r.scene == scene && r.width == *w);
        let ties = rows
            .iter()
            .filter(|r| r.study == "accuracy" && &r.scene == scene && r.width == *w)
            .find_map(|r| r.ties)
            .map_or("-".into(), |t| t.to_string());
        let _ = write!(
            s,
            "| {scene}@{w} ({}, {ties}) |",
            first.map_or(0, |r| r.triangles)
        );
        for h in hiders {
            let _ = write!(s, " {} |", accuracy_text(cell(rows, scene, *w, h)));
        }
        s.push('\n');
    }
}

/// What the accuracy table shows for one run: `0`, the wrong ids in bold
/// and the coverage mismatches, the coverage error of a multi-sample
/// hider, `ref`, `err` or `-`.
fn accuracy_text(row: Option<&Row>) -> String {
    let text = ids_text(row);
    match row {
        Some(r) if r.is_ok() && !r.simulates_all_effects() => {
            format!("{text} (*ignores {}*)", r.ignored_effects)
        }
        _ => text,
    }
}

/// [`accuracy_text`] without the mark of an ignored effect.
fn ids_text(row: Option<&Row>) -> String {
    match row {
        None => "".into(),
        Some(r) if !r.is_ok() => "err".into(),
        Some(r) if r.kind == "MultiSample" && r.coverage_error.is_some() => {
            format!("c {}", fmt_error(r.coverage_error.unwrap_or(0.0)))
        }
        Some(r) => match (r.wrong_ids, r.coverage_mismatches) {
            (Some(0), Some(0)) => "0".into(),
            (Some(a), Some(0)) => format!("**{}**", fmt_count(a)),
            (Some(a), Some(b)) => format!("**{}** + {} cov.", fmt_count(a), fmt_count(b)),
            _ if r.accuracy == "reference" => "ref".into(),
            _ => "-".into(),
        },
    }
}

/// Median render time per scene and hider.
fn time_table(s: &mut String, rows: &[Row], hiders: &[String], cases: &[(String, u32)]) {
    let _ = writeln!(s, "\n## Time per scene (median render ms)\n");
    header(s, "scene", hiders);
    for (scene, w) in cases {
        let _ = write!(s, "| {scene}@{w} |");
        for h in hiders {
            let text = cell(rows, scene, *w, h)
                .filter(|r| r.is_ok())
                .map_or("-".into(), |r| fmt_ms(r.render_ms));
            let _ = write!(s, " {text} |");
        }
        s.push('\n');
    }
    s.push('\n');
}
