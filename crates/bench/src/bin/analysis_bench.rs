//! Measures the scene analysis and the effect stages, and draws the
//! picture of `docs/analysis.md`.
//!
//! ```text
//! cargo run --release -p hider-bench --bin analysis_bench -- [OUT.png]
//! ```
//!
//! 1. Analysis time on scenes of about 10^5 triangles (the intersection
//!    search on its grid, the overlap graph on its tiles).
//! 2. The colour pass with only the stages the scene calls for against the
//!    same pass with unused stages forced on (a scene without textures or
//!    lights pays for neither).
//! 3. What the planner costs next to the render it plans (thread CPU
//!    time, one render thread): the plan as a raster `hider render`
//!    asks for it (no pair searches), its closed-shell proof alone, and
//!    the planned render with and without the back-face culling that
//!    proof buys.
//! 4. The scaling of the analysis's pair searches on random triangles
//!    overlapping in a cube, N doubling (`hider analyze`'s default
//!    budget), and on the family whose overlaps grow linearly.
//! 5. The checkerboard plane at a grazing angle, perspective-correct
//!    beside affine, written to `OUT.png` (default
//!    `docs/images/analysis-checker.png`).
//! 6. The scaling of the pair searches on stars (a flat fan, a cone and a
//!    steeply pleated fan of N triangles around one vertex) and on a book
//!    (N triangles around one edge), N doubling. `analysis_bench stars`
//!    runs this section alone.
//!
//! `analysis_bench scaling` runs section 4 alone.

use std::path::PathBuf;

use glam::DVec3;
use hider_bench::analysis::{book, overlapping_triangles, pleated_fan, star_fan};
use hider_bench::programs::thread_cpu_seconds;
use hider_plan::analyze::backface;
use hider_plan::{HiderConfig, RenderOptions, analyze_prepared, auto};
use hider_scene::geom::Camera;
use hider_scene::shade::{Filter, Mapping, Prims, Shader, ShaderOptions, Stages};
use hider_scene::{
    Frame, Hider, PrepareOptions, Scene, ScreenScene, load_model, load_obj, procedural,
};
use hider_testkit::timer::Timer;
use hider_zbuffer::{DepthFormat, ZBuffer, ZBufferOptions};

/// The visible primitive at every pixel centre (the f64 z-buffer, exact on
/// these scenes), colours left for the shader.
fn ids(screen: &ScreenScene) -> Frame {
    let options = ZBufferOptions::default().with_depth_format(DepthFormat::F64);
    hider_testkit::render(&mut ZBuffer::new(options), screen).0
}

/// The fastest of 20 runs of `f`, in milliseconds.
fn best_of_20(f: impl FnMut()) -> f64 {
    Timer::new(20).time(f).min_ms
}

/// Section 1: how long the analysis takes on large scenes.
fn analysis_times() {
    println!("## analysis time (512 x 512)");
    println!(
        "| scene | triangles | exact tri-tri tests | intersections ms | overlaps ms | total ms | found |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (name, scene) in [
        ("uv_sphere(224)", procedural::uv_sphere(224)),
        ("random_soup(100000)", procedural::random_soup(100_000, 1)),
        ("random_soup(10000)", procedural::random_soup(10_000, 1)),
    ] {
        let fx = hider_plan::analyze(&scene, &RenderOptions::default()).unwrap();
        let tests = fx
            .intersections
            .detail
            .split('(')
            .nth(1)
            .and_then(|s| s.split(' ').next())
            .unwrap_or("?")
            .to_owned();
        println!(
            "| {name} | {} | {tests} | {:.0} | {:.0} | {:.0} | {} pairs cross, {} cycles{} |",
            fx.triangles,
            fx.times.intersections_ms,
            fx.times.overlaps_ms,
            fx.times.total_ms,
            fx.intersections.count,
            fx.cyclic_overlap.count,
            if fx.cyclic_overlap.certain {
                ""
            } else {
                " (budget)"
            }
        );
    }
}

/// Thread CPU milliseconds of `f` (wall time where the platform has no
/// thread clock), the least of `runs`: on a machine shared with other
/// jobs the CPU time is what the work costs.
fn cpu_ms(runs: usize, mut f: impl FnMut()) -> f64 {
    (0..runs)
        .map(|_| {
            let (c0, w0) = (thread_cpu_seconds(), std::time::Instant::now());
            f();
            match (c0, thread_cpu_seconds()) {
                (Some(a), Some(b)) => (b - a) * 1e3,
                _ => w0.elapsed().as_secs_f64() * 1e3,
            }
        })
        .fold(f64::INFINITY, f64::min)
}

/// Section 3: the planner's cost next to the render it plans.
fn planner_cost() {
    println!("\n## planner cost vs render (thread CPU ms, one render thread, least of 3)");
    println!(
        "| scene | size | plan | of it: shell proof | render as planned | render without culling | plan / render |"
    );
    println!("|---|---|---|---|---|---|---|");
    for (model, size) in [
        ("gen:soup:1000000", 512),
        ("gen:sphere:300", 1024),
        ("gen:sphere:1000", 2048),
        ("gen:sphere:708", 1024),
    ] {
        let scene = load_model(model).unwrap();
        let options = RenderOptions::default()
            .with_size(size, size)
            .with_pair_searches(false);
        let planned = auto(&scene, &options).unwrap();
        let plan_ms = cpu_ms(3, || {
            std::hint::black_box(auto(&scene, &options).unwrap());
        });
        let proof_ms = cpu_ms(3, || {
            for m in &scene.meshes {
                std::hint::black_box(backface::maybe_closed(&m.positions, &m.indices));
            }
            std::hint::black_box(backface::hidden_back_faces(&scene, &planned.view));
        });
        let config = HiderConfig::default().with_threads(1);
        let render = |prepare: &PrepareOptions| {
            let mut hider = planned.plan.build(&config).unwrap();
            let mut frame = Frame::new(size, size).unwrap();
            cpu_ms(3, || {
                // A fresh screen scene each time: a prepared one is reused.
                let mut screen = ScreenScene::empty(&planned.view);
                hider
                    .render_scene(&scene, &planned.view, prepare, &mut screen, &mut frame)
                    .unwrap();
            })
        };
        let planned_ms = render(&planned.prepare);
        let plain_ms = render(&options.prepare);
        println!(
            "| `{model}` | {size} | {plan_ms:.0} | {proof_ms:.0} | {planned_ms:.0} ({}) | {plain_ms:.0} | {:.0}% |",
            planned.plan.algo,
            100.0 * plan_ms / planned_ms
        );
    }
}

/// A family of scenes: its name, the reach of its triangles for a count,
/// and the counts measured.
type Family = (&'static str, fn(u32) -> f64, &'static [u32]);

/// A family of section 6: name, scene of N, the Ns.
type StarFamily = (&'static str, fn(u32) -> Scene, &'static [u32]);

/// Section 4: the pair searches on overlapping random triangles, N
/// doubling.
fn analysis_scaling() {
    println!("\n## analysis scaling: random triangles overlapping in a cube (512 x 512)");
    println!(
        "| family | N | pairs listed | pairs tested | crossing pairs | overlapping pairs in the graph | analysis ms (thread CPU) |"
    );
    println!("|---|---|---|---|---|---|---|");
    let families: [Family; 2] = [
        (
            "corners uniform in the cube",
            |_| 1.0,
            &[500, 1000, 2000, 4000, 8000],
        ),
        (
            "reach 3 / sqrt(N)",
            |n| 3.0 / f64::from(n).sqrt(),
            &[1000, 2000, 4000, 8000, 16000, 32000],
        ),
    ];
    for (family, reach, counts) in families {
        for &n in counts {
            let scene: Scene = overlapping_triangles(n, reach(n), 7);
            let mut fx = None;
            let ms = cpu_ms(1, || {
                fx = Some(hider_plan::analyze(&scene, &RenderOptions::default()).unwrap())
            });
            let fx = fx.unwrap();
            let w = fx.work;
            let overlapping = overlapping_pairs(&fx);
            println!(
                "| {family} | {n} | {} | {} | {}{} | {overlapping} | {ms:.0} |",
                w.intersection_candidates + w.overlap_candidates,
                w.intersection_tests + w.overlap_tests,
                fx.intersections.count,
                if fx.intersections.certain && fx.cyclic_overlap.certain {
                    ""
                } else {
                    " (budget)"
                }
            );
        }
    }
}

/// The overlapping pairs on screen that the overlap graph's report names.
fn overlapping_pairs(fx: &hider_plan::Effects) -> String {
    fx.cyclic_overlap
        .detail
        .split(" among ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .unwrap_or("?")
        .to_owned()
}

/// Section 6: the pair searches on a fan, a cone and a steeply pleated
/// fan of N triangles around one vertex, and on a book of N pages around
/// one edge, N doubling.
fn star_scaling() {
    println!("\n## analysis scaling: stars of N triangles around one vertex (512 x 512)");
    println!(
        "| family | N | pairs listed | pairs tested | overlapping pairs on screen | intersections ms | overlaps ms | analysis ms (thread CPU) |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let families: [StarFamily; 4] = [
        (
            "flat fan",
            |n| star_fan(n, 0.0),
            &[1000, 2000, 4000, 8000, 16000, 32000],
        ),
        (
            "cone",
            |n| star_fan(n, 0.5),
            &[1000, 2000, 4000, 8000, 16000, 32000],
        ),
        (
            "steeply pleated fan",
            |n| pleated_fan(n, 0.2),
            &[1000, 2000, 4000, 8000, 16000, 32000],
        ),
        ("book", book, &[1000, 2000, 4000]),
    ];
    for (family, make, counts) in families {
        for &n in counts {
            let scene = make(n);
            let mut fx = None;
            let ms = cpu_ms(1, || {
                fx = Some(hider_plan::analyze(&scene, &RenderOptions::default()).unwrap())
            });
            let fx = fx.unwrap();
            let w = fx.work;
            println!(
                "| {family} | {n} | {} + {} | {} + {} | {} | {:.1} | {:.1} | {ms:.1} |",
                w.intersection_candidates,
                w.overlap_candidates,
                w.intersection_tests,
                w.overlap_tests,
                overlapping_pairs(&fx),
                fx.times.intersections_ms,
                fx.times.overlaps_ms,
            );
        }
    }
}

/// Section 2: the colour pass with the stages needed against all of them.
fn colour_pass() {
    println!("\n## colour pass: needed stages only vs unused stages forced on (512 x 512)");
    println!("| scene | stages needed | needed ms | all colour stages ms |");
    println!("|---|---|---|---|");
    for (name, scene) in [
        ("cube", procedural::cube()),
        ("uv_sphere(64)", procedural::uv_sphere(64)),
    ] {
        let analysis = analyze_prepared(&scene, &RenderOptions::default()).unwrap();
        let screen = &analysis.screen;
        let mut frame = ids(screen);
        let needed = analysis.effects.stages();
        let mut shader = Shader::default();
        let t_needed = best_of_20(|| {
            shader.shade(Prims::Screen(screen), &mut frame, &needed);
        });
        // Lighting forced on costs per primitive; a texture stage on a
        // scene without uvs costs a check per primitive and nothing per
        // pixel: the pass is the same one.
        let t_all = best_of_20(|| {
            shader.shade(Prims::Screen(screen), &mut frame, &Stages::ALL);
        });
        println!(
            "| {name} | {:?} | {t_needed:.2} | {t_all:.2} |",
            needed.names()
        );
    }
}

/// Section 5: the textured plane, the stage that does real work per pixel,
/// timed and drawn perspective-correct (left) beside affine (right).
fn checker_plane(out: &PathBuf) {
    let plane_path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/checker_plane.obj");
    let plane = load_obj(&plane_path).unwrap();
    let camera = Camera::perspective(DVec3::new(0.0, 0.5, 2.0), DVec3::ZERO, 0.1, 10.0);
    let options = RenderOptions::default()
        .with_size(256, 256)
        .with_camera(Some(camera));
    let analysis = analyze_prepared(&plane, &options).unwrap();
    let screen = &analysis.screen;
    let stages = analysis.effects.stages();
    let mut untextured = plane.clone();
    untextured.materials[0].diffuse_texture = None;
    let fx_plain = hider_plan::analyze(&untextured, &options).unwrap();
    let mut frame = ids(screen);
    let mut shader = Shader::new(ShaderOptions::default());
    let t_tex = best_of_20(|| {
        shader.shade(Prims::Screen(screen), &mut frame, &stages);
    });
    let t_plain = best_of_20(|| {
        shader.shade(Prims::Screen(screen), &mut frame, &fx_plain.stages());
    });
    println!(
        "| checker plane 256 x 256 | {:?} | {t_tex:.2} | without its texture ({:?}): {t_plain:.2} |",
        stages.names(),
        fx_plain.stages().names()
    );

    let mut picture = image::RgbaImage::new(512, 256);
    for (k, mapping) in [Mapping::PerspectiveCorrect, Mapping::Affine]
        .into_iter()
        .enumerate()
    {
        let mut frame = ids(screen);
        Shader::new(
            ShaderOptions::default()
                .with_filter(Filter::Bilinear)
                .with_mapping(mapping),
        )
        .shade(Prims::Screen(screen), &mut frame, &stages);
        for y in 0..256 {
            for x in 0..256 {
                let c = frame.color[frame.index(x, y)];
                picture.put_pixel(x + 256 * k as u32, y, image::Rgba(c));
            }
        }
    }
    picture.save(out).unwrap();
    println!("\nwrote {}", out.display());
}

fn main() {
    match std::env::args().nth(1).as_deref() {
        Some("stars") => return star_scaling(),
        Some("scaling") => return analysis_scaling(),
        _ => {}
    }
    let out = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/images/analysis-checker.png")
        });
    analysis_times();
    colour_pass();
    planner_cost();
    analysis_scaling();
    checker_plane(&out);
    star_scaling();
}
