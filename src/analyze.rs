//! `hider analyze`: which effects a model calls for, with the evidence, and
//! what `--algo auto` would pick; plus the auto choice for `hider render`.

use anyhow::{Context, Result, bail};
use clap::Args;
use hider::plan::{self, Plan};
use hider::scene::analyze::DEFAULT_PAIR_BUDGET;
use hider::scene::{Hider, RenderOptions, Scene, View};

/// Arguments of `hider analyze`.
#[derive(Args, Debug)]
pub struct AnalyzeArgs {
    /// OBJ file, or a generated scene (as for `hider render`).
    model: String,
    /// Square image size in pixels the analysis assumes.
    #[arg(long, default_value_t = 512)]
    size: u32,
    /// Anti-aliasing will be asked for.
    #[arg(long)]
    aa: bool,
    /// Vector output (SVG) will be asked for.
    #[arg(long)]
    vector: bool,
    /// Only ids / false colours will be asked for (no shading).
    #[arg(long)]
    no_shading: bool,
    /// Most candidate pairs each pair search examines.
    #[arg(long, default_value_t = DEFAULT_PAIR_BUDGET)]
    pair_budget: u64,
}

/// Runs `hider analyze`: prints the effects report and the plan.
pub fn run(args: &AnalyzeArgs) -> Result<()> {
    hider::scene::view::check_image_size(args.size, args.size).context("bad image size")?;
    let scene = crate::render::load_model(&args.model)?;
    let options = RenderOptions::default()
        .with_size(args.size, args.size)
        .with_antialiasing(args.aa)
        .with_vector_output(args.vector)
        .with_shading(!args.no_shading)
        .with_pair_budget(args.pair_budget);
    let (effects, plan) =
        plan::auto(&scene, &options).with_context(|| format!("cannot analyse {}", args.model))?;
    println!("{}: {effects}", args.model);
    println!("{}", plan.summary());
    Ok(())
}

/// The `--algo auto` choice for `hider render`: analyses the scene for the
/// view, prints one line with the choice and why, and returns the plan with
/// a fresh hider.
pub fn auto_hider(scene: &Scene, view: &View, shading: bool) -> Result<(Plan, Box<dyn Hider>)> {
    let options = RenderOptions::default()
        .with_size(view.viewport.width, view.viewport.height)
        .with_camera(Some(view.camera))
        .with_shading(shading);
    let (_, plan) = plan::auto(scene, &options).context("scene analysis for --algo auto")?;
    let Some(hider) = plan.hider() else {
        bail!("--algo auto chose '{}', which is not registered", plan.algo);
    };
    eprintln!("{}", plan.summary());
    Ok((plan, hider))
}
