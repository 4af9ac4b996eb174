//! Growth of every registered hider's time with the depth complexity of
//! one pixel: `N` tiny triangles all covering one pixel centre at 64 x 64
//! (`hard_cases::one_pixel_pile`), `N` from `1e5` to `1e6` by default.
//!
//! Prints one row per hider with its render time (median of a few runs,
//! the shared front end excluded and timed on its own line) at each `N`
//! and the exponent of the least-squares fit `time ~ N^k` over the sizes
//! it ran: about 1 is linear, about 1.1 is `N log N` over this range, 2 is
//! quadratic. A hider whose last time, scaled quadratically, would pass
//! the time limit is skipped at the larger sizes (shown as `-`).
//!
//! ```text
//! cargo run --release -p hider-testkit --features hostile --example one_pixel_scaling -- [N...] [--only NAME] [--limit SECONDS]
//! ```

use std::time::Instant;

use hider_plan::registry;
use hider_scene::{Frame, ScreenScene};
use hider_testkit::{hard_cases, screen};

/// The sizes, the hiders to run (all when empty) and the time limit.
struct Args {
    sizes: Vec<u32>,
    only: Vec<String>,
    limit: f64,
}

fn parse_args() -> Args {
    let mut args = Args {
        sizes: Vec::new(),
        only: Vec::new(),
        limit: 30.0,
    };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--only" => args.only.push(it.next().expect("--only NAME")),
            "--limit" => {
                args.limit = it
                    .next()
                    .and_then(|s| s.parse().ok())
                    .expect("--limit SECONDS");
            }
            n => args.sizes.push(
                n.parse::<f64>()
                    .unwrap_or_else(|_| panic!("not a size: {n}")) as u32,
            ),
        }
    }
    if args.sizes.is_empty() {
        args.sizes = vec![100_000, 200_000, 400_000, 1_000_000];
    }
    args
}

/// Least-squares slope of `ln t` against `ln n`.
fn exponent(points: &[(u32, f64)]) -> Option<f64> {
    if points.len() < 2 {
        return None;
    }
    let xs: Vec<f64> = points.iter().map(|&(n, _)| f64::from(n).ln()).collect();
    let ys: Vec<f64> = points.iter().map(|&(_, t)| t.max(1e-9).ln()).collect();
    let k = xs.len() as f64;
    let (mx, my) = (xs.iter().sum::<f64>() / k, ys.iter().sum::<f64>() / k);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    Some(sxy / sxx)
}

/// Seconds of the median of up to three renders (one when a render takes
/// over a second), or the error.
fn time_render(hider: &mut dyn hider_scene::DynHider, s: &ScreenScene) -> Result<f64, String> {
    let mut frame = Frame::new(s.viewport.width, s.viewport.height).map_err(|e| e.to_string())?;
    let mut times = Vec::new();
    for _ in 0..3 {
        let start = Instant::now();
        hider.render(s, &mut frame).map_err(|e| e.to_string())?;
        times.push(start.elapsed().as_secs_f64());
        if times[0] > 1.0 {
            break;
        }
    }
    times.sort_by(f64::total_cmp);
    Ok(times[times.len() / 2])
}

fn main() {
    let args = parse_args();
    let entries: Vec<registry::Entry> = registry::all()
        .into_iter()
        .filter(|e| args.only.is_empty() || args.only.iter().any(|o| o == e.name))
        .collect();
    let screens: Vec<(u32, ScreenScene)> = args
        .sizes
        .iter()
        .map(|&n| {
            let scene = hard_cases::one_pixel_pile(n, 1);
            let start = Instant::now();
            let s = screen(&scene, 64, 64);
            println!(
                "N = {n:>8}: front end {:.3} s, {} screen triangles",
                start.elapsed().as_secs_f64(),
                s.tris.len()
            );
            (n, s)
        })
        .collect();
    print!("{:<24}", "hider");
    for (n, _) in &screens {
        print!("{:>12}", format!("N={n}"));
    }
    println!("{:>10}", "exponent");
    for entry in entries {
        let mut hider = entry.make();
        let mut points: Vec<(u32, f64)> = Vec::new();
        let mut row = format!("{:<24}", entry.name);
        for (n, s) in &screens {
            let too_slow = points.last().is_some_and(|&(m, t)| {
                let r = f64::from(*n) / f64::from(m);
                t * r * r > args.limit
            });
            if too_slow {
                row.push_str(&format!("{:>12}", "-"));
                continue;
            }
            match time_render(hider.as_mut(), s) {
                Ok(t) => {
                    row.push_str(&format!("{:>11.3}s", t));
                    points.push((*n, t));
                }
                Err(e) => {
                    row.push_str(&format!("{:>12}", "refused"));
                    eprintln!("{} at N = {n}: {e}", entry.name);
                }
            }
        }
        match exponent(&points) {
            Some(k) => row.push_str(&format!("{k:>10.2}")),
            None => row.push_str(&format!("{:>10}", "-")),
        }
        println!("{row}");
    }
}
