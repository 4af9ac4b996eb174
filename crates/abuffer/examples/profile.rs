//! Renders one scene with one hider a few times, for profilers
//! (`perf record`, `valgrind --tool=callgrind`).
//!
//! `cargo run --release -p hider-abuffer --example profile -- SCENE HIDER [RUNS] [SIZE]`
//!
//! SCENE: `soup1k`, `soup10k`, `soup100k`, `sphere` (uv_sphere(200)), `one`
//! (a single triangle: the fixed cost of a frame);
//! HIDER: `ssaa1`, `ssaa32`, `ps` (A-buffer, per-sample), `ps-nomerge`
//! (merging off), `mm` (min/max),
//! `carpenter`, or `cov` (mask generation alone). Prints the CPU and wall time of each render.

use std::time::Instant;

use hider_abuffer::coverage::{TriCoverage, pixel_range};
use hider_abuffer::{
    ABuffer, ABufferOptions, DepthMode, SamplePattern, SsaaOptions, SupersampledZBuffer,
};
use hider_scene::{DynHider, Frame, Hider, PrepareOptions, View, prepare, procedural};

/// CPU time of this thread (ns), from `/proc/thread-self/schedstat`.
fn cpu_ns() -> u64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse().ok())
        .unwrap_or(0)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let scene = match args.first().map_or("soup10k", String::as_str) {
        "soup1k" => procedural::random_soup(1_000, 1),
        "soup10k" => procedural::random_soup(10_000, 1),
        "soup100k" => procedural::random_soup(100_000, 1),
        "sphere" => procedural::uv_sphere(200),
        "one" => procedural::random_soup(1, 1),
        other => panic!("unknown scene {other}"),
    };
    let mut hider: Box<dyn DynHider> = match args.get(1).map_or("ps", String::as_str) {
        "ssaa1" => Box::new(SupersampledZBuffer::new(
            SsaaOptions::default().with_pattern(SamplePattern::Centre),
        )),
        "ssaa32" => Box::new(SupersampledZBuffer::new(SsaaOptions::default())),
        "ps" => Box::new(ABuffer::new(ABufferOptions::default())),
        "ps-nomerge" => Box::new(ABuffer::new(
            ABufferOptions::default().with_merge(hider_abuffer::MergePolicy::Off),
        )),
        "mm" => Box::new(ABuffer::new(
            ABufferOptions::default().with_depth(DepthMode::MinMax),
        )),
        "carpenter" => Box::new(ABuffer::new(ABufferOptions::carpenter())),
        "cov" => Box::new(ABuffer::default()),
        other => panic!("unknown hider {other}"),
    };
    let runs: u32 = args.get(2).map_or(3, |r| r.parse().expect("runs"));
    let size: u32 = args.get(3).map_or(1024, |r| r.parse().expect("size"));
    let view = View::for_scene(&scene, size, size).expect("view");
    let s = prepare(&scene, &view, &PrepareOptions::default()).expect("prepare");
    if args.get(1).map(String::as_str) == Some("cov") {
        // Mask generation alone: the shared front of every hider here.
        for _ in 0..runs {
            let cpu = cpu_ns();
            let (mut hits, mut bits, mut visits) = (0u64, 0u64, 0u64);
            for tri in &s.tris {
                let pattern = SamplePattern::Grid32;
                let Some((x0, y0, x1, y1)) = pixel_range(tri, pattern, size, size) else {
                    continue;
                };
                let setup = TriCoverage::new(tri, pattern);
                visits += u64::from(x1 - x0 + 1) * u64::from(y1 - y0 + 1);
                for j in y0..=y1 {
                    for (_, c) in setup.row(x0, x1, j) {
                        hits += 1;
                        bits += u64::from(c.mask.count_ones());
                    }
                }
            }
            println!(
                "cpu {:.1} ms  visits {visits} hits {hits} bits {bits}",
                (cpu_ns() - cpu) as f64 / 1e6
            );
        }
        return;
    }
    let mut frame = Frame::new(size, size).expect("frame");
    for _ in 0..runs {
        let (wall, cpu) = (Instant::now(), cpu_ns());
        let stats = hider.render(&s, &mut frame).expect("render");
        println!(
            "cpu {:.1} ms  wall {:.1} ms  {stats}",
            (cpu_ns() - cpu) as f64 / 1e6,
            wall.elapsed().as_secs_f64() * 1e3
        );
    }
}
