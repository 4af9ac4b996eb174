//! `hider render`: one model, one hider, PNG and dumps out, optional timing.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use glam::DVec3;
use hider::geom::{Camera, Projection};
use hider::painter::{NaivePainter, Painter};
use hider::scene::{
    DepthScene, Frame, Hider, PrepareOptions, Scene, ShadeMode, TransformPrecision, View,
    fit_camera, load_obj, prepare, prepare_depth_into, prepare_into, procedural, shade_frame,
};
use hider::zbuffer::{
    DepthFormat, DepthSource, TiledZBuffer, TiledZBufferOptions, ZBuffer, ZBufferOptions,
};

/// Arguments of `hider render`.
#[derive(Args, Debug)]
pub struct RenderArgs {
    /// OBJ file, or a generated scene: gen:cube, gen:sphere[:N],
    /// gen:soup[:COUNT[:SEED]], gen:intersecting, gen:cyclic, gen:coplanar.
    model: String,
    /// Output PNG.
    #[arg(short, long)]
    output: PathBuf,
    /// Square image size in pixels (1 to 16384).
    #[arg(long, conflicts_with_all = ["width", "height"])]
    size: Option<u32>,
    /// Image width in pixels (with --height).
    #[arg(long, requires = "height")]
    width: Option<u32>,
    /// Image height in pixels (with --width).
    #[arg(long, requires = "width")]
    height: Option<u32>,
    /// Hidden-surface algorithm (see `hider list`).
    #[arg(long, default_value = "zbuffer")]
    algo: String,
    /// Depth buffer format of the z-buffer.
    #[arg(long, value_enum)]
    depth_format: Option<DepthFormatArg>,
    /// What the z-buffer compares.
    #[arg(long, value_enum)]
    depth_source: Option<DepthSourceArg>,
    /// Transform arithmetic of the front end (f32 reproduces GL).
    #[arg(long, value_enum, default_value = "f64")]
    precision: PrecisionArg,
    /// Also write the painter's ordered, split polygon list as SVG (with
    /// --algo painter or painter-naive).
    #[arg(long)]
    svg: Option<PathBuf>,
    /// Write the visible primitive ids (int32 LE, -1 background).
    #[arg(long)]
    ids_out: Option<PathBuf>,
    /// Write the window depth (float32 LE, 1.0 background).
    #[arg(long)]
    depth_out: Option<PathBuf>,
    /// How to colour the image.
    #[arg(long, value_enum, default_value = "lambert")]
    shade: ShadeArg,
    /// Eye position x,y,z (default: the fit camera).
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    eye: Option<DVec3>,
    /// Point looked at x,y,z.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    target: Option<DVec3>,
    /// Up direction x,y,z.
    #[arg(long, value_parser = parse_vec3, allow_hyphen_values = true)]
    up: Option<DVec3>,
    /// Vertical field of view in degrees.
    #[arg(long)]
    fovy: Option<f64>,
    /// Near plane distance.
    #[arg(long)]
    near: Option<f64>,
    /// Far plane distance.
    #[arg(long)]
    far: Option<f64>,
    /// Worker threads: the tiled z-buffer renders tiles in parallel, and
    /// above 1 the front end prepares large scenes in parallel too.
    #[arg(long, default_value_t = 1)]
    threads: usize,
    /// Render K times after a warm-up and print the median and minimum
    /// milliseconds of prepare + clear + rasterise.
    #[arg(long, default_value_t = 0)]
    repeat: u32,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum DepthFormatArg {
    F32,
    F64,
    Fixed24,
    Fixed16,
    ReversedF32,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum DepthSourceArg {
    WindowZ,
    LinearViewZ,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum PrecisionArg {
    F32,
    F64,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum ShadeArg {
    Lambert,
    Ids,
}

fn parse_vec3(s: &str) -> Result<DVec3, String> {
    let parts: Vec<&str> = s.split(',').collect();
    if parts.len() != 3 {
        return Err(format!("expected x,y,z, got '{s}'"));
    }
    let mut v = [0.0; 3];
    for (slot, p) in v.iter_mut().zip(&parts) {
        *slot = p
            .trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| format!("'{p}' is not a finite number"))?;
    }
    Ok(DVec3::from_array(v))
}

/// Loads an OBJ file or builds a generated scene.
pub fn load_model(model: &str) -> Result<Scene> {
    if let Some(spec) = model.strip_prefix("gen:") {
        return generated(spec);
    }
    let scene = load_obj(model).with_context(|| format!("cannot load model {model}"))?;
    for w in &scene.warnings {
        eprintln!("hider: warning: {w}");
    }
    Ok(scene)
}

fn generated(spec: &str) -> Result<Scene> {
    let mut parts = spec.split(':');
    let name = parts.next().unwrap_or_default();
    let mut num = |default: u64, what: &str| -> Result<u64> {
        match parts.next() {
            None => Ok(default),
            Some(p) => p
                .parse()
                .with_context(|| format!("gen:{spec}: bad {what} '{p}'")),
        }
    };
    Ok(match name {
        "cube" => procedural::cube(),
        "sphere" => {
            let n = num(64, "segment count")?;
            if !(3..=2000).contains(&n) {
                bail!("gen:{spec}: segment count {n} must be 3 to 2000");
            }
            procedural::uv_sphere(n as u32)
        }
        "soup" => {
            let count = num(10_000, "triangle count")?;
            let seed = num(1, "seed")?;
            if count > 10_000_000 {
                bail!("gen:{spec}: triangle count {count} is over the limit of 10000000");
            }
            procedural::random_soup(count as u32, seed)
        }
        "intersecting" => procedural::intersecting_pair(),
        "cyclic" => procedural::cyclic_triple(),
        "coplanar" => procedural::coplanar_pair(),
        _ => bail!(
            "unknown generated scene '{name}' (cube, sphere, soup, intersecting, cyclic, coplanar)"
        ),
    })
}

fn camera(args: &RenderArgs, scene: &Scene) -> Camera {
    let mut c = scene.camera.unwrap_or_else(|| fit_camera(scene));
    c.eye = args.eye.unwrap_or(c.eye);
    c.target = args.target.unwrap_or(c.target);
    c.up = args.up.unwrap_or(c.up);
    if let Projection::Perspective {
        fovy_degrees,
        near,
        far,
    } = &mut c.projection
    {
        *fovy_degrees = args.fovy.unwrap_or(*fovy_degrees);
        *near = args.near.unwrap_or(*near);
        *far = args.far.unwrap_or(*far);
    }
    c
}

/// The z-buffers' depth format from `--depth-format` (f32 by default).
fn depth_format(args: &RenderArgs) -> DepthFormat {
    match args.depth_format.unwrap_or(DepthFormatArg::F32) {
        DepthFormatArg::F32 => DepthFormat::F32,
        DepthFormatArg::F64 => DepthFormat::F64,
        DepthFormatArg::Fixed24 => DepthFormat::Fixed24,
        DepthFormatArg::Fixed16 => DepthFormat::Fixed16,
        DepthFormatArg::ReversedF32 => DepthFormat::ReversedF32,
    }
}

fn make_hider(args: &RenderArgs) -> Result<Box<dyn Hider>> {
    let zbuffer_flags = args.depth_format.is_some() || args.depth_source.is_some();
    let format = depth_format(args);
    if args.algo == "zbuffer" {
        let source = match args.depth_source.unwrap_or(DepthSourceArg::WindowZ) {
            DepthSourceArg::WindowZ => DepthSource::WindowZ,
            DepthSourceArg::LinearViewZ => DepthSource::LinearViewZ,
        };
        let options = ZBufferOptions::default()
            .with_depth_format(format)
            .with_depth_source(source);
        return Ok(Box::new(ZBuffer::new(options)));
    }
    if args.algo == "zbuffer-tiled" {
        if args.depth_source.is_some() {
            bail!(
                "--depth-source applies to --algo zbuffer only (the tiled path compares window depth)"
            );
        }
        let options = TiledZBufferOptions::default()
            .with_depth_format(format)
            .with_threads(args.threads);
        return Ok(Box::new(TiledZBuffer::new(options)));
    }
    if zbuffer_flags {
        bail!("--depth-format and --depth-source apply to --algo zbuffer and zbuffer-tiled only");
    }
    let entry = hider::registry::by_name(&args.algo).with_context(|| {
        let names: Vec<&str> = hider::registry::all().iter().map(|e| e.name).collect();
        format!(
            "unknown --algo '{}' (one of: {})",
            args.algo,
            names.join(", ")
        )
    })?;
    Ok((entry.make)())
}

/// The median of `times` (sorted in place; not empty).
fn median(times: &mut [f64]) -> f64 {
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

/// "median X ms, min Y ms over N runs" of `times` (sorted in place).
fn median_min(times: &mut [f64]) -> String {
    let m = median(times);
    format!(
        "median {m:.3} ms, min {:.3} ms over {} runs",
        times[0],
        times.len()
    )
}

/// `--repeat` for the tiled z-buffer: its own pipeline, the lean front end
/// (`prepare_depth_into`: transform, clip, set-up) and a draw that leaves
/// the image in the hider's tiled framebuffer, which is the span a GL draw
/// call plus `glFinish` covers. The read-back into a frame (GL's
/// `glReadPixels`) is timed apart, and the image read back is checked
/// against the one the ordinary path rendered.
fn time_tiled(
    args: &RenderArgs,
    scene: &hider::scene::Scene,
    view: &View,
    options: &PrepareOptions,
    want: &Frame,
) -> Result<String> {
    let mut tiled = TiledZBuffer::new(
        TiledZBufferOptions::default()
            .with_depth_format(depth_format(args))
            .with_threads(args.threads),
    );
    let mut lean = DepthScene::new();
    // Warm-up.
    prepare_depth_into(scene, view, options, &mut lean)?;
    tiled.draw_depth_scene(&lean)?;
    let (mut times, mut reads) = (Vec::new(), Vec::new());
    let mut got = Frame::new(want.width(), want.height())?;
    for _ in 0..args.repeat {
        let start = Instant::now();
        prepare_depth_into(scene, view, options, &mut lean)?;
        tiled.draw_depth_scene(&lean)?;
        times.push(start.elapsed().as_secs_f64() * 1e3);
        let start = Instant::now();
        tiled.read_into(&mut got)?;
        reads.push(start.elapsed().as_secs_f64() * 1e3);
    }
    if got.ids != want.ids || got.depth != want.depth {
        bail!("internal error: the timed tiled pipeline's image differs from the rendered one");
    }
    Ok(format!(
        "{} (prepare + clear + rasterise, lean front end, image left in the tiles; read-back into a frame {:.3} ms more)",
        median_min(&mut times),
        median(&mut reads)
    ))
}

/// Runs `hider render`.
pub fn run(args: &RenderArgs) -> Result<()> {
    let (width, height) = match (args.size, args.width, args.height) {
        (Some(n), _, _) => (n, n),
        (None, Some(w), Some(h)) => (w, h),
        _ => (512, 512),
    };
    hider::scene::view::check_image_size(width, height).context("bad image size")?;
    if args.threads == 0 || args.threads > 1024 {
        bail!("--threads must be 1 to 1024, got {}", args.threads);
    }
    if args.threads > 1 {
        rayon::ThreadPoolBuilder::new()
            .num_threads(args.threads)
            .build_global()
            .context("cannot start the thread pool")?;
    }
    if args.svg.is_some() && !args.algo.starts_with("painter") {
        bail!(
            "--svg needs --algo painter or painter-naive (vector output comes from the depth order)"
        );
    }
    // `--algo auto` needs the scene and view before it can choose.
    let planned = args.algo == "auto";
    if planned && (args.depth_format.is_some() || args.depth_source.is_some()) {
        bail!("--depth-format and --depth-source apply to --algo zbuffer and zbuffer-tiled only");
    }
    let fixed = if planned {
        None
    } else {
        Some(make_hider(args)?)
    };
    let scene = load_model(&args.model)?;
    let view = View::new(camera(args, &scene), width, height)?;
    let (plan, mut hider) = match fixed {
        Some(h) => (None, h),
        None => {
            let shading = matches!(args.shade, ShadeArg::Lambert);
            let (plan, h) = crate::analyze::auto_hider(&scene, &view, shading)?;
            (Some(plan), h)
        }
    };
    let options = PrepareOptions::default()
        .with_precision(match args.precision {
            PrecisionArg::F32 => TransformPrecision::F32,
            PrecisionArg::F64 => TransformPrecision::F64,
        })
        .with_parallel(args.threads > 1);
    let options = plan
        .as_ref()
        .map_or(options, |p| p.prepare_options(options));
    let mut frame = Frame::new(width, height)?;
    let mut screen = prepare(&scene, &view, &options)?;
    let stats = hider.render(&screen, &mut frame)?;
    if args.repeat > 0 {
        let line = if args.algo == "zbuffer-tiled" {
            time_tiled(args, &scene, &view, &options, &frame)?
        } else {
            // The first render above is the warm-up; each timed run redoes
            // everything after loading, reusing memory as a real frame
            // loop would.
            let mut times = Vec::with_capacity(args.repeat as usize);
            for _ in 0..args.repeat {
                let start = Instant::now();
                prepare_into(&scene, &view, &options, &mut screen)?;
                hider.render(&screen, &mut frame)?;
                times.push(start.elapsed().as_secs_f64() * 1e3);
            }
            format!("{} (prepare + clear + rasterise)", median_min(&mut times))
        };
        println!(
            "{}: {} triangles, {}x{}, threads {}: {line}",
            hider.name(),
            scene.triangle_count(),
            width,
            height,
            args.threads,
        );
    }
    if !hider.resolves_color() {
        let mode = match args.shade {
            ShadeArg::Lambert => ShadeMode::Lambert,
            ShadeArg::Ids => ShadeMode::Ids,
        };
        match &plan {
            // Auto: only the colour stages the scene calls for.
            Some(p) if mode == ShadeMode::Lambert => {
                hider::scene::Shader::default().shade(&screen, &mut frame, &p.stages);
            }
            _ => shade_frame(&screen, &mut frame, mode),
        }
    }
    write_outputs(args, &frame)?;
    if let Some(svg) = &args.svg {
        let mode = match args.shade {
            ShadeArg::Lambert => ShadeMode::Lambert,
            ShadeArg::Ids => ShadeMode::Ids,
        };
        let written = if args.algo == "painter-naive" {
            NaivePainter::default().render_svg(&screen, svg, mode)
        } else {
            Painter::default().render_svg(&screen, svg, mode)
        };
        written.with_context(|| format!("cannot write {}", svg.display()))?;
    }
    eprintln!(
        "{}: {} triangles in, {} on screen, {} pixels covered; {}",
        hider.name(),
        scene.triangle_count(),
        screen.tris.len(),
        frame.covered_count(),
        stats
    );
    Ok(())
}

fn write_outputs(args: &RenderArgs, frame: &Frame) -> Result<()> {
    let out = |p: &Path| format!("cannot write {}", p.display());
    frame
        .write_png(&args.output)
        .with_context(|| out(&args.output))?;
    if let Some(p) = &args.ids_out {
        frame.write_ids(p).with_context(|| out(p))?;
    }
    if let Some(p) = &args.depth_out {
        frame.write_depth(p).with_context(|| out(p))?;
    }
    Ok(())
}
