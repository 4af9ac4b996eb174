//! Times the z-buffer on the scenes of the llvmpipe comparison (the fast
//! z-buffer targets' table): spider, UV sphere 200 and 500, random soup of
//! 100,000 triangles, at 1024 x 1024 with the fit camera. Render only (clear + rasterise,
//! prepare excluded), median and minimum of `K` runs after a warm-up
//! (the shared timer).
//!
//! `cargo run --release -p hider-bench --bin zbuffer_timing -- [K]`

use hider_bench::programs;
use hider_scene::{Frame, Hider, PrepareOptions, View, prepare};
use hider_testkit::timer::Timer;
use hider_zbuffer::ZBuffer;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let runs: u32 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(7);
    let scenes = programs::llvmpipe_scenes();
    println!("| scene | triangles | median ms | min ms |");
    println!("|---|---|---|---|");
    for (name, scene) in &scenes {
        let view = View::for_scene(scene, 1024, 1024)?;
        let screen = prepare(scene, &view, &PrepareOptions::default())?;
        let mut frame = Frame::new(1024, 1024)?;
        let mut z = ZBuffer::default();
        let times =
            Timer::new(runs).try_time(&|| false, || z.render(&screen, &mut frame).map(drop))?;
        println!(
            "| {name} | {} | {:.1} | {:.1} |",
            scene.triangle_count(),
            times.median_ms,
            times.min_ms
        );
    }
    Ok(())
}
