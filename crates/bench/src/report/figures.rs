//! Which plots the report draws: time against error over all accuracy
//! scenes and per scene at the largest size, and one plot per scaling
//! study.

use std::path::Path;

use anyhow::Result;

use super::answer::{aa_plot, precision_plot};
use super::rows::{accuracy_cases, accuracy_rows, geometric_mean, hider_order};
use crate::matrix::Study;
use crate::plots::{ERROR_AXIS, Plot, Series, pareto_front, pareto_plot, scaling_plot, write_plot};
use crate::record::{Results, Row};

/// Writes every plot into `dir` (`bench-*.svg` and `.png`) and returns
/// the stems written.
pub fn write_plots(results: &Results, dir: &Path) -> Result<Vec<String>> {
    std::fs::create_dir_all(dir)?;
    let rows = &results.rows;
    let hiders = hider_order(rows);
    let mut stems = Vec::new();
    let answers = [
        ("bench-answer-aa", aa_plot(rows, &hiders)),
        ("bench-answer-precision", precision_plot(rows, &hiders)),
    ];
    for (stem, plot) in answers {
        if let Some(plot) = plot {
            write_plot(dir, stem, &plot)?;
            stems.push(stem.to_owned());
        }
    }
    if let Some(plot) = pareto_all(rows, &hiders) {
        write_plot(dir, "bench-pareto-all", &plot)?;
        stems.push("bench-pareto-all".to_owned());
    }
    // Per scene at the largest accuracy size only, where times are least
    // dominated by fixed costs (and the docs folder stays small).
    let cases = accuracy_cases(rows);
    let largest = cases.iter().map(|c| c.1).max();
    for (scene, w) in cases.into_iter().filter(|c| Some(c.1) == largest) {
        let case_rows: Vec<&Row> = rows
            .iter()
            .filter(|r| r.study == "accuracy" && r.scene == scene && r.width == w)
            .collect();
        if case_rows.iter().all(|r| r.error().is_none()) {
            continue;
        }
        let stem = format!("bench-pareto-{scene}-{w}");
        write_plot(
            dir,
            &stem,
            &pareto_plot(
                &format!("{scene} at {w} px: time against error"),
                &case_rows,
                &hiders,
            ),
        )?;
        stems.push(stem);
    }
    for study in &Study::SCALING {
        if !rows.iter().any(|r| r.study == study.as_str() && r.is_ok()) {
            continue;
        }
        let stem = format!("bench-{}", study.as_str());
        write_plot(dir, &stem, &scaling_plot(rows, *study, &hiders))?;
        stems.push(stem);
    }
    Ok(stems)
}

/// Time against error summed up over the accuracy scenes: per hider the
/// geometric-mean time and the mean error, with the Pareto front; `None`
/// when no hider was scored.
fn pareto_all(rows: &[Row], hiders: &[String]) -> Option<Plot> {
    let mut series_all = Vec::new();
    for (k, h) in hiders.iter().enumerate() {
        let scored: Vec<&Row> = accuracy_rows(rows, h)
            .filter(|r| r.error().is_some())
            .collect();
        let (Some(t), false) = (
            geometric_mean(scored.iter().map(|r| r.render_ms)),
            scored.is_empty(),
        ) else {
            continue;
        };
        let err = scored.iter().filter_map(|r| r.error()).sum::<f64>() / scored.len() as f64;
        series_all.push(Series {
            name: h.clone(),
            colour: k,
            points: vec![(t, err)],
            line: false,
        });
    }
    if series_all.is_empty() {
        return None;
    }
    let pts: Vec<(f64, f64)> = series_all.iter().map(|s| s.points[0]).collect();
    Some(Plot {
        title: "Accuracy study, all scenes: time against error".into(),
        x_label: "render time, ms (geometric mean over scenes)".into(),
        y_label: format!("{ERROR_AXIS} (mean)"),
        front: pareto_front(&pts),
        series: series_all,
        zero_label: "0 wrong, exact".into(),
    })
}
