//! hider-bench: the comparative benchmark of the hider workspace — what
//! accuracy costs in time.
//!
//! The benchmark runs a *matrix* ([`matrix`]) of scenes (the bundled
//! assets, the hard-case scenes of `hider-testkit`, any OBJ the user
//! names, and generated scaling families, [`scenes`]) at several
//! resolutions through every hider the registry of `hider-plan` lists
//! (each entry is one algorithm with one set of options). Its studies: real
//! size (models and generated scenes at 1024 x 1024, timed from the
//! world-space scene to the frame), depth precision ([`precision`]: two
//! nearly coplanar surfaces per depth format), accuracy at small sizes, and
//! scaling in polygons, pixels and depth complexity. Per scene and
//! resolution it prepares the scene once, evaluates the exact oracle once
//! ([`run`]), and for every hider:
//! - times the render (with the shared [`Timer`](hider_scene::timing::Timer):
//!   warm-up, repeated runs, median and min-max, separate from load and
//!   prepare time, with the [`machine`] recorded);
//! - scores it ([`accuracy`]): wrong ids on non-tie pixels, ties, depth
//!   error against the ray-cast oracle; coverage error against analytic
//!   coverage for multi-sample hiders; peak memory from its stats table.
//!
//! Rows go to `results.csv` as they finish and to `results.json`
//! ([`record`]); [`report`] turns them into a terminal table, a Markdown
//! report that leads with its answer to what accuracy costs in time, and
//! plots ([`plots`]: time vs error with the Pareto front, time
//! vs triangles, resolution and depth complexity, with fitted growth
//! exponents, [`scaling`]); [`contact`] draws each hard case's renders with
//! their wrong pixels. [`cli`] is the command line, run by the
//! `hider-bench` binary and by `hider bench`.
//!
//! The package's other binaries (`src/bin`) are the timing and profiling
//! programs of the single algorithms (`cargo run --release -p hider-bench
//! --bin NAME -- ARGS`, each file's first lines say what it measures);
//! [`programs`] holds what they share.
//!
//! # Example
//!
//! A tiny matrix: the hard case of triangles crossing the near plane, at
//! 32 x 32, through two z-buffers; the exact one agrees with the oracle,
//! the one interpolating camera depth linearly (the error scratchapixel's
//! depth-buffer lesson warns of) does not.
//!
//! ```
//! use std::sync::atomic::AtomicBool;
//! use hider_bench::matrix::{MatrixOptions, Study};
//! use hider_bench::run::{run, RunOptions};
//! use hider_scene::timing::Timer;
//!
//! let out_dir = std::env::temp_dir().join(format!("hider-bench-doc-{}", std::process::id()));
//! let options = RunOptions {
//!     matrix: MatrixOptions::default()
//!         .with_studies(vec![Study::Accuracy])
//!         .with_scenes(vec!["near_plane_crossing".into()])
//!         .with_sizes(vec![32])
//!         .with_algos(vec!["zbuffer".into(), "zbuffer-linear-z".into()]),
//!     timing: Timer::new(1).with_warmup(0).with_max_seconds(1.0),
//!     out_dir: out_dir.clone(),
//!     ..RunOptions::default()
//! };
//! let out = run(&options, &AtomicBool::new(false), "doc example")?;
//! let rows = &out.results.rows;
//! assert_eq!(rows.len(), 2);
//! assert_eq!(rows[0].wrong_ids, Some(0));
//! assert!(rows[1].wrong_ids.unwrap() > 0);
//! assert!(out_dir.join("results.csv").is_file());
//! # std::fs::remove_dir_all(&out_dir).ok();
//! # Ok::<(), anyhow::Error>(())
//! ```

pub mod accuracy;
pub mod analysis;
pub mod cli;
pub mod contact;
pub mod machine;
pub mod matrix;
pub mod plots;
pub mod precision;
pub mod programs;
pub mod record;
pub mod report;
mod rounds;
pub mod run;
pub mod scaling;
pub mod scenes;

pub use cli::{BenchArgs, run_command};
