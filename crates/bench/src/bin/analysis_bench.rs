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
//! 3. The checkerboard plane at a grazing angle, perspective-correct
//!    beside affine, written to `OUT.png` (default
//!    `docs/images/analysis-checker.png`).

use std::path::PathBuf;

use glam::DVec3;
use hider_plan::{RenderOptions, analyze_prepared};
use hider_scene::geom::Camera;
use hider_scene::shade::{Filter, Mapping, Prims, Shader, ShaderOptions, Stages};
use hider_scene::{Frame, Hider, ScreenScene, load_obj, procedural};
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

/// Section 3: the textured plane, the stage that does real work per pixel,
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
    let out = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| {
            PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/images/analysis-checker.png")
        });
    analysis_times();
    colour_pass();
    checker_plane(&out);
}
