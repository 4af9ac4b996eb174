//! Makes the pictures and numbers of `docs/oracle.md` and
//! `docs/hard-cases.md`:
//! - `docs/images/oracle-hard-cases.png`: every hard case rendered by the
//!   ray-cast oracle (flat shading), tie pixels in magenta;
//! - `docs/images/oracle-coverage.png`: the exact box-filtered image of the
//!   interpenetrating boxes from analytic coverage, next to the pixel-centre one;
//! - timings of the oracle and of analytic coverage, and how often the
//!   source-plane oracle disagrees with the snapped-plane one.
//!
//! `cargo run --release -p hider-oracle --example oracle_picture`

use std::path::PathBuf;
use std::time::Instant;

use hider_oracle::{
    DEFAULT_TIE_TOLERANCE, DepthPlane, OracleOptions, RayCastOracle, analytic_coverage,
};
use hider_scene::shade::{prim_color, to_srgb8};
use hider_scene::{
    Frame, Hider, NO_ID, PrepareOptions, Scene, ScreenScene, ShadeMode, View, hard_cases, prepare,
    procedural,
};

fn screen(scene: &Scene, size: u32) -> Result<ScreenScene, hider_scene::Error> {
    let view = View::for_scene(scene, size, size)?;
    prepare(scene, &view, &PrepareOptions::default())
}

fn colour(s: &ScreenScene, id: u32) -> [f32; 3] {
    prim_color(s, id, ShadeMode::Lambert).0
}

fn srgb(c: [f32; 3]) -> [u8; 4] {
    [to_srgb8(c[0]), to_srgb8(c[1]), to_srgb8(c[2]), 255]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let images = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/images");
    std::fs::create_dir_all(&images)?;

    // Contact sheet of the hard cases.
    let (tile, cols) = (84u32, 6u32);
    let cases = hard_cases::all(1);
    let rows = (cases.len() as u32).div_ceil(cols);
    let mut sheet = Frame::new(tile * cols, tile * rows)?;
    for (n, (name, scene)) in cases.iter().enumerate() {
        let s = screen(scene, tile)?;
        let r = RayCastOracle::default().evaluate(&s);
        let (ox, oy) = ((n as u32 % cols) * tile, (n as u32 / cols) * tile);
        for y in 0..tile {
            for x in 0..tile {
                let k = (y * tile + x) as usize;
                let c = match r.ids[k] {
                    NO_ID => [24, 24, 32, 255],
                    _ if r.gap[k] < DEFAULT_TIE_TOLERANCE => [255, 0, 255, 255],
                    id => srgb(colour(&s, id)),
                };
                let i = sheet.index(ox + x, oy + y);
                sheet.color[i] = c;
            }
        }
        println!(
            "{name:<24} {:>6} tris, {:>5} covered, {:>4} ties",
            s.tris.len(),
            r.covered_count(),
            r.tie_count(DEFAULT_TIE_TOLERANCE)
        );
    }
    sheet.write_png(&images.join("oracle-hard-cases.png"))?;

    // Exact box filter vs pixel centres, magnified.
    let (size, zoom) = (40u32, 6u32);
    let s = screen(&hard_cases::interpenetrating_boxes(3, 4), size)?;
    let r = RayCastOracle::default().evaluate(&s);
    let cov = analytic_coverage(&s);
    let mut pic = Frame::new(2 * size * zoom + zoom, size * zoom)?;
    for y in 0..size {
        for x in 0..size {
            let k = (y * size + x) as usize;
            let centre = if r.ids[k] == NO_ID {
                [0, 0, 0, 255]
            } else {
                srgb(colour(&s, r.ids[k]))
            };
            let mut acc = [0.0f32; 3];
            for (prim, a) in cov.pixel_fragments(x, y) {
                let c = colour(&s, prim);
                (0..3).for_each(|i| acc[i] += c[i] * a as f32);
            }
            let boxed = srgb(acc);
            for dy in 0..zoom {
                for dx in 0..zoom {
                    let i = pic.index(x * zoom + dx, y * zoom + dy);
                    pic.color[i] = centre;
                    let j = pic.index((size + 1 + x) * zoom + dx, y * zoom + dy);
                    pic.color[j] = boxed;
                }
            }
        }
    }
    pic.write_png(&images.join("oracle-coverage.png"))?;

    // Timings.
    for (count, size) in [(10_000u32, 128u32), (79_600, 128)] {
        let scene = if count == 79_600 {
            procedural::uv_sphere(200)
        } else {
            hard_cases::heavy_overdraw(count, 1)
        };
        let s = screen(&scene, size)?;
        let t = Instant::now();
        let r = RayCastOracle::default().evaluate(&s);
        println!(
            "oracle: {count} triangles (heavy overdraw / uv sphere) at {size}x{size}: {:.1} ms, {} pixel tests, {} ties",
            t.elapsed().as_secs_f64() * 1e3,
            RayCastOracle::pixel_tests(&s),
            r.tie_count(DEFAULT_TIE_TOLERANCE)
        );
    }
    for (name, scene, size) in [
        ("random_soup(200)", procedural::random_soup(200, 1), 64u32),
        ("random_soup(1000)", procedural::random_soup(1000, 1), 64),
        ("uv_sphere(24)", procedural::uv_sphere(24), 64),
    ] {
        let s = screen(&scene, size)?;
        let t = Instant::now();
        let c = analytic_coverage(&s);
        println!(
            "analytic coverage: {name} at {size}x{size}: {:.1} ms, {} fragments",
            t.elapsed().as_secs_f64() * 1e3,
            c.fragments.len()
        );
    }

    // What snapping does: source-plane oracle vs snapped-plane oracle.
    for (name, scene) in hard_cases::all(1) {
        let s = screen(&scene, 64)?;
        let snapped = RayCastOracle::default().evaluate(&s);
        let source =
            RayCastOracle::new(OracleOptions::default().with_depth_plane(DepthPlane::Source))
                .evaluate(&s);
        let mut differ = 0;
        let mut worst: f64 = 0.0;
        for k in 0..snapped.ids.len() {
            if snapped.ids[k] != source.ids[k] && snapped.gap[k] >= DEFAULT_TIE_TOLERANCE {
                differ += 1;
                worst = worst.max(source.gap[k].min(snapped.gap[k]));
            }
        }
        if differ > 0 {
            println!(
                "source vs snapped plane: {name}: {differ} non-tie pixels differ, largest gap {worst:.1e}"
            );
        }
    }
    Ok(())
}
