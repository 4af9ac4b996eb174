//! The outputs people read: the terminal table, the plots and the Markdown
//! report (`docs/report.md`), all generated from [`Results`] alone, so a
//! merged set of shards gives the same report as one run.

use std::collections::BTreeSet;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;

use crate::matrix::Study;
use crate::plots::{Plot, Series, pareto_plot, scaling_plot, write_plot};
use crate::record::{Results, Row, write_text_atomic};
use crate::scaling::{axis_label, fit_power_law, series};

/// Hider names in first-appearance order of the rows (matrix order keeps
/// registry order).
pub fn hider_order(rows: &[Row]) -> Vec<String> {
    let mut seen = Vec::new();
    for r in rows {
        if !seen.contains(&r.hider) {
            seen.push(r.hider.clone());
        }
    }
    seen
}

fn kind_of(rows: &[Row], hider: &str) -> String {
    rows.iter()
        .find(|r| r.hider == hider)
        .map_or_else(String::new, |r| r.kind.clone())
}

fn fmt_ms(ms: f64) -> String {
    if ms >= 100.0 {
        format!("{ms:.0}")
    } else if ms >= 1.0 {
        format!("{ms:.2}")
    } else {
        format!("{ms:.3}")
    }
}

fn fmt_bytes(b: u64) -> String {
    if b >= 10 << 20 {
        format!("{} MiB", b >> 20)
    } else if b >= 10 << 10 {
        format!("{} KiB", b >> 10)
    } else {
        format!("{b} B")
    }
}

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
        let wrong = match (r.coverage_error, r.wrong_ids, r.coverage_mismatches) {
            (Some(e), _, _) => format!("c {e:.1e}"),
            (None, Some(w), Some(c)) => (w + c).to_string(),
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
    let exps = exponent_table(&results.rows);
    if !exps.is_empty() {
        s.push_str("\nGrowth exponents b of time ~ x^b (least squares on log-log):\n");
        s.push_str(&exps);
    }
    s
}

/// Growth exponents per hider and scaling study as a Markdown-ish table
/// (readable in a terminal too).
pub fn exponent_table(rows: &[Row]) -> String {
    let studies: Vec<Study> = Study::ALL[1..]
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

fn geometric_mean(values: impl Iterator<Item = f64>) -> Option<f64> {
    let (sum, n) = values
        .filter(|v| *v > 0.0)
        .fold((0.0, 0u32), |(s, n), v| (s + v.ln(), n + 1));
    (n > 0).then(|| (sum / f64::from(n)).exp())
}

fn accuracy_rows<'a>(rows: &'a [Row], hider: &'a str) -> impl Iterator<Item = &'a Row> + 'a {
    rows.iter()
        .filter(move |r| r.study == "accuracy" && r.hider == hider && r.is_ok())
}

/// Writes every plot into `dir` (`bench-*.svg` and `.png`) and returns
/// the stems written.
pub fn write_plots(results: &Results, dir: &Path) -> Result<Vec<String>> {
    std::fs::create_dir_all(dir)?;
    let rows = &results.rows;
    let hiders = hider_order(rows);
    let mut stems = Vec::new();
    // Time vs error summed up over the accuracy scenes.
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
            points: vec![(t, err.max(crate::plots::ERROR_FLOOR))],
            line: false,
        });
    }
    if !series_all.is_empty() {
        let pts: Vec<(f64, f64)> = series_all.iter().map(|s| s.points[0]).collect();
        let plot = Plot {
            title: "all accuracy scenes: time vs error".into(),
            x_label: "render time, ms (geometric mean over scenes)".into(),
            y_label: "mean error over scenes".into(),
            front: crate::plots::pareto_front(&pts),
            series: series_all,
        };
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
                &format!("{scene} at {w} px: time vs error"),
                &case_rows,
                &hiders,
            ),
        )?;
        stems.push(stem);
    }
    for study in &Study::ALL[1..] {
        if !rows.iter().any(|r| r.study == study.as_str() && r.is_ok()) {
            continue;
        }
        let stem = format!("bench-{}", study.as_str());
        write_plot(dir, &stem, &scaling_plot(rows, *study, &hiders))?;
        stems.push(stem);
    }
    Ok(stems)
}

/// `(scene, width)` of the accuracy cases, in matrix order.
fn accuracy_cases(rows: &[Row]) -> Vec<(String, u32)> {
    let mut seen = Vec::new();
    for r in rows.iter().filter(|r| r.study == "accuracy") {
        let key = (r.scene.clone(), r.width);
        if !seen.contains(&key) {
            seen.push(key);
        }
    }
    seen
}

/// Options of [`markdown`].
#[derive(Clone, Debug, Default)]
pub struct ReportOptions {
    /// How the report's images are linked from the report (`images/`).
    pub image_prefix: String,
    /// Folder holding the images, to link only those that exist.
    pub image_dir: PathBuf,
    /// The command that regenerates the report, quoted at the top.
    pub command: String,
}

/// The Markdown report.
pub fn markdown(results: &Results, options: &ReportOptions) -> String {
    let rows = &results.rows;
    let hiders = hider_order(rows);
    let img = |stem: &str, ext: &str| -> Option<String> {
        let file = format!("{stem}.{ext}");
        options
            .image_dir
            .join(&file)
            .is_file()
            .then(|| format!("{}{file}", options.image_prefix))
    };
    let mut s = String::new();
    let _ = writeln!(s, "# Benchmark report: what accuracy costs in time\n");
    let _ = writeln!(
        s,
        "Generated by `{}`; do not edit by hand (the reading of these numbers is in [bench.md](bench.md)).\n",
        options.command
    );
    let ok = rows.iter().filter(|r| r.is_ok()).count();
    let _ = writeln!(
        s,
        "{} runs ({} finished, {} refused or failed or skipped){}.\n",
        rows.len(),
        ok,
        rows.len() - ok,
        if results.complete {
            ""
        } else {
            "; **the sweep was interrupted: some runs are missing**"
        }
    );
    let _ = writeln!(s, "## Machine and method\n");
    for m in &results.machines {
        let _ = writeln!(
            s,
            "- {} ({} logical cores, {} threads available), {}",
            m.cpu, m.cores, m.threads, m.os
        );
    }
    for c in &results.commands {
        let _ = writeln!(s, "- command: `{c}`");
    }
    let set = |f: fn(&Row) -> u32| {
        let v: BTreeSet<u32> = rows.iter().filter(|r| r.is_ok()).map(f).collect();
        v.iter()
            .map(u32::to_string)
            .collect::<Vec<_>>()
            .join(" or ")
    };
    let _ = writeln!(
        s,
        "- each run: {} unmeasured warm-up render(s), then {} measured renders (fewer when one job passes its time budget); times are the median with the min-max range, render only (loading and `prepare()` are timed separately)",
        set(|r| r.warmup),
        set(|r| r.runs)
    );
    let _ = writeln!(
        s,
        "- accuracy: ids against the exact ray-cast oracle at pixel centres (a pixel whose two nearest surfaces are within the tie tolerance is a *tie*: counted, any id accepted); error = (wrong ids on non-tie pixels + coverage mismatches) / covered pixels; multi-sample hiders: mean |coverage - analytic coverage|\n"
    );

    // Summary per hider.
    let _ = writeln!(s, "## Summary per hider (accuracy study)\n");
    let reference_time = hiders
        .iter()
        .filter(|h| kind_of(rows, h) == "ExactPixelCentre")
        .filter_map(|h| {
            geometric_mean(accuracy_rows(rows, h).map(|r| r.render_ms)).map(|t| (h.clone(), t))
        })
        .min_by(|a, b| a.1.total_cmp(&b.1));
    let _ = writeln!(
        s,
        "| hider | kind | scenes with 0 wrong ids | mean error | worst scene (error) | time, geometric mean (ms) | relative to {} | median peak memory |",
        reference_time.as_ref().map_or("-", |r| r.0.as_str())
    );
    let _ = writeln!(s, "|---|---|---:|---:|---|---:|---:|---:|");
    for h in &hiders {
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
        let rel = match (t, &reference_time) {
            (Some(t), Some((_, r))) => format!("{:.2}x", t / r),
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
    s.push('\n');
    if let Some(p) = img("bench-pareto-all", "svg") {
        let _ = writeln!(s, "![time vs error over all accuracy scenes]({p})\n");
    }

    // Accuracy and time tables: scenes x hiders.
    let cases = accuracy_cases(rows);
    if !cases.is_empty() {
        let header = |s: &mut String, first: &str| {
            let _ = write!(s, "| {first} |");
            for h in &hiders {
                let _ = write!(s, " {h} |");
            }
            let _ = writeln!(s, "\n|---|{}", "---:|".repeat(hiders.len()));
        };
        let cell = |scene: &str, w: u32, h: &str| {
            rows.iter()
                .find(|r| r.study == "accuracy" && r.scene == scene && r.width == w && r.hider == h)
        };
        let _ = writeln!(s, "## Accuracy: wrong pixels per scene\n");
        let _ = writeln!(
            s,
            "Wrong = non-tie wrong ids + coverage mismatches; `ties` is the oracle's tie count for the scene; `c` is the coverage error of multi-sample hiders.\n"
        );
        header(&mut s, "scene (triangles, ties)");
        for (scene, w) in &cases {
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
            for h in &hiders {
                let text = match cell(scene, *w, h) {
                    None => "".into(),
                    Some(r) if !r.is_ok() => "err".into(),
                    Some(r) if r.kind == "MultiSample" && r.coverage_error.is_some() => {
                        format!("c {:.1e}", r.coverage_error.unwrap_or(0.0))
                    }
                    Some(r) => match (r.wrong_ids, r.coverage_mismatches) {
                        (Some(0), Some(0)) => "0".into(),
                        (Some(a), Some(b)) => format!("**{}**", a + b),
                        _ if r.accuracy == "reference" => "ref".into(),
                        _ => "-".into(),
                    },
                };
                let _ = write!(s, " {text} |");
            }
            s.push('\n');
        }
        let _ = writeln!(s, "\n## Time per scene (median render ms)\n");
        header(&mut s, "scene");
        for (scene, w) in &cases {
            let _ = write!(s, "| {scene}@{w} |");
            for h in &hiders {
                let text = cell(scene, *w, h)
                    .filter(|r| r.is_ok())
                    .map_or("-".into(), |r| fmt_ms(r.render_ms));
                let _ = write!(s, " {text} |");
            }
            s.push('\n');
        }
        s.push('\n');
        let pareto: Vec<String> = cases
            .iter()
            .filter_map(|(scene, w)| {
                img(&format!("bench-pareto-{scene}-{w}"), "svg")
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

    // Scaling.
    let scaling: Vec<Study> = Study::ALL[1..]
        .iter()
        .copied()
        .filter(|st| rows.iter().any(|r| r.study == st.as_str()))
        .collect();
    if !scaling.is_empty() {
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
            let _ = writeln!(s, "### Time vs {}\n", axis_label(st));
            let xs: Vec<(String, f64)> = {
                let mut v: Vec<(String, f64)> = Vec::new();
                for r in rows.iter().filter(|r| r.study == st.as_str()) {
                    let label = format!("{}@{}", r.scene, r.width);
                    if !v.iter().any(|(l, _)| *l == label) {
                        v.push((label, crate::scaling::axis(st, r).unwrap_or(0.0)));
                    }
                }
                v
            };
            let _ = write!(s, "| case | {} |", axis_label(st));
            for h in &hiders {
                let _ = write!(s, " {h} |");
            }
            let _ = writeln!(s, "\n|---|---:|{}", "---:|".repeat(hiders.len()));
            for (label, x) in &xs {
                let _ = write!(
                    s,
                    "| {label} | {} |",
                    if *x >= 100.0 {
                        format!("{x:.0}")
                    } else {
                        format!("{x:.2}")
                    }
                );
                for h in &hiders {
                    let r = rows.iter().find(|r| {
                        r.study == st.as_str()
                            && format!("{}@{}", r.scene, r.width) == *label
                            && &r.hider == h
                    });
                    let text = match r {
                        Some(r) if r.is_ok() => {
                            let mark = match r.error() {
                                Some(e) if e > 0.0 => " (wrong)",
                                _ => "",
                            };
                            format!("{}{mark}", fmt_ms(r.render_ms))
                        }
                        Some(_) => "err".into(),
                        None => "-".into(),
                    };
                    let _ = write!(s, " {text} |");
                }
                s.push('\n');
            }
            s.push('\n');
            if let Some(p) = img(&format!("bench-{}", st.as_str()), "svg") {
                let _ = writeln!(s, "![time vs {}]({p})\n", axis_label(st));
            }
        }
    }

    // Contact sheets.
    let mut sheets: Vec<(String, String)> = Vec::new();
    for (scene, _) in &cases {
        if let Some(p) = img(&format!("bench-contact-{scene}"), "png") {
            if !sheets.iter().any(|(s, _)| s == scene) {
                sheets.push((scene.clone(), p));
            }
        }
    }
    if !sheets.is_empty() {
        let _ = writeln!(s, "## Contact sheets\n");
        let _ = writeln!(
            s,
            "Each hard case: the oracle first, then every hider's render; wrong pixels in magenta, ties decided differently from the oracle (accepted) in yellow.\n"
        );
        for (scene, p) in sheets {
            let _ = writeln!(s, "### {scene}\n\n![{scene}]({p})\n");
        }
    }

    // Problems.
    let problems: Vec<&Row> = rows
        .iter()
        .filter(|r| {
            !r.is_ok()
                || r.accuracy.starts_with("skipped")
                || (r.study == "accuracy" && r.accuracy.contains("only"))
        })
        .collect();
    if !problems.is_empty() {
        let _ = writeln!(s, "## Refused, failed, skipped or unscored runs\n");
        for r in problems {
            let what = if r.is_ok() { &r.accuracy } else { &r.status };
            let _ = writeln!(
                s,
                "- {} {}@{} {}: {}",
                r.study,
                r.scene,
                r.width,
                r.hider,
                what.replace('\n', " ")
            );
        }
        s.push('\n');
    }
    s
}

/// Writes the plots into `image_dir` and the report to `report_path`.
pub fn write_report(
    results: &Results,
    report_path: &Path,
    image_dir: &Path,
    command: &str,
) -> Result<()> {
    write_plots(results, image_dir)?;
    let report_dir = report_path.parent().unwrap_or(Path::new(""));
    let prefix = match image_dir.strip_prefix(report_dir) {
        Ok(rel) if rel.as_os_str().is_empty() => String::new(),
        Ok(rel) => format!("{}/", rel.display()),
        Err(_) => format!("{}/", image_dir.display()),
    };
    let md = markdown(
        results,
        &ReportOptions {
            image_prefix: prefix,
            image_dir: image_dir.to_path_buf(),
            command: command.to_owned(),
        },
    );
    write_text_atomic(report_path, &md)
}
