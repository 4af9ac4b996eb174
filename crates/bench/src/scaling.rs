//! The scaling study of Sutherland, Sproull & Schumacker (1974): how each
//! hider's time grows with the number of polygons, the resolution and the
//! depth complexity, summarised by the exponent `b` of a power law
//! `time ~ a x^b` fitted by least squares on log-log axes.
//!
//! `b` near 1 is linear growth; a depth buffer should show about 1 in
//! pixels and in depth complexity, and sublinear growth in polygon count
//! while per-pixel work dominates; a list-priority (sorting) algorithm
//! grows faster than linearly in polygons.

use crate::matrix::Study;
use crate::record::Row;

/// The quantity a scaling study varies, read from a row.
pub fn axis(study: Study, row: &Row) -> Option<f64> {
    match study {
        Study::Accuracy | Study::RealSize | Study::DepthPrecision => None,
        Study::Polygons => Some(row.triangles as f64),
        Study::Resolution => Some(f64::from(row.width) * f64::from(row.height)),
        Study::DepthComplexity => Some(row.depth_complexity),
    }
}

/// Axis label for tables and plots.
pub fn axis_label(study: Study) -> &'static str {
    match study {
        Study::Accuracy | Study::RealSize | Study::DepthPrecision => "",
        Study::Polygons => "triangles",
        Study::Resolution => "pixels",
        Study::DepthComplexity => "depth complexity",
    }
}

/// A fitted power law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PowerLaw {
    /// The growth exponent `b`.
    pub exponent: f64,
    /// The factor `a`.
    pub factor: f64,
    /// Points the fit used.
    pub points: usize,
}

/// Least-squares fit of `ln y = ln a + b ln x` over the points with
/// positive coordinates; `None` with fewer than two distinct `x`.
pub fn fit_power_law(points: &[(f64, f64)]) -> Option<PowerLaw> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = logs.len() as f64;
    if logs.len() < 2 {
        return None;
    }
    let mx = logs.iter().map(|p| p.0).sum::<f64>() / n;
    let my = logs.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx).powi(2)).sum();
    if sxx <= 1e-12 {
        return None;
    }
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let b = sxy / sxx;
    Some(PowerLaw {
        exponent: b,
        factor: (my - b * mx).exp(),
        points: logs.len(),
    })
}

/// `(axis value, median render ms)` of the finished rows of one hider in
/// one study, sorted by axis value.
pub fn series(rows: &[Row], study: Study, hider: &str) -> Vec<(f64, f64)> {
    let mut pts: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.is_ok() && r.study == study.as_str() && r.hider == hider)
        .filter_map(|r| Some((axis(study, r)?, r.render_ms)))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_power_laws_are_recovered() {
        let pts: Vec<(f64, f64)> = [1.0, 2.0, 4.0, 8.0]
            .iter()
            .map(|&x: &f64| (x, 3.0 * x.powf(1.5)))
            .collect();
        let f = fit_power_law(&pts).unwrap();
        assert!((f.exponent - 1.5).abs() < 1e-12);
        assert!((f.factor - 3.0).abs() < 1e-9);
        assert_eq!(f.points, 4);
        assert!(fit_power_law(&[(1.0, 1.0)]).is_none());
        assert!(fit_power_law(&[(2.0, 1.0), (2.0, 3.0)]).is_none());
        assert!(fit_power_law(&[(0.0, 1.0), (-1.0, 3.0), (2.0, 0.0)]).is_none());
    }

    #[test]
    fn series_reads_the_study_axis() {
        let row = |w: u32, ms: f64| Row {
            study: "resolution".into(),
            hider: "h".into(),
            status: "ok".into(),
            width: w,
            height: w,
            render_ms: ms,
            ..Row::default()
        };
        let rows = vec![
            row(20, 4.0),
            row(10, 1.0),
            Row {
                status: "error: x".into(),
                ..row(30, 9.0)
            },
        ];
        assert_eq!(
            series(&rows, Study::Resolution, "h"),
            [(100.0, 1.0), (400.0, 4.0)]
        );
        assert!(series(&rows, Study::Polygons, "h").is_empty());
    }
}
