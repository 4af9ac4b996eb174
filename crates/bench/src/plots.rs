//! Plots with plotters, each written as SVG and PNG with the same text:
//! time against error per scene with the Pareto front, and time against
//! triangle count, resolution and depth complexity.
//!
//! The bitmap backend draws text only through a font feature; the crate
//! enables plotters' `ab_glyph` and registers the DejaVu Sans subset in
//! `fonts/` (its licence beside it), so the PNGs carry the titles, axis
//! titles, ticks and legend the SVGs do. The legend sits in a column of its
//! own right of the data, and values of exactly 0 (no error), which a
//! logarithmic axis cannot show, are drawn in a labelled band under the
//! axis's smallest value instead of at a silent floor.

use std::path::{Path, PathBuf};
use std::sync::Once;

use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{FontStyle, register_font};

use crate::matrix::Study;
use crate::record::Row;
use crate::scaling::{axis_label, series};

/// Size of every plot, pixels.
pub const SIZE: (u32, u32) = (900, 540);
/// Width of the legend column right of the data, pixels.
const LEGEND_WIDTH: u32 = 200;
/// Height of the title strip, pixels.
pub const TITLE_HEIGHT: u32 = 40;
/// Height of the x-axis strip (ticks and axis title), pixels.
pub const X_AXIS_HEIGHT: u32 = 56;
/// Width of the y-axis strip (ticks and axis title), pixels.
pub const Y_AXIS_WIDTH: u32 = 84;
/// The font every plot uses (registered as `sans-serif`).
const FONT: &str = "sans-serif";
/// The Pareto front: a thin dark-grey line under the points, thin enough
/// that the points it joins stay readable where it passes through them.
const FRONT_COLOUR: RGBColor = RGBColor(90, 90, 90);
/// DejaVu Sans, printable ASCII and a few symbols (see `fonts/LICENSE`).
static FONT_BYTES: &[u8] = include_bytes!("../fonts/DejaVuSans-subset.ttf");

/// Registers the bundled font with plotters, once per process.
fn register_the_font() -> Result<()> {
    static ONCE: Once = Once::new();
    let mut ok = true;
    ONCE.call_once(|| ok = register_font(FONT, FontStyle::Normal, FONT_BYTES).is_ok());
    if ok {
        Ok(())
    } else {
        Err(anyhow!("the bundled plot font could not be read"))
    }
}

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
    /// Title.
    pub title: String,
    /// X axis title, with its unit.
    pub x_label: String,
    /// Y axis title, with its unit.
    pub y_label: String,
    /// The data; `y` may be 0 (drawn in the zero band).
    pub series: Vec<Series>,
    /// A polyline drawn under the points (the Pareto front).
    pub front: Vec<(f64, f64)>,
    /// The label of the band under the y axis where values of exactly 0
    /// are drawn (`"0 wrong"`); the band is drawn only when some value is
    /// 0.
    pub zero_label: String,
}

/// `(lo, hi)` of the positive finite values, widened to whole decades so
/// that every axis shows at least two labelled powers of ten; `None`
/// without such values.
fn range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .filter(|v| *v > 0.0 && v.is_finite())
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return None;
    }
    // A little room so that points do not sit on the frame; out to the
    // enclosing decades when fewer than two powers of ten would show.
    let (mut a, mut b) = (lo.log10() - 0.12, hi.log10() + 0.12);
    if b.floor() - a.ceil() < 1.0 {
        a = a.floor();
        b = b.max(a + 1.0);
    }
    Some((10f64.powf(a), 10f64.powf(b)))
}

/// A tick label people read at a glance: `0.5`, `20`, `1k`, `10k`, `1M`,
/// `1e-4`.
pub fn tick_label(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        return "0".into();
    }
    if !(1e-3..1e9).contains(&a) {
        return format!("{v:.0e}");
    }
    let (value, suffix) = if a >= 1e6 {
        (v / 1e6, "M")
    } else if a >= 1e3 {
        (v / 1e3, "k")
    } else {
        (v, "")
    };
    // Three significant digits, trailing zeros dropped.
    let digits = (2 - value.abs().log10().floor() as i32).clamp(0, 6) as usize;
    let mut text = format!("{value:.digits$}");
    if text.contains('.') {
        text = text.trim_end_matches('0').trim_end_matches('.').to_owned();
    }
    format!("{text}{suffix}")
}

/// The y range, with room for the zero band when some value is 0: `(axis
/// from, axis to, where zeros are drawn, band top)`.
fn y_layout(plot: &Plot, has_zero: bool) -> (f64, f64, f64, f64) {
    let ys = plot
        .series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1));
    let (lo, hi) = range(ys.chain(plot.front.iter().map(|p| p.1))).unwrap_or((1e-3, 1.0));
    if has_zero {
        // The band spans a factor of 4 under the smallest decade.
        (lo / 4.0, hi, lo / 2.0, lo / 1.19)
    } else {
        (lo, hi, lo, lo)
    }
}

fn draw<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, plot: &Plot) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(e)?;
    let (chart_area, legend_area) = root.split_horizontally(SIZE.0 - LEGEND_WIDTH);
    let xs = plot
        .series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.0));
    let (x0, x1) = range(xs.chain(plot.front.iter().map(|p| p.0))).unwrap_or((0.1, 10.0));
    let has_zero = plot
        .series
        .iter()
        .any(|s| s.points.iter().any(|p| p.1 == 0.0));
    let (y0, y1, zero_y, band_top) = y_layout(plot, has_zero);
    let at = |p: (f64, f64)| (p.0, if p.1 > 0.0 { p.1 } else { zero_y });
    let mut chart = ChartBuilder::on(&chart_area)
        .margin(10)
        .caption(&plot.title, (FONT, 22))
        .x_label_area_size(X_AXIS_HEIGHT - 10)
        .y_label_area_size(Y_AXIS_WIDTH - 10)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
        .map_err(e)?;
    chart
        .configure_mesh()
        .light_line_style(RGBColor(242, 242, 242))
        .bold_line_style(RGBColor(215, 215, 215))
        .x_labels(8)
        .y_labels(8)
        .x_desc(&plot.x_label)
        .y_desc(&plot.y_label)
        .label_style((FONT, 14))
        .axis_desc_style((FONT, 16))
        .x_label_formatter(&|v| tick_label(*v))
        // No tick labels inside the zero band: its label says what it is.
        .y_label_formatter(&|v| {
            if *v < band_top {
                String::new()
            } else {
                tick_label(*v)
            }
        })
        .draw()
        .map_err(e)?;
    if has_zero {
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(x0, y0), (x1, band_top)],
                RGBColor(225, 240, 225).filled(),
            )))
            .map_err(e)?;
        chart
            .draw_series(std::iter::once(Text::new(
                plot.zero_label.clone(),
                // At the right end and under the zero line: the fast
                // exact results (and the Pareto front through them) sit
                // at the left, and lines reach down only to the zero line.
                (x1 / (x1 / x0).powf(0.01), y0 * (zero_y / y0).powf(0.1)),
                (FONT, 14)
                    .into_font()
                    .color(&RGBColor(40, 110, 40))
                    .pos(Pos::new(HPos::Right, VPos::Bottom)),
            )))
            .map_err(e)?;
    }
    if plot.front.len() > 1 {
        chart
            .draw_series(LineSeries::new(
                plot.front.iter().map(|&p| at(p)),
                FRONT_COLOUR.stroke_width(2),
            ))
            .map_err(e)?;
    }
    for (k, s) in plot.series.iter().enumerate() {
        let c = colour(s.colour);
        // In plots of a few lines, earlier lines are drawn wider, so a
        // later one lying on top of another leaves it showing as a rim
        // instead of hiding it (with many lines the rims would crowd).
        let wider = if s.line && plot.series.len() <= 6 {
            (plot.series.len() - 1 - k).min(4) as u32
        } else {
            0
        };
        if s.line && s.points.len() > 1 {
            chart
                .draw_series(LineSeries::new(
                    s.points.iter().map(|&p| at(p)),
                    c.stroke_width(2 + wider),
                ))
                .map_err(e)?;
        }
        chart
            .draw_series(
                s.points
                    .iter()
                    .map(|&p| Circle::new(at(p), 4 + wider, c.filled())),
            )
            .map_err(e)?;
    }
    draw_legend(&legend_area, plot).map_err(e)?;
    root.present().map_err(e)?;
    Ok(())
}

/// The legend, in its own column: one line per series, then the front.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    plot: &Plot,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let style = (FONT, 14).into_font().color(&BLACK);
    let mut y = TITLE_HEIGHT as i32 + 10;
    let step = (((SIZE.1 - TITLE_HEIGHT - 20) / (plot.series.len() as u32 + 1).max(1)) as i32)
        .clamp(12, 22);
    for s in &plot.series {
        area.draw(&Circle::new((14, y), 5, colour(s.colour).filled()))?;
        area.draw(&Text::new(s.name.clone(), (26, y - 8), style.clone()))?;
        y += step;
    }
    if plot.front.len() > 1 {
        let grey = FRONT_COLOUR.stroke_width(2);
        area.draw(&PathElement::new(vec![(6, y), (22, y)], grey))?;
        area.draw(&Text::new("Pareto front", (26, y - 8), style))?;
    }
    Ok(())
}

/// Writes `DIR/STEM.svg` and `DIR/STEM.png`, atomically.
pub fn write_plot(dir: &Path, stem: &str, plot: &Plot) -> Result<Vec<PathBuf>> {
    register_the_font()?;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        draw(&root, plot).map_err(|e| anyhow!("plot {stem}: {e}"))?;
    }
    let svg_path = dir.join(format!("{stem}.svg"));
    crate::record::write_text_atomic(&svg_path, &svg)?;
    let mut rgb = vec![0u8; (SIZE.0 * SIZE.1 * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, SIZE).into_drawing_area();
        draw(&root, plot).map_err(|e| anyhow!("plot {stem}: {e}"))?;
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
        let p = (r.render_ms.max(1e-4), err);
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
        y_label: ERROR_AXIS.into(),
        front: pareto_front(&pts),
        series,
        zero_label: "0 wrong, exact".into(),
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
        title: format!("Render time against {}", axis_label(study)),
        x_label: axis_title(study).into(),
        y_label: "render time, ms (median)".into(),
        series,
        front: Vec::new(),
        zero_label: String::new(),
    }
}

/// The y axis title of plots mixing both kinds of error.
pub const ERROR_AXIS: &str = "error: wrong-pixel share, or mean coverage error";

/// A scaling study's x axis title, with its unit.
fn axis_title(study: Study) -> &'static str {
    match study {
        Study::Polygons => "triangles after clipping (count)",
        Study::Resolution => "image size (pixels)",
        Study::DepthComplexity => "depth complexity (surfaces per covered pixel)",
        _ => axis_label(study),
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
    fn ticks_read_as_numbers_people_write() {
        let got: Vec<String> = [
            1e-6, 1e-4, 0.001, 0.05, 0.5, 2.0, 20.0, 100.0, 1e3, 1e4, 2.5e5, 1e6, 1e10,
        ]
        .iter()
        .map(|v| tick_label(*v))
        .collect();
        assert_eq!(
            got,
            [
                "1e-6", "1e-4", "0.001", "0.05", "0.5", "2", "20", "100", "1k", "10k", "250k",
                "1M", "1e10"
            ]
        );
        assert_eq!(tick_label(0.0), "0");
    }

    /// Dark pixels (text or marks) in a rectangle of the image.
    fn dark_pixels(img: &image::RgbImage, x: (u32, u32), y: (u32, u32)) -> usize {
        (y.0..y.1)
            .flat_map(|py| (x.0..x.1).map(move |px| (px, py)))
            .filter(|&(px, py)| img.get_pixel(px, py).0.iter().all(|&c| c < 110))
            .count()
    }

    #[test]
    fn the_png_carries_title_axis_titles_ticks_and_legend() {
        let dir = std::env::temp_dir().join(format!("hider-bench-plots-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let plot = Plot {
            title: "Time against error".into(),
            x_label: "render time, ms".into(),
            y_label: "error".into(),
            series: vec![Series {
                name: "zbuffer".into(),
                colour: 0,
                points: vec![(1.0, 2.0), (10.0, 30.0), (100.0, 0.0)],
                line: true,
            }],
            front: vec![(1.0, 2.0), (100.0, 0.0)],
            zero_label: "0 wrong".into(),
        };
        let files = write_plot(&dir, "bench-test", &plot).unwrap();
        let svg = std::fs::read_to_string(&files[0]).unwrap();
        assert!(svg.contains("<svg") && svg.contains("render time, ms") && svg.contains("zbuffer"));
        assert!(svg.contains("0 wrong"), "the zero band is labelled");
        let png = image::open(&files[1]).unwrap().to_rgb8();
        assert_eq!((png.width(), png.height()), SIZE);
        let (w, h) = SIZE;
        let chart_w = w - LEGEND_WIDTH;
        // Title strip: text only (no axis or data is drawn there).
        assert!(
            dark_pixels(&png, (0, chart_w), (0, TITLE_HEIGHT - 8)) > 50,
            "title"
        );
        // The y axis title, rotated, in the leftmost column.
        assert!(
            dark_pixels(&png, (0, 30), (TITLE_HEIGHT, h - X_AXIS_HEIGHT)) > 20,
            "y title"
        );
        // The x axis title, under the tick labels.
        assert!(
            dark_pixels(&png, (Y_AXIS_WIDTH, chart_w), (h - 28, h)) > 30,
            "x title"
        );
        // Tick labels, between the axis line and the axis title.
        assert!(
            dark_pixels(
                &png,
                (Y_AXIS_WIDTH, chart_w),
                (h - X_AXIS_HEIGHT + 6, h - 30)
            ) > 30
        );
        // The legend column holds the series name.
        assert!(dark_pixels(&png, (chart_w + 20, w), (TITLE_HEIGHT, TITLE_HEIGHT + 30)) > 20);
        // An empty plot still draws (a frame without points).
        write_plot(&dir, "bench-empty", &Plot::default()).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
