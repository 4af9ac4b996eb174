//! The scanline against the z-buffer (`hider-zbuffer`, f32 and f64 depth)
//! on scenes with few large polygons and with many small ones.
//!
//! `cargo run --release -p hider-bench --bin scanline_versus_zbuffer -- [SIZE] [FILTER]`
//! (a program of the benchmark package, which links both hiders: neither
//! algorithm crate depends on the other)
//! (FILTER keeps the scenes whose name contains it).
//!
//! Prints, per scene and hider, the fastest frame of repeated runs (after
//! a warm-up, about 0.5 s per hider and scene; the minimum, because on a
//! shared machine every disturbance only adds time) with the shared timer
//! of `hider-testkit`, and the counters that explain it.
//! Both hiders write the same ids (checked here); the table is for the
//! closing note of `docs/scanline.md`.

use hider_scanline::{Scanline, ScanlineStats};
use hider_scene::geom::Camera;
use hider_scene::geom::glam::DVec3;
use hider_scene::{
    Frame, Hider, Mesh, PrepareOptions, Scene, ScreenScene, View, prepare, procedural,
};
use hider_testkit::timer::Timer;
use hider_zbuffer::{DepthFormat, ZBuffer, ZBufferOptions};

/// `layers` screen-filling quads one behind the other; `tilt` (radians)
/// turns every other one about the vertical axis so that neighbours
/// interpenetrate.
fn layers(layers: u32, tilt: f64) -> Scene {
    let mut s = Scene::default();
    for k in 0..layers {
        let z = -0.25 * f64::from(k);
        let a = if k % 2 == 0 { tilt } else { -tilt };
        let corner = |x: f64, y: f64| DVec3::new(x * a.cos(), y, z + x * a.sin());
        s.push_mesh(
            Mesh {
                name: format!("layer{k}"),
                positions: vec![
                    corner(-4.0, -4.0),
                    corner(4.0, -4.0),
                    corner(4.0, 4.0),
                    corner(-4.0, 4.0),
                ],
                indices: vec![[0, 1, 2], [0, 2, 3]],
                ..Mesh::default()
            },
            None,
        );
    }
    s
}

fn front_camera() -> Camera {
    hider_testkit::cameras::look_at(DVec3::new(0.0, 0.0, 3.0), DVec3::ZERO, 0.5, 20.0)
}

/// Milliseconds per frame: the fastest of up to 1000 runs within
/// `budget` seconds, after one warm-up run.
fn time<H: Hider>(hider: &mut H, s: &ScreenScene, frame: &mut Frame, budget: f64) -> f64 {
    Timer::new(1000)
        .with_max_seconds(budget)
        .time(|| {
            hider.render(s, frame).expect("render");
        })
        .min_ms
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let size: u32 = std::env::args().nth(1).map_or(Ok(512), |a| a.parse())?;
    let filter = std::env::args().nth(2).unwrap_or_default();
    let budget = 0.5;
    let scenes: Vec<(&str, Scene, Option<Camera>)> = vec![
        (
            "2 layers (4 big tris)",
            layers(2, 0.0),
            Some(front_camera()),
        ),
        (
            "8 layers (16 big tris)",
            layers(8, 0.0),
            Some(front_camera()),
        ),
        (
            "8 tilted layers, piercing",
            layers(8, 0.3),
            Some(front_camera()),
        ),
        ("intersecting pair", procedural::intersecting_pair(), None),
        ("uv sphere 40 (3k tris)", procedural::uv_sphere(40), None),
        ("uv sphere 200 (80k tris)", procedural::uv_sphere(200), None),
        (
            "soup 20k small tris",
            procedural::random_soup(20_000, 1),
            None,
        ),
        (
            "soup 200k small tris",
            procedural::random_soup(200_000, 1),
            None,
        ),
    ];
    println!(
        "| scene ({size}x{size}) | tris | covered px | scanline ms | zbuffer f32 ms | zbuffer f64 ms | scan/z32 | spans | px/span | split spans | active polys/row (mean, max) | z depth tests |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for (name, scene, camera) in scenes {
        if !name.contains(&filter) {
            continue;
        }
        let view = match camera {
            Some(c) => View::new(c, size, size)?,
            None => View::for_scene(&scene, size, size)?,
        };
        let s = prepare(&scene, &view, &PrepareOptions::default())?;
        let mut frame = Frame::new(size, size)?;
        let mut scan = Scanline::default();
        let st: ScanlineStats = scan.render(&s, &mut frame)?;
        let ids = frame.ids.clone();
        let t_scan = time(&mut scan, &s, &mut frame, budget);
        let mut z32 = ZBuffer::new(ZBufferOptions::default());
        let zst = z32.render(&s, &mut frame)?;
        let t_z32 = time(&mut z32, &s, &mut frame, budget);
        let mut z64 = ZBuffer::new(ZBufferOptions::default().with_depth_format(DepthFormat::F64));
        z64.render(&s, &mut frame)?;
        let differ = ids.iter().zip(&frame.ids).filter(|(a, b)| a != b).count();
        let t_z64 = time(&mut z64, &s, &mut frame, budget);
        println!(
            "| {name}{} | {} | {} | {:.3} | {:.3} | {:.3} | {:.2} | {} | {:.1} | {} | {:.1}, {} | {} |",
            if differ > 0 {
                format!(" ({differ} px differ from z-f64)")
            } else {
                String::new()
            },
            s.tris.len(),
            st.pixels_written,
            t_scan,
            t_z32,
            t_z64,
            t_scan / t_z32,
            st.spans,
            st.pixels_written as f64 / st.spans.max(1) as f64,
            st.split_spans,
            st.active_polygons_mean(),
            st.active_polygons_max,
            zst.depth_tests,
        );
    }
    Ok(())
}
