//! `peers`: times hider's peers — the `euc` crate and Mesa's llvmpipe —
//! on this machine, in one run, with the scenes, camera and span of hider's
//! tiled z-buffer benchmark (its targets against GL and euc), and checks that each peer covers the
//! pixels hider covers (so the camera is provably the same).
//!
//! ```text
//! cargo run --release --manifest-path peers/Cargo.toml -- \
//!     --runs 11 --sizes 1024 --json peers.json
//! ```
//!
//! Options: `--runs K` timed runs per scene and size after at least 2
//! warm-up frames and 40 ms of them (default 11); `--sizes A,B,..` (default 1024); `--threads A,B,..`
//! llvmpipe thread counts, `LP_NUM_THREADS` (default 1,2); `--rounds R`
//! (default 2): the peers take turns R times — euc, then one llvmpipe child
//! process per thread count — and each keeps its best median and its
//! overall minimum; `--peers euc,llvmpipe` (default both); `--gl-target
//! fbo|window` (default fbo, see `llvmpipe.rs`); `--msaa` adds llvmpipe
//! drawing with 4x MSAA and resolving (`msaa.rs`, peer `llvmpipe-msaa4`,
//! at the same thread counts); `--json PATH` writes an
//! array of `{scene, size, peer, threads, median_ms, min_ms}`.
//!
//! llvmpipe reads `LP_NUM_THREADS` once per process, so each thread count
//! runs in a child: this binary re-executed with `--child llvmpipe
//! --threads N` and that variable set, which prints its results as JSON on
//! standard output.

mod args;
mod euc;
mod llvmpipe;
mod scenes;

use std::collections::BTreeMap;
use std::process::{Command, ExitCode, Stdio};

use serde::{Deserialize, Serialize};

use crate::args::{Args, parse_args};
use crate::llvmpipe::Llvmpipe;
use crate::scenes::{NamedScene, Workload, hider_coverage, hider_msaa_samples, load_scenes};

/// Warm-up frames before the timed runs of each scene and size (at the
/// least; see [`WARM_UP`]).
const WARMUPS: usize = 2;
/// The least time spent on warm-up frames: on these virtual machines a
/// core that sat idle takes tens of milliseconds to run at full speed
/// again, which would flatter hider against a multi-threaded peer.
/// hider's benchmark warms up the same way.
const WARM_UP: std::time::Duration = std::time::Duration::from_millis(40);

/// Runs `frame` (which returns its own time in ms) for at least `warmups`
/// frames and [`WARM_UP`], then `runs` more, and returns those times.
pub(crate) fn timed_runs(warmups: usize, runs: usize, mut frame: impl FnMut() -> f64) -> Vec<f64> {
    let start = std::time::Instant::now();
    let mut count = 0;
    while count < warmups || start.elapsed() < WARM_UP {
        frame();
        count += 1;
    }
    (0..runs).map(|_| frame()).collect()
}
/// Exit status of a child that found no libOSMesa (it said so already).
const NO_LIBRARY: i32 = 3;
/// Largest coverage difference from hider accepted for llvmpipe (0.5 %):
/// same snapping and fill rule, so only the odd edge pixel may differ.
const GL_TOLERANCE: f64 = 0.005;
/// The peer name of llvmpipe with 4x MSAA in the table and the JSON.
const MSAA_PEER: &str = "llvmpipe-msaa4";
/// The peer name of llvmpipe's frame delivered in client memory (draw
/// plus `glReadPixels` of colour and depth).
const READ_PEER: &str = "llvmpipe+read";
/// The same for llvmpipe with 4x MSAA, on covered *samples* against the
/// samples hider's front end covers at llvmpipe's 4 positions (0.5 %):
/// the same snapping, fill rule and sample points.
const MSAA_TOLERANCE: f64 = 0.005;
/// The same for euc (1 %): it has no fill rule (a pixel centre on an edge
/// is inside both triangles) and its own float edge tests.
const EUC_TOLERANCE: f64 = 0.01;

/// The timed runs of one peer on one scene and size, as a child reports
/// them.
#[derive(Serialize, Deserialize)]
struct RawResult {
    scene: String,
    size: u32,
    ms: Vec<f64>,
    covered: u64,
    /// Samples covered (pixels when single-sampled).
    #[serde(default)]
    samples: u64,
    /// The runs of the frame read back into client memory (llvmpipe).
    #[serde(default)]
    read_ms: Vec<f64>,
}

/// What an llvmpipe child prints on standard output.
#[derive(Serialize, Deserialize)]
struct ChildReport {
    renderer: String,
    other_threads: Option<usize>,
    results: Vec<RawResult>,
    /// With `--msaa`: the same workloads with 4x MSAA, resolved.
    #[serde(default)]
    msaa: Vec<RawResult>,
}

/// One row of `--json`.
#[derive(Serialize)]
struct JsonRow<'a> {
    scene: &'a str,
    size: u32,
    peer: &'a str,
    threads: u32,
    median_ms: f64,
    min_ms: f64,
}

/// Median (the upper one for an even count) and minimum.
fn median_min(ms: &[f64]) -> (f64, f64) {
    let mut v = ms.to_vec();
    v.sort_by(f64::total_cmp);
    (v[v.len() / 2], v[0])
}

/// All rounds of one peer and thread count on one scene and size.
#[derive(Default)]
struct Agg {
    best_median: f64,
    min: f64,
    covered: u64,
    samples: u64,
    rounds: usize,
}

impl Agg {
    fn add(&mut self, ms: &[f64], (covered, samples): (u64, u64)) {
        let (median, min) = median_min(ms);
        if self.rounds == 0 {
            (self.best_median, self.min) = (median, min);
        } else {
            self.best_median = self.best_median.min(median);
            self.min = self.min.min(min);
        }
        self.covered = covered;
        self.samples = samples;
        self.rounds += 1;
    }
}

/// Results keyed by (size, scene, peer, threads).
type Results = BTreeMap<(u32, String, &'static str, u32), Agg>;

/// The workloads of every scene at every size.
fn workloads(scenes: &[NamedScene], sizes: &[u32]) -> Result<Vec<Workload>, String> {
    sizes
        .iter()
        .flat_map(|&size| scenes.iter().map(move |s| Workload::new(s, size)))
        .collect()
}

/// The child: llvmpipe on every workload, results as JSON on stdout.
fn run_child(args: &Args) -> ExitCode {
    let scenes = load_scenes(true);
    let work = match workloads(&scenes, &args.sizes) {
        Ok(w) => w,
        Err(e) => {
            eprintln!("llvmpipe: {e}");
            return ExitCode::FAILURE;
        }
    };
    let mut gl = match Llvmpipe::open() {
        Ok(gl) => gl,
        Err(e) => {
            eprintln!("llvmpipe skipped: {e}");
            return ExitCode::from(NO_LIBRARY as u8);
        }
    };
    let mut results = Vec::new();
    let mut msaa = Vec::new();
    for w in &work {
        if args.msaa {
            match gl.time_msaa(w, WARMUPS, args.runs) {
                Ok(run) => msaa.push(RawResult {
                    scene: w.name.to_owned(),
                    size: w.size,
                    ms: run.ms,
                    covered: run.covered,
                    samples: run.samples,
                    read_ms: Vec::new(),
                }),
                Err(e) => {
                    eprintln!("llvmpipe 4x MSAA on {} at {}: {e}", w.name, w.size);
                    return ExitCode::FAILURE;
                }
            }
        }
        match gl.time(w, args.target, WARMUPS, args.runs) {
            Ok(run) => results.push(RawResult {
                scene: w.name.to_owned(),
                size: w.size,
                ms: run.ms,
                covered: run.covered,
                samples: run.samples,
                read_ms: run.read_ms,
            }),
            Err(e) => {
                eprintln!("llvmpipe on {} at {}: {e}", w.name, w.size);
                return ExitCode::FAILURE;
            }
        }
    }
    let report = ChildReport {
        renderer: gl.describe(),
        other_threads: llvmpipe::other_threads(),
        results,
        msaa,
    };
    match serde_json::to_string(&report) {
        Ok(s) => {
            println!("{s}");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("llvmpipe: {e}");
            ExitCode::FAILURE
        }
    }
}

/// Runs one llvmpipe child with `threads` threads. `Ok(None)`: no
/// libOSMesa (the child said so).
fn llvmpipe_child(args: &Args, threads: u32) -> Result<Option<ChildReport>, String> {
    let exe = std::env::current_exe().map_err(|e| format!("cannot find this program: {e}"))?;
    let join = |v: &[u32]| v.iter().map(u32::to_string).collect::<Vec<_>>().join(",");
    let out = Command::new(exe)
        .args(["--child", "llvmpipe", "--runs", &args.runs.to_string()])
        .args([
            "--sizes",
            &join(&args.sizes),
            "--threads",
            &threads.to_string(),
        ])
        .args(["--gl-target", args.target.name()])
        .args(args.msaa.then_some("--msaa"))
        .env("LP_NUM_THREADS", threads.to_string())
        .stdin(Stdio::null())
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| format!("cannot start the llvmpipe child: {e}"))?;
    if out.status.code() == Some(NO_LIBRARY) {
        return Ok(None);
    }
    if !out.status.success() {
        return Err(format!(
            "llvmpipe with {threads} threads failed ({})",
            out.status
        ));
    }
    serde_json::from_slice(&out.stdout)
        .map(Some)
        .map_err(|e| format!("llvmpipe with {threads} threads: unreadable report: {e}"))
}

fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .map(|s| s.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|_| "?".into())
}

/// The coverage checks against hider's reference z-buffer (pixel
/// centres) and, for 4x MSAA, against the samples hider's front end
/// covers at llvmpipe's sample positions; prints one line per workload
/// and returns the failures.
fn check_coverage(
    work: &[Workload],
    scenes: &[NamedScene],
    columns: &[(&'static str, u32)],
    results: &Results,
) -> Vec<String> {
    println!(
        "\ncovered pixels (hider's ZBuffer, f32 front end, vs each peer's last frame; 4x MSAA: covered samples):"
    );
    let mut failures = Vec::new();
    for w in work {
        let Some(scene) = scenes.iter().find(|s| s.name == w.name) else {
            continue;
        };
        let want = match hider_coverage(scene, w.size) {
            Ok(n) => n,
            Err(e) => {
                failures.push(e);
                continue;
            }
        };
        let msaa = columns.iter().any(|&(peer, _)| peer == MSAA_PEER);
        let want_samples = match msaa.then(|| hider_msaa_samples(scene, w.size)) {
            Some(Ok(n)) => Some(n),
            Some(Err(e)) => {
                failures.push(e);
                continue;
            }
            None => None,
        };
        let mut line = format!("  {} at {}: hider {want}", w.name, w.size);
        if let Some(n) = want_samples {
            line += &format!(" ({n} samples of 4 per pixel)");
        }
        for &(peer, t) in columns {
            let Some(a) = results.get(&(w.size, w.name.to_owned(), peer, t)) else {
                continue;
            };
            let (tolerance, got, want, unit) = match peer {
                "euc" => (EUC_TOLERANCE, a.covered, want, "pixels"),
                MSAA_PEER => (
                    MSAA_TOLERANCE,
                    a.samples,
                    want_samples.unwrap_or(0),
                    "samples",
                ),
                _ => (GL_TOLERANCE, a.covered, want, "pixels"),
            };
            let diff = (got as f64 - want as f64) / (want.max(1) as f64);
            let verdict = if diff.abs() <= tolerance {
                "ok"
            } else {
                failures.push(format!(
                    "{peer} {t}T on {} at {} covers {got} {unit}, hider {want}: {:+.3} %, over the {} % allowed",
                    w.name,
                    w.size,
                    diff * 100.0,
                    tolerance * 100.0
                ));
                "FAILED"
            };
            line += &format!(
                "; {peer} {t}T {got} {unit} ({:+.3} %, {verdict} within {} %)",
                diff * 100.0,
                tolerance * 100.0
            );
        }
        println!("{line}");
    }
    failures
}

/// Writes the medians and minima of every workload and column to `path`
/// as JSON, in the table's order, milliseconds rounded to the microsecond.
fn write_json(
    path: &str,
    work: &[Workload],
    columns: &[(&'static str, u32)],
    results: &Results,
) -> Result<(), String> {
    let us = |ms: f64| (ms * 1e3).round() / 1e3;
    let rows: Vec<JsonRow<'_>> = work
        .iter()
        .flat_map(|w| columns.iter().map(move |&(peer, t)| (w, peer, t)))
        .filter_map(|(w, peer, threads)| {
            let a = results.get(&(w.size, w.name.to_owned(), peer, threads))?;
            Some(JsonRow {
                scene: w.name,
                size: w.size,
                peer,
                threads,
                median_ms: us(a.best_median),
                min_ms: us(a.min),
            })
        })
        .collect();
    serde_json::to_string_pretty(&rows)
        .map_err(|e| e.to_string())
        .and_then(|s| std::fs::write(path, s + "\n").map_err(|e| e.to_string()))
}

/// Prints the table (one row per workload, one column per peer and
/// thread count that ran) and returns its columns.
fn print_table(
    args: &Args,
    llvmpipe: bool,
    work: &[Workload],
    results: &Results,
) -> Vec<(&'static str, u32)> {
    let mut header = "| scene | triangles | size |".to_owned();
    let mut columns: Vec<(&'static str, u32)> = Vec::new();
    if args.euc {
        header += " euc 1T |";
        columns.push(("euc", 1));
    }
    if llvmpipe {
        for &t in &args.threads {
            header += &format!(" llvmpipe {t}T |");
            columns.push(("llvmpipe", t));
        }
        for &t in &args.threads {
            header += &format!(" llvmpipe + read-back {t}T |");
            columns.push((READ_PEER, t));
        }
        for &t in args.threads.iter().filter(|_| args.msaa) {
            header += &format!(" llvmpipe 4x MSAA {t}T |");
            columns.push((MSAA_PEER, t));
        }
    }
    println!(
        "median (min) ms at size x size, fit camera; clear + draw (+ glFinish); + read-back: clear + draw + glReadPixels of colour (RGBA8) and depth (float)\n"
    );
    println!("{header}");
    println!("|---|---|---|{}", "---|".repeat(columns.len()));
    for w in work {
        let mut row = format!("| {} | {} | {} |", w.name, w.triangles(), w.size);
        for &(peer, t) in &columns {
            match results.get(&(w.size, w.name.to_owned(), peer, t)) {
                Some(a) => row += &format!(" {:.2} ({:.2}) |", a.best_median, a.min),
                None => row += " - |",
            }
        }
        println!("{row}");
    }
    columns
}

fn main() -> ExitCode {
    if let Some(code) = llvmpipe::reference::from_args() {
        return code;
    }
    let args = match parse_args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
    };
    if args.child {
        return run_child(&args);
    }

    let scenes = load_scenes(false);
    let work = match workloads(&scenes, &args.sizes) {
        Ok(w) => w,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::FAILURE;
        }
    };
    println!(
        "peers: {} timed runs after at least {WARMUPS} warm-ups and {} ms of them, best median of {} rounds; load average at start {}",
        args.runs,
        WARM_UP.as_millis(),
        args.rounds,
        load_average()
    );

    let mut results = Results::new();
    let mut llvmpipe = args.llvmpipe;
    for round in 0..args.rounds {
        if args.euc {
            for w in &work {
                let run = euc::time(w, WARMUPS, args.runs);
                results
                    .entry((w.size, w.name.to_owned(), "euc", 1))
                    .or_default()
                    .add(&run.ms, (run.covered, run.covered));
            }
        }
        for &threads in &args.threads {
            if !llvmpipe {
                break;
            }
            match llvmpipe_child(&args, threads) {
                Ok(Some(report)) => {
                    if round == 0 {
                        println!(
                            "llvmpipe, LP_NUM_THREADS={threads}: {}, {} other threads in the process, target {}",
                            report.renderer,
                            report.other_threads.map_or("?".into(), |n| n.to_string()),
                            args.target.name()
                        );
                    }
                    for r in report.results {
                        if !r.read_ms.is_empty() {
                            results
                                .entry((r.size, r.scene.clone(), READ_PEER, threads))
                                .or_default()
                                .add(&r.read_ms, (r.covered, r.samples));
                        }
                        results
                            .entry((r.size, r.scene, "llvmpipe", threads))
                            .or_default()
                            .add(&r.ms, (r.covered, r.samples));
                    }
                    for r in report.msaa {
                        results
                            .entry((r.size, r.scene, MSAA_PEER, threads))
                            .or_default()
                            .add(&r.ms, (r.covered, r.samples));
                    }
                }
                Ok(None) => llvmpipe = false,
                Err(e) => eprintln!("{e}"),
            }
        }
    }
    println!("load average at end {}\n", load_average());

    let columns = print_table(&args, llvmpipe, &work, &results);

    let failures = check_coverage(&work, &scenes, &columns, &results);
    if !failures.is_empty() {
        for f in &failures {
            eprintln!("COVERAGE CHECK FAILED: {f}");
        }
        eprintln!("the peers do not draw what hider draws: no JSON written");
        return ExitCode::FAILURE;
    }

    if let Some(path) = &args.json {
        match write_json(path, &work, &columns, &results) {
            Ok(()) => println!("\nwrote {path}"),
            Err(e) => {
                eprintln!("cannot write {path}: {e}");
                return ExitCode::FAILURE;
            }
        }
    }
    ExitCode::SUCCESS
}
