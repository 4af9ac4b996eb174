//! Many tiny triangles over one pixel: `N` triangles, each under a pixel
//! across, all covering the centre of one pixel of a 64 x 64 image, each
//! tilted at random and at a random depth (the testkit's
//! `one_pixel_pile`). Every one of them overlaps
//! every other on screen, so anything quadratic in the depth complexity of
//! one pixel shows here. Times the painter's `render` (release build, one
//! run per size; thread CPU time and wall time), prints its counters, checks the pixel against the window-depth
//! z-buffer, and gives the growth exponent between successive sizes.
//!
//! `cargo run --release -p hider-bench --bin painter_pile -- [sizes...]`
//! (default sizes: 100000 300000 1000000).

use hider_bench::programs::thread_cpu_seconds;
use hider_painter::{Painter, PainterOptions};
use hider_scene::{Frame, Hider, PrepareOptions, View, prepare};
use hider_testkit::hard_cases::one_pixel_pile;
use hider_testkit::reference;

fn main() -> Result<(), hider_scene::Error> {
    let sizes: Vec<u32> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let sizes = if sizes.is_empty() {
        vec![100_000, 300_000, 1_000_000]
    } else {
        sizes
    };
    println!(
        "| triangles | painter CPU s | wall s | comparisons | blocked | moves | splits | pieces out | wrong px | exponent (CPU) |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut last: Option<(f64, f64)> = None;
    for &n in &sizes {
        let scene = one_pixel_pile(n, 1);
        let view = View::for_scene(&scene, 64, 64)?;
        let s = prepare(&scene, &view, &PrepareOptions::default())?;
        let mut frame = Frame::new(64, 64)?;
        let mut painter = Painter::new(PainterOptions::default());
        let start = std::time::Instant::now();
        let cpu = thread_cpu_seconds();
        let stats = painter.render(&s, &mut frame)?;
        let wall = start.elapsed().as_secs_f64();
        // CPU time of this thread, when the platform gives it: the machine
        // is often shared, and wall time then measures the load.
        let seconds = thread_cpu_seconds().zip(cpu).map_or(wall, |(b, a)| b - a);
        let r = reference::pixel_centre(&s);
        let wrong = r.ids.iter().zip(&frame.ids).filter(|(a, b)| a != b).count();
        let exponent = last.map_or(String::from("-"), |(n0, t0)| {
            format!("{:.2}", (seconds / t0).ln() / (f64::from(n) / n0).ln())
        });
        println!(
            "| {} | {seconds:.2} | {wall:.2} | {} | {} | {} | {} | {} | {wrong} | {exponent} |",
            s.tris.len(),
            stats.comparisons,
            stats.blocked,
            stats.moves,
            stats.splits,
            stats.pieces_out,
        );
        last = Some((f64::from(n), seconds));
    }
    Ok(())
}
