//! Times the front end alone on the stress scenes at 1024 x 1024.
//!
//! `cargo run --release -p hider-scene --example prepare_timing`

use std::time::Instant;

use hider_scene::{PrepareOptions, View, prepare, prepare_into, procedural};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    for (name, scene) in [
        ("sphere 200", procedural::uv_sphere(200)),
        ("sphere 500", procedural::uv_sphere(500)),
        ("soup 100k", procedural::random_soup(100_000, 1)),
    ] {
        let view = View::for_scene(&scene, 1024, 1024)?;
        let options = PrepareOptions::default();
        let mut screen = prepare(&scene, &view, &options)?;
        let mut times: Vec<f64> = (0..7)
            .map(|_| {
                let t = Instant::now();
                prepare_into(&scene, &view, &options, &mut screen)
                    .map(|_| t.elapsed().as_secs_f64() * 1e3)
            })
            .collect::<Result<_, _>>()?;
        times.sort_by(f64::total_cmp);
        println!(
            "{name}: {} triangles, prepare median {:.1} ms, min {:.1} ms",
            scene.triangle_count(),
            times[3],
            times[0]
        );
    }
    Ok(())
}
