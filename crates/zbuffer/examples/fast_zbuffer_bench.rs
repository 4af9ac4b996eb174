//! The benchmark of issue 12: the scenes of the llvmpipe comparison
//! (spider, UV sphere 200 and 500, random soup of 100,000 triangles) with
//! the fit camera at 512, 1024 and 2048, timed over the span a GL draw call
//! plus `glFinish` covers: everything after loading (transform, clip,
//! set-up; clear; rasterise), with the GL-compatible f32 front end.
//!
//! - `zbuffer`: the reference pipeline, [`prepare`] then [`ZBuffer`].
//! - `tiled 1T` / `tiled 2T`: the fast pipeline, [`prepare_depth_into`]
//!   then [`TiledZBuffer::draw_depth_scene`], on 1 thread (no pool) and on
//!   a 2-thread pool (front end and tiles in parallel, in that one pool:
//!   the hider uses the pool it is called from when it has the right
//!   number of threads). The image stays in
//!   the hider's tiles, as GL's stays in its framebuffer; the read-back is
//!   not timed, but it is checked equal to the reference, pixel for pixel,
//!   for every scene and size.
//!
//! Rounds are interleaved so that machine noise hits all three alike (in
//! each round a pipeline runs twice and the second, steady-state run is
//! timed); the table gives median (minimum) ms of `K` rounds, Mtri/s from
//! the median, and at 1024 the ratios to llvmpipe's and euc's figures from
//! the issue (above 1 = faster than them).
//!
//! `cargo run --release -p hider-zbuffer --example fast_zbuffer_bench [K] [SIZES...]`
//! (default K = 9, sizes 512 1024 2048).

use std::path::PathBuf;
use std::time::Instant;

use hider_scene::{
    DepthScene, Frame, Hider, PrepareOptions, Scene, View, load_obj, prepare, prepare_depth_into,
    procedural,
};
use hider_zbuffer::{TiledZBuffer, TiledZBufferOptions, ZBuffer};

/// Issue 12's figures at 1024: (scene, llvmpipe 1 thread, 2 threads, euc).
const FIGURES: [(&str, f64, f64, f64); 4] = [
    ("spider", 2.6, 1.8, 5.7),
    ("sphere 200", 20.0, 22.0, 13.6),
    ("sphere 500", 100.0, 59.0, 29.0),
    ("soup 100k", 117.0, 72.0, 298.0),
];

fn ms(t: Instant) -> f64 {
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

    let serial = PrepareOptions::gl_compatible();
    let parallel = serial.with_parallel(true);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build()?;
    println!(
        "median (min) ms of {runs} interleaved runs of prepare + clear + rasterise (f32 front end)\n"
    );
    println!(
        "| scene | triangles | size | zbuffer | tiled 1 thread | tiled 2 threads | Mtri/s 1T / 2T | speed-up 1T / 2T | vs llvmpipe 1T / 2T | vs euc 1T |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for &size in &sizes {
        for (name, scene) in &scenes {
            let view = View::for_scene(scene, size, size)?;
            let mut screen = prepare(scene, &view, &serial)?;
            let mut reference = ZBuffer::default();
            let mut want = Frame::new(size, size)?;
            reference.render(&screen, &mut want)?;
            let mut one = TiledZBuffer::new(TiledZBufferOptions::default().with_threads(1));
            let mut two = TiledZBuffer::new(TiledZBufferOptions::default().with_threads(2));
            let (mut lean1, mut lean2) = (DepthScene::new(), DepthScene::new());
            let mut got = Frame::new(size, size)?;
            // Warm-up, and the check that the fast pipeline's image is the
            // reference's.
            prepare_depth_into(scene, &view, &serial, &mut lean1)?;
            one.draw_depth_scene(&lean1)?;
            one.read_into(&mut got)?;
            assert!(got == want, "{name} at {size}: 1 thread differs");
            pool.install(|| {
                prepare_depth_into(scene, &view, &parallel, &mut lean2)?;
                two.draw_depth_scene(&lean2)
            })?;
            two.read_into(&mut got)?;
            assert!(got == want, "{name} at {size}: 2 threads differ");

            let (mut tz, mut t1, mut t2) = (Vec::new(), Vec::new(), Vec::new());
            for _ in 0..runs {
                // Each pipeline runs twice in a row and the second run is
                // timed: a frame loop's steady state, not the first frame
                // after another pipeline has filled the caches with its
                // own data (the rounds still interleave the three, so
                // machine noise hits them alike).
                for round in 0..2 {
                    let t = Instant::now();
                    hider_scene::prepare_into(scene, &view, &serial, &mut screen)?;
                    reference.render(&screen, &mut want)?;
                    if round == 1 {
                        tz.push(ms(t));
                    }
                }
                for round in 0..2 {
                    let t = Instant::now();
                    prepare_depth_into(scene, &view, &serial, &mut lean1)?;
                    one.draw_depth_scene(&lean1)?;
                    if round == 1 {
                        t1.push(ms(t));
                    }
                }
                for round in 0..2 {
                    let t = Instant::now();
                    pool.install(|| {
                        prepare_depth_into(scene, &view, &parallel, &mut lean2)?;
                        two.draw_depth_scene(&lean2)
                    })?;
                    if round == 1 {
                        t2.push(ms(t));
                    }
                }
            }
            let ((mz, nz), (m1, n1), (m2, n2)) = (stats(tz), stats(t1), stats(t2));
            let tris = scene.triangle_count() as f64;
            let vs = FIGURES
                .iter()
                .find(|f| f.0 == *name && size == 1024)
                .map_or("- | -".to_owned(), |f| {
                    format!("{:.2}x / {:.2}x | {:.2}x", f.1 / m1, f.2 / m2, f.3 / m1)
                });
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
