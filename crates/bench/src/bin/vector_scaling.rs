//! How the exact regions and lines grow with the input on scenes whose
//! drawing is bounded by the image: the random soup of `gen:soup:N` and
//! `N` large random triangles piled in a cube (the testkit's
//! `heavy_overdraw`), at 256 x 256, `N` doubling from a start until one
//! drawing takes longer than a cap (or a largest `N`). Prints one
//! markdown table with the work counters and the thread CPU time of
//! `visible_regions` + `regions_svg` and of `line_pairs` +
//! `hidden_lines_in` + `lines_svg` (what `hider render --svg` runs), and
//! the growth exponent of each time between successive sizes.
//!
//! `cargo run --release -p hider-bench --bin vector_scaling -- [cap seconds] [largest N] [soup|pile]`
//! (defaults: 20 s, 1,024,000 triangles, both families).

use std::time::Instant;

use hider_bench::programs::thread_cpu_seconds;
use hider_scene::{PrepareOptions, Scene, ScreenScene, ShadeMode, View, prepare, procedural};
use hider_testkit::hard_cases::heavy_overdraw;
use hider_vector::{
    ObjectGroups, VectorOptions, hidden_lines_in, line_pairs, lines_svg, regions_svg,
    visible_regions,
};

/// Image side in pixels (the outsider's report measured at 256).
const SIZE: u32 = 256;

/// Seconds of CPU time (wall time where the platform gives none) of `f`.
fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let wall = Instant::now();
    let cpu = thread_cpu_seconds();
    let out = f();
    let seconds = thread_cpu_seconds()
        .zip(cpu)
        .map_or(wall.elapsed().as_secs_f64(), |(b, a)| b - a);
    (out, seconds)
}

fn exponent(last: Option<(f64, f64)>, n: f64, t: f64) -> String {
    last.map_or("-".into(), |(n0, t0)| {
        format!("{:.2}", (t / t0.max(1e-4)).ln() / (n / n0).ln())
    })
}

fn main() -> Result<(), hider_scene::Error> {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let cap = args.first().copied().unwrap_or(20.0);
    let largest = args.get(1).copied().unwrap_or(1_024_000.0) as u32;
    let only = std::env::args().nth(3);
    let options = VectorOptions::default();
    println!(
        "| scene | N | culled | overlapping pairs | differences | outline triangles | region points | regions s | exponent | line features | culled features | occluder tests | lines s | exponent |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    type Family = (&'static str, u32, fn(u32) -> Scene);
    let families: [Family; 2] = [
        ("`gen:soup:N`", 2_000, |n| procedural::random_soup(n, 1)),
        ("`heavy_overdraw(N, 1)`", 250, |n| heavy_overdraw(n, 1)),
    ];
    for (name, start, make) in families {
        let key = if name.contains("soup") {
            "soup"
        } else {
            "pile"
        };
        if only.as_deref().is_some_and(|o| o != key) {
            continue;
        }
        let mut n = start;
        let (mut last_r, mut last_l) = (None, None);
        while n <= largest {
            let scene = make(n);
            let view = View::for_scene(&scene, SIZE, SIZE)?;
            let s: ScreenScene = prepare(&scene, &view, &PrepareOptions::default())?;
            let (map, tr) = timed(|| {
                let map = visible_regions(&s, &options, ShadeMode::Lambert)?;
                let svg = regions_svg(&s, &map, &options);
                Ok::<_, hider_scene::Error>((map, svg.len()))
            });
            let (map, _) = map?;
            let (lines, tl) = timed(|| {
                let pairs = line_pairs(&s, &options)?;
                let lines = hidden_lines_in(&s, &pairs, &options, &ObjectGroups::default())?;
                let svg = lines_svg(&s, &lines, &options);
                Ok::<_, hider_scene::Error>((lines, svg.len()))
            });
            let (lines, _) = lines?;
            let (r, l) = (map.stats, lines.stats);
            let x = f64::from(n);
            println!(
                "| {name} | {n} | {} | {} | {} | {} | {} | {tr:.2} | {} | {} | {} | {} | {tl:.2} | {} |",
                r.culled,
                r.overlapping_pairs,
                r.differences,
                r.outline_triangles,
                r.region_points,
                exponent(last_r, x, tr),
                l.feature_edges,
                l.culled_features,
                l.occluder_tests,
                exponent(last_l, x, tl),
            );
            last_r = Some((x, tr));
            last_l = Some((x, tl));
            if tr.max(tl) > cap {
                break;
            }
            n *= 2;
        }
    }
    Ok(())
}
