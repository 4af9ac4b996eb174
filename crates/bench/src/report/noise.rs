//! Repeat noise and the report's tie threshold for times: how far apart
//! the measured renders of one job lie, and the relative difference under
//! which the report calls two times the same.

use crate::record::Row;

/// Two times closer than this (relative to the smaller) are the same speed
/// in the report's sentences: the machines these runs are made on are
/// shared, and a few percent is what repeating a whole run moves a median
/// by. The report prints the run's own spread beside it
/// ([`noise_sentence`]) so a reader can check that the noise is below it.
pub(super) const TIME_TIE: f64 = 0.05;

/// The median over the finished rows with at least two measured renders of
/// their relative spread, (slowest - fastest) / median; `None` without
/// such rows.
pub(super) fn median_spread(rows: &[Row]) -> Option<f64> {
    let mut spreads: Vec<f64> = rows
        .iter()
        .filter(|r| r.is_ok() && r.runs >= 2 && r.render_ms > 0.0)
        .map(|r| (r.render_max_ms - r.render_min_ms) / r.render_ms)
        .collect();
    if spreads.is_empty() {
        return None;
    }
    spreads.sort_by(f64::total_cmp);
    Some(spreads[spreads.len() / 2])
}

/// The method line on noise: the run's median spread and the threshold.
pub(super) fn noise_sentence(rows: &[Row]) -> String {
    let threshold = format!(
        "the report calls two times the same speed when they differ by less than {:.0}%",
        TIME_TIE * 100.0
    );
    match median_spread(rows) {
        Some(spread) => format!(
            "repeat noise: the measured renders of a job lie {:.1}% apart (slowest minus fastest over the median, the median over the jobs); {threshold}",
            spread * 100.0
        ),
        None => format!("repeat noise: not measured (one render per job); {threshold}"),
    }
}

/// Whether `a` and `b` are the same speed under [`TIME_TIE`].
pub(super) fn same_speed(a: f64, b: f64) -> bool {
    let (lo, hi) = if a < b { (a, b) } else { (b, a) };
    lo > 0.0 && hi / lo - 1.0 < TIME_TIE
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_is_the_median_of_the_rows_relative_ranges() {
        let row = |min: f64, median: f64, max: f64| Row {
            status: "ok".into(),
            runs: 3,
            render_min_ms: min,
            render_ms: median,
            render_max_ms: max,
            ..Row::default()
        };
        let rows = [row(9.0, 10.0, 11.0), row(1.0, 1.0, 1.0), row(1.0, 2.0, 5.0)];
        assert!((median_spread(&rows).unwrap() - 0.2).abs() < 1e-12);
        assert!(noise_sentence(&rows).contains("20.0% apart"));
        assert_eq!(median_spread(&[]), None);
        assert!(same_speed(1.0, 1.04) && !same_speed(1.0, 1.06) && !same_speed(0.0, 0.0));
    }
}
