//! Regions and lines SVG against the painter's SVG: file size, path
//! count and time, on the two intersecting 100 x 100 surface grids
//! (39,204 triangles), the spider and a 100k-triangle UV sphere; with
//! `--edge-on` also the grids seen exactly along the tilted sheet.
//!
//! `cargo run --release -p hider-bench --bin vector_bench -- [--edge-on] [spider.obj] [size]`
//! (default spider: the bundled `assets/spider/spider.obj`, size 800).
//! Times are the best of three runs, in this process, so the ratios are
//! same-run ratios.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use glam::DVec3;
use hider_painter::Painter;
use hider_scene::{
    Frame, Hider, Material, Mesh, PrepareOptions, Scene, ScreenScene, ShadeMode, View, load_obj,
    prepare, procedural,
};
use hider_vector::{VectorOptions, hidden_lines, lines_svg, regions_svg, visible_regions};

/// A sheet: its name, colour and height over the ground plane.
type Sheet = (&'static str, [f32; 3], fn(f64, f64) -> f64);

/// Two height-field grids of `n x n` vertices crossing each other: a
/// rippled sheet and a tilted one, as in a scientific 3D figure.
fn intersecting_grids(n: u32) -> Scene {
    let mut scene = Scene::default();
    let sheets: [Sheet; 2] = [
        ("ripple", [0.85, 0.45, 0.2], |x, z| {
            0.25 * (3.0 * x).sin() * (2.0 * z).cos()
        }),
        ("tilted", [0.2, 0.45, 0.85], |x, z| 0.4 * x - 0.2 * z),
    ];
    for (name, colour, height) in sheets {
        let mut positions = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let x = -1.0 + 2.0 * f64::from(i) / f64::from(n - 1);
                let z = -1.0 + 2.0 * f64::from(j) / f64::from(n - 1);
                positions.push(DVec3::new(x, height(x, z), z));
            }
        }
        let mut indices = Vec::new();
        for j in 0..n - 1 {
            for i in 0..n - 1 {
                let k = j * n + i;
                indices.push([k, k + n, k + 1]);
                indices.push([k + 1, k + n, k + n + 1]);
            }
        }
        let mesh = Mesh {
            name: name.into(),
            positions,
            indices,
            ..Mesh::default()
        };
        scene.push_mesh(
            mesh,
            Some(Material {
                name: name.into(),
                diffuse: colour,
                ..Material::default()
            }),
        );
    }
    // A figure's usual view: from above and aside, not edge-on.
    scene.camera = Some(hider_geom::Camera::perspective(
        DVec3::new(2.2, 2.4, 3.0),
        DVec3::ZERO,
        0.5,
        20.0,
    ));
    scene
}

fn best_of<T>(runs: u32, mut f: impl FnMut() -> T) -> (T, Duration) {
    let mut best = Duration::MAX;
    let mut out = None;
    for _ in 0..runs {
        let start = Instant::now();
        let value = f();
        best = best.min(start.elapsed());
        out = Some(value);
    }
    (out.expect("at least one run"), best)
}

fn painter_svg(s: &ScreenScene) -> Result<String, hider_scene::Error> {
    let mut painter = Painter::default();
    let mut frame = Frame::new(s.viewport.width, s.viewport.height)?;
    painter.render(s, &mut frame)?;
    let path =
        std::env::temp_dir().join(format!("vector-bench-painter-{}.svg", std::process::id()));
    painter
        .ordered_polygons()
        .expect("the painter writes SVG")
        .write_svg(s, &path, ShadeMode::Lambert)?;
    let text = std::fs::read_to_string(&path).map_err(|source| hider_scene::Error::Io {
        path: path.clone(),
        source,
    })?;
    let _ = std::fs::remove_file(&path);
    Ok(text)
}

fn main() -> Result<(), hider_scene::Error> {
    let mut args: Vec<String> = std::env::args().collect();
    let edge_on = args.iter().any(|a| a == "--edge-on");
    args.retain(|a| a != "--edge-on");
    let spider = args
        .get(1)
        .map_or_else(hider_bench::programs::spider_path, PathBuf::from);
    let size: u32 = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(800);
    let mut scenes = vec![("intersecting grids", intersecting_grids(100))];
    if edge_on {
        // The same grids from a point of the tilted sheet's plane, which
        // sees that sheet exactly edge-on: a pile of slivers along a line.
        let mut grids = intersecting_grids(100);
        grids.camera = Some(hider_geom::Camera::perspective(
            DVec3::new(3.0, 0.6, 3.0),
            DVec3::ZERO,
            0.5,
            20.0,
        ));
        scenes.push(("intersecting grids, edge-on", grids));
    }
    if spider.exists() {
        scenes.push(("spider", load_obj(&spider)?));
    } else {
        println!("(no spider at {}, skipped)", spider.display());
    }
    scenes.push(("uv sphere", procedural::uv_sphere(224)));
    let options = VectorOptions::default();
    println!(
        "| scene | triangles | painter pieces | painter SVG | painter ms | region paths | regions SVG | regions ms | ratio | lines | lines SVG | lines ms |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (name, scene) in scenes {
        let view = View::for_scene(&scene, size, size)?;
        let s = prepare(&scene, &view, &PrepareOptions::default())?;
        let (painter, painter_time) = best_of(3, || painter_svg(&s));
        let painter = painter?;
        let (regions, regions_time) = best_of(3, || {
            visible_regions(&s, &options, ShadeMode::Lambert)
                .map(|map| (regions_svg(&s, &map, &options), map))
        });
        let (regions, map) = regions?;
        let (lines, lines_time) = best_of(3, || {
            hidden_lines(&s, &map, &options).map(|d| (lines_svg(&s, &d, &options), d))
        });
        let (lines, drawing) = lines?;
        let ms = |d: Duration| d.as_secs_f64() * 1e3;
        let kb = |t: &str| t.len() as f64 / 1024.0;
        println!(
            "| {name} | {} | {} | {:.0} KiB | {:.0} | {} | {:.0} KiB | {:.0} | {:.2} | {} | {:.0} KiB | {:.0} |",
            s.tris.len(),
            painter.matches("<path").count(),
            kb(&painter),
            ms(painter_time),
            map.groups.len(),
            kb(&regions),
            ms(regions_time),
            ms(regions_time) / ms(painter_time),
            drawing.visible.len(),
            kb(&lines),
            ms(lines_time),
        );
        eprintln!(
            "{name}: regions {}; lines {}",
            hider_scene::HiderStats::table(&map.stats),
            hider_scene::HiderStats::table(&drawing.stats)
        );
    }
    Ok(())
}
