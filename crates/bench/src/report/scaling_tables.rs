//! The report's scaling section, after Sutherland, Sproull & Schumacker
//! (1974): the growth exponents, then per study a table of median times
//! along the study's axis and its plot.

use std::fmt::Write as _;

use super::format::{fmt_axis, fmt_ms};
use super::options::ReportOptions;
use super::terminal::exponent_table;
use crate::matrix::Study;
use crate::record::Row;
use crate::scaling::{axis, axis_label};

/// The scaling section (nothing without scaling rows).
pub(super) fn scaling_section(
    s: &mut String,
    rows: &[Row],
    hiders: &[String],
    options: &ReportOptions,
) {
    let scaling: Vec<Study> = Study::SCALING
        .iter()
        .copied()
        .filter(|st| rows.iter().any(|r| r.study == st.as_str()))
        .collect();
    if scaling.is_empty() {
        return;
    }
    let _ = writeln!(
        s,
        "## Scaling (after Sutherland, Sproull & Schumacker 1974)\n"
    );
    let _ = writeln!(
        s,
        "Growth exponent `b` of `time ~ x^b`, least squares on log-log axes:\n"
    );
    s.push_str(&exponent_table(rows));
    s.push('\n');
    for st in scaling {
        study_table(s, rows, hiders, st);
        if let Some(p) = options.image_link(&format!("bench-{}", st.as_str()), "svg") {
            let _ = writeln!(s, "![time vs {}]({p})\n", axis_label(st));
        }
    }
}

/// `(scene@width, axis value)` of the study's cases, in matrix order.
fn study_cases(rows: &[Row], st: Study) -> Vec<(String, f64)> {
    let mut v: Vec<(String, f64)> = Vec::new();
    for r in rows.iter().filter(|r| r.study == st.as_str()) {
        let label = format!("{}@{}", r.scene, r.width);
        if !v.iter().any(|(l, _)| *l == label) {
            v.push((label, axis(st, r).unwrap_or(0.0)));
        }
    }
    v
}

/// One study's table: a line per case, its axis value, a column per hider.
fn study_table(s: &mut String, rows: &[Row], hiders: &[String], st: Study) {
    let _ = writeln!(s, "### Time vs {}\n", axis_label(st));
    let _ = write!(s, "| case | {} |", axis_label(st));
    for h in hiders {
        let _ = write!(s, " {h} |");
    }
    let _ = writeln!(s, "\n|---|---:|{}", "---:|".repeat(hiders.len()));
    for (label, x) in &study_cases(rows, st) {
        let _ = write!(s, "| {label} | {} |", fmt_axis(*x));
        for h in hiders {
            let r = rows.iter().find(|r| {
                r.study == st.as_str()
                    && format!("{}@{}", r.scene, r.width) == *label
                    && &r.hider == h
            });
            let _ = write!(s, " {} |", time_text(r));
        }
        s.push('\n');
    }
    s.push('\n');
}

/// The median time of a run, marked `(wrong)` when it was scored wrong.
fn time_text(row: Option<&Row>) -> String {
    match row {
        Some(r) if r.is_ok() => {
            let mark = match r.error() {
                Some(e) if e > 0.0 => " (wrong)",
                _ => "",
            };
            format!("{}{mark}", fmt_ms(r.render_ms))
        }
        Some(_) => "err".into(),
        None => "-".into(),
    }
}
