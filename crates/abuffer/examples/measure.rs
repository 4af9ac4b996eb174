//! Measures the A-buffer against supersampled z-buffers: coverage error
//! against the analytic oracle (1 to 32 samples), and time at 1024 x 1024.
//!
//! `cargo run --release -p hider-abuffer --example measure [-- --quick]`
//!
//! Prints two markdown tables (used in `docs/abuffer.md`). Timings are
//! the best CPU time of a few runs of `render` alone (the front end is shared and not
//! timed). `--quick` skips the 100k-triangle scene.

use std::time::{Duration, Instant};

use hider_abuffer::{
    ABuffer, ABufferOptions, DepthMode, MergePolicy, SamplePattern, SsaaOptions,
    SupersampledZBuffer,
};
use hider_oracle::analytic_coverage;
use hider_scene::{
    Frame, Hider, PrepareOptions, Scene, ScreenScene, View, hard_cases, prepare, procedural,
};

fn screen(scene: &Scene, w: u32, h: u32) -> ScreenScene {
    let view = View::for_scene(scene, w, h).expect("view");
    prepare(scene, &view, &PrepareOptions::default()).expect("prepare")
}

/// CPU time of this thread so far: from `/proc/thread-self/schedstat` (ns
/// on a CPU) on Linux, so that other processes sharing the machine do not
/// inflate the numbers; wall time elsewhere.
fn cpu_time(start: Instant) -> Duration {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<u64>().ok())
        .map_or_else(|| start.elapsed(), Duration::from_nanos)
}

/// Best CPU time of `runs` renders, and the stats of the last.
fn time(h: &mut dyn Hider, s: &ScreenScene, runs: u32) -> (Duration, hider_scene::Stats) {
    let mut frame = Frame::new(s.viewport.width, s.viewport.height).expect("frame");
    let mut best = Duration::MAX;
    let mut stats = hider_scene::Stats::default();
    let origin = Instant::now();
    for _ in 0..runs {
        let t = cpu_time(origin);
        stats = h.render(s, &mut frame).expect("render");
        best = best.min(cpu_time(origin).saturating_sub(t));
    }
    (best, stats)
}

fn hiders() -> Vec<(String, Box<dyn Hider>)> {
    let mut out: Vec<(String, Box<dyn Hider>)> = Vec::new();
    for pattern in SamplePattern::ALL {
        out.push((
            format!("ssaa {}", pattern.count()),
            Box::new(SupersampledZBuffer::new(
                SsaaOptions::default().with_pattern(pattern),
            )),
        ));
    }
    out.push((
        "abuffer (per-sample)".into(),
        Box::new(ABuffer::new(ABufferOptions::default())),
    ));
    out.push((
        "abuffer (minmax)".into(),
        Box::new(ABuffer::new(
            ABufferOptions::default().with_depth(DepthMode::MinMax),
        )),
    ));
    out.push((
        "abuffer (carpenter)".into(),
        Box::new(ABuffer::new(ABufferOptions::carpenter())),
    ));
    out
}

fn coverage_table() {
    let mut scenes: Vec<(String, Scene)> = vec![
        ("random_soup(300)".into(), procedural::random_soup(300, 1)),
        ("uv_sphere(24)".into(), procedural::uv_sphere(24)),
    ];
    for name in ["intersecting_pairs", "cyclic_overlap", "slivers", "torus"] {
        if let Some((n, s)) = hard_cases::all(1).into_iter().find(|(n, _)| *n == name) {
            scenes.push((n.to_string(), s));
        }
    }
    println!("## Coverage error against the analytic oracle (128 x 128)\n");
    println!("Mean absolute error of `Frame::coverage` per edge pixel (0 < exact coverage < 1).\n");
    let names: Vec<String> = hiders().into_iter().map(|(n, _)| n).collect();
    println!("| scene | edge px | {} |", names.join(" | "));
    println!("|---|---|{}", "---|".repeat(names.len()));
    for (name, scene) in &scenes {
        let s = screen(scene, 128, 128);
        let exact = analytic_coverage(&s);
        let edge: Vec<usize> = (0..exact.covered.len())
            .filter(|&k| exact.covered[k] > 1e-9 && exact.covered[k] < 1.0 - 1e-9)
            .collect();
        let mut row = format!("| {name} | {} |", edge.len());
        for (_, mut h) in hiders() {
            let mut f = Frame::new(128, 128).expect("frame");
            h.render(&s, &mut f).expect("render");
            let err: f64 = edge
                .iter()
                .map(|&k| (exact.covered[k] - f64::from(f.coverage[k])).abs())
                .sum::<f64>()
                / edge.len().max(1) as f64;
            row += &format!(" {err:.4} |");
        }
        println!("{row}");
    }
    println!();
}

fn speed_table(quick: bool) {
    let mut scenes: Vec<(String, Scene)> = vec![
        ("random_soup 1k".into(), procedural::random_soup(1_000, 1)),
        ("random_soup 10k".into(), procedural::random_soup(10_000, 1)),
        ("uv_sphere(200) 79.6k".into(), procedural::uv_sphere(200)),
    ];
    if !quick {
        scenes.push((
            "random_soup 100k".into(),
            procedural::random_soup(100_000, 1),
        ));
    }
    println!("## CPU time at 1024 x 1024 (render only, best of 3, ms)\n");
    let names: Vec<String> = hiders().into_iter().map(|(n, _)| n).collect();
    println!(
        "| scene | {} | ssaa 32 / abuffer (per-sample) | ssaa 32 / abuffer (minmax) |",
        names.join(" | ")
    );
    println!("|---|{}---|---|", "---|".repeat(names.len()));
    for (name, scene) in &scenes {
        let s = screen(scene, 1024, 1024);
        let mut row = format!("| {name} |");
        let mut ms = Vec::new();
        let mut notes = Vec::new();
        for (hname, mut h) in hiders() {
            let (t, stats) = time(h.as_mut(), &s, 3);
            let v = t.as_secs_f64() * 1e3;
            ms.push(v);
            row += &format!(" {v:.0} |");
            notes.push(format!("{hname}: {stats}"));
        }
        let (ssaa32, ps, mm) = (ms[4], ms[5], ms[6]);
        row += &format!(" {:.2} | {:.2} |", ssaa32 / ps, ssaa32 / mm);
        println!("{row}");
        for n in notes {
            eprintln!("  {name} / {n}");
        }
    }
    println!();
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    coverage_table();
    speed_table(quick);
    // Merging: how much Carpenter's same-surface merge saves on a mesh.
    let s = screen(&procedural::uv_sphere(200), 1024, 1024);
    for merge in [
        MergePolicy::Off,
        MergePolicy::SameColor,
        MergePolicy::SameSurface,
    ] {
        let mut a = ABuffer::new(ABufferOptions::default().with_merge(merge));
        let (t, _) = time(&mut a, &s, 1);
        let st = a.stats();
        println!(
            "uv_sphere(200) merge {merge:?}: {:.0} ms, fragments {}, merged {}, mean list {:.3}, max list {}, peak MB {:.1}",
            t.as_secs_f64() * 1e3,
            st.fragments,
            st.merged,
            st.mean_list_len,
            st.max_list_len,
            st.bytes as f64 / 1e6
        );
    }
}
