//! The arguments of `hider render` and what they mean to the library: the
//! image size, the camera, the front end's options, the knobs for the
//! hider and the shading.

use std::path::PathBuf;
use std::sync::OnceLock;
use std::time::Duration;

use anyhow::{Result, bail};

use clap::{Args, ValueEnum};
use hider::abuffer::OverflowPolicy;
use hider::geom::Camera;
use hider::plan::HiderConfig;
use hider::scene::{Cancel, PrepareOptions, Scene, ShadeMode};
use hider::zbuffer::{DepthFormat, DepthSource};

use crate::args;
use crate::camera_args::{PrecisionArg, ShadeArg, ViewArgs};

/// Arguments of `hider render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// OBJ file, or a generated scene: gen:cube, gen:sphere[:N],
    /// gen:soup[:COUNT[:SEED]], gen:intersecting, gen:cyclic, gen:coplanar.
    pub model: String,
    /// Output PNG.
    #[arg(short, long)]
    pub output: PathBuf,
    /// The image size and the camera (shared with `hider analyze`).
    #[command(flatten)]
    view: ViewArgs,
    /// Hidden-surface algorithm (see `hider list`), or `auto`: the planner
    /// picks the cheapest one exact for what the scene calls for (and for
    /// --aa and --svg-mode painter) and says why.
    #[arg(long, default_value = "auto")]
    pub algo: String,
    /// Ask for anti-aliased edges: `--algo auto` picks the cheapest exact
    /// anti-aliasing hider.
    #[arg(long)]
    pub aa: bool,
    /// Depth buffer format of the z-buffer.
    #[arg(long, value_enum)]
    depth_format: Option<DepthFormatArg>,
    /// What the z-buffer compares.
    #[arg(long, value_enum)]
    depth_source: Option<DepthSourceArg>,
    /// Transform arithmetic of the front end (f32 reproduces GL).
    #[arg(long, value_enum, default_value = "f64")]
    precision: PrecisionArg,
    /// Also write an SVG: the exact visible regions by default (see
    /// --svg-mode).
    #[arg(long)]
    pub svg: Option<PathBuf>,
    /// What --svg writes: `regions` (every surface's exact visible region,
    /// one path per flat face), `lines` (the visible silhouettes, creases,
    /// boundaries and intersection lines as polylines), both from any
    /// hider's scene, or `painter` (the painters' ordered, split polygon
    /// list: --algo painter or painter-naive; --algo auto then picks one).
    #[arg(long, value_enum, default_value = "regions")]
    pub svg_mode: SvgMode,
    /// --svg-mode lines: dihedral angle in degrees (0 to 180) above which
    /// a shared edge is drawn as a crease.
    #[arg(long, value_parser = vector_flags::degrees, default_value_t = 30.0)]
    pub crease_angle: f64,
    /// --svg-mode lines: line width, in pixels (`1`, `1px`) or millimetres
    /// (`0.3mm`: on the --page-size page, else at 96 pixels per inch).
    #[arg(long, value_parser = vector_flags::length, default_value = "1")]
    pub stroke_width: vector_flags::Length,
    /// --svg-mode regions and lines: the page the drawing is fitted to,
    /// centred: A3, A4, A5, Letter, or WIDTHxHEIGHT in millimetres
    /// (`200x150`); the SVG's width and height are then in mm.
    #[arg(long, value_parser = vector_flags::page)]
    pub page_size: Option<(f64, f64)>,
    /// --svg-mode lines: `none` leaves hidden lines out, `dashed` draws
    /// them dashed and grey, in layers of their own.
    #[arg(long, value_enum, default_value = "none")]
    pub hidden: HiddenArg,
    /// --svg-mode regions and lines: `none` (nothing behind the drawing)
    /// or an SVG colour (`white`, `#203040`) for a background rectangle.
    #[arg(long, default_value = "none", value_parser = vector_flags::colour)]
    pub background: String,
    /// --svg-mode regions: `on` strokes each region in its own colour
    /// (clipped to the covered set) so anti-aliasing viewers show no
    /// seams between regions; `off` writes the bare exact regions.
    #[arg(long, value_enum, default_value = "on")]
    pub seams: SeamsArg,
    /// Write the visible primitive ids (int32 LE, -1 background).
    #[arg(long)]
    pub ids_out: Option<PathBuf>,
    /// Write the window depth (float32 LE, 1.0 background).
    #[arg(long)]
    pub depth_out: Option<PathBuf>,
    /// How to colour the image.
    #[arg(long, value_enum, default_value = "lambert")]
    shade: ShadeArg,
    /// Worker threads: the tiled z-buffer renders tiles in parallel, and
    /// above 1 the front end prepares large scenes in parallel too.
    #[arg(long, default_value_t = 1, value_parser = args::threads)]
    pub threads: usize,
    /// Most bytes of decoded texture the process may hold (default 1G,
    /// suffixes K, M, G): a texture that would pass it is drawn in its
    /// material's colour, with a warning naming file, size and limit.
    #[arg(long, value_parser = args::bytes)]
    pub texture_budget: Option<u64>,
    /// The painter's split budget: exactly this many splits (default: an
    /// automatic budget that grows with the triangles).
    #[arg(long, value_parser = clap::value_parser!(u64).range(0..))]
    pub max_splits: Option<u64>,
    /// The A-buffers' bound on one pixel's fragment list (default 128).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
    pub max_list_len: Option<u32>,
    /// What the A-buffers do with a full fragment list: `drop-farthest`
    /// (the default: drop the farthest fragment, counted in a warning) or
    /// `error` (fail the frame naming the pixel).
    #[arg(long, value_enum)]
    pub overflow: Option<OverflowArg>,
    /// --svg-mode regions and lines: most overlapping triangle pairs the
    /// exact geometry may examine (default 50,000,000).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    pub max_pairs: Option<u64>,
    /// Stop after this many seconds (the analysis, the front end, the
    /// hider and the vector output; counted from the first of them), with
    /// a one-line error.
    #[arg(long, value_parser = args::seconds)]
    pub timeout: Option<f64>,
    /// --svg-mode regions: most polygon vertices the exact regions may
    /// send into their map-wide passes (default 4,000,000).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..))]
    pub max_region_points: Option<u64>,
    /// Render K times after a warm-up and print the median and minimum
    /// milliseconds of prepare + clear + rasterise.
    #[arg(long, default_value_t = 0, value_parser = args::repeat)]
    pub repeat: u32,
}

impl RenderArgs {
    /// The token `--timeout` sets: one for the process, its deadline
    /// counted from the first call (never cancelled without the flag).
    pub fn cancel(&self) -> Cancel {
        static TOKEN: OnceLock<Cancel> = OnceLock::new();
        match self.timeout {
            Some(seconds) => {
                *TOKEN.get_or_init(|| Cancel::new().with_timeout(Duration::from_secs_f64(seconds)))
            }
            None => Cancel::default(),
        }
    }
}

/// `--depth-format`.
#[derive(Clone, Copy, Debug, ValueEnum)]
enum DepthFormatArg {
    F32,
    F64,
    Fixed24,
    Fixed16,
    ReversedF32,
}

/// `--depth-source`.
#[derive(Clone, Copy, Debug, ValueEnum)]
enum DepthSourceArg {
    WindowZ,
    LinearViewZ,
}

/// `--overflow`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum OverflowArg {
    /// Drop the farthest fragment of a full list (counted in a warning).
    DropFarthest,
    /// Fail the frame, naming the pixel.
    Error,
}

/// `--svg-mode`: what the SVG holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SvgMode {
    /// The painter's ordered polygon list (its hidden parts painted over).
    Painter,
    /// The exact visible regions, one path per face group.
    Regions,
    /// The visible lines as polylines.
    Lines,
}

/// `--hidden`: what the lines SVG does with hidden lines.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum HiddenArg {
    /// Leave them out.
    None,
    /// Draw them dashed and grey.
    Dashed,
}

/// `--seams`: the regions' seam stroke.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum SeamsArg {
    /// Stroke each region in its colour, clipped to the covered set.
    On,
    /// The bare regions.
    Off,
}

/// The parsers of the vector output's flags.
pub mod vector_flags {
    /// A length in pixels or millimetres.
    #[derive(Clone, Copy, Debug, PartialEq)]
    pub enum Length {
        /// Pixels of the image.
        Pixels(f64),
        /// Millimetres on the page.
        Millimetres(f64),
    }

    fn positive(s: &str) -> Result<f64, String> {
        match s.trim().parse::<f64>() {
            Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
            _ => Err(format!("'{s}' is not a positive number")),
        }
    }

    /// `--stroke-width`: `1`, `1px` or `0.3mm`.
    pub fn length(s: &str) -> Result<Length, String> {
        if let Some(mm) = s.strip_suffix("mm") {
            positive(mm).map(Length::Millimetres)
        } else {
            positive(s.strip_suffix("px").unwrap_or(s)).map(Length::Pixels)
        }
    }

    /// `--crease-angle`: 0 to 180 degrees.
    pub fn degrees(s: &str) -> Result<f64, String> {
        match s.trim().parse::<f64>() {
            Ok(x) if (0.0..=180.0).contains(&x) => Ok(x),
            _ => Err(format!("'{s}' is not an angle from 0 to 180 degrees")),
        }
    }

    /// `--page-size`: a paper name or `WIDTHxHEIGHT` in millimetres.
    pub fn page(s: &str) -> Result<(f64, f64), String> {
        let named = match s.to_ascii_lowercase().as_str() {
            "a3" => Some((297.0, 420.0)),
            "a4" => Some((210.0, 297.0)),
            "a5" => Some((148.0, 210.0)),
            "letter" => Some((215.9, 279.4)),
            _ => None,
        };
        if let Some(size) = named {
            return Ok(size);
        }
        let body = s.strip_suffix("mm").unwrap_or(s);
        let (w, h) = body
            .split_once(['x', 'X'])
            .ok_or_else(|| format!("'{s}' is not A3, A4, A5, Letter or WIDTHxHEIGHT (mm)"))?;
        Ok((positive(w)?, positive(h)?))
    }

    /// `--background`: `none` or a colour name or `#rgb`/`#rrggbb`
    /// (letters, digits and `#` only: it is written into the SVG).
    pub fn colour(s: &str) -> Result<String, String> {
        let ok = !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '#');
        if ok {
            Ok(s.to_owned())
        } else {
            Err(format!("'{s}' is not none, a colour name or #rrggbb"))
        }
    }
}

impl RenderArgs {
    /// The image size, `--size` or `--width` and `--height` (512 x 512 by
    /// default), checked.
    pub fn image_size(&self) -> Result<(u32, u32)> {
        self.view.image_size()
    }

    /// Every output path with the flag that names it.
    pub fn outputs(&self) -> Vec<(&'static str, &std::path::Path)> {
        let mut outputs = vec![("-o", self.output.as_path())];
        for (flag, path) in [
            ("--ids-out", &self.ids_out),
            ("--depth-out", &self.depth_out),
            ("--svg", &self.svg),
        ] {
            if let Some(p) = path {
                outputs.push((flag, p.as_path()));
            }
        }
        outputs
    }

    /// Whether `--svg` asks for a painter's polygon list (`--svg-mode
    /// painter`); the other modes work from any hider's scene.
    pub fn painter_svg(&self) -> bool {
        self.svg.is_some() && self.svg_mode == SvgMode::Painter
    }

    /// The vector output's options from the flags (`--crease-angle`,
    /// `--stroke-width`, `--page-size`, `--hidden`, `--background`,
    /// `--seams`) for an image `width` x `height`.
    pub fn vector_options(&self, width: u32, height: u32) -> hider::vector::VectorOptions {
        let options = hider::vector::VectorOptions::default()
            .with_cancel(self.cancel())
            .with_crease_degrees(self.crease_angle)
            .with_page_mm(self.page_size)
            .with_dashed_hidden(self.hidden == HiddenArg::Dashed)
            .with_background((self.background != "none").then(|| self.background.clone()));
        let options = if self.seams == SeamsArg::Off {
            options.with_seam_stroke(0.0)
        } else {
            options
        };
        let options = match self.max_pairs {
            Some(pairs) => options.with_max_pairs(pairs),
            None => options,
        };
        let options = match self.max_region_points {
            Some(points) => options.with_max_region_points(points),
            None => options,
        };
        match self.stroke_width {
            vector_flags::Length::Pixels(px) => options.with_stroke_width(px),
            vector_flags::Length::Millimetres(mm) => options.with_stroke_mm(mm, width, height),
        }
    }

    /// Whether `--algo auto` asks the planner to choose.
    pub fn planned(&self) -> bool {
        self.algo == "auto"
    }

    /// Checks the requests to the planner: `--aa` needs `--algo auto` (a
    /// named hider does what it does), and `--svg-mode painter` needs
    /// `--svg` to write the ordered polygons to.
    pub fn check_requests(&self) -> Result<()> {
        if self.aa && !self.planned() {
            bail!(
                "--aa is a request to the planner (--algo auto), but --algo {} was named",
                self.algo
            );
        }
        if self.svg_mode == SvgMode::Painter && self.svg.is_none() {
            bail!("--svg-mode painter needs --svg FILE to write the ordered polygons to");
        }
        // Only the regions send polygon vertices into map-wide passes:
        // the lines and the painter's list build no regions, so the
        // budget would do nothing without a word.
        let other_mode = match self.svg_mode {
            SvgMode::Regions => None,
            SvgMode::Lines => Some("lines"),
            SvgMode::Painter => Some("painter"),
        };
        if let (Some(mode), Some(_)) = (other_mode, self.max_region_points) {
            bail!(
                "--max-region-points applies to --svg-mode regions only; --svg-mode {mode} \
                 builds no regions"
            );
        }
        // The vector flags shape the regions and lines drawings; the
        // painter's polygons are written as the painter orders them, so a
        // flag set for them would do nothing without a word.
        if self.svg_mode == SvgMode::Painter {
            let set = [
                ("--crease-angle", self.crease_angle != 30.0),
                (
                    "--stroke-width",
                    self.stroke_width != vector_flags::Length::Pixels(1.0),
                ),
                ("--page-size", self.page_size.is_some()),
                ("--hidden", self.hidden != HiddenArg::None),
                ("--background", self.background != "none"),
                ("--seams", self.seams != SeamsArg::On),
                ("--max-pairs", self.max_pairs.is_some()),
            ];
            if let Some((flag, _)) = set.iter().find(|(_, given)| *given) {
                bail!(
                    "{flag} applies to --svg-mode regions or lines; the painter's ordered \
                     polygons (--svg-mode painter) are written as they are"
                );
            }
        }
        Ok(())
    }

    /// The knobs for the hider: depth format and source, threads, ordered
    /// polygons, shade mode.
    pub fn hider_config(&self) -> HiderConfig {
        let mut config = HiderConfig::default()
            .with_cancel(self.cancel())
            .with_threads(self.threads)
            .with_ordered_polygons(self.painter_svg())
            .with_shade(self.shade_mode());
        if let Some(format) = self.depth_format {
            config = config.with_depth_format(match format {
                DepthFormatArg::F32 => DepthFormat::F32,
                DepthFormatArg::F64 => DepthFormat::F64,
                DepthFormatArg::Fixed24 => DepthFormat::Fixed24,
                DepthFormatArg::Fixed16 => DepthFormat::Fixed16,
                DepthFormatArg::ReversedF32 => DepthFormat::ReversedF32,
            });
        }
        if let Some(splits) = self.max_splits {
            config = config.with_max_splits(splits);
        }
        if let Some(len) = self.max_list_len {
            config = config.with_max_list_len(len);
        }
        if let Some(overflow) = self.overflow {
            config = config.with_overflow(match overflow {
                OverflowArg::DropFarthest => OverflowPolicy::DropFarthest,
                OverflowArg::Error => OverflowPolicy::Error,
            });
        }
        if let Some(source) = self.depth_source {
            config = config.with_depth_source(match source {
                DepthSourceArg::WindowZ => DepthSource::WindowZ,
                DepthSourceArg::LinearViewZ => DepthSource::LinearViewZ,
            });
        }
        config
    }

    /// The front end's options: `--precision` (`f32` is the GL-compatible
    /// front end, which also clips at the viewport's sides as llvmpipe
    /// does), parallel above one thread, and stopped by `--timeout`.
    pub fn prepare_options(&self) -> PrepareOptions {
        self.precision
            .prepare_options(self.threads)
            .with_cancel(self.cancel())
    }

    /// How to colour the image (`--shade`).
    pub fn shade_mode(&self) -> ShadeMode {
        self.shade.mode()
    }

    /// The camera: the scene's (or the fit camera) with the flags given
    /// applied.
    pub fn camera(&self, scene: &Scene) -> Camera {
        self.view.camera(scene)
    }
}
