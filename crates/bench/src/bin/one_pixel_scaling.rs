//! Growth of every registered hider's time with the depth complexity of
//! one pixel: `N` tiny triangles all covering one pixel centre at 64 x 64
//! (`hard_cases::one_pixel_pile`), `N` from `1e5` to `1e6` by default.
//!
//! Prints one row per hider with its render time (median of `--runs`
//! renders, 3 by default, or one when a render takes over a second; `--runs
//! 1` for instruction counts under `valgrind --tool=callgrind`,
//! the shared front end excluded and timed on its own line) at each `N`
//! and the exponent of the least-squares fit `time ~ N^k` over the sizes
//! it ran: about 1 is linear, about 1.1 is `N log N` over this range, 2 is
//! quadratic. A hider whose last time, scaled quadratically, would pass
//! the time limit is skipped at the larger sizes (shown as `-`).
//!
//! Above the hiders, in the same run, yardsticks say what those exponents
//! mean on this machine: `N log N` itself (the model, no timing), a
//! `sort_unstable_by` of `N` random `f32` keys (what an `N log N` hider
//! cannot beat), and one linear pass over `N` records of 32 bytes (the
//! Warnock classification record), 128 bytes (two cache lines) and the
//! size of a screen triangle (what every hider's set-up reads once). A
//! linear pass whose records outgrow the caches between the sizes shows an
//! exponent above 1 too: that part of a hider's excess is the memory
//! system, not the algorithm.
//!
//! ```text
//! cargo run --release -p hider-bench --bin one_pixel_scaling -- [N...] [--only NAME] [--limit SECONDS] [--counters NAME] [--runs COUNT]
//! ```

use std::time::Instant;

use std::hint::black_box;

use hider_plan::registry;
use hider_scene::procedural::SplitMix64;
use hider_scene::{Frame, ScreenScene, ScreenTri, StatsTable};
use hider_testkit::{hard_cases, screen};

/// The sizes, the hiders to run (all when empty), the time limit, the
/// hiders whose work counters to print and the renders per size.
struct Args {
    sizes: Vec<u32>,
    only: Vec<String>,
    limit: f64,
    counters: Vec<String>,
    runs: usize,
}

fn parse_args() -> Args {
    let mut args = Args {
        sizes: Vec::new(),
        only: Vec::new(),
        limit: 30.0,
        counters: Vec::new(),
        runs: 3,
    };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--only" => args.only.push(it.next().expect("--only NAME")),
            "--counters" => args.counters.push(it.next().expect("--counters NAME")),
            "--runs" => {
                args.runs = it
                    .next()
                    .and_then(|s| s.parse().ok())
                    .filter(|&r| r > 0)
                    .expect("--runs COUNT (at least 1)");
            }
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

/// Seconds of the median of up to `runs` renders (one when a render takes
/// over a second) and the last render's counters, or the error.
fn time_render(
    hider: &mut dyn hider_scene::DynHider,
    s: &ScreenScene,
    runs: usize,
) -> Result<(f64, StatsTable), String> {
    let mut frame = Frame::new(s.viewport.width, s.viewport.height).map_err(|e| e.to_string())?;
    let mut times = Vec::new();
    let mut table = StatsTable::default();
    for _ in 0..runs {
        let start = Instant::now();
        table = hider.render(s, &mut frame).map_err(|e| e.to_string())?;
        times.push(start.elapsed().as_secs_f64());
        if times[0] > 1.0 {
            break;
        }
    }
    times.sort_by(f64::total_cmp);
    Ok((times[times.len() / 2], table))
}

/// Prints the non-zero counters of `name` at each size, one line each.
fn print_counters(name: &str, tables: &[(u32, StatsTable)]) {
    for (n, table) in tables {
        let counters: Vec<String> = table
            .counters
            .iter()
            .filter(|&&(_, v)| v != 0)
            .map(|(k, v)| format!("{k} {v}"))
            .collect();
        println!("  {name} N = {n}: {}", counters.join(", "));
    }
}

/// Seconds of the median of five runs of `f`, each after `setup` (the
/// machine is shared: one run can be twice as slow as the next).
fn median_time<T>(mut setup: impl FnMut() -> T, mut f: impl FnMut(T)) -> f64 {
    let mut times: Vec<f64> = (0..5)
        .map(|_| {
            let input = setup();
            let start = Instant::now();
            f(input);
            start.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[2]
}

/// Time to sort `n` random `f32` keys with `sort_unstable_by`.
fn sort_time(n: u32) -> f64 {
    let mut rng = SplitMix64::new(u64::from(n));
    let keys: Vec<f32> = (0..n).map(|_| rng.range(0.0, 1.0) as f32).collect();
    median_time(
        || keys.clone(),
        |mut k| {
            k.sort_unstable_by(f32::total_cmp);
            black_box(k);
        },
    )
}

/// Time of one pass summing every word of `n` records of `W` words.
fn pass_time<const W: usize>(n: u32) -> f64 {
    let records: Vec<[u64; W]> = (0..u64::from(n)).map(|i| [i; W]).collect();
    median_time(
        || (),
        |()| {
            let sum = records
                .iter()
                .flatten()
                .fold(0u64, |acc, &w| acc.wrapping_add(w));
            black_box(sum);
        },
    )
}

/// Words (8 bytes) of a screen triangle, rounded up.
const SCREEN_TRI_WORDS: usize = std::mem::size_of::<ScreenTri>().div_ceil(8);

/// Prints one table row: `name`, a time per size (`-` where missing) and
/// the fitted exponent.
fn print_row(name: &str, sizes: &[u32], points: &[(u32, f64)]) {
    let mut row = format!("{name:<24}");
    for n in sizes {
        match points.iter().find(|&&(m, _)| m == *n) {
            Some(&(_, t)) => row.push_str(&format!("{t:>11.5}s")),
            None => row.push_str(&format!("{:>12}", "-")),
        }
    }
    match exponent(points) {
        Some(k) => row.push_str(&format!("{k:>10.2}")),
        None => row.push_str(&format!("{:>10}", "-")),
    }
    println!("{row}");
}

/// A timed yardstick: its row name and the seconds it takes at a size.
type Yardstick = (String, fn(u32) -> f64);

/// The yardstick rows: the `N log N` model, a sort, linear passes.
fn print_yardsticks(sizes: &[u32]) {
    let model: Vec<(u32, f64)> = sizes
        .iter()
        .map(|&n| (n, f64::from(n) * f64::from(n).ln() * 1e-8))
        .collect();
    print_row("N log N (model)", sizes, &model);
    let rows: [Yardstick; 4] = [
        ("sort N f32 keys".to_owned(), sort_time),
        ("pass N x 32 B".to_owned(), pass_time::<4>),
        ("pass N x 128 B".to_owned(), pass_time::<16>),
        (
            format!("pass N x {} B", 8 * SCREEN_TRI_WORDS),
            pass_time::<SCREEN_TRI_WORDS>,
        ),
    ];
    for (name, time) in rows {
        let points: Vec<(u32, f64)> = sizes.iter().map(|&n| (n, time(n))).collect();
        print_row(&name, sizes, &points);
    }
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
    print_yardsticks(&args.sizes);
    for entry in entries {
        let mut hider = entry.make();
        let mut points: Vec<(u32, f64)> = Vec::new();
        let mut tables: Vec<(u32, StatsTable)> = Vec::new();
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
            match time_render(hider.as_mut(), s, args.runs) {
                Ok((t, table)) => {
                    row.push_str(&format!("{:>11.5}s", t));
                    points.push((*n, t));
                    tables.push((*n, table));
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
        if args.counters.iter().any(|c| c == entry.name) {
            print_counters(entry.name, &tables);
        }
    }
}
