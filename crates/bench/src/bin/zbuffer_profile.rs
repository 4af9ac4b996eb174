//! Renders one scene of the benchmark a few times with one hider, for
//! profilers (`valgrind --tool=callgrind`, `perf record`).
//!
//! `cargo run --release -p hider-bench --bin zbuffer_profile -- SCENE HIDER [SIZE] [RUNS] [THREADS]`
//! with SCENE one of `spider`, `sphere200`, `sphere500`, `soup`, and HIDER
//! `zbuffer`, `tiled` (both on the full front end's scene, render only) or
//! `lean` (the tiled hider's own pipeline: lean front end, then a draw
//! into its tiles; prints both times) or `frame` (that pipeline with the
//! read-back: `render_scene` into a frame of every buffer, one thread, in
//! the thread's CPU time, with the median last).

use std::time::Instant;

use hider_bench::programs;
use hider_scene::{
    DynHider, Frame, Hider, PrepareOptions, Scene, ScreenScene, View, prepare, procedural,
};
use hider_zbuffer::{DepthScene, TiledZBuffer, TiledZBufferOptions, ZBuffer, prepare_depth_into};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize, default: &str| args.get(i).cloned().unwrap_or_else(|| default.to_owned());
    let size: u32 = arg(2, "1024").parse()?;
    let runs: usize = arg(3, "3").parse()?;
    let threads: usize = arg(4, "1").parse()?;
    let scene: Scene = match arg(0, "sphere500").as_str() {
        "spider" => programs::spider()?,
        "sphere200" => procedural::uv_sphere(200),
        "sphere500" => procedural::uv_sphere(500),
        "soup" => procedural::random_soup(100_000, 1),
        other => return Err(format!("unknown scene {other}").into()),
    };
    let view = View::for_scene(&scene, size, size)?;
    if arg(1, "tiled") == "frame" {
        let options = PrepareOptions::gl_compatible();
        let mut tiled = TiledZBuffer::new(TiledZBufferOptions::default().with_threads(1));
        let mut screen = ScreenScene::empty(&view);
        let mut frame = Frame::new(size, size)?;
        let mut times = Vec::with_capacity(runs);
        for _ in 0..runs {
            // This thread's CPU time (other processes on the machine do
            // not count), wall time where the platform has no such clock.
            let t = Instant::now();
            let start = programs::thread_cpu_seconds();
            let stats =
                Hider::render_scene(&mut tiled, &scene, &view, &options, &mut screen, &mut frame)?;
            let ms = match (start, programs::thread_cpu_seconds()) {
                (Some(a), Some(b)) => (b - a) * 1e3,
                _ => t.elapsed().as_secs_f64() * 1e3,
            };
            times.push(ms);
            println!("{ms:.2} ms  {stats:?}");
        }
        times.sort_by(f64::total_cmp);
        if let Some(m) = times.get(times.len() / 2) {
            println!("median {m:.3} ms of {runs} frames");
        }
        return Ok(());
    }
    if arg(1, "tiled") == "lean" {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()?;
        let options = PrepareOptions::gl_compatible().with_parallel(threads > 1);
        let mut tiled = TiledZBuffer::new(TiledZBufferOptions::default().with_threads(threads));
        let mut lean = DepthScene::new();
        // On one thread, CPU time of this thread (so that other processes
        // on the machine do not count); wall time otherwise.
        let clock = |t: Instant| {
            if threads == 1 {
                programs::thread_cpu_seconds().unwrap_or_else(|| t.elapsed().as_secs_f64()) * 1e3
            } else {
                t.elapsed().as_secs_f64() * 1e3
            }
        };
        for _ in 0..runs {
            let t = Instant::now();
            let start = clock(t);
            // Front end and draw in the one pool (the hider uses the pool
            // it is called from): a second pool would take turns with it.
            let mut frame = || {
                prepare_depth_into(&scene, &view, &options, &mut lean)?;
                let prepared = clock(t) - start;
                tiled.draw_depth_scene(&lean).map(|s| (prepared, s))
            };
            // One thread: on this thread, whose CPU time `clock` reads.
            let (prepared, stats) = if threads == 1 {
                frame()?
            } else {
                pool.install(frame)?
            };
            let total = clock(t) - start;
            println!(
                "{total:.2} ms = prepare {prepared:.2} + draw {:.2}  {:?} {:?}",
                total - prepared,
                lean.stats,
                stats
            );
        }
        return Ok(());
    }
    let mut hider: Box<dyn DynHider> = match arg(1, "tiled").as_str() {
        "zbuffer" => Box::new(ZBuffer::default()),
        "tiled" => Box::new(TiledZBuffer::new(
            TiledZBufferOptions::default().with_threads(threads),
        )),
        other => return Err(format!("unknown hider {other}").into()),
    };
    let screen = prepare(&scene, &view, &PrepareOptions::default())?;
    let mut frame = Frame::new(size, size)?;
    for _ in 0..runs {
        let t = Instant::now();
        let stats = hider.render(&screen, &mut frame)?;
        println!(
            "{:.2} ms  {:?}",
            t.elapsed().as_secs_f64() * 1e3,
            stats.counters
        );
    }
    Ok(())
}
