//! Plots with plotters, each written as SVG (labelled) and PNG: time
//! against error per scene with the Pareto front, and time against
//! triangle count, resolution and depth complexity.
//!
//! Only the features in the workspace's plotters dependency are used. The
//! SVG backend writes text as `<text>` elements, but the bitmap backend
//! needs a font feature (ttf or ab_glyph, with font files) to draw text at
//! all, so the PNG versions carry the same marks and colours without any
//! text; the report shows the SVGs.

use std::path::{Path, PathBuf};

use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::matrix::Study;
use crate::record::Row;
use crate::scaling::{axis_label, series};

/// Errors of 0 are drawn at this value on the logarithmic error axis.
pub const ERROR_FLOOR: f64 = 1e-6;

const SIZE: (u32, u32) = (720, 480);

/// Twenty well-separated colours (Tableau 20, dark shades first); hider
/// `k` of the registry order gets colour `k mod 20` in every plot.
const PALETTE: [RGBColor; 20] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
    RGBColor(174, 199, 232),
    RGBColor(255, 187, 120),
    RGBColor(152, 223, 138),
    RGBColor(255, 152, 150),
    RGBColor(197, 176, 213),
    RGBColor(196, 156, 148),
    RGBColor(247, 182, 210),
    RGBColor(199, 199, 199),
    RGBColor(219, 219, 141),
    RGBColor(158, 218, 229),
];

/// The colour of the `k`-th hider.
pub fn colour(k: usize) -> RGBColor {
    PALETTE[k % PALETTE.len()]
}

/// One named set of points.
#[derive(Clone, Debug)]
pub struct Series {
    /// Legend name.
    pub name: String,
    /// Colour index (see [`colour`]).
    pub colour: usize,
    /// Points, `(x, y)`, both positive (log axes).
    pub points: Vec<(f64, f64)>,
    /// Join the points with a line.
    pub line: bool,
}

/// A log-log plot.
#[derive(Clone, Debug, Default)]
pub struct Plot {
    /// Title (SVG only).
    pub title: String,
    /// X axis description (SVG only).
    pub x_label: String,
    /// Y axis description (SVG only).
    pub y_label: String,
    /// The data.
    pub series: Vec<Series>,
    /// A polyline drawn under the points (the Pareto front).
    pub front: Vec<(f64, f64)>,
}

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| *v > 0.0 && v.is_finite())
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return (0.1, 10.0);
    }
    // Pad by a factor so points do not sit on the frame.
    let (lo, hi) = (lo / 1.6, hi * 1.6);
    if hi / lo < 10.0 {
        let mid = (lo * hi).sqrt();
        (mid / 3.2, mid * 3.2)
    } else {
        (lo, hi)
    }
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    plot: &Plot,
    text: bool,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let all = plot
        .series
        .iter()
        .flat_map(|s| s.points.iter())
        .chain(&plot.front);
    let (x0, x1) = range(all.clone().map(|p| p.0));
    let (y0, y1) = range(all.map(|p| p.1));
    let mut builder = ChartBuilder::on(root);
    builder.margin(12);
    if text {
        builder
            .caption(&plot.title, ("sans-serif", 20))
            .x_label_area_size(40)
            .y_label_area_size(64);
    }
    let mut chart = builder
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
        .map_err(e)?;
    let mut mesh = chart.configure_mesh();
    mesh.light_line_style(RGBColor(235, 235, 235));
    if text {
        mesh.x_desc(&plot.x_label)
            .y_desc(&plot.y_label)
            .x_label_formatter(&|v| format!("{v:.3}"))
            .y_label_formatter(&|v| format!("{v:.0e}"));
    } else {
        mesh.x_labels(0).y_labels(0);
    }
    mesh.draw().map_err(e)?;
    if plot.front.len() > 1 {
        chart
            .draw_series(LineSeries::new(
                plot.front.iter().copied(),
                RGBColor(160, 160, 160).stroke_width(6),
            ))
            .map_err(e)?;
    }
    for s in &plot.series {
        let c = colour(s.colour);
        if s.line && s.points.len() > 1 {
            chart
                .draw_series(LineSeries::new(s.points.iter().copied(), c.stroke_width(2)))
                .map_err(e)?;
        }
        let drawn = chart
            .draw_series(s.points.iter().map(|&p| Circle::new(p, 5, c.filled())))
            .map_err(e)?;
        if text {
            drawn
                .label(s.name.clone())
                .legend(move |(x, y)| Circle::new((x + 8, y), 5, c.filled()));
        }
    }
    if text && !plot.series.is_empty() {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperLeft)
            .draw()
            .map_err(e)?;
    }
    root.present().map_err(e)?;
    Ok(())
}

/// Writes `DIR/STEM.svg` and `DIR/STEM.png`, atomically.
pub fn write_plot(dir: &Path, stem: &str, plot: &Plot) -> Result<Vec<PathBuf>> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        draw(&root, plot, true).map_err(|e| anyhow!("plot {stem}: {e}"))?;
    }
    let svg_path = dir.join(format!("{stem}.svg"));
    crate::record::write_text_atomic(&svg_path, &svg)?;
    let mut rgb = vec![0u8; (SIZE.0 * SIZE.1 * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, SIZE).into_drawing_area();
        draw(&root, plot, false).map_err(|e| anyhow!("plot {stem}: {e}"))?;
    }
    let png_path = dir.join(format!("{stem}.png"));
    let img = image::RgbImage::from_raw(SIZE.0, SIZE.1, rgb)
        .ok_or_else(|| anyhow!("plot {stem}: buffer size"))?;
    hider_scene::atomic::write_atomic(&png_path, |out| {
        img.write_to(out, image::ImageFormat::Png)
            .map_err(|e| hider_scene::Error::Image {
                path: png_path.clone(),
                message: e.to_string(),
            })
    })?;
    Ok(vec![svg_path, png_path])
}

/// The points not dominated by any other (no other point is both at most
/// as slow and at most as wrong, and better in one): sorted by time.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut front: Vec<(f64, f64)> = Vec::new();
    for p in sorted {
        if front.last().is_none_or(|q| p.1 < q.1) {
            front.push(p);
        }
    }
    front
}

/// Time against error for the rows of one scene (one point per hider),
/// with the Pareto front. `hiders` gives the colour order.
pub fn pareto_plot(title: &str, rows: &[&Row], hiders: &[String]) -> Plot {
    let mut series = Vec::new();
    let mut pts = Vec::new();
    for r in rows {
        let (Some(err), true) = (r.error(), r.is_ok()) else {
            continue;
        };
        let p = (r.render_ms.max(1e-4), err.max(ERROR_FLOOR));
        pts.push(p);
        series.push(Series {
            name: r.hider.clone(),
            colour: hiders.iter().position(|h| *h == r.hider).unwrap_or(0),
            points: vec![p],
            line: false,
        });
    }
    Plot {
        title: title.to_owned(),
        x_label: "render time, ms (median)".into(),
        y_label: format!("error: wrong pixels / covered (0 drawn at {ERROR_FLOOR:.0e})"),
        front: pareto_front(&pts),
        series,
    }
}

/// Median render time against the study's axis, one line per hider.
pub fn scaling_plot(rows: &[Row], study: Study, hiders: &[String]) -> Plot {
    let series = hiders
        .iter()
        .enumerate()
        .map(|(k, h)| Series {
            name: h.clone(),
            colour: k,
            points: series(rows, study, h),
            line: true,
        })
        .filter(|s| !s.points.is_empty())
        .collect();
    Plot {
        title: format!("render time vs {}", axis_label(study)),
        x_label: axis_label(study).into(),
        y_label: "render time, ms (median)".into(),
        series,
        front: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pareto_front_keeps_only_undominated_points() {
        let pts = [
            (1.0, 0.5),
            (2.0, 0.1),
            (3.0, 0.2),
            (4.0, 0.0),
            (0.5, 0.9),
            (2.0, 0.3),
        ];
        assert_eq!(
            pareto_front(&pts),
            [(0.5, 0.9), (1.0, 0.5), (2.0, 0.1), (4.0, 0.0)]
        );
        assert!(pareto_front(&[]).is_empty());
    }

    #[test]
    fn plots_are_written_as_svg_with_text_and_png_without() {
        let dir = std::env::temp_dir().join(format!("hider-bench-plots-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let plot = Plot {
            title: "t".into(),
            x_label: "x axis".into(),
            y_label: "y".into(),
            series: vec![Series {
                name: "zbuffer".into(),
                colour: 0,
                points: vec![(1.0, 2.0), (10.0, 30.0)],
                line: true,
            }],
            front: vec![(1.0, 2.0)],
        };
        let files = write_plot(&dir, "bench-test", &plot).unwrap();
        let svg = std::fs::read_to_string(&files[0]).unwrap();
        assert!(svg.contains("<svg") && svg.contains("x axis") && svg.contains("zbuffer"));
        let png = image::open(&files[1]).unwrap();
        assert_eq!((png.width(), png.height()), SIZE);
        // An empty plot still draws (a frame without points).
        write_plot(&dir, "bench-empty", &Plot::default()).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
