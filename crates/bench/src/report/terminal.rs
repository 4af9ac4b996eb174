//! What the terminal shows after a run: one line per row, then the growth
//! exponents of the scaling studies (also the report's exponent table).

use std::fmt::Write as _;

use super::format::{fmt_bytes, fmt_error, fmt_ms};
use super::rows::hider_order;
use crate::matrix::Study;
use crate::record::{Results, Row};
use crate::scaling::{axis_label, fit_power_law, series};

/// The terminal table: one line per row, then the growth exponents.
pub fn terminal_table(results: &Results) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{:<34} {:<20} {:>10} {:>19} {:>8} {:>7} {:>10}  status",
        "case", "hider", "median ms", "min-max ms", "wrong", "ties", "peak"
    );
    let mut last_case = u32::MAX;
    for r in &results.rows {
        if r.case != last_case && last_case != u32::MAX {
            s.push('\n');
        }
        last_case = r.case;
        terminal_line(&mut s, r);
    }
    let exps = exponent_table(&results.rows);
    if !exps.is_empty() {
        s.push_str("\nGrowth exponents b of time ~ x^b (least squares on log-log):\n");
        s.push_str(&exps);
    }
    s
}

/// One row of the terminal table.
fn terminal_line(s: &mut String, r: &Row) {
    let wrong = match (r.coverage_error, r.wrong_ids, r.coverage_mismatches) {
        (Some(e), _, _) if r.kind == "MultiSample" => format!("c {}", fmt_error(e)),
        (_, Some(w), Some(c)) => (w + c).to_string(),
        _ => "-".into(),
    };
    let ties = r.ties.map_or_else(|| "-".into(), |t| t.to_string());
    let status = if r.is_ok() {
        if r.accuracy.starts_with("skipped") {
            "ok, not scored"
        } else {
            "ok"
        }
    } else {
        r.status.as_str()
    };
    let _ = writeln!(
        s,
        "{:<34} {:<20} {:>10} {:>19} {:>8} {:>7} {:>10}  {}",
        format!("{} {}@{}", r.study, r.scene, r.width),
        r.hider,
        if r.is_ok() {
            fmt_ms(r.render_ms)
        } else {
            "-".into()
        },
        if r.is_ok() {
            format!("{}-{}", fmt_ms(r.render_min_ms), fmt_ms(r.render_max_ms))
        } else {
            "-".into()
        },
        wrong,
        ties,
        fmt_bytes(r.peak_bytes),
        status
    );
}

/// Growth exponents per hider and scaling study as a Markdown-ish table
/// (readable in a terminal too).
pub fn exponent_table(rows: &[Row]) -> String {
    let studies: Vec<Study> = Study::SCALING
        .iter()
        .copied()
        .filter(|s| rows.iter().any(|r| r.study == s.as_str()))
        .collect();
    if studies.is_empty() {
        return String::new();
    }
    let mut s = String::from("| hider |");
    for st in &studies {
        let _ = write!(s, " vs {} |", axis_label(*st));
    }
    s.push_str("\n|---|");
    s.push_str(&"---:|".repeat(studies.len()));
    s.push('\n');
    for h in hider_order(rows) {
        let _ = write!(s, "| {h} |");
        for st in &studies {
            match fit_power_law(&series(rows, *st, &h)) {
                Some(f) => {
                    let _ = write!(s, " {:.2} |", f.exponent);
                }
                None => s.push_str(" - |"),
            }
        }
        s.push('\n');
    }
    s
}
