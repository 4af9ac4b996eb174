//! `hider analyze`: which effects a model calls for, with the evidence, and
//! what `--algo auto` would pick.

use anyhow::{Context, Result};
use clap::Args;
use hider::plan::RenderOptions;
use hider::plan::analyze::DEFAULT_PAIR_BUDGET;

/// Arguments of `hider analyze`.
#[derive(Args, Debug)]
pub struct AnalyzeArgs {
    /// OBJ file, or a generated scene (as for `hider render`).
    model: String,
    /// Square image size in pixels the analysis assumes (1 to 16384).
    #[arg(long, default_value_t = 512, value_parser = crate::args::side)]
    size: u32,
    /// Anti-aliasing will be asked for.
    #[arg(long)]
    aa: bool,
    /// The SVG that will be asked for (`--svg-mode` of `hider render`):
    /// `painter` asks for the painter's ordered polygons (the pair
    /// searches then decide the plan); `regions` and `lines` work from any
    /// hider's scene and change no plan.
    #[arg(long, value_enum)]
    svg_mode: Option<crate::render_args::SvgMode>,
    /// Only ids / false colours will be asked for (no shading).
    #[arg(long)]
    no_shading: bool,
    /// Most candidate pairs each pair search examines.
    #[arg(long, default_value_t = DEFAULT_PAIR_BUDGET, value_parser = crate::args::pair_budget)]
    pair_budget: u64,
}

/// Runs `hider analyze`: prints the effects report and the plan.
pub fn run(args: &AnalyzeArgs) -> Result<()> {
    hider::scene::view::check_image_size(args.size, args.size).context("bad image size")?;
    let progress = crate::progress::Progress::start("loading the model");
    let scene = crate::model::load(&args.model, &progress)?;
    progress.stage("analysing the scene");
    let options = RenderOptions::default()
        .with_size(args.size, args.size)
        .with_antialiasing(args.aa)
        .with_ordered_polygons(args.svg_mode == Some(crate::render_args::SvgMode::Painter))
        .with_shading(!args.no_shading)
        .with_pair_budget(args.pair_budget);
    let planned = hider::plan::auto(&scene, &options)
        .with_context(|| format!("cannot analyse {}", args.model))?;
    drop(progress);
    println!("{}: {}", args.model, planned.effects);
    println!("{}", planned.summary());
    Ok(())
}
