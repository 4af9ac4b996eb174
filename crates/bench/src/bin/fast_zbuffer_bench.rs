//! The benchmark of the fast z-buffer targets: the scenes of the llvmpipe
//! comparison (spider, UV sphere 200 and 500, random soup of 100,000
//! triangles) with the fit camera at 512, 1024 and 2048, timed over the span a GL draw call
//! plus `glFinish` covers: everything after loading (transform, clip,
//! set-up; clear; rasterise), with the GL-compatible f32 front end.
//!
//! - `zbuffer`: the reference pipeline, [`prepare()`] then [`ZBuffer`].
//! - `tiled 1T` / `tiled 2T`: the fast pipeline, [`prepare_depth_into`]
//!   then [`TiledZBuffer::draw_depth_scene`], on 1 thread (no pool) and on
//!   a 2-thread pool (front end and tiles in parallel, in that one pool:
//!   the hider uses the pool it is called from when it has the right
//!   number of threads). The image stays in
//!   the hider's tiles, as GL's stays in its framebuffer; the read-back is
//!   not timed, but it is checked equal to the reference, pixel for pixel,
//!   for every scene and size.
//!
//! Rounds are interleaved so that machine noise hits all three alike; in
//! each round every scene is rendered by each pipeline for a 40 ms warm-up
//! and then [`TIMED`] frames in a row, timed (a frame loop's steady state:
//! caches hold the pipeline's own data, and the pool's threads and both
//! cores are awake). The table gives median (minimum) ms over all timed
//! frames and Mtri/s from the median.
//!
//! Peers only from this machine, in this run: with `--peers-bin PATH`
//! (the `peers` package's binary: `cargo build --release --manifest-path
//! peers/Cargo.toml`, then `peers/target/release/peers`) each round starts
//! by running the peers once on every scene of the size (euc on 1 thread,
//! llvmpipe on 1 and 2), so that they and hider share the same minutes of
//! a noisy machine; the table then adds the ratios of their medians over
//! the rounds to hider's (above 1 = faster than them). Without it the
//! table has no peer columns and says that no peers were measured: a
//! figure from another machine or another day is not a comparison.
//!
//! `cargo run --release -p hider-bench --bin fast_zbuffer_bench -- [K] [SIZES...] [--peers-bin PATH]`
//! (default K = 9 rounds, sizes 512 1024 2048).

use std::time::Instant;

use hider_bench::programs;
use hider_scene::{Frame, Hider, PrepareOptions, Scene, View, prepare};
use hider_zbuffer::{DepthScene, TiledZBuffer, TiledZBufferOptions, ZBuffer, prepare_depth_into};

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

fn stats(mut v: Vec<f64>) -> (f64, f64) {
    v.sort_by(f64::total_cmp);
    (v[v.len() / 2], v[0])
}

/// Frames timed per pipeline and round, after the warm-up.
const TIMED: usize = 3;
/// How long each pipeline renders untimed frames before, per round.
const WARM_UP: std::time::Duration = std::time::Duration::from_millis(40);

/// Peers' figures measured on this machine: (scene, size, peer, threads)
/// to the median ms of each measurement.
type Peers = Vec<((String, u32, String, u32), f64)>;

/// Runs the peers binary once on every scene at `size` and adds what it
/// measured to `out`.
fn run_peers(bin: &str, size: u32, out: &mut Peers) -> Result<(), String> {
    out.extend(
        programs::run_peers(bin, &[], size)?
            .into_iter()
            .map(|r| ((r.scene, r.size, r.peer, r.threads), r.median_ms)),
    );
    Ok(())
}

/// One scene at one size, ready to time: its view, and each pipeline's
/// reusable state.
struct Workload<'a> {
    name: &'a str,
    scene: &'a Scene,
    view: View,
    screen: hider_scene::ScreenScene,
    reference: ZBuffer,
    want: Frame,
    one: TiledZBuffer,
    two: TiledZBuffer,
    lean1: DepthScene,
    lean2: DepthScene,
    times: [Vec<f64>; 3],
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    if args.iter().any(|a| a == "--peers") {
        return Err(
            "--peers FILE: peers are compared only when measured in this run; pass --peers-bin PATH"
                .into(),
        );
    }
    let peers_bin = programs::take_flag(&mut args, "--peers-bin")?;
    let same_machine = peers_bin.is_some();
    let runs: usize = args.first().and_then(|a| a.parse().ok()).unwrap_or(9);
    let mut sizes: Vec<u32> = args.iter().skip(1).filter_map(|a| a.parse().ok()).collect();
    if sizes.is_empty() {
        sizes = vec![512, 1024, 2048];
    }
    let scenes = programs::llvmpipe_scenes();

    let serial = PrepareOptions::gl_compatible();
    let parallel = serial.with_parallel(true);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build()?;
    print_header(runs, same_machine);
    for &size in &sizes {
        let mut work = Vec::new();
        for (name, scene) in &scenes {
            let view = View::for_scene(scene, size, size)?;
            let screen = prepare(scene, &view, &serial)?;
            let mut reference = ZBuffer::default();
            let mut want = Frame::new(size, size)?;
            reference.render(&screen, &mut want)?;
            let mut w = Workload {
                name,
                scene,
                view,
                screen,
                reference,
                want,
                one: TiledZBuffer::new(TiledZBufferOptions::default().with_threads(1)),
                two: TiledZBuffer::new(TiledZBufferOptions::default().with_threads(2)),
                lean1: DepthScene::new(),
                lean2: DepthScene::new(),
                times: [Vec::new(), Vec::new(), Vec::new()],
            };
            // Warm-up, and the check that the fast pipeline's image is the
            // reference's.
            let mut got = Frame::new(size, size)?;
            prepare_depth_into(scene, &w.view, &serial, &mut w.lean1)?;
            w.one.draw_depth_scene(&w.lean1)?;
            w.one.read_into(&mut got)?;
            assert!(got == w.want, "{name} at {size}: 1 thread differs");
            pool.install(|| {
                prepare_depth_into(scene, &w.view, &parallel, &mut w.lean2)?;
                w.two.draw_depth_scene(&w.lean2)
            })?;
            w.two.read_into(&mut got)?;
            assert!(got == w.want, "{name} at {size}: 2 threads differ");
            work.push(w);
        }
        let mut here = Peers::new();
        for _ in 0..runs {
            if let Some(bin) = &peers_bin {
                run_peers(bin, size, &mut here)?;
            }
            for w in &mut work {
                time_round(w, &pool, &serial, &parallel)?;
            }
        }
        for w in &mut work {
            report(w, size, &here, same_machine);
        }
    }
    Ok(())
}

/// The table's title lines and header, with peer columns only when the
/// peers are measured in this run.
fn print_header(runs: usize, same_machine: bool) {
    println!(
        "median (min) ms of {} frames ({runs} interleaved rounds) of prepare + clear + rasterise (f32 front end)\n",
        runs * TIMED
    );
    if !same_machine {
        println!(
            "No peers were measured in this run (pass --peers-bin PATH to time llvmpipe and euc beside hider): the table has no peer columns.\n"
        );
    }
    println!(
        "| scene | triangles | size | zbuffer | tiled 1 thread | tiled 2 threads | Mtri/s 1T / 2T | speed-up 1T / 2T |{}",
        if same_machine {
            " measured in this run: vs llvmpipe 1T / 2T | vs euc 1T |"
        } else {
            ""
        }
    );
    println!(
        "|---|---|---|---|---|---|---|---|{}",
        if same_machine { "---|---|" } else { "" }
    );
}

/// One round of one workload: each pipeline renders frames in a row, the
/// last [`TIMED`] timed (see [`frames`]).
fn time_round(
    w: &mut Workload<'_>,
    pool: &rayon::ThreadPool,
    serial: &PrepareOptions,
    parallel: &PrepareOptions,
) -> Result<(), Box<dyn std::error::Error>> {
    let scene = w.scene;
    let [tz, t1, t2] = &mut w.times;
    frames(tz, || {
        hider_scene::prepare_into(scene, &w.view, serial, &mut w.screen)?;
        w.reference.render(&w.screen, &mut w.want)?;
        Ok(())
    })?;
    frames(t1, || {
        prepare_depth_into(scene, &w.view, serial, &mut w.lean1)?;
        w.one.draw_depth_scene(&w.lean1)?;
        Ok(())
    })?;
    frames(t2, || {
        pool.install(|| {
            prepare_depth_into(scene, &w.view, parallel, &mut w.lean2)?;
            w.two.draw_depth_scene(&w.lean2)
        })?;
        Ok(())
    })?;
    Ok(())
}

/// Renders frames until [`WARM_UP`] has passed (and at least two), then
/// [`TIMED`] more, timed: a frame loop's steady state. On these virtual
/// machines a core that sat idle through the other pipelines' frames takes
/// tens of milliseconds to run at full speed again: without the warm-up
/// the 2-thread medians were those of one thread.
fn frames(
    times: &mut Vec<f64>,
    mut frame: impl FnMut() -> hider_scene::Result<()>,
) -> hider_scene::Result<()> {
    let start = Instant::now();
    let mut count = 0;
    while count < 2 || start.elapsed() < WARM_UP {
        frame()?;
        count += 1;
    }
    for _ in 0..TIMED {
        let t = Instant::now();
        frame()?;
        times.push(ms(t));
    }
    Ok(())
}

/// Prints a workload's row.
fn report(w: &mut Workload<'_>, size: u32, peers: &Peers, same_machine: bool) {
    let [tz, t1, t2] = std::mem::take(&mut w.times);
    let ((mz, nz), (m1, n1), (m2, n2)) = (stats(tz), stats(t1), stats(t2));
    let name = w.name;
    let tris = w.scene.triangle_count() as f64;
    // The median over this run's measurements of a peer.
    let peer = |peer: &str, threads: u32| {
        let v: Vec<f64> = peers
            .iter()
            .filter(|((s, z, p, t), _)| s == name && *z == size && p == peer && *t == threads)
            .map(|(_, ms)| *ms)
            .collect();
        (!v.is_empty()).then(|| stats(v).0)
    };
    let ratio = |peer: Option<f64>, ours: f64| {
        peer.map_or("-".to_owned(), |p| format!("{:.2}x ({p:.2})", p / ours))
    };
    let here = if same_machine {
        format!(
            " {} / {} | {} |",
            ratio(peer("llvmpipe", 1), m1),
            ratio(peer("llvmpipe", 2), m2),
            ratio(peer("euc", 1), m1),
        )
    } else {
        String::new()
    };
    println!(
        "| {name} | {} | {size} | {mz:.2} ({nz:.2}) | {m1:.2} ({n1:.2}) | {m2:.2} ({n2:.2}) | {:.0} / {:.0} | {:.1}x / {:.1}x |{here}",
        w.scene.triangle_count(),
        tris / m1 / 1e3,
        tris / m2 / 1e3,
        mz / m1,
        mz / m2,
    );
}
