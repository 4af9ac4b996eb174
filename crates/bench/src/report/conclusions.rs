//! The conclusions at the top of the report: a few sentences whose every
//! number is read from the run (nothing here is written in advance).

use super::answer::{
    FORMATS, REAL, aa_aggregates, aggregate, common_cases, farther_share, hard_case_wrong,
    precision_axes, precision_row,
};
use super::format::{fmt_count, fmt_error, fmt_ms, fmt_pct, fmt_ratio};
use super::noise::{TIME_TIE, same_speed};
use super::rows::kind_of;
use crate::record::Row;

/// The sentences, in the order of the answer's parts.
pub(super) fn sentences(rows: &[Row], hiders: &[String]) -> Vec<String> {
    let mut v = Vec::new();
    v.extend(exact_sentences(rows, hiders));
    v.extend(aa_sentence(rows, hiders));
    v.push(aa_recommendation(rows, hiders));
    v.extend(shortcut_sentence(rows));
    v.extend(precision_sentence(rows));
    v
}

/// The fastest and slowest exact hider, and the tiled z-buffer against the
/// plain one.
fn exact_sentences(rows: &[Row], hiders: &[String]) -> Vec<String> {
    let exact: Vec<&str> = hiders
        .iter()
        .filter(|h| kind_of(rows, h) == "ExactPixelCentre")
        .map(String::as_str)
        .collect();
    let cases = common_cases(rows, REAL, &exact, false);
    let (mut aggs, ignoring): (Vec<_>, Vec<_>) = exact
        .iter()
        .filter_map(|h| aggregate(rows, h, &cases))
        .partition(|a| a.ignored_cases == 0);
    aggs.sort_by(|a, b| a.time_ms.total_cmp(&b.time_ms));
    // A hider that draws a scene's glass opaque is not exact for it,
    // however fast: it is left out of "the fastest exact hider", and said so.
    let left_out = if ignoring.is_empty() {
        String::new()
    } else {
        let names: Vec<String> = ignoring.iter().map(|a| format!("`{}`", a.hider)).collect();
        format!(
            " Left out as not exact on these scenes (they ignore an effect a scene calls for, such as translucency): {}.",
            names.join(", ")
        )
    };
    let (Some(first), Some(last)) = (aggs.first(), aggs.last()) else {
        return (!ignoring.is_empty())
            .then(|| format!("Exact visibility at real size: no pixel-centre hider simulates every effect of these scenes.{left_out}"))
            .into_iter()
            .collect();
    };
    let mut v = vec![format!(
        "Exact visibility at real size: the fastest exact hider is `{}` at {} ms per frame (geometric mean over {} scenes); the slowest, `{}`, takes {} as long ({} ms).{left_out}",
        first.hider,
        fmt_ms(first.time_ms),
        cases.len(),
        last.hider,
        fmt_ratio(last.time_ms / first.time_ms),
        fmt_ms(last.time_ms)
    )];
    let find = |h: &str| aggs.iter().find(|a| a.hider == h);
    if let (Some(t), Some(z)) = (find("zbuffer-tiled"), find("zbuffer")) {
        let ratio = z.time_ms / t.time_ms;
        let verdict = if same_speed(t.time_ms, z.time_ms) {
            format!(
                "the same speed (within the {:.0}% the report treats as noise)",
                TIME_TIE * 100.0
            )
        } else {
            format!(
                "{} {}",
                fmt_ratio(ratio.max(1.0 / ratio)),
                if ratio >= 1.0 { "faster" } else { "slower" }
            )
        };
        v.push(format!(
            "The tiled z-buffer takes {} ms against the plain z-buffer's {} ms: {verdict} on the same scenes, with the same pixels.",
            fmt_ms(t.time_ms),
            fmt_ms(z.time_ms),
        ));
    }
    v
}

/// The A-buffer and 4 samples against 32 samples.
fn aa_sentence(rows: &[Row], hiders: &[String]) -> Option<String> {
    let aggs = aa_aggregates(rows, hiders);
    let find = |h: &str| aggs.iter().find(|a| a.hider == h);
    let full = find("ssaa-32")?;
    let full_error = full.coverage_error?;
    let mut parts = Vec::new();
    for (h, what) in [
        ("abuffer", "the A-buffer"),
        ("abuffer-carpenter", "Carpenter's A-buffer"),
        ("warnock-4x4", "anti-aliased Warnock"),
        ("ssaa-4", "4 samples"),
    ] {
        if let Some(a) = find(h) {
            parts.push(format!(
                "{what}: {} at {} of the 32-sample time",
                a.coverage_error.map_or("-".into(), fmt_error),
                fmt_pct(a.time_ms / full.time_ms)
            ));
        }
    }
    let one = find("zbuffer")
        .and_then(|a| a.coverage_error)
        .map_or(String::new(), |e| {
            format!(" (one sample per pixel: {})", fmt_error(e))
        });
    Some(format!(
        "Anti-aliasing at real size: 32 samples per pixel leave a mean coverage error of {}{one} in {} ms; the coverage error and the share of that time of the others: {}.",
        fmt_error(full_error),
        fmt_ms(full.time_ms),
        parts.join("; ")
    ))
}

/// How much worse than the smallest measured coverage error a hider may be
/// and still be recommended for anti-aliasing: 25%, a difference a viewer
/// does not see at these error levels (a few 1e-5 of a pixel's coverage),
/// while the time differences between the candidates are several-fold.
const AA_ERROR_SLACK: f64 = 1.25;

/// The anti-aliasing recommendation, always given: the fastest hider whose
/// mean coverage error is within [`AA_ERROR_SLACK`] of the smallest
/// measured, among those that simulate every effect of the scenes; or why
/// this run cannot recommend one.
fn aa_recommendation(rows: &[Row], hiders: &[String]) -> String {
    let aggs = aa_aggregates(rows, hiders);
    let scored: Vec<_> = aggs
        .iter()
        .filter(|a| a.ignored_cases == 0)
        .filter_map(|a| Some((a, a.coverage_error?)))
        .collect();
    let Some(best) = scored.iter().map(|(_, e)| *e).min_by(f64::total_cmp) else {
        return "Anti-aliasing recommendation: none from this run: no anti-aliasing hider was measured at real size with analytic coverage (run the real-size study with an A-buffer, `ssaa-N` or `warnock-4x4` among the hiders).".into();
    };
    let Some((pick, error)) = scored
        .iter()
        .filter(|(_, e)| *e <= best * AA_ERROR_SLACK)
        .min_by(|a, b| a.0.time_ms.total_cmp(&b.0.time_ms))
    else {
        unreachable!("the hider with the smallest error is within the slack");
    };
    let slowest = scored
        .iter()
        .filter(|(_, e)| *e <= best * AA_ERROR_SLACK)
        .max_by(|a, b| a.0.time_ms.total_cmp(&b.0.time_ms))
        .map(|(a, _)| *a);
    let against = match slowest {
        Some(s) if s.hider != pick.hider => format!(
            ", {} of the time of `{}` at that accuracy",
            fmt_pct(pick.time_ms / s.time_ms),
            s.hider
        ),
        _ => String::new(),
    };
    format!(
        "Anti-aliasing recommendation: `{}`, the fastest hider whose mean coverage error ({}) is within {} of the smallest measured ({}): {} ms per frame{against}.",
        pick.hider,
        fmt_error(*error),
        fmt_pct(AA_ERROR_SLACK - 1.0),
        fmt_error(best),
        fmt_ms(pick.time_ms)
    )
}

/// What the naive painter and linear z cost against what they save.
fn shortcut_sentence(rows: &[Row]) -> Option<String> {
    let mut parts = Vec::new();
    for (fast, exact) in [
        ("painter-naive", "painter"),
        ("zbuffer-linear-z", "zbuffer"),
    ] {
        let cases = common_cases(rows, REAL, &[fast, exact], false);
        let (Some(f), Some(e)) = (
            aggregate(rows, fast, &cases),
            aggregate(rows, exact, &cases),
        ) else {
            continue;
        };
        let hard = hard_case_wrong(rows, fast).map_or(String::new(), |(w, k, n)| {
            format!(" ({} on {k} of {n} hard cases)", fmt_count(w))
        });
        let saved = if f.time_ms <= e.time_ms {
            format!(
                "saves {} of `{exact}`'s time",
                fmt_pct(1.0 - f.time_ms / e.time_ms)
            )
        } else {
            format!(
                "saves no time (it takes {} longer than `{exact}`)",
                fmt_pct(f.time_ms / e.time_ms - 1.0)
            )
        };
        parts.push(format!(
            "`{fast}` {saved} and gets {} pixels wrong on {} of {} real-size scenes{hard}",
            fmt_count(f.wrong_ids + f.coverage_mismatches),
            f.wrong_cases,
            f.cases
        ));
    }
    (!parts.is_empty()).then(|| format!("Shortcuts: {}.", parts.join("; ")))
}

/// The smallest gap each depth format resolves everywhere at the smallest
/// near/far ratio, and the share it loses at the smallest gap.
fn precision_sentence(rows: &[Row]) -> Option<String> {
    let (gaps, ratios) = precision_axes(rows);
    let ratio = *ratios.last()?;
    let smallest = *gaps.last()?;
    let mut parts = Vec::new();
    for (hider, label) in FORMATS {
        let share = |g: f64| precision_row(rows, hider, g, ratio).and_then(farther_share);
        let Some(worst) = share(smallest) else {
            continue;
        };
        // Gaps run from large to small: the last one still resolved
        // everywhere before the first failure.
        let resolved = gaps
            .iter()
            .take_while(|&&g| share(g) == Some(0.0))
            .last()
            .map_or("none of the sweep".to_owned(), |g| format!("{g:.0e}"));
        parts.push(format!(
            "{label} down to {resolved} (at {smallest:.0e} the farther surface shows on {} of the pixels)",
            fmt_pct(worst)
        ));
    }
    (!parts.is_empty()).then(|| {
        format!(
            "Depth precision at near/far {ratio:.0e}, the smallest gap each format keeps the nearer surface everywhere: {}.",
            parts.join("; ")
        )
    })
}
