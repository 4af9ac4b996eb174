//! Random triangles overlapping in a cube: `N` large triangles with
//! corners anywhere in [-1, 1]^3, so that nearly every pair overlaps on
//! screen and many pierce each other (the scene of issue 37, item 3).
//! Orders them with the painter at 512 x 512 (fit camera), N doubling from
//! the first size until a run fails or takes more than a minute, and
//! prints the counters and the growth exponent of the CPU time.
//!
//! `cargo run --release -p hider-bench --bin painter_cube -- [first [last]]`
//! (default: 125, doubling until a run fails or takes over a minute).

use hider_bench::programs::thread_cpu_seconds;
use hider_painter::{Painter, PainterOptions};
use hider_scene::{Frame, Hider, PrepareOptions, View, prepare};
use hider_testkit::crossing::cube_triangles;
use hider_testkit::reference;

fn main() -> Result<(), hider_scene::Error> {
    let args: Vec<u32> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let first = args.first().copied().unwrap_or(125);
    let last = args.get(1).copied().unwrap_or(1_024_000);
    let size = 512;
    println!(
        "| triangles | CPU s | comparisons | blocked | moves | splits | culled | pieces out | peak MiB | wrong px | exponent (CPU) |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut prev: Option<(f64, f64)> = None;
    let mut n = first;
    while n <= last {
        let scene = cube_triangles(n, 1);
        let view = View::for_scene(&scene, size, size)?;
        let s = prepare(&scene, &view, &PrepareOptions::default())?;
        let mut frame = Frame::new(size, size)?;
        let mut painter = Painter::new(PainterOptions::default());
        let start = std::time::Instant::now();
        let cpu = thread_cpu_seconds();
        let result = painter.render(&s, &mut frame);
        let wall = start.elapsed().as_secs_f64();
        let seconds = thread_cpu_seconds().zip(cpu).map_or(wall, |(b, a)| b - a);
        let stats = match result {
            Ok(stats) => stats,
            Err(e) => {
                println!("| {n} | {seconds:.2} | failed: {e} |");
                break;
            }
        };
        let r = reference::pixel_centre(&s);
        let wrong = r.ids.iter().zip(&frame.ids).filter(|(a, b)| a != b).count();
        let exponent = prev.map_or(String::from("-"), |(n0, t0)| {
            format!("{:.2}", (seconds / t0).ln() / (f64::from(n) / n0).ln())
        });
        println!(
            "| {n} | {seconds:.2} | {} | {} | {} | {} | {} | {} | {:.1} | {wrong} | {exponent} |",
            stats.comparisons,
            stats.blocked,
            stats.moves,
            stats.splits,
            stats.culled,
            stats.pieces_out,
            stats.peak_bytes as f64 / (1024.0 * 1024.0),
        );
        prev = Some((f64::from(n), seconds));
        if seconds > 60.0 {
            break;
        }
        n *= 2;
    }
    Ok(())
}
