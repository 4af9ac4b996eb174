//! What `--algo auto` costs over naming the hider it picks: whole-process
//! wall time of `hider render` with the planner and with `--algo
//! zbuffer-tiled`, run alternately, the minimum and the median of each.
//! A benchmark, not a check: ignored by default, and meant for the
//! release binary. docs/analysis.md's table comes from
//!
//! ```sh
//! cargo build --release --bin hider
//! HIDER_BIN=target/release/hider cargo test -p hider-cli --test planner_overhead -- --ignored --nocapture
//! ```

use std::process::Command;
use std::time::Instant;

/// The binary measured: `HIDER_BIN`, else the one built for the tests.
fn binary() -> String {
    std::env::var("HIDER_BIN").unwrap_or_else(|_| env!("CARGO_BIN_EXE_hider").to_owned())
}

/// Wall seconds of one `hider render MODEL --size SIZE ALGO` run.
fn run(model: &str, size: u32, algo: &str, png: &std::path::Path) -> f64 {
    let started = Instant::now();
    let size = size.to_string();
    let out = Command::new(binary())
        .args(["render", model, "--size", &size, "--algo", algo, "-o"])
        .arg(png)
        .output()
        .expect("hider runs");
    let seconds = started.elapsed().as_secs_f64();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    seconds
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn min(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::INFINITY, f64::min)
}

#[test]
#[ignore = "a benchmark: run it on the release binary (see the module documentation)"]
fn planner_overhead() {
    let runs = 7;
    let dir = std::env::temp_dir().join(format!("hider-overhead-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let png = dir.join("out.png");
    println!(
        "| scene | size | auto min / median s | zbuffer-tiled min / median s | overhead (min, median) |"
    );
    println!("|---|---|---|---|---|");
    for (model, size) in [
        ("gen:soup:1000000", 512),
        ("gen:soup:100000", 1024),
        ("gen:sphere:300", 1024),
        ("gen:sphere:1000", 2048),
        ("gen:sphere:708", 1024),
    ] {
        let (mut auto, mut tiled) = (Vec::new(), Vec::new());
        for _ in 0..runs {
            auto.push(run(model, size, "auto", &png));
            tiled.push(run(model, size, "zbuffer-tiled", &png));
        }
        let over = |a: f64, t: f64| (a / t - 1.0) * 100.0;
        println!(
            "| `{model}` | {size} | {:.2} / {:.2} | {:.2} / {:.2} | {:+.0}%, {:+.0}% |",
            min(&auto),
            median(auto.clone()),
            min(&tiled),
            median(tiled.clone()),
            over(min(&auto), min(&tiled)),
            over(median(auto), median(tiled)),
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
