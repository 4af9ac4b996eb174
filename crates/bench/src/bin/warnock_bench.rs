//! Times Warnock on the workspace's stress scenes (random soups and UV
//! spheres of about 1k, 10k and 100k triangles) at 512 and 2048 pixels, and
//! prints how the region counts grow with scene complexity and resolution.
//!
//! `cargo run --release -p hider-bench --bin warnock_bench [-- --aa]`
//!
//! Small cases take the best of three runs (the shared timer of
//! `hider-testkit`, no warm-up); the 100k-triangle ones at 2048 run once. With `--aa` the 4 x 4 sub-pixel mode is timed as well.

use hider_scene::{Frame, Hider, PrepareOptions, Scene, View, prepare, procedural};
use hider_testkit::timer::Timer;
use hider_warnock::{Rule, Warnock, WarnockOptions};

fn main() -> Result<(), hider_scene::Error> {
    let aa = std::env::args().any(|a| a == "--aa");
    let scenes: Vec<(String, Scene)> = [1_000u32, 10_000, 100_000]
        .iter()
        .flat_map(|&n| {
            // A UV sphere of n segments has 2n(n - 1) triangles.
            let segments = ((f64::from(n) / 2.0).sqrt() + 0.5) as u32;
            [
                (format!("soup {n}"), procedural::random_soup(n, 1)),
                (
                    format!("sphere {}", 2 * segments * (segments - 1)),
                    procedural::uv_sphere(segments),
                ),
            ]
        })
        .collect();
    println!(
        "| scene | size | mode | ms | regions | regions/pixel | max level | empty | single | surr. alone | surr. in front | at sample | pixels subdiv. | culled | classified | peak cand. |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let mut levels = Vec::new();
    for (name, scene) in &scenes {
        for size in [512u32, 2048] {
            let view = View::for_scene(scene, size, size)?;
            let screen = prepare(scene, &view, &PrepareOptions::default())?;
            let mut frame = Frame::new(size, size)?;
            let modes: &[u32] = if aa { &[1, 4] } else { &[1] };
            for &n in modes {
                let mut warnock = Warnock::new(WarnockOptions::default().with_samples_per_side(n));
                let runs = if screen.tris.len() >= 50_000 && size >= 2048 {
                    1
                } else {
                    3
                };
                let mut stats = None;
                let timing = Timer::new(runs).with_warmup(0).try_time(&|| false, || {
                    stats = Some(warnock.render(&screen, &mut frame)?);
                    Ok::<(), hider_scene::Error>(())
                })?;
                let best = timing.min_ms;
                let Some(s) = stats else { continue };
                let pixels = f64::from(size) * f64::from(size);
                println!(
                    "| {name} | {size} | {} | {best:.1} | {} | {:.3} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                    if n == 1 {
                        "pixel".to_owned()
                    } else {
                        format!("{n}x{n}")
                    },
                    s.regions,
                    s.regions as f64 / pixels,
                    s.max_level(),
                    s.decided_by(Rule::Empty),
                    s.decided_by(Rule::SinglePolygon),
                    s.decided_by(Rule::SurrounderAlone),
                    s.decided_by(Rule::SurrounderInFront),
                    s.decided_by(Rule::Sample),
                    s.decided_by(Rule::PixelSubdivided),
                    s.culled_behind_surrounder,
                    s.polygons_classified,
                    s.peak_candidates,
                );
                if n == 1 {
                    levels.push((format!("{name} @ {size}"), s.regions_per_level.clone()));
                }
            }
        }
    }
    println!("\nregions per level (level 0 = whole window; 9 = pixel at 512, 11 = pixel at 2048):");
    for (name, per_level) in levels {
        println!("{name}: {per_level:?}");
    }
    Ok(())
}
