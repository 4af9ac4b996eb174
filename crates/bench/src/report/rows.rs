//! Picking rows out of the results: the hiders in matrix order, a hider's
//! kind, its finished accuracy rows, the accuracy cases, and the geometric
//! mean the summaries use for times.

use crate::record::Row;

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

/// The registry kind the rows record for `hider` (empty if it has none).
pub(super) fn kind_of(rows: &[Row], hider: &str) -> String {
    rows.iter()
        .find(|r| r.hider == hider)
        .map_or_else(String::new, |r| r.kind.clone())
}

/// What a registry kind means, for people: `exact, pixel centre` for
/// `ExactPixelCentre`.
pub fn kind_label(kind: &str) -> &str {
    match kind {
        "ExactPixelCentre" => "exact, pixel centre",
        "ApproximatePixelCentre" => "shortcut (approximate)",
        "MultiSample" => "anti-aliased (multi-sample)",
        "Reference" => "reference (oracle)",
        other => other,
    }
}

/// The finished rows of one hider in one study.
pub(super) fn study_rows<'a>(
    rows: &'a [Row],
    study: &'a str,
    hider: &'a str,
) -> impl Iterator<Item = &'a Row> + 'a {
    rows.iter()
        .filter(move |r| r.study == study && r.hider == hider && r.is_ok())
}

/// `(scene, width)` of a study's cases, in matrix order.
pub(super) fn study_cases(rows: &[Row], study: &str) -> Vec<(String, u32)> {
    let mut seen = Vec::new();
    for r in rows.iter().filter(|r| r.study == study) {
        let key = (r.scene.clone(), r.width);
        if !seen.contains(&key) {
            seen.push(key);
        }
    }
    seen
}

/// The row of `hider` on one case of a study.
pub(super) fn cell<'a>(
    rows: &'a [Row],
    study: &str,
    case: &(String, u32),
    hider: &str,
) -> Option<&'a Row> {
    rows.iter()
        .find(|r| r.study == study && r.scene == case.0 && r.width == case.1 && r.hider == hider)
}

/// Geometric mean of the positive values, `None` if there are none.
pub(super) fn geometric_mean(values: impl Iterator<Item = f64>) -> Option<f64> {
    let (sum, n) = values
        .filter(|v| *v > 0.0)
        .fold((0.0, 0u32), |(s, n), v| (s + v.ln(), n + 1));
    (n > 0).then(|| (sum / f64::from(n)).exp())
}

/// The finished accuracy-study rows of one hider.
pub(super) fn accuracy_rows<'a>(
    rows: &'a [Row],
    hider: &'a str,
) -> impl Iterator<Item = &'a Row> + 'a {
    rows.iter()
        .filter(move |r| r.study == "accuracy" && r.hider == hider && r.is_ok())
}

/// `(scene, width)` of the accuracy cases, in matrix order.
pub(super) fn accuracy_cases(rows: &[Row]) -> Vec<(String, u32)> {
    study_cases(rows, "accuracy")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn means_skip_non_positive_values() {
        let m = geometric_mean([1.0, 4.0, 0.0, -2.0].into_iter()).unwrap();
        assert!((m - 2.0).abs() < 1e-12);
        assert_eq!(geometric_mean(std::iter::empty()), None);
    }
}
