//! Times the front end alone on the stress scenes at 1024 x 1024.
//!
//! `cargo run --release -p hider-bench --bin prepare_timing`

use hider_scene::timing::Timer;
use hider_scene::{PrepareOptions, View, prepare, prepare_into, procedural};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // One warm-up (the first prepare below), then 7 measured runs reusing
    // the screen scene's memory, as a frame loop would.
    let timer = Timer::new(7).with_warmup(0).with_max_seconds(f64::INFINITY);
    for (name, scene) in [
        ("sphere 200", procedural::uv_sphere(200)),
        ("sphere 500", procedural::uv_sphere(500)),
        ("soup 100k", procedural::random_soup(100_000, 1)),
    ] {
        let view = View::for_scene(&scene, 1024, 1024)?;
        let options = PrepareOptions::default();
        let mut screen = prepare(&scene, &view, &options)?;
        let summary = timer.try_time(&|| false, || {
            prepare_into(&scene, &view, &options, &mut screen)
        })?;
        println!(
            "{name}: {} triangles, prepare {summary}",
            scene.triangle_count()
        );
    }
    Ok(())
}
