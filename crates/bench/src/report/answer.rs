//! The report's first screen: what accuracy costs in time, answered from
//! the run's own numbers. Exact pixel-centre visibility on real-size work,
//! anti-aliasing's coverage error against its time (with a Pareto plot),
//! what each cheap shortcut costs in wrong pixels against the time it
//! saves, depth precision per format, and a few sentences of conclusions.

use std::fmt::Write as _;

use super::format::{fmt_count, fmt_error, fmt_ms, fmt_pct, fmt_ratio};
use super::options::ReportOptions;
use super::rows::{cell, geometric_mean, kind_of, study_cases};
use crate::plots::{Plot, Series, pareto_front};
use crate::precision::parse_scene_name;
use crate::record::Row;

/// The real-size study's name in the rows.
pub(super) const REAL: &str = "real-size";
/// The depth-precision study's name in the rows.
pub(super) const PRECISION: &str = "depth-precision";

/// The shortcuts and the exact hider each stands in for.
const SHORTCUTS: [(&str, &str, &str); 4] = [
    (
        "painter-naive",
        "painter",
        "sort by farthest vertex, no splitting",
    ),
    (
        "zbuffer-linear-z",
        "zbuffer",
        "camera z interpolated linearly on screen",
    ),
    ("zbuffer-fixed16", "zbuffer", "16-bit fixed-point depth"),
    ("zbuffer-fixed24", "zbuffer", "24-bit fixed-point depth"),
];

/// The depth formats of the precision study, coarsest first.
pub(super) const FORMATS: [(&str, &str); 5] = [
    ("zbuffer-fixed16", "16-bit fixed point"),
    ("zbuffer-fixed24", "24-bit fixed point"),
    ("zbuffer", "f32"),
    ("zbuffer-reversed", "f32, reversed Z"),
    ("zbuffer-f64", "f64"),
];

/// The hider that stands for one sample per pixel on the anti-aliasing
/// curve.
const ONE_SAMPLE: &str = "zbuffer";

/// Per hider, what the real-size study measured over a set of cases.
#[derive(Clone, Debug)]
pub(super) struct Aggregate {
    /// Registry name.
    pub hider: String,
    /// Geometric mean of the median times over the cases, ms.
    pub time_ms: f64,
    /// Wrong ids on non-tie pixels, summed over the cases.
    pub wrong_ids: u64,
    /// Coverage mismatches at pixel centres, summed over the cases.
    pub coverage_mismatches: u64,
    /// Cases with a wrong id or a coverage mismatch.
    pub wrong_cases: usize,
    /// Mean coverage error over the cases (when every case has one).
    pub coverage_error: Option<f64>,
    /// Cases whose scene calls for an effect the hider does not simulate
    /// (it is not exact there, whatever its ids score).
    pub ignored_cases: usize,
    /// Cases aggregated.
    pub cases: usize,
}

/// The cases of `study` on which every hider of `hiders` finished (and,
/// with `need_coverage`, has a coverage error).
pub(super) fn common_cases(
    rows: &[Row],
    study: &str,
    hiders: &[&str],
    need_coverage: bool,
) -> Vec<(String, u32)> {
    study_cases(rows, study)
        .into_iter()
        .filter(|c| {
            hiders.iter().all(|h| {
                cell(rows, study, c, h)
                    .is_some_and(|r| r.is_ok() && (!need_coverage || r.coverage_error.is_some()))
            })
        })
        .collect()
}

/// What `hider` measured over `cases` of the real-size study; `None` when
/// it did not finish them all.
pub(super) fn aggregate(rows: &[Row], hider: &str, cases: &[(String, u32)]) -> Option<Aggregate> {
    let got: Vec<&Row> = cases
        .iter()
        .map(|c| cell(rows, REAL, c, hider).filter(|r| r.is_ok()))
        .collect::<Option<_>>()?;
    let errors: Option<Vec<f64>> = got.iter().map(|r| r.coverage_error).collect();
    Some(Aggregate {
        hider: hider.to_owned(),
        time_ms: geometric_mean(got.iter().map(|r| r.render_ms))?,
        wrong_ids: got.iter().filter_map(|r| r.wrong_ids).sum(),
        coverage_mismatches: got.iter().filter_map(|r| r.coverage_mismatches).sum(),
        wrong_cases: got
            .iter()
            .filter(|r| r.wrong_ids.unwrap_or(0) + r.coverage_mismatches.unwrap_or(0) > 0)
            .count(),
        coverage_error: errors
            .filter(|e| !e.is_empty())
            .map(|e| e.iter().sum::<f64>() / e.len() as f64),
        ignored_cases: got.iter().filter(|r| !r.simulates_all_effects()).count(),
        cases: got.len(),
    })
}

/// The hiders of a kind, in matrix order.
fn of_kind<'a>(rows: &[Row], hiders: &'a [String], kind: &str) -> Vec<&'a str> {
    hiders
        .iter()
        .filter(|h| kind_of(rows, h) == kind)
        .map(String::as_str)
        .collect()
}

/// The anti-aliasing curve's hiders: one sample, then every multi-sample
/// hider.
pub(super) fn aa_hiders<'a>(rows: &[Row], hiders: &'a [String]) -> Vec<&'a str> {
    let mut v: Vec<&str> = hiders
        .iter()
        .map(String::as_str)
        .filter(|h| *h == ONE_SAMPLE)
        .collect();
    v.extend(of_kind(rows, hiders, "MultiSample"));
    v
}

/// The anti-aliasing aggregates over the cases every one of them scored.
pub(super) fn aa_aggregates(rows: &[Row], hiders: &[String]) -> Vec<Aggregate> {
    let aa = aa_hiders(rows, hiders);
    let cases = common_cases(rows, REAL, &aa, true);
    if cases.is_empty() {
        return Vec::new();
    }
    aa.iter()
        .filter_map(|h| aggregate(rows, h, &cases))
        .collect()
}

/// The answer section (nothing without real-size or precision rows).
pub(super) fn answer_section(
    s: &mut String,
    rows: &[Row],
    hiders: &[String],
    options: &ReportOptions,
) {
    let real = study_cases(rows, REAL);
    let precision = study_cases(rows, PRECISION);
    if real.is_empty() && precision.is_empty() {
        return;
    }
    let _ = writeln!(s, "## The answer: what accuracy costs in time\n");
    if !real.is_empty() {
        let names: Vec<String> = real.iter().map(|c| c.0.clone()).collect();
        let _ = writeln!(
            s,
            "Real-size work: {} scenes at {} x {} ({}), each timed from the world-space scene to the finished frame (the front end included, as a frame loop waits for it; median ms).\n",
            real.len(),
            real[0].1,
            real[0].1,
            names.join(", ")
        );
        exact_table(s, rows, hiders, &real);
        aa_section(s, rows, hiders, options);
        shortcut_table(s, rows);
    }
    if !precision.is_empty() {
        precision_section(s, rows, options);
    }
    conclusions(s, rows, hiders);
}

/// (a) Every exact pixel-centre hider's time per real-size scene, their
/// geometric mean and the ratio to the fastest.
fn exact_table(s: &mut String, rows: &[Row], hiders: &[String], cases: &[(String, u32)]) {
    let exact = of_kind(rows, hiders, "ExactPixelCentre");
    if exact.is_empty() {
        return;
    }
    let _ = writeln!(s, "### Exact visibility at pixel centres\n");
    let _ = writeln!(
        s,
        "Every hider here gives the oracle's surface at every pixel centre (a run that did not is marked with its wrong pixels; a run on a scene with an effect the hider does not simulate, such as translucent surfaces it draws opaque, is marked *ignores EFFECT*: not exact for that scene).\n"
    );
    let _ = write!(s, "| scene (triangles) |");
    for h in &exact {
        let _ = write!(s, " {h} |");
    }
    let _ = writeln!(s, "\n|---|{}", "---:|".repeat(exact.len()));
    for c in cases {
        let tris = rows
            .iter()
            .find(|r| r.study == REAL && r.scene == c.0 && r.width == c.1)
            .map_or(0, |r| r.triangles);
        let _ = write!(s, "| {} ({}) |", c.0, fmt_count(tris));
        for h in &exact {
            let text = match cell(rows, REAL, c, h) {
                Some(r) if r.is_ok() => {
                    let wrong = r.wrong_ids.unwrap_or(0) + r.coverage_mismatches.unwrap_or(0);
                    let mut text = fmt_ms(r.render_ms);
                    if wrong > 0 {
                        text += &format!(" (**{} wrong**)", fmt_count(wrong));
                    }
                    if !r.simulates_all_effects() {
                        text += &format!(" (*ignores {}*)", r.ignored_effects);
                    }
                    text
                }
                Some(_) => "err".into(),
                None => "-".into(),
            };
            let _ = write!(s, " {text} |");
        }
        s.push('\n');
    }
    let common = common_cases(rows, REAL, &exact, false);
    let aggs: Vec<Option<Aggregate>> = exact.iter().map(|h| aggregate(rows, h, &common)).collect();
    let best = aggs
        .iter()
        .flatten()
        .map(|a| a.time_ms)
        .min_by(f64::total_cmp);
    let _ = write!(s, "| **geometric mean** ({} scenes) |", common.len());
    for a in &aggs {
        let _ = write!(
            s,
            " {} |",
            a.as_ref().map_or("-".into(), |a| fmt_ms(a.time_ms))
        );
    }
    let _ = write!(s, "\n| relative to the fastest |");
    for a in &aggs {
        let text = match (a, best) {
            (Some(a), Some(b)) => fmt_ratio(a.time_ms / b),
            _ => "-".into(),
        };
        let _ = write!(s, " {text} |");
    }
    s.push_str("\n\n");
}

/// (b) Coverage error against time for one sample, supersampling, the
/// A-buffers and anti-aliased Warnock, with the Pareto plot.
fn aa_section(s: &mut String, rows: &[Row], hiders: &[String], options: &ReportOptions) {
    let aggs = aa_aggregates(rows, hiders);
    if aggs.is_empty() {
        return;
    }
    let _ = writeln!(s, "### Anti-aliasing: coverage error against time\n");
    let _ = writeln!(
        s,
        "Mean |coverage - exact analytic coverage| per pixel over the {} real-size scenes whose analytic coverage was computed; one sample per pixel is `{ONE_SAMPLE}` (coverage 0 or 1).\n",
        aggs[0].cases
    );
    if let Some(p) = options.image_link("bench-answer-aa", "svg") {
        let png = options
            .image_link("bench-answer-aa", "png")
            .unwrap_or_default();
        let _ = writeln!(s, "![coverage error against time]({p}) ([PNG]({png}))\n");
    }
    let reference = aggs
        .iter()
        .find(|a| a.hider == "ssaa-32")
        .map(|a| a.time_ms);
    let _ = writeln!(
        s,
        "| hider | mean coverage error | time, geometric mean (ms) | time relative to ssaa-32 |"
    );
    let _ = writeln!(s, "|---|---:|---:|---:|");
    for a in &aggs {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} |",
            a.hider,
            a.coverage_error.map_or("-".into(), fmt_error),
            fmt_ms(a.time_ms),
            reference.map_or("-".into(), |r| fmt_ratio(a.time_ms / r)),
        );
    }
    s.push('\n');
}

/// The anti-aliasing Pareto plot, `None` without scored aggregates.
pub(super) fn aa_plot(rows: &[Row], hiders: &[String]) -> Option<Plot> {
    let aggs = aa_aggregates(rows, hiders);
    let series: Vec<Series> = aggs
        .iter()
        .filter_map(|a| {
            Some(Series {
                name: a.hider.clone(),
                colour: hiders.iter().position(|h| *h == a.hider).unwrap_or(0),
                points: vec![(a.time_ms, a.coverage_error?)],
                line: false,
            })
        })
        .collect();
    if series.is_empty() {
        return None;
    }
    let pts: Vec<(f64, f64)> = series.iter().map(|s| s.points[0]).collect();
    let size = rows.iter().find(|r| r.study == REAL).map_or(0, |r| r.width);
    Some(Plot {
        title: format!("Anti-aliasing at {size} px: coverage error against time"),
        x_label: "time per frame, ms (geometric mean over scenes)".into(),
        y_label: "mean coverage error per pixel".into(),
        front: pareto_front(&pts),
        series,
        zero_label: "0 error".into(),
    })
}

/// (c) What each shortcut costs in wrong pixels against the time it saves
/// over the exact hider it stands in for.
fn shortcut_table(s: &mut String, rows: &[Row]) {
    let _ = writeln!(s, "### What each shortcut costs\n");
    let _ = writeln!(
        s,
        "Wrong pixels: non-tie wrong ids plus coverage mismatches against the oracle, summed over the real-size scenes and over the hard cases of the accuracy study at their largest size; time: geometric means over the real-size scenes.\n"
    );
    let _ = writeln!(
        s,
        "| shortcut | instead of | wrong pixels, real size (scenes) | wrong pixels, hard cases | time (ms) | exact time (ms) | time saved |"
    );
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|");
    for (fast, exact, what) in SHORTCUTS {
        let cases = common_cases(rows, REAL, &[fast, exact], false);
        let (Some(f), Some(e)) = (
            aggregate(rows, fast, &cases),
            aggregate(rows, exact, &cases),
        ) else {
            continue;
        };
        let hard = hard_case_wrong(rows, fast);
        let _ = writeln!(
            s,
            "| {fast} ({what}) | {exact} | {} ({}/{}) | {} | {} | {} | {} |",
            fmt_count(f.wrong_ids + f.coverage_mismatches),
            f.wrong_cases,
            f.cases,
            hard.map_or("-".into(), |(w, k, n)| format!(
                "{} ({k}/{n})",
                fmt_count(w)
            )),
            fmt_ms(f.time_ms),
            fmt_ms(e.time_ms),
            time_saved(f.time_ms, e.time_ms),
        );
    }
    s.push('\n');
}

/// What a shortcut saves against its exact hider: `38%`, or `none (41%
/// slower)` when it is slower.
pub(super) fn time_saved(fast_ms: f64, exact_ms: f64) -> String {
    if fast_ms <= exact_ms {
        fmt_pct(1.0 - fast_ms / exact_ms)
    } else {
        format!("none ({} slower)", fmt_pct(fast_ms / exact_ms - 1.0))
    }
}

/// Wrong pixels of `hider` over the hard cases at the accuracy study's
/// largest size, the scenes with any, and the scenes scored: `None`
/// without such rows.
pub(super) fn hard_case_wrong(rows: &[Row], hider: &str) -> Option<(u64, usize, usize)> {
    let largest = rows
        .iter()
        .filter(|r| r.study == "accuracy" && r.group == "hard-case")
        .map(|r| r.width)
        .max()?;
    let got: Vec<&Row> = rows
        .iter()
        .filter(|r| {
            r.study == "accuracy"
                && r.group == "hard-case"
                && r.width == largest
                && r.hider == hider
                && r.wrong_ids.is_some()
        })
        .collect();
    let wrong: Vec<u64> = got
        .iter()
        .map(|r| r.wrong_ids.unwrap_or(0) + r.coverage_mismatches.unwrap_or(0))
        .collect();
    let scenes = wrong.iter().filter(|w| **w > 0).count();
    (!got.is_empty()).then(|| (wrong.iter().sum(), scenes, got.len()))
}

/// Share of covered pixels showing the farther surface, per row.
pub(super) fn farther_share(r: &Row) -> Option<f64> {
    Some(r.farther_pixels? as f64 / r.covered_pixels.max(1) as f64)
}

/// The sweep's gaps and near/far ratios, largest first.
pub(super) fn precision_axes(rows: &[Row]) -> (Vec<f64>, Vec<f64>) {
    let mut gaps = Vec::new();
    let mut ratios = Vec::new();
    for (scene, _) in study_cases(rows, PRECISION) {
        if let Some((g, r)) = parse_scene_name(&scene) {
            if !gaps.contains(&g) {
                gaps.push(g);
            }
            if !ratios.contains(&r) {
                ratios.push(r);
            }
        }
    }
    gaps.sort_by(|a, b| b.total_cmp(a));
    ratios.sort_by(|a, b| b.total_cmp(a));
    (gaps, ratios)
}

/// The precision row of `hider` at one point of the sweep.
pub(super) fn precision_row<'a>(
    rows: &'a [Row],
    hider: &str,
    gap: f64,
    ratio: f64,
) -> Option<&'a Row> {
    rows.iter().find(|r| {
        r.study == PRECISION
            && r.hider == hider
            && r.is_ok()
            && parse_scene_name(&r.scene) == Some((gap, ratio))
    })
}

/// (d) The share of pixels showing the farther of two nearly coplanar
/// surfaces per depth format, gap and near/far ratio.
fn precision_section(s: &mut String, rows: &[Row], options: &ReportOptions) {
    let (gaps, ratios) = precision_axes(rows);
    let _ = writeln!(s, "### Depth precision\n");
    let _ = writeln!(
        s,
        "Two parallel surfaces seen at 45 degrees, a gap apart (relative to their distance from the eye), the farther one drawn first: the share of pixels where the farther one shows, because the depth format cannot tell the two apart.\n"
    );
    if let Some(p) = options.image_link("bench-answer-precision", "svg") {
        let png = options
            .image_link("bench-answer-precision", "png")
            .unwrap_or_default();
        let _ = writeln!(s, "![depth precision]({p}) ([PNG]({png}))\n");
    }
    let _ = write!(s, "| format | near/far |");
    for g in &gaps {
        let _ = write!(s, " gap {g:.0e} |");
    }
    let _ = writeln!(s, "\n|---|---:|{}", "---:|".repeat(gaps.len()));
    for (hider, label) in FORMATS {
        for &ratio in &ratios {
            if !gaps
                .iter()
                .any(|&g| precision_row(rows, hider, g, ratio).is_some())
            {
                continue;
            }
            let _ = write!(s, "| {label} (`{hider}`) | {ratio:.0e} |");
            for &g in &gaps {
                let text = precision_row(rows, hider, g, ratio)
                    .and_then(farther_share)
                    .map_or("-".into(), fmt_pct);
                let _ = write!(s, " {text} |");
            }
            s.push('\n');
        }
    }
    s.push('\n');
}

/// The precision plot: share against gap per format at the smallest
/// near/far ratio of the sweep.
pub(super) fn precision_plot(rows: &[Row], hiders: &[String]) -> Option<Plot> {
    let (gaps, ratios) = precision_axes(rows);
    let ratio = *ratios.last()?;
    let series: Vec<Series> = FORMATS
        .iter()
        .map(|(hider, label)| Series {
            name: (*label).to_owned(),
            colour: hiders.iter().position(|h| h == hider).unwrap_or(0),
            points: gaps
                .iter()
                .filter_map(|&g| Some((g, farther_share(precision_row(rows, hider, g, ratio)?)?)))
                .collect(),
            line: true,
        })
        .filter(|s| !s.points.is_empty())
        .collect();
    (!series.is_empty()).then(|| Plot {
        title: format!("Depth precision at near/far {ratio:.0e}: the farther surface showing"),
        x_label: "gap between the surfaces / their distance from the eye".into(),
        y_label: "share of pixels showing the farther surface".into(),
        series,
        front: Vec::new(),
        zero_label: "0: the nearer surface everywhere".into(),
    })
}

/// The conclusions, every number from the run.
fn conclusions(s: &mut String, rows: &[Row], hiders: &[String]) {
    let lines = super::conclusions::sentences(rows, hiders);
    if lines.is_empty() {
        return;
    }
    let _ = writeln!(s, "### Conclusions\n");
    for l in lines {
        let _ = writeln!(s, "- {l}");
    }
    s.push('\n');
}
