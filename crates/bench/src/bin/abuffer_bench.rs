//! The benchmark of the A-buffer's targets against llvmpipe's 4x MSAA and
//! the tiled z-buffer: the scenes of the llvmpipe comparison (spider, UV
//! sphere 200 and 500, random soup of 100,000 triangles) with the fit
//! camera, timed over the span a GL draw call, its resolve and `glFinish`
//! cover: everything after loading (`Hider::render_scene` with the f32
//! GL-compatible options: the lean front end, then bins, tiles, lists,
//! resolve into the frame).
//!
//! - `abuffer 1T` / `2T`: the exact A-buffer (per-sample depth) on 1
//!   thread (no pool) and in a 2-thread pool (front end and bands in
//!   parallel, in that pool);
//! - `carpenter 1T`: [`ABufferOptions::carpenter`] (`zmin`/`zmax`
//!   fragments, same-surface merging) on 1 thread;
//! - `lists 1T`: the exact A-buffer with every tile on fragment lists
//!   ([`ABufferOptions::with_sample_tiles`] off), what it was before
//!   opaque tiles took the sample buffer, and what Carpenter's
//!   configuration (lists always) compares with like for like;
//! - `lean 1T`: the lean front end alone, storing its triangles
//!   (`render_scene` runs it binning each triangle as it is set up
//!   instead), to show its share; `prepare 1T`: the shared front end
//!   `prepare` alone, which the A-buffer ran before it had the lean one.
//!
//! Same run, same machine: with `--peers-bin PATH` (the `peers` package's
//! binary) each round runs llvmpipe with 4x MSAA (`--msaa`) on 1 and 2
//! threads, and with `--zbuffer-bin PATH` (the tiled z-buffer's benchmark,
//! `target/release/fast_zbuffer_bench` of this package) each round times
//! the tiled z-buffer on the same scenes and span; the table gives the
//! medians over the rounds and the target ratios. Rounds interleave everything, so machine noise
//! hits all alike; per round each pipeline renders for a 40 ms warm-up,
//! then at least [`TIMED`] frames and [`TIMED_SPAN`] of them, timed.
//!
//! `cargo run --release -p hider-bench --bin abuffer_bench -- [ROUNDS] [SIZE] [--peers-bin PATH] [--zbuffer-bin PATH]`
//! (default 5 rounds at 1024).

use std::process::Command;
use std::time::{Duration, Instant};

use hider_abuffer::{ABuffer, ABufferOptions};
use hider_bench::programs;
use hider_scene::prepare::lean::{LeanScene, prepare_lean_into};
use hider_scene::{Frame, Hider, PrepareOptions, Scene, ScreenScene, View};

/// Frames timed per pipeline and round, after the warm-up: at least
/// this many, and as many more as fit in [`TIMED_SPAN`].
const TIMED: usize = 3;
/// The least time each pipeline spends on timed frames per round: a
/// scene of 3 ms frames gets about 10 a round, not 3. On the 2-vCPU
/// virtual machine some 2-thread frames of a short scene run at the
/// 1-thread time (the second worker's vCPU comes back late and the first
/// one takes every band); with 9 frames in all their median flipped
/// between the two from run to run.
const TIMED_SPAN: Duration = Duration::from_millis(30);
/// How long each pipeline renders untimed frames first, per round.
const WARM_UP: Duration = Duration::from_millis(40);
/// The pipelines timed here, in the table's order.
const PIPELINES: [&str; 6] = [
    "abuffer 1T",
    "abuffer 2T",
    "carpenter 1T",
    "lean 1T",
    "prepare 1T",
    "lists 1T",
];

/// What [`frames`] times.
enum Timed<'a> {
    /// The whole pipeline through this hider.
    Hider(&'a mut ABuffer),
    /// The lean front end alone.
    Lean,
    /// `prepare` alone.
    Prepare,
}

/// Median of `v` (the upper one for an even count); NaN when empty.
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
}

/// Runs llvmpipe with 4x MSAA on 1 and 2 threads once; its medians per
/// (scene, threads).
fn run_peers(bin: &str, size: u32) -> Result<Vec<(String, u32, f64)>, String> {
    let rows = programs::run_peers(bin, &["--peers", "llvmpipe", "--msaa"], size)?;
    Ok(rows
        .into_iter()
        .filter(|r| r.peer == "llvmpipe-msaa4")
        .map(|r| (r.scene, r.threads, r.median_ms))
        .collect())
}

/// Runs the tiled z-buffer's benchmark for one round at `size`; the median
/// ms of its `tiled 1 thread` column per scene (the fifth cell of its
/// markdown rows, `median (min)`).
fn run_tiled(bin: &str, size: u32) -> Result<Vec<(String, f64)>, String> {
    let out = Command::new(bin)
        .args(["1", &size.to_string()])
        .output()
        .map_err(|e| format!("{bin}: {e}"))?;
    if !out.status.success() {
        return Err(format!("{bin} failed ({})", out.status));
    }
    let text = String::from_utf8_lossy(&out.stdout);
    Ok(text
        .lines()
        .filter_map(|line| {
            let cells: Vec<&str> = line.split('|').map(str::trim).collect();
            let ms = cells.get(5)?.split_whitespace().next()?.parse().ok()?;
            (cells.get(3)? == &size.to_string()).then(|| (cells[1].to_owned(), ms))
        })
        .collect())
}

/// Times `count` frames of `scene` from world space: the whole pipeline
/// of a hider, or a front end alone; the time of each, ms.
fn frames(
    scene: &Scene,
    view: &View,
    options: &PrepareOptions,
    mut what: Timed<'_>,
    count: usize,
) -> Vec<f64> {
    let mut screen = ScreenScene::empty(view);
    let mut lean = LeanScene::new();
    let mut frame = Frame::new(view.viewport.width, view.viewport.height).expect("frame");
    let mut one = || {
        let t = Instant::now();
        match &mut what {
            Timed::Hider(h) => drop(
                h.render_scene(scene, view, options, &mut screen, &mut frame)
                    .expect("render"),
            ),
            Timed::Lean => prepare_lean_into(scene, view, options, &mut lean).expect("lean"),
            Timed::Prepare => {
                hider_scene::prepare_into(scene, view, options, &mut screen).expect("prepare")
            }
        }
        t.elapsed().as_secs_f64() * 1e3
    };
    let start = Instant::now();
    while start.elapsed() < WARM_UP {
        one();
    }
    let start = Instant::now();
    let mut times = Vec::new();
    while times.len() < count || start.elapsed() < TIMED_SPAN {
        times.push(one());
    }
    times
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let peers_bin = programs::take_flag(&mut args, "--peers-bin")?;
    let tiled_bin = programs::take_flag(&mut args, "--zbuffer-bin")?;
    let rounds: usize = args.first().and_then(|a| a.parse().ok()).unwrap_or(5);
    let size: u32 = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(1024);
    let scenes = programs::llvmpipe_scenes();

    let serial = PrepareOptions::gl_compatible();
    let parallel = serial.with_parallel(true);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build()?;
    let mut one = ABuffer::new(ABufferOptions::default().with_threads(1));
    let mut two = ABuffer::new(ABufferOptions::default().with_threads(2));
    let mut carpenter = ABuffer::new(ABufferOptions::carpenter().with_threads(1));
    let mut lists = ABuffer::new(
        ABufferOptions::default()
            .with_sample_tiles(false)
            .with_threads(1),
    );
    // Per scene: the pipelines' frame times, then the peers' and the tiled
    // z-buffer's medians of each round.
    let mut times = vec![vec![Vec::new(); PIPELINES.len()]; scenes.len()];
    let mut msaa: Vec<[Vec<f64>; 2]> = vec![[Vec::new(), Vec::new()]; scenes.len()];
    let mut tiled = vec![Vec::new(); scenes.len()];
    for _ in 0..rounds {
        if let Some(bin) = &peers_bin {
            for (scene, threads, ms) in run_peers(bin, size)? {
                if let Some(k) = scenes.iter().position(|(n, _)| *n == scene) {
                    msaa[k][(threads.clamp(1, 2) - 1) as usize].push(ms);
                }
            }
        }
        if let Some(bin) = &tiled_bin {
            for (scene, ms) in run_tiled(bin, size)? {
                if let Some(k) = scenes.iter().position(|(n, _)| *n == scene) {
                    tiled[k].push(ms);
                }
            }
        }
        for (k, (_, scene)) in scenes.iter().enumerate() {
            let view = View::for_scene(scene, size, size)?;
            let t = &mut times[k];
            t[0].extend(frames(scene, &view, &serial, Timed::Hider(&mut one), TIMED));
            t[1].extend(
                pool.install(|| frames(scene, &view, &parallel, Timed::Hider(&mut two), TIMED)),
            );
            t[2].extend(frames(
                scene,
                &view,
                &serial,
                Timed::Hider(&mut carpenter),
                TIMED,
            ));
            t[3].extend(frames(scene, &view, &serial, Timed::Lean, TIMED));
            t[4].extend(frames(scene, &view, &serial, Timed::Prepare, TIMED));
            t[5].extend(frames(
                scene,
                &view,
                &serial,
                Timed::Hider(&mut lists),
                TIMED,
            ));
        }
    }
    println!(
        "median ms of at least {} frames (at least {} ms of frames a round, {rounds} interleaved rounds) at {size} x {size}: front end + render \
         (llvmpipe 4x MSAA: clear + draw + resolve blit + glFinish; tiled z-buffer: its lean front end + draw)\n",
        rounds * TIMED,
        TIMED_SPAN.as_millis()
    );
    println!(
        "| scene | triangles | {} | tiled 1T | MSAA 1T | MSAA 2T | MSAA/A 1T | MSAA/A 2T | A/tiled 1T | carpenter/A | carpenter/lists | lists/A | 2T speed-up |",
        PIPELINES.join(" | ")
    );
    println!("|---|---|{}", "---|".repeat(PIPELINES.len() + 10));
    // Per target, the scenes that meet it in this run.
    let mut met: [Vec<&str>; 3] = Default::default();
    for (k, (name, scene)) in scenes.iter().enumerate() {
        let m: Vec<f64> = times[k].iter().cloned().map(median).collect();
        let (t1, m1, m2) = (
            median(tiled[k].clone()),
            median(msaa[k][0].clone()),
            median(msaa[k][1].clone()),
        );
        let cells: Vec<String> = m.iter().map(|v| format!("{v:.2}")).collect();
        // The target ratios, printed and then checked.
        let (msaa_1t, msaa_2t, tiled_1t, carpenter) =
            (m1 / m[0], m2 / m[1], m[0] / t1, m[2] / m[0]);
        println!(
            "| {name} | {} | {} | {t1:.2} | {m1:.2} | {m2:.2} | {msaa_1t:.2} | {msaa_2t:.2} | {tiled_1t:.2} | {carpenter:.2} | {:.2} | {:.2} | {:.2} |",
            scene.triangle_count(),
            cells.join(" | "),
            m[2] / m[5],
            m[5] / m[0],
            m[0] / m[1],
        );
        let targets = [
            msaa_1t >= 4.0 && msaa_2t >= 4.0,
            tiled_1t <= 2.0,
            carpenter <= 1.0,
        ];
        for (list, hit) in met.iter_mut().zip(targets) {
            if hit {
                list.push(name);
            }
        }
    }
    // Without a peer's numbers its ratios are NaN, and NaN meets nothing.
    println!("\ntargets met in this run ({} scenes):", scenes.len());
    for (target, list) in [
        "MSAA / A >= 4 at 1 and 2 threads",
        "A / tiled <= 2 at 1 thread",
        "Carpenter at most A at 1 thread",
    ]
    .into_iter()
    .zip(&met)
    {
        let scenes = if list.is_empty() {
            "none".to_string()
        } else {
            list.join(", ")
        };
        println!("- {target}: {scenes}");
    }
    Ok(())
}
