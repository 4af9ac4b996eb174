//! Times the z-buffer on the scenes of the llvmpipe comparison (the fast z-buffer targets'
//! table): spider, UV sphere 200 and 500, random soup of 100,000 triangles,
//! at 1024 x 1024 with the fit camera. Render only (clear + rasterise,
//! prepare excluded), median and minimum of `K` runs after a warm-up.
//!
//! `cargo run --release -p hider-zbuffer --example zbuffer_timing [K]`

use std::path::PathBuf;
use std::time::Instant;

use hider_scene::{Frame, Hider, PrepareOptions, Scene, View, load_obj, prepare, procedural};
use hider_zbuffer::ZBuffer;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let runs: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(7);
    let spider = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/gl-reference/models/spider.obj");
    let mut scenes: Vec<(&str, Scene)> = Vec::new();
    if spider.exists() {
        scenes.push(("spider", load_obj(&spider)?));
    }
    scenes.push(("sphere 200", procedural::uv_sphere(200)));
    scenes.push(("sphere 500", procedural::uv_sphere(500)));
    scenes.push(("soup 100k", procedural::random_soup(100_000, 1)));
    println!("| scene | triangles | median ms | min ms |");
    println!("|---|---|---|---|");
    for (name, scene) in &scenes {
        let view = View::for_scene(scene, 1024, 1024)?;
        let screen = prepare(scene, &view, &PrepareOptions::default())?;
        let mut frame = Frame::new(1024, 1024)?;
        let mut z = ZBuffer::default();
        z.render(&screen, &mut frame)?;
        let mut times: Vec<f64> = (0..runs)
            .map(|_| {
                let t = Instant::now();
                z.render(&screen, &mut frame)
                    .map(|_| t.elapsed().as_secs_f64() * 1e3)
            })
            .collect::<Result<_, _>>()?;
        times.sort_by(f64::total_cmp);
        println!(
            "| {name} | {} | {:.1} | {:.1} |",
            scene.triangle_count(),
            times[times.len() / 2],
            times[0]
        );
    }
    Ok(())
}
