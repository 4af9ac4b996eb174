//! `hider render`: one model, one hider, PNG and dumps out, optional timing.
//!
//! The hider comes from the registry of `hider-plan` (built with the knobs
//! the flags set) or, with `--algo auto`, from the planner, whose plan is
//! options: the hider, the front end's options and the colour stages.
//! Every frame, the one written and the ones `--repeat` times, comes from
//! one call: the hider's own pipeline, [`DynHider::render_scene`].

use anyhow::{Context, Result};
use hider::plan::{RenderOptions, planner, registry};
use hider::scene::atomic::OutputSet;
use hider::scene::shade::{Stages, render_frame, transparency_warning};
use hider::scene::timing::{Summary, Timer};
use hider::scene::{
    DynHider, Frame, PrepareOptions, Scene, ScreenScene, ShadeMode, StatsTable, View,
};

use crate::progress::{Progress, eprint_line, print_line};
pub use crate::render_args::RenderArgs;

/// The hider to run and the options it runs with (the plan's, with
/// `--algo auto`).
struct Chosen {
    hider: Box<dyn DynHider>,
    /// The front end's options: the flags', with the plan's choices.
    prepare: PrepareOptions,
    /// The colour stages: the plan's, or those the scene calls for.
    stages: Stages,
}

/// `--algo auto`: analyses the scene for the view, prints one line with
/// the choice and why, and returns the chosen hider with the plan's
/// options.
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
        .with_ordered_polygons(args.painter_svg())
        // The searches over pairs decide only the painter's plans and cost
        // seconds on large scenes: a raster render leaves them out.
        .with_pair_searches(false)
        .with_max_splits(args.max_splits)
        .with_cancel(args.cancel())
        .with_prepare(options);
    let planned = hider::plan::auto(scene, &analysis)
        .map_err(crate::args::flag_error)
        .context("scene analysis for --algo auto")?;
    let hider = planned.plan.build(&args.hider_config())?;
    progress.suspend(|| eprint_line(&planned.summary()));
    Ok(Chosen {
        hider,
        prepare: planned.prepare,
        stages: planned.plan.stages,
    })
}

/// `--repeat`: times the same call that made the written frame
/// ([`DynHider::render_scene`]: the hider's front end, then the render into
/// the frame) `args.repeat` more times, reusing memory as a frame loop
/// would.
fn time_frames(
    args: &RenderArgs,
    chosen: &mut Chosen,
    scene: &Scene,
    view: &View,
    screen: &mut ScreenScene,
    frame: &mut Frame,
) -> Result<Summary> {
    let summary = Timer::new(args.repeat).try_time(&|| false, || {
        chosen
            .hider
            .render_scene(scene, view, &chosen.prepare, screen, frame)
            .map(drop)
    })?;
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
fn report(
    scene: &Scene,
    view: &View,
    chosen: &Chosen,
    frame: &Frame,
    stats: &StatsTable,
) -> Result<()> {
    let covered = frame.covered_count();
    if covered == 0 {
        // Why: from the shared front end's account of every triangle (the
        // hider's own front end may keep none).
        let screen = hider::scene::prepare(scene, view, &chosen.prepare)?;
        if let Some(warning) = crate::empty::nothing_on_screen(scene, &screen, covered) {
            eprint_line(&format!("hider: warning: {warning}"));
        }
    }
    for warning in &stats.warnings {
        eprint_line(&format!("hider: warning: {warning}"));
    }
    eprint_line(&format!(
        "{}: {} triangles in, {covered} pixels covered; {stats}",
        chosen.hider.name(),
        scene.triangle_count(),
    ));
    Ok(())
}

/// Textures a textured mesh names that cannot be used, once per file:
/// those whose decode failed during the frame, and those never decoded
/// whose header does not read (a texture is decoded only when a pixel
/// samples it, so one off screen, or one the analysis found unreadable,
/// was never tried). A missing file is left out: the loader's warnings
/// name it already.
fn texture_warnings(scene: &Scene) -> Vec<String> {
    let mut seen = Vec::new();
    let mut warnings = Vec::new();
    let textures = scene
        .meshes
        .iter()
        .filter(|m| !m.uvs.is_empty())
        .flat_map(|mesh| scene.mesh_materials(mesh))
        .flatten()
        .flat_map(|m| {
            [
                (&m.diffuse_texture, "colour"),
                (&m.specular_texture, "specular colour"),
                (&m.alpha_texture, "opacity"),
            ]
        })
        .filter_map(|(t, fallback)| Some((t.as_ref()?, fallback)));
    for (texture, fallback) in textures {
        if seen.contains(&texture.path()) || !texture.path().exists() {
            continue;
        }
        seen.push(texture.path());
        if let Some(why) = texture.problem() {
            warnings.push(format!("{why}; the material's {fallback} is used"));
        }
    }
    warnings
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
        // The whole command runs on one of the pool's threads: every
        // parallel step of a frame (the front end's chunks, the bins, the
        // bands) is then a join inside the pool, where the main thread's
        // each would be a hand-off to the pool and a sleep until it is
        // done, two thread wake-ups that cost a small frame a third of its
        // time on a virtual machine (the spider at 2 threads).
        return rayon::scope(|_| render_command(args, (width, height)));
    }
    render_command(args, (width, height))
}

/// `hider render` once the thread pool is set up.
fn render_command(args: &RenderArgs, (width, height): (u32, u32)) -> Result<()> {
    // A named hider is built before the model loads, so a bad flag fails
    // at once; `--algo auto` needs the scene before it can choose.
    let config = args.hider_config();
    let fixed = if args.planned() {
        planner::check_config(&config).map_err(crate::args::flag_error)?;
        None
    } else {
        let entry = registry::find(&args.algo).map_err(crate::args::flag_error)?;
        let hider = entry.build(&config).map_err(crate::args::flag_error)?;
        // A size over the hider's memory budget fails before the model is
        // read and before any frame is allocated.
        hider.check_size(width, height)?;
        Some(hider)
    };
    // The outputs are checked before any work: against each other, the
    // model, and (once loaded) its textures.
    let model_path: Vec<std::path::PathBuf> = if args.model.starts_with("gen:") {
        Vec::new()
    } else {
        vec![args.model.clone().into()]
    };
    crate::outputs::check(&args.outputs(), &model_path)?;
    if let Some(bytes) = args.texture_budget {
        hider::scene::shade::set_texture_budget(bytes);
    }
    let progress = Progress::start("loading the model");
    let scene = crate::model::load(&args.model, &progress)?;
    // Every file the scene was read from: the OBJ, its MTL files and
    // every texture a material names.
    let mut inputs = model_path;
    inputs.extend(scene.source_files.iter().cloned());
    inputs.extend(
        scene
            .materials
            .iter()
            .flat_map(|m| [&m.diffuse_texture, &m.specular_texture, &m.alpha_texture])
            .flatten()
            .map(|t| t.path().to_path_buf()),
    );
    crate::outputs::check(&args.outputs(), &inputs)?;
    progress.stage(if args.planned() {
        "analysing the scene"
    } else {
        "preparing the scene"
    });
    let view = View::new(args.camera(&scene), width, height)?;
    let options = args.prepare_options();
    let mut chosen = match fixed {
        Some(hider) => Chosen {
            hider,
            prepare: options,
            stages: Stages::for_scene(&scene, args.shade_mode() == ShadeMode::Lambert),
        },
        None => auto(args, &scene, &view, options, &progress)?,
    };
    if let Some(warning) = transparency_warning(chosen.hider.as_ref(), &chosen.stages) {
        progress.suspend(|| eprint_line(&format!("hider: warning: {warning}")));
    }
    progress.stage(&format!("rendering with {}", chosen.hider.name()));
    chosen.hider.check_size(width, height)?;
    let mut frame = Frame::new(width, height)?.with_buffers(crate::outputs::frame_buffers(
        args.depth_out.is_some(),
        chosen.hider.resolves_color(),
    ));
    let mut screen = ScreenScene::empty(&view);
    // The hider's pipeline, then the colour pass unless the hider
    // resolved colour itself: what a library user gets from one call.
    let stats = render_frame(
        chosen.hider.as_mut(),
        &scene,
        &view,
        &chosen.prepare,
        &chosen.stages,
        args.shade_mode(),
        &mut screen,
        &mut frame,
    )?;
    if args.shade_mode() == ShadeMode::Lambert {
        for warning in texture_warnings(&scene) {
            progress.suspend(|| eprint_line(&format!("hider: warning: {warning}")));
        }
    }
    progress.stage("writing");
    write_outputs(args, &chosen, &scene, &view, &screen, &frame)?;
    if args.repeat > 0 {
        progress.stage(&format!("timing {} renders", args.repeat));
        let summary = time_frames(args, &mut chosen, &scene, &view, &mut screen, &mut frame)?;
        let line = timing_line(args, chosen.hider.name(), &scene, &view, &summary);
        // A closed stdout is no error: the outputs are written by now.
        progress
            .suspend(|| print_line(&line))
            .context("cannot print the timing")?;
    }
    drop(progress);
    report(&scene, &view, &chosen, &frame, &stats)?;
    Ok(())
}

/// Writes the PNG, the dumps asked for and the SVG, all or none: the SVG
/// first (the likeliest to fail: its budgets), then the PNG and the dumps
/// staged and moved into place together. The painter's ordered polygons
/// (`--svg-mode painter`) are the painter's last frame, drawn from the
/// shared front end's scene its pipeline left in `screen`; the regions and
/// lines are computed from the scene prepared with the frame's options.
fn write_outputs(
    args: &RenderArgs,
    chosen: &Chosen,
    scene: &Scene,
    view: &View,
    screen: &ScreenScene,
    frame: &Frame,
) -> Result<()> {
    // The scene crate's errors name the file; the context says which
    // output it is.
    let mut set = OutputSet::new();
    frame
        .write_png_into(&mut set, &args.output)
        .context("cannot write the PNG")?;
    if let Some(p) = &args.ids_out {
        frame
            .write_ids_into(&mut set, p)
            .context("cannot write the id dump")?;
    }
    if let Some(p) = &args.depth_out {
        frame
            .write_depth_into(&mut set, p)
            .context("cannot write the depth dump")?;
    }
    match &args.svg {
        Some(svg) if args.painter_svg() => chosen
            .hider
            .ordered_polygons()
            .with_context(|| format!("--svg: {} gave no ordered polygons", chosen.hider.name()))?
            .write_svg(screen, svg, args.shade_mode())
            .context("cannot write the SVG")?,
        Some(svg) => {
            let prepared = hider::scene::prepare(scene, view, &chosen.prepare)?;
            write_vector_svg(args, scene, &prepared, svg)?;
        }
        None => {}
    }
    set.commit().context("cannot write the outputs")
}

/// `--svg-mode regions` or `lines`: the exact visible regions or the
/// hidden-line drawing of the prepared scene, from hider-vector, with the
/// vector flags' options, titled with the model and layered by its
/// objects. The lines need only the intersection pairs, not the regions
/// ([`hider_vector::line_pairs`]).
fn write_vector_svg(
    args: &RenderArgs,
    scene: &Scene,
    screen: &ScreenScene,
    svg: &std::path::Path,
) -> Result<()> {
    use hider_vector::{SvgInfo, hidden_lines_in, line_pairs, visible_regions};
    let (width, height) = (screen.viewport.width, screen.viewport.height);
    let options = args.vector_options(width, height);
    let mut info = SvgInfo::for_scene(scene, &args.model, screen);
    let document = if args.svg_mode == crate::render_args::SvgMode::Lines {
        // The lines need only the map's intersection pairs: no regions.
        let map = line_pairs(screen, &options).context("cannot find the intersection lines")?;
        let drawing = hidden_lines_in(screen, &map, &options, &info.groups)
            .context("cannot compute the hidden lines")?;
        hider_vector::lines_document(screen, &drawing, &options, &info)
    } else {
        // Region fills are one colour per face group: a texture is not
        // written, and the reader should know.
        let textured = scene.materials.iter().any(|m| m.diffuse_texture.is_some());
        if textured && args.shade_mode() == ShadeMode::Lambert {
            let note = "region fills are flat colours: textures are not written";
            eprint_line(&format!("hider: warning: --svg: {note}"));
            info = info.with_note(note);
        }
        let map = visible_regions(screen, &options, args.shade_mode())
            .context("cannot compute the visible regions")?;
        hider_vector::regions_document(screen, &map, &options, &info)
    };
    hider_vector::write_document(svg, &document).context("cannot write the SVG")
}
