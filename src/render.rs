//! `hider render`: one model, one hider, PNG and dumps out, optional timing.
//!
//! The hider comes from the registry of `hider-plan` (built with the knobs
//! the flags set) or, with `--algo auto`, from the planner, which also
//! hands over the scene its analysis prepared.

use anyhow::{Context, Result, bail};
use hider::plan::stages::{prepare_surface, transparency_warning};
use hider::plan::{Plan, RenderOptions, Shader, Stages, planner, registry};
use hider::scene::timing::{Summary, Timer};
use hider::scene::{
    DynHider, Frame, PrepareOptions, Scene, ScreenScene, ShadeMode, StatsTable, View, prepare,
    shade_frame,
};

use crate::progress::Progress;
pub use crate::render_args::RenderArgs;

/// The hider to run, the scene prepared for it, and the plan behind it
/// with `--algo auto`.
struct Chosen {
    hider: Box<dyn DynHider>,
    screen: ScreenScene,
    plan: Option<Plan>,
}

/// `--algo auto`: analyses the scene for the view, prints one line with
/// the choice and why, and returns the chosen hider with the scene the
/// analysis prepared (the plan's culling applied).
fn auto(
    args: &RenderArgs,
    scene: &Scene,
    view: &View,
    options: PrepareOptions,
    progress: &Progress,
) -> Result<Chosen> {
    let analysis = RenderOptions::default()
        .with_size(view.viewport.width, view.viewport.height)
        .with_camera(Some(view.camera))
        .with_shading(args.shade_mode() == ShadeMode::Lambert)
        .with_antialiasing(args.aa)
        .with_vector_output(args.vector || args.painter_svg())
        // The searches over pairs decide only vector plans and cost
        // seconds on large scenes: a raster render leaves them out.
        .with_pair_searches(false)
        .with_prepare(options);
    let planned = hider::plan::auto(scene, &analysis).context("scene analysis for --algo auto")?;
    let hider = planned.plan.build(&args.hider_config())?;
    progress.suspend(|| eprintln!("{}", planned.summary()));
    Ok(Chosen {
        hider,
        screen: planned.screen,
        plan: Some(planned.plan),
    })
}

/// `--repeat`: times the hider's whole pipeline from the world-space scene
/// ([`DynHider::render_scene`]: its front end, then the render into the
/// frame) after a warm-up, reusing memory as a frame loop would, and checks
/// that the frame comes out as the first render left it.
fn time_frames(
    args: &RenderArgs,
    hider: &mut dyn DynHider,
    scene: &Scene,
    view: &View,
    options: &PrepareOptions,
    screen: &mut ScreenScene,
    frame: &mut Frame,
) -> Result<Summary> {
    let (ids, depth) = (frame.ids.clone(), frame.depth.clone());
    let summary = Timer::new(args.repeat).try_time(&|| false, || {
        hider
            .render_scene(scene, view, options, screen, frame)
            .map(drop)
    })?;
    if frame.ids != ids || frame.depth != depth {
        bail!("internal error: the timed pipeline's image differs from the rendered one");
    }
    Ok(summary)
}

/// The line `--repeat` prints on stdout.
fn timing_line(
    args: &RenderArgs,
    name: &str,
    scene: &Scene,
    view: &View,
    summary: &Summary,
) -> String {
    format!(
        "{name}: {} triangles, {}x{}, threads {}: {summary} (prepare + clear + rasterise)",
        scene.triangle_count(),
        view.viewport.width,
        view.viewport.height,
        args.threads,
    )
}

/// What the run ends with on stderr: why nothing is on screen if nothing
/// is, then the hider's counts.
fn report(scene: &Scene, chosen: &Chosen, frame: &Frame, stats: &StatsTable) {
    let covered = frame.covered_count();
    if let Some(warning) = crate::empty::nothing_on_screen(scene, &chosen.screen, covered) {
        eprintln!("hider: warning: {warning}");
    }
    for warning in &stats.warnings {
        eprintln!("hider: warning: {warning}");
    }
    eprintln!(
        "{}: {} triangles in, {} on screen, {covered} pixels covered; {stats}",
        chosen.hider.name(),
        scene.triangle_count(),
        chosen.screen.tris.len(),
    );
}

/// The colour stages the scene calls for: the plan's under `--algo auto`,
/// else those found cheaply from the scene (textures, lighting).
fn colour_stages(args: &RenderArgs, chosen: &Chosen, scene: &Scene) -> Stages {
    match &chosen.plan {
        Some(p) => p.stages,
        None => Stages::for_scene(scene, args.shade_mode() == ShadeMode::Lambert),
    }
}

/// Colours the frame unless the hider did: from the ids, with only the
/// stages the scene calls for under Lambert shading.
fn shade(
    args: &RenderArgs,
    chosen: &Chosen,
    stages: &Stages,
    frame: &mut Frame,
    progress: &Progress,
) {
    if chosen.hider.resolves_color() {
        return;
    }
    match args.shade_mode() {
        ShadeMode::Lambert => {
            let trace = Shader::default().shade(&chosen.screen, frame, stages);
            for failure in trace.texture_failures {
                progress.suspend(|| {
                    eprintln!("hider: warning: {failure}; the material's colour is used");
                });
            }
        }
        mode => shade_frame(&chosen.screen, frame, mode),
    }
}

/// Runs `hider render`.
pub fn run(args: &RenderArgs) -> Result<()> {
    let (width, height) = args.image_size()?;
    args.check_requests()?;
    if args.threads > 1 {
        rayon::ThreadPoolBuilder::new()
            .num_threads(args.threads)
            .build_global()
            .context("cannot start the thread pool")?;
    }
    // A named hider is built before the model loads, so a bad flag fails
    // at once; `--algo auto` needs the scene before it can choose.
    let config = args.hider_config();
    let fixed = if args.planned() {
        planner::check_config(&config)?;
        None
    } else {
        Some(registry::find(&args.algo)?.build(&config)?)
    };
    let progress = Progress::start("loading the model");
    let scene = crate::model::load(&args.model, &progress)?;
    progress.stage(if args.planned() {
        "analysing the scene"
    } else {
        "preparing the scene"
    });
    let view = View::new(args.camera(&scene), width, height)?;
    let mut options = args.prepare_options();
    let mut chosen = match fixed {
        Some(hider) => Chosen {
            hider,
            screen: prepare(&scene, &view, &options)?,
            plan: None,
        },
        None => auto(args, &scene, &view, options, &progress)?,
    };
    if let Some(plan) = &chosen.plan {
        options = plan.prepare_options(options);
    }
    let stages = colour_stages(args, &chosen, &scene);
    if let Some(warning) = transparency_warning(chosen.hider.name(), &stages) {
        progress.suspend(|| eprintln!("hider: warning: {warning}"));
    }
    if chosen.hider.resolves_color() {
        // Hiders that composite colour themselves sample the textures.
        for failure in prepare_surface(&mut chosen.screen, &stages) {
            progress.suspend(|| {
                eprintln!("hider: warning: {failure}; the material's colour is used");
            });
        }
    }
    progress.stage(&format!("rendering with {}", chosen.hider.name()));
    let mut frame = Frame::new(width, height)?;
    let stats = chosen.hider.render(&chosen.screen, &mut frame)?;
    if args.repeat > 0 {
        progress.stage(&format!("timing {} renders", args.repeat));
        let summary = time_frames(
            args,
            chosen.hider.as_mut(),
            &scene,
            &view,
            &options,
            &mut chosen.screen,
            &mut frame,
        )?;
        let line = timing_line(args, chosen.hider.name(), &scene, &view, &summary);
        progress.suspend(|| println!("{line}"));
    }
    progress.stage("shading");
    shade(args, &chosen, &stages, &mut frame, &progress);
    progress.stage("writing");
    write_outputs(args, &chosen, &frame)?;
    drop(progress);
    report(&scene, &chosen, &frame, &stats);
    Ok(())
}

/// Writes the PNG, the dumps asked for and the SVG (the vector output of
/// the hider that ran), each atomically; nothing when the SVG cannot be
/// had.
fn write_outputs(args: &RenderArgs, chosen: &Chosen, frame: &Frame) -> Result<()> {
    let vector = match &args.svg {
        Some(svg) if args.painter_svg() => {
            let output = chosen
                .hider
                .vector_output()
                .with_context(|| format!("--svg: {} gave no vector output", chosen.hider.name()))?;
            Some((svg, output))
        }
        _ => None,
    };
    // The scene crate's errors name the file; the context says which
    // output it is.
    frame
        .write_png(&args.output)
        .context("cannot write the PNG")?;
    if let Some(p) = &args.ids_out {
        frame.write_ids(p).context("cannot write the id dump")?;
    }
    if let Some(p) = &args.depth_out {
        frame
            .write_depth(p)
            .context("cannot write the depth dump")?;
    }
    if let Some((svg, output)) = vector {
        output
            .write_svg(&chosen.screen, svg, args.shade_mode())
            .context("cannot write the SVG")?;
    }
    if let Some(svg) = args.svg.as_ref().filter(|_| !args.painter_svg()) {
        write_vector_svg(args, chosen, svg)?;
    }
    Ok(())
}

/// `--svg-mode regions` or `lines`: the exact visible regions or the
/// hidden-line drawing of the scene the hider rendered, from hider-vector.
fn write_vector_svg(args: &RenderArgs, chosen: &Chosen, svg: &std::path::Path) -> Result<()> {
    use hider_vector::{VectorOptions, hidden_lines, visible_regions};
    let options = VectorOptions::default();
    let map = visible_regions(&chosen.screen, &options, args.shade_mode())
        .context("cannot compute the visible regions")?;
    let written = if args.svg_mode == crate::render_args::SvgMode::Lines {
        let drawing = hidden_lines(&chosen.screen, &map, &options)
            .context("cannot compute the hidden lines")?;
        hider_vector::write_lines_svg(&chosen.screen, &drawing, &options, svg)
    } else {
        hider_vector::write_regions_svg(&chosen.screen, &map, &options, svg)
    };
    written.context("cannot write the SVG")
}
