//! What delivering a frame costs the tiled z-buffer, against the machine's
//! memory bandwidth: the scenes of the llvmpipe comparison at the fit
//! camera, each timed as
//!
//! - `draw`: the lean front end and the draw into the hider's tiles
//!   ([`TiledZBuffer::draw_depth_scene`], GL's draw call plus `glFinish`);
//! - `all`, `ids+depth`, `ids`: [`Hider::render_scene`] into a [`Frame`]
//!   requesting those buffers ([`FrameBuffers`]): the same draw with the
//!   read-back done band by band;
//! - `read`: [`TiledZBuffer::read_into`] alone (every buffer, after a draw);
//! - the floor: a plain `memset` and a `memcpy` of the frame's bytes
//!   (ids, depth and colour, 12 bytes a pixel), on 1 thread and on 2;
//! - `draw + memset`: the draw followed by that `memset`, the floor of
//!   delivering the frame after this draw (`all` over it is how far the
//!   read-back is from memory speed).
//!
//! Rounds interleave the rows so that the machine's noise hits all alike;
//! each measurement renders untimed for 40 ms (an idle vCPU takes tens of
//! milliseconds to run at full speed), then [`TIMED`] frames, timed. The
//! table gives the median ms over all rounds.
//!
//! With `--peers-bin PATH` (the `peers` package's binary) every round
//! first runs llvmpipe on the same scenes, and the table adds the
//! same-run ratios of its medians to hider's: render only (its clear +
//! draw + `glFinish` over `draw`), the frame in client memory (its
//! clear + draw + `glReadPixels` of colour and depth over `all`, which
//! delivers ids besides), the same over `ids+depth` (8 bytes a pixel
//! like llvmpipe's colour and depth, and what `hider.render` in Python
//! returns) and over `ids` (what `hider render --repeat` times without
//! `--depth-out`). All times are then wall time, as the peers'.
//!
//! `cargo run --release -p hider-bench --bin frame_readback -- [K] [SIZES...] [--peers-bin PATH]`
//! (default K = 5 rounds, size 1024).

use std::time::{Duration, Instant};

use hider_bench::programs;
use hider_scene::{Frame, FrameBuffers, Hider, PrepareOptions, Scene, ScreenScene, View};
use hider_zbuffer::{DepthScene, TiledZBuffer, TiledZBufferOptions, prepare_depth_into};
use rayon::prelude::*;

/// Frames timed per measurement and round, after the warm-up.
const TIMED: usize = 5;
/// Untimed frames before each measurement.
const WARM_UP: Duration = Duration::from_millis(40);

static EPOCH: std::sync::LazyLock<Instant> = std::sync::LazyLock::new(Instant::now);

/// Median of `v`.
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Runs `frame` for the warm-up, then [`TIMED`] times, pushing ms: the
/// calling thread's CPU time with `cpu` (a loaded machine's waits left
/// out), wall time otherwise.
fn time(times: &mut Vec<f64>, cpu: bool, mut frame: impl FnMut()) {
    let now = || {
        if cpu {
            programs::thread_cpu_seconds().expect("thread CPU time")
        } else {
            Instant::now().duration_since(*EPOCH).as_secs_f64()
        }
    };
    let start = Instant::now();
    let mut count = 0;
    while count < 2 || start.elapsed() < WARM_UP {
        frame();
        count += 1;
    }
    for _ in 0..TIMED {
        let t = now();
        frame();
        times.push((now() - t) * 1e3);
    }
}

/// One scene, size and thread count, with its reusable state.
struct Row<'a> {
    name: &'a str,
    scene: &'a Scene,
    view: View,
    threads: usize,
    hider: TiledZBuffer,
    lean: DepthScene,
    screen: ScreenScene,
    frame: Frame,
    times: [Vec<f64>; 8],
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let peers_bin = programs::take_flag(&mut args, "--peers-bin")?;
    let rounds: usize = args.first().and_then(|a| a.parse().ok()).unwrap_or(5);
    let mut sizes: Vec<u32> = args.iter().skip(1).filter_map(|a| a.parse().ok()).collect();
    if sizes.is_empty() {
        sizes = vec![1024];
    }
    let scenes = programs::llvmpipe_scenes();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build()?;
    let serial = PrepareOptions::gl_compatible();
    let parallel = serial.with_parallel(true);
    println!(
        "median ms of {} frames ({rounds} interleaved rounds): {}; floor = the frame's 12 bytes a pixel\n",
        rounds * TIMED,
        if peers_bin.is_some() {
            "wall time"
        } else {
            "1 thread in the thread's CPU time, 2 threads in wall time"
        }
    );
    println!(
        "| scene | size | threads | draw | all | ids+depth | ids | read (all) | memset | memcpy | read / memset | draw + memset | all / (draw + memset) |{}",
        if peers_bin.is_some() {
            " vs llvmpipe render only | vs llvmpipe + read-back | ids+depth vs llvmpipe + read-back | ids vs llvmpipe + read-back |"
        } else {
            ""
        }
    );
    println!(
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|{}",
        if peers_bin.is_some() {
            "---|---|---|---|"
        } else {
            ""
        }
    );
    for &size in &sizes {
        let mut rows = Vec::new();
        for (name, scene) in &scenes {
            for threads in [1, 2] {
                let view = View::for_scene(scene, size, size)?;
                rows.push(Row {
                    name,
                    scene,
                    view,
                    threads,
                    hider: TiledZBuffer::new(TiledZBufferOptions::default().with_threads(threads)),
                    lean: DepthScene::new(),
                    screen: ScreenScene::empty(&view),
                    frame: Frame::new(size, size)?,
                    times: Default::default(),
                });
            }
        }
        let bytes = size as usize * size as usize * 12;
        let (mut dst, src) = (vec![0_u8; bytes], vec![1_u8; bytes]);
        let mut peers = Vec::new();
        for _ in 0..rounds {
            if let Some(bin) = &peers_bin {
                peers.extend(programs::run_peers(bin, &["--peers", "llvmpipe"], size)?);
            }
            for row in &mut rows {
                let options = if row.threads == 1 { &serial } else { &parallel };
                let mut t = std::mem::take(&mut row.times);
                // One thread runs here (its CPU time is the measure), two
                // on the pool (wall time).
                let cpu = row.threads == 1 && peers_bin.is_none();
                let on = |f: &mut (dyn FnMut() + Send)| if cpu { f() } else { pool.install(f) };
                time(&mut t[0], cpu, || {
                    on(&mut || {
                        prepare_depth_into(row.scene, &row.view, options, &mut row.lean)
                            .and_then(|()| row.hider.draw_depth_scene(&row.lean))
                            .expect("draw");
                    });
                });
                for (i, wanted) in [
                    FrameBuffers::ALL,
                    FrameBuffers::IDS_DEPTH,
                    FrameBuffers::IDS,
                ]
                .into_iter()
                .enumerate()
                {
                    row.frame.set_buffers(wanted);
                    time(&mut t[1 + i], cpu, || {
                        on(&mut || {
                            row.hider
                                .render_scene(
                                    row.scene,
                                    &row.view,
                                    options,
                                    &mut row.screen,
                                    &mut row.frame,
                                )
                                .expect("render");
                        });
                    });
                }
                // The read-back alone reads the image of the last draw.
                row.frame.set_buffers(FrameBuffers::ALL);
                time(&mut t[4], cpu, || {
                    on(&mut || row.hider.read_into(&mut row.frame).expect("read"));
                });
                let chunk = bytes.div_ceil(row.threads);
                time(&mut t[5], cpu, || {
                    on(&mut || dst.par_chunks_mut(chunk).for_each(|c| c.fill(0xff)));
                });
                time(&mut t[6], cpu, || {
                    on(&mut || {
                        dst.par_chunks_mut(chunk)
                            .zip(src.par_chunks(chunk))
                            .for_each(|(d, s)| d.copy_from_slice(s));
                    });
                });
                // The floor of delivering this draw's frame: the draw,
                // then a plain `memset` of the frame's bytes, which meets
                // the caches as the draw left them (the `memset` alone,
                // repeated, finds its buffer in the last-level cache).
                time(&mut t[7], cpu, || {
                    on(&mut || {
                        prepare_depth_into(row.scene, &row.view, options, &mut row.lean)
                            .and_then(|()| row.hider.draw_depth_scene(&row.lean))
                            .expect("draw");
                        dst.par_chunks_mut(chunk).for_each(|c| c.fill(0xff));
                    });
                });
                std::hint::black_box(&dst);
                row.times = t;
            }
        }
        for row in &mut rows {
            let m: Vec<f64> = std::mem::take(&mut row.times)
                .into_iter()
                .map(median)
                .collect();
            let cells: Vec<String> = m[..7].iter().map(|v| format!("{v:.2}")).collect();
            // The median over this run's measurements of a peer.
            let peer = |name: &str| {
                let v: Vec<f64> = peers
                    .iter()
                    .filter(|p| p.scene == row.name && p.size == size && p.peer == name)
                    .filter(|p| p.threads as usize == row.threads)
                    .map(|p| p.median_ms)
                    .collect();
                (!v.is_empty()).then(|| median(v))
            };
            let ratio = |p: Option<f64>, ours: f64| {
                p.map_or("-".to_owned(), |p| format!("{:.2}x ({p:.2})", p / ours))
            };
            let vs = if peers_bin.is_some() {
                format!(
                    " {} | {} | {} | {} |",
                    ratio(peer("llvmpipe"), m[0]),
                    ratio(peer("llvmpipe+read"), m[1]),
                    ratio(peer("llvmpipe+read"), m[2]),
                    ratio(peer("llvmpipe+read"), m[3])
                )
            } else {
                String::new()
            };
            println!(
                "| {} | {size} | {} | {} | {:.2}x | {:.2} | {:.2}x |{vs}",
                row.name,
                row.threads,
                cells.join(" | "),
                m[4] / m[5],
                m[7],
                m[1] / m[7],
            );
        }
    }
    Ok(())
}
