//! Measures the scene analysis and the effect stages, and draws the
//! picture of `docs/analysis.md`.
//!
//! ```text
//! cargo run --release -p hider-scene --example analysis [OUT.png]
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
use std::time::Instant;

use glam::DVec3;
use hider_scene::geom::{Camera, Projection};
use hider_scene::stages::Mapping;
use hider_scene::texture::Filter;
use hider_scene::{
    Frame, NO_ID, PrepareOptions, RenderOptions, ScreenScene, Shader, ShaderOptions, Stages,
    analyze, load_obj, prepare, procedural,
};

/// Nearest primitive per pixel centre by brute force over a tile of
/// candidates: enough for the example's small scenes (the scene crate has
/// no hider of its own).
fn ids(screen: &ScreenScene) -> Frame {
    let vp = screen.viewport;
    let mut frame = Frame::new(vp.width, vp.height).unwrap();
    for t in &screen.tris {
        let Some((x0, y0, x1, y1)) = t.pixel_bounds(vp) else {
            continue;
        };
        let edges = t.edges();
        for j in y0..=y1 {
            for i in x0..=x1 {
                let (x, y) = (i64::from(i) * 256 + 128, i64::from(j) * 256 + 128);
                if edges.iter().all(|e| e.contains(x, y)) {
                    let k = frame.index(i, j);
                    let d = t.depth.at_pixel(i, j) as f32;
                    if frame.ids[k] == NO_ID || d < frame.depth[k] {
                        frame.ids[k] = t.prim;
                        frame.depth[k] = d;
                    }
                }
            }
        }
    }
    frame
}

fn best_of<F: FnMut()>(runs: usize, mut f: F) -> f64 {
    (0..runs)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64() * 1e3
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    let out = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("docs/images/analysis-checker.png"));

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
        let fx = analyze(&scene, &RenderOptions::default()).unwrap();
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

    println!("\n## colour pass: needed stages only vs unused stages forced on (512 x 512)");
    println!("| scene | stages needed | needed ms | all colour stages ms |");
    println!("|---|---|---|---|");
    for (name, scene) in [
        ("cube", procedural::cube()),
        ("uv_sphere(64)", procedural::uv_sphere(64)),
    ] {
        let options = RenderOptions::default();
        let fx = analyze(&scene, &options).unwrap();
        let view = options.view(&scene).unwrap();
        let screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
        let mut frame = ids(&screen);
        let needed = Stages::for_effects(&fx);
        let mut shader = Shader::default();
        let t_needed = best_of(20, || {
            shader.shade(&screen, &mut frame, &needed);
        });
        // Lighting forced on costs per primitive; a texture stage on a
        // scene without uvs costs a check per primitive and nothing per
        // pixel: the pass is the same one.
        let t_all = best_of(20, || {
            shader.shade(&screen, &mut frame, &Stages::ALL);
        });
        println!(
            "| {name} | {:?} | {t_needed:.2} | {t_all:.2} |",
            needed.names()
        );
    }

    // The textured plane: the stage that does real work per pixel.
    let plane_path =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/checker_plane.obj");
    let plane = load_obj(&plane_path).unwrap();
    let camera = Camera {
        eye: DVec3::new(0.0, 0.5, 2.0),
        target: DVec3::ZERO,
        up: DVec3::Y,
        projection: Projection::Perspective {
            fovy_degrees: 60.0,
            near: 0.1,
            far: 10.0,
        },
    };
    let options = RenderOptions::default()
        .with_size(256, 256)
        .with_camera(Some(camera));
    let fx = analyze(&plane, &options).unwrap();
    let view = options.view(&plane).unwrap();
    let screen = prepare(&plane, &view, &PrepareOptions::default()).unwrap();
    let stages = Stages::for_effects(&fx);
    let mut untextured = plane.clone();
    untextured.materials[0].diffuse_texture = None;
    let fx_plain = analyze(&untextured, &options).unwrap();
    let mut frame = ids(&screen);
    let mut shader = Shader::new(ShaderOptions::default());
    let t_tex = best_of(20, || {
        shader.shade(&screen, &mut frame, &stages);
    });
    let t_plain = best_of(20, || {
        shader.shade(&screen, &mut frame, &Stages::for_effects(&fx_plain));
    });
    println!(
        "| checker plane 256 x 256 | {:?} | {t_tex:.2} | without its texture ({:?}): {t_plain:.2} |",
        stages.names(),
        Stages::for_effects(&fx_plain).names()
    );

    // The picture: perspective-correct (left) and affine (right).
    let mut picture = image::RgbaImage::new(512, 256);
    for (k, mapping) in [Mapping::PerspectiveCorrect, Mapping::Affine]
        .into_iter()
        .enumerate()
    {
        let mut frame = ids(&screen);
        Shader::new(
            ShaderOptions::default()
                .with_filter(Filter::Bilinear)
                .with_mapping(mapping),
        )
        .shade(&screen, &mut frame, &stages);
        for y in 0..256 {
            for x in 0..256 {
                let c = frame.color[frame.index(x, y)];
                picture.put_pixel(x + 256 * k as u32, y, image::Rgba(c));
            }
        }
    }
    picture.save(&out).unwrap();
    println!("\nwrote {}", out.display());
}
