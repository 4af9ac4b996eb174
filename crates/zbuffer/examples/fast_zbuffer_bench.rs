//! The benchmark of issue 12: the scenes of the llvmpipe comparison
//! (spider, UV sphere 200 and 500, random soup of 100,000 triangles) with
//! the fit camera at 512, 1024 and 2048, rendered by the reference
//! [`ZBuffer`] and by [`TiledZBuffer`] on 1 and 2 threads, runs interleaved
//! so that machine noise hits all three alike. Render only (clear +
//! rasterise; prepare excluded), median and minimum ms of `K` runs after a
//! warm-up, Mtri/s from the median, and at 1024 the ratios to llvmpipe's
//! and euc's figures from the issue. Every frame is checked equal to the
//! reference's.
//!
//! `cargo run --release -p hider-zbuffer --example fast_zbuffer_bench [K] [SIZES...]`
//! (default K = 9, sizes 512 1024 2048).

use std::path::PathBuf;
use std::time::Instant;

use hider_scene::{
    Frame, Hider, PrepareOptions, Scene, ScreenScene, View, load_obj, prepare, procedural,
};
use hider_zbuffer::{TiledZBuffer, TiledZBufferOptions, ZBuffer};

/// Issue 12's figures at 1024: (scene, llvmpipe 1 thread, 2 threads, euc).
const FIGURES: [(&str, f64, f64, f64); 4] = [
    ("spider", 2.6, 1.8, 5.7),
    ("sphere 200", 20.0, 22.0, 13.6),
    ("sphere 500", 100.0, 59.0, 29.0),
    ("soup 100k", 117.0, 72.0, 298.0),
];

fn time(h: &mut dyn Hider, s: &ScreenScene, f: &mut Frame) -> f64 {
    let t = Instant::now();
    h.render(s, f).expect("render");
    t.elapsed().as_secs_f64() * 1e3
}

fn stats(mut v: Vec<f64>) -> (f64, f64) {
    v.sort_by(f64::total_cmp);
    (v[v.len() / 2], v[0])
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let runs: usize = args.first().and_then(|a| a.parse().ok()).unwrap_or(9);
    let mut sizes: Vec<u32> = args.iter().skip(1).filter_map(|a| a.parse().ok()).collect();
    if sizes.is_empty() {
        sizes = vec![512, 1024, 2048];
    }
    let spider = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/gl-reference/models/spider.obj");
    let mut scenes: Vec<(&str, Scene)> = Vec::new();
    if spider.exists() {
        scenes.push(("spider", load_obj(&spider)?));
    } else {
        eprintln!("skipped the spider: {} not found", spider.display());
    }
    scenes.push(("sphere 200", procedural::uv_sphere(200)));
    scenes.push(("sphere 500", procedural::uv_sphere(500)));
    scenes.push(("soup 100k", procedural::random_soup(100_000, 1)));

    println!("median (min) ms of {runs} interleaved runs, render only (clear + rasterise)\n");
    println!(
        "| scene | triangles | size | zbuffer | tiled 1 thread | tiled 2 threads | Mtri/s 1T / 2T | speed-up 1T / 2T | vs llvmpipe 1T / 2T | vs euc 1T |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for &size in &sizes {
        for (name, scene) in &scenes {
            let view = View::for_scene(scene, size, size)?;
            let screen = prepare(scene, &view, &PrepareOptions::default())?;
            let mut reference = ZBuffer::default();
            let mut one = TiledZBuffer::new(TiledZBufferOptions::default().with_threads(1));
            let mut two = TiledZBuffer::new(TiledZBufferOptions::default().with_threads(2));
            let mut want = Frame::new(size, size)?;
            let mut got = Frame::new(size, size)?;
            reference.render(&screen, &mut want)?;
            for h in [&mut one as &mut dyn Hider, &mut two] {
                h.render(&screen, &mut got)?;
                assert!(
                    got == want,
                    "{name} at {size}: {} differs from the reference",
                    h.name()
                );
            }
            let (mut tz, mut t1, mut t2) = (Vec::new(), Vec::new(), Vec::new());
            for _ in 0..runs {
                tz.push(time(&mut reference, &screen, &mut want));
                t1.push(time(&mut one, &screen, &mut got));
                t2.push(time(&mut two, &screen, &mut got));
            }
            let ((mz, nz), (m1, n1), (m2, n2)) = (stats(tz), stats(t1), stats(t2));
            let tris = scene.triangle_count() as f64;
            let vs = FIGURES
                .iter()
                .find(|f| f.0 == *name && size == 1024)
                .map_or("-".to_owned(), |f| {
                    format!("{:.1}x / {:.1}x | {:.1}x", f.1 / m1, f.2 / m2, f.3 / m1)
                });
            let vs = if vs == "-" { "- | -".to_owned() } else { vs };
            println!(
                "| {name} | {} | {size} | {mz:.2} ({nz:.2}) | {m1:.2} ({n1:.2}) | {m2:.2} ({n2:.2}) | {:.0} / {:.0} | {:.1}x / {:.1}x | {vs} |",
                scene.triangle_count(),
                tris / m1 / 1e3,
                tris / m2 / 1e3,
                mz / m1,
                mz / m2,
            );
        }
    }
    Ok(())
}
