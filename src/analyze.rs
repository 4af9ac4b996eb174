//! `hider analyze`: which effects a model calls for, with the evidence, and
//! what `--algo auto` would pick.
//!
//! It takes every flag of `hider render` that changes the plan (the image
//! size, the camera, `--precision`, `--shade`, `--aa`, `--svg-mode`,
//! `--threads`) and builds the analysis's options the way `render`'s
//! `--algo auto` does, so that both print the same plan line.

use anyhow::{Context, Result};
use clap::Args;
use hider::plan::RenderOptions;
use hider::plan::analyze::DEFAULT_PAIR_BUDGET;
use hider::scene::{ShadeMode, View};

use crate::camera_args::{PrecisionArg, ShadeArg, ViewArgs};
use crate::render_args::SvgMode;

/// Arguments of `hider analyze`.
#[derive(Args, Debug)]
pub struct AnalyzeArgs {
    /// OBJ file, or a generated scene (as for `hider render`).
    model: String,
    /// The image size and camera, as for `hider render`.
    #[command(flatten)]
    view: ViewArgs,
    /// Anti-aliasing will be asked for.
    #[arg(long)]
    aa: bool,
    /// The SVG that will be asked for (`--svg-mode` of `hider render`):
    /// `painter` asks for the painter's ordered polygons (the pair
    /// searches then decide the plan); `regions` and `lines` work from any
    /// hider's scene and change no plan.
    #[arg(long, value_enum)]
    svg_mode: Option<SvgMode>,
    /// How the image will be coloured (`ids`: no shading, so no lighting).
    #[arg(long, value_enum, default_value = "lambert")]
    shade: ShadeArg,
    /// Only ids / false colours will be asked for (the same as `--shade
    /// ids`).
    #[arg(long, conflicts_with = "shade")]
    no_shading: bool,
    /// Transform arithmetic of the front end (f32 reproduces GL).
    #[arg(long, value_enum, default_value = "f64")]
    precision: PrecisionArg,
    /// Worker threads: above 1 the front end prepares large scenes in
    /// parallel.
    #[arg(long, default_value_t = 1, value_parser = crate::args::threads)]
    threads: usize,
    /// Most candidate pairs each pair search examines.
    #[arg(long, default_value_t = DEFAULT_PAIR_BUDGET, value_parser = crate::args::pair_budget)]
    pair_budget: u64,
}

impl AnalyzeArgs {
    /// The shade mode asked for.
    fn shade_mode(&self) -> ShadeMode {
        if self.no_shading {
            ShadeMode::Ids
        } else {
            self.shade.mode()
        }
    }
}

/// Runs `hider analyze`: prints the effects report and the plan.
pub fn run(args: &AnalyzeArgs) -> Result<()> {
    let (width, height) = args.view.image_size()?;
    if args.threads > 1 {
        rayon::ThreadPoolBuilder::new()
            .num_threads(args.threads)
            .build_global()
            .context("cannot start the thread pool")?;
    }
    let progress = crate::progress::Progress::start("loading the model");
    let scene = crate::model::load(&args.model, &progress)?;
    progress.stage("analysing the scene");
    // As `hider render --algo auto` builds its options: the view first
    // (the camera checked), then the request.
    let view = View::new(args.view.camera(&scene), width, height)?;
    let options = RenderOptions::default()
        .with_size(width, height)
        .with_camera(Some(view.camera))
        .with_shading(args.shade_mode() == ShadeMode::Lambert)
        .with_antialiasing(args.aa)
        .with_ordered_polygons(args.svg_mode == Some(SvgMode::Painter))
        .with_prepare(args.precision.prepare_options(args.threads))
        .with_pair_budget(args.pair_budget);
    let planned = hider::plan::auto(&scene, &options)
        .with_context(|| format!("cannot analyse {}", args.model))?;
    drop(progress);
    crate::progress::print_line(&format!("{}: {}", args.model, planned.effects))?;
    crate::progress::print_line(&planned.summary())?;
    Ok(())
}
