//! Measures the A-buffer against supersampled z-buffers: coverage error
//! against the analytic oracle (1 to 32 samples), and time at 1024 x 1024.
//!
//! `cargo run --release -p hider-bench --bin abuffer_measure [-- --quick]`
//!
//! Prints two markdown tables (used in `docs/abuffer.md`). Timings are
//! wall-clock time of `render` alone (the front end is shared and not
//! timed), from the workspace's shared timer: per scene, every hider is
//! timed for a few renders once per round, for 5 rounds (interleaved, so
//! load changes hit all alike); the fastest render counts. `--quick` skips
//! the 100k-triangle scene.

use hider_abuffer::{
    ABuffer, ABufferOptions, DepthMode, MergePolicy, SamplePattern, SsaaOptions,
    SupersampledZBuffer,
};
use hider_oracle::analytic_coverage;
use hider_scene::{DynHider, Frame, Hider, Scene, ScreenScene, StatsTable, procedural};
use hider_testkit::timer::Timer;
use hider_testkit::{hard_cases, screen};

/// Measured renders per hider and round.
const RUNS: u32 = 3;

/// Times every hider of `hiders` on `s` with the shared timer,
/// interleaved: `rounds` rounds, each timing every hider for [`RUNS`]
/// renders (after one warm-up render in the first round), so that a change
/// in machine load hits all of them alike. Returns each hider's fastest
/// render (ms) and the stats of its last.
fn time_interleaved(
    hiders: &mut [(String, Box<dyn DynHider>)],
    s: &ScreenScene,
    rounds: u32,
) -> Vec<(f64, StatsTable)> {
    let mut frame = Frame::new(s.viewport.width, s.viewport.height).expect("frame");
    let mut best = vec![(f64::INFINITY, StatsTable::default()); hiders.len()];
    for round in 0..rounds {
        for (k, (_, h)) in hiders.iter_mut().enumerate() {
            let mut stats = StatsTable::default();
            let timer = Timer::new(RUNS).with_warmup(u32::from(round == 0));
            let summary = timer.time(|| stats = h.render(s, &mut frame).expect("render"));
            best[k] = (best[k].0.min(summary.min_ms), stats);
        }
    }
    best
}

fn hiders() -> Vec<(String, Box<dyn DynHider>)> {
    let mut out: Vec<(String, Box<dyn DynHider>)> = Vec::new();
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
    let rounds = 5;
    println!(
        "## CPU time at 1024 x 1024 (render only, ms per render: best of {rounds} interleaved rounds of batched renders)\n"
    );
    let names: Vec<String> = hiders().into_iter().map(|(n, _)| n).collect();
    println!(
        "| scene | {} | ssaa 32 / abuffer (per-sample) | ssaa 32 / abuffer (minmax) |",
        names.join(" | ")
    );
    println!("|---|{}---|---|", "---|".repeat(names.len()));
    for (name, scene) in &scenes {
        let s = screen(scene, 1024, 1024);
        let mut hs = hiders();
        let times = time_interleaved(&mut hs, &s, rounds);
        let ms: Vec<f64> = times.iter().map(|(t, _)| *t).collect();
        let mut row = format!("| {name} |");
        for v in &ms {
            row += &format!(" {v:.1} |");
        }
        let (ssaa32, ps, mm) = (ms[4], ms[5], ms[6]);
        row += &format!(" {:.2} | {:.2} |", ssaa32 / ps, ssaa32 / mm);
        println!("{row}");
        for ((hname, _), (_, stats)) in hs.iter().zip(&times) {
            eprintln!("  {name} / {hname}: {stats}");
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
    let mut hs: Vec<(String, Box<dyn DynHider>)> = [
        MergePolicy::Off,
        MergePolicy::SameColor,
        MergePolicy::SameSurface,
    ]
    .into_iter()
    .map(|merge| {
        let h: Box<dyn DynHider> =
            Box::new(ABuffer::new(ABufferOptions::default().with_merge(merge)));
        (format!("{merge:?}"), h)
    })
    .collect();
    let times = time_interleaved(&mut hs, &s, 3);
    let mut frame = Frame::new(1024, 1024).expect("frame");
    for ((merge, _), (t, _)) in hs.iter().zip(&times) {
        // The typed counters of one more render (every render counts the
        // same work).
        let merge = match merge.as_str() {
            "Off" => MergePolicy::Off,
            "SameColor" => MergePolicy::SameColor,
            _ => MergePolicy::SameSurface,
        };
        let mut abuffer = ABuffer::new(ABufferOptions::default().with_merge(merge));
        let st = Hider::render(&mut abuffer, &s, &mut frame).expect("render");
        println!(
            "uv_sphere(200) merge {merge:?}: {t:.1} ms, fragments {}, merged {}, mean list {:.3}, max list {}, peak MB {:.1}",
            st.fragments,
            st.merged,
            st.mean_list_len,
            st.max_list_len,
            st.bytes as f64 / 1e6
        );
    }
    // What occlusion culling saves (same image).
    for (name, scene) in [
        ("random_soup 10k", procedural::random_soup(10_000, 1)),
        ("uv_sphere(200)", procedural::uv_sphere(200)),
    ] {
        let s = screen(&scene, 1024, 1024);
        let mut hs: Vec<(String, Box<dyn DynHider>)> = vec![
            (
                "culling on".into(),
                Box::new(ABuffer::new(ABufferOptions::default())),
            ),
            (
                "culling off".into(),
                Box::new(ABuffer::new(
                    ABufferOptions::default().with_occlusion_culling(false),
                )),
            ),
        ];
        let times = time_interleaved(&mut hs, &s, 3);
        for ((label, _), (t, st)) in hs.iter().zip(&times) {
            println!("{name} {label}: {t:.1} ms, {st}");
        }
    }
}
