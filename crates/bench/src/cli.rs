//! `hider bench`: the command line of the benchmark, run by the
//! `hider-bench` binary and by the `hider` command's `bench` subcommand
//! (both take the same arguments).
//!
//! - `hider bench [OPTIONS]` runs the matrix and writes `results.csv`,
//!   `results.json`, `report.md` and the plots into `--out` (default
//!   `bench-out/`); with `--docs docs` the report goes to `docs/report.md`
//!   and its images to `docs/images/`.
//! - `hider bench merge DIR... --out DIR` combines the outputs of shards
//!   (`--shard i/n`) into one set of results and one report.
//! - `hider bench report --from DIR` regenerates the report and plots from
//!   existing results.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::{Context, Result, bail};
use clap::{Args, Subcommand};
use hider_plan::registry;
use hider_scene::timing::Timer;

use crate::matrix::{MatrixOptions, Shard, Study, build_cases, select_hiders};
use crate::record::{Results, SCHEMA_VERSION, read_results, write_results};
use crate::report::{conclusions, terminal_table, write_report};
use crate::run::{RunOptions, run};

/// Arguments of `hider bench`.
#[derive(Args, Debug, Clone, PartialEq)]
#[command(args_conflicts_with_subcommands = true)]
pub struct BenchArgs {
    /// `merge` or `report`; without one, run the matrix.
    #[command(subcommand)]
    pub action: Option<Action>,
    /// Options of a run.
    #[command(flatten)]
    pub run: RunArgs,
}

/// The steps besides running.
#[derive(Subcommand, Debug, Clone, PartialEq)]
pub enum Action {
    /// Combine the result folders of shards into one, with one report.
    Merge(MergeArgs),
    /// Regenerate the report and the plots from existing results.
    Report(ReportArgs),
}

/// Where the outputs go (shared by every action).
#[derive(Args, Debug, Clone, PartialEq)]
pub struct OutputArgs {
    /// Folder for results.csv, results.json, report.md and images/.
    #[arg(long, default_value = "bench-out")]
    pub out: PathBuf,
    /// Also write the report to DOCS/report.md with its plots and contact
    /// sheets in DOCS/images/ (the project's docs/ folder).
    #[arg(long)]
    pub docs: Option<PathBuf>,
}

/// Arguments of a run.
#[derive(Args, Debug, Clone, PartialEq)]
pub struct RunArgs {
    /// Outputs.
    #[command(flatten)]
    pub output: OutputArgs,
    /// Scenes: names, groups (asset, hard-case, obj, scaling) or patterns
    /// with `*`; comma-separated. Default: all.
    #[arg(long, value_delimiter = ',')]
    pub scenes: Vec<String>,
    /// Hiders from the registry (`hider list`): names or patterns with `*`;
    /// comma-separated. Default: all.
    #[arg(long, value_delimiter = ',')]
    pub algos: Vec<String>,
    /// Studies: real-size, depth-precision, accuracy, polygons, resolution,
    /// depth-complexity.
    #[arg(long, value_delimiter = ',', value_parser = parse_study)]
    pub studies: Vec<Study>,
    /// Square image sizes of the accuracy study (default 64,256).
    #[arg(long, value_delimiter = ',')]
    pub sizes: Vec<u32>,
    /// Square size of the real-size study (default 1024).
    #[arg(long)]
    pub real_size: Option<u32>,
    /// Extra OBJ files to benchmark (accuracy study); repeatable.
    #[arg(long = "obj")]
    pub objs: Vec<PathBuf>,
    /// Folder of the bundled scenes (default: ./assets).
    #[arg(long)]
    pub assets: Option<PathBuf>,
    /// UV sphere segment counts of the polygon study.
    #[arg(long, value_delimiter = ',')]
    pub polygon_steps: Vec<u32>,
    /// Square sizes of the resolution study.
    #[arg(long, value_delimiter = ',')]
    pub resolution_steps: Vec<u32>,
    /// Layer counts of the depth-complexity study.
    #[arg(long, value_delimiter = ',')]
    pub depth_steps: Vec<u32>,
    /// Square size of the polygon and depth-complexity studies.
    #[arg(long)]
    pub scaling_size: Option<u32>,
    /// Unmeasured warm-up renders per job.
    #[arg(long, default_value_t = RunOptions::default().timing.warmup)]
    pub warmup: u32,
    /// Measured renders per job (at least 1).
    #[arg(long, default_value_t = RunOptions::default().timing.runs)]
    pub repeats: u32,
    /// Stop repeating a job after this many seconds of measured renders.
    #[arg(long, default_value_t = RunOptions::default().timing.max_seconds)]
    pub max_seconds: f64,
    /// Run only shard i of n (1 <= i <= n), splitting by case; combine
    /// the shards' folders with `hider bench merge`.
    #[arg(long, default_value = "1/1")]
    pub shard: Shard,
    /// Most (triangle, pixel) tests the oracle may spend on one case;
    /// larger cases are timed but not scored.
    #[arg(long, default_value_t = RunOptions::default().oracle_budget)]
    pub oracle_budget: u64,
    /// A small matrix for a smoke test (32 px, 2 repeats, short sweeps).
    #[arg(long)]
    pub quick: bool,
    /// List the cases and hiders the options select, and exit.
    #[arg(long)]
    pub dry_run: bool,
    /// No progress bar.
    #[arg(long)]
    pub no_progress: bool,
}

/// Arguments of `hider bench merge`.
#[derive(Args, Debug, Clone, PartialEq)]
pub struct MergeArgs {
    /// The shards' output folders.
    #[arg(required = true)]
    pub inputs: Vec<PathBuf>,
    /// Outputs.
    #[command(flatten)]
    pub output: OutputArgs,
}

/// Arguments of `hider bench report`.
#[derive(Args, Debug, Clone, PartialEq)]
pub struct ReportArgs {
    /// Folder holding results.json (or results.csv).
    #[arg(long, default_value = "bench-out")]
    pub from: PathBuf,
    /// Outputs (`--out` defaults to the `--from` folder's parent layout:
    /// report.md and images/ are written into `--out`).
    #[command(flatten)]
    pub output: OutputArgs,
}

fn parse_study(s: &str) -> std::result::Result<Study, String> {
    Study::parse(s).ok_or_else(|| {
        let names: Vec<&str> = Study::ALL.iter().map(|s| s.as_str()).collect();
        format!("unknown study '{s}' (expected one of {})", names.join(", "))
    })
}

impl RunArgs {
    /// The run these arguments describe, writing into `out`.
    pub fn options(&self) -> RunOptions {
        let mut m = MatrixOptions::default();
        let mut timing = Timer::new(self.repeats.max(1))
            .with_warmup(self.warmup)
            .with_max_seconds(self.max_seconds);
        if self.quick {
            m.sizes = vec![32];
            m.real_size = 128;
            m.real_spheres = vec![32];
            m.real_layers = vec![2];
            m.precision_gaps = vec![1e-2, 1e-4, 1e-6];
            m.precision_ratios = vec![1e-2, 1e-4];
            m.precision_size = 32;
            m.polygon_steps = vec![8, 16, 32];
            m.resolution_steps = vec![32, 64, 128];
            m.resolution_sphere = 16;
            m.depth_steps = vec![1, 2, 4];
            m.scaling_size = 64;
            timing = timing.with_runs(timing.runs.min(2));
        }
        let set = |v: &Vec<u32>, dst: &mut Vec<u32>| {
            if !v.is_empty() {
                dst.clone_from(v);
            }
        };
        set(&self.sizes, &mut m.sizes);
        set(&self.polygon_steps, &mut m.polygon_steps);
        set(&self.resolution_steps, &mut m.resolution_steps);
        set(&self.depth_steps, &mut m.depth_steps);
        if let Some(s) = self.real_size {
            m.real_size = s;
        }
        if let Some(s) = self.scaling_size {
            m.scaling_size = s;
        }
        if let Some(a) = &self.assets {
            m.assets_dir = a.clone();
        }
        if !self.studies.is_empty() {
            m.studies = self.studies.clone();
        }
        m.scenes.clone_from(&self.scenes);
        m.algos.clone_from(&self.algos);
        m.objs.clone_from(&self.objs);
        RunOptions {
            matrix: m,
            timing,
            shard: self.shard,
            out_dir: self.output.out.clone(),
            contact_dir: Some(image_dir(&self.output)),
            oracle_budget: self.oracle_budget,
            progress: !self.no_progress,
            ..RunOptions::default()
        }
    }
}

/// Where images go: `DOCS/images` with `--docs`, else `OUT/images`.
fn image_dir(output: &OutputArgs) -> PathBuf {
    output
        .docs
        .as_ref()
        .map_or_else(|| output.out.join("images"), |d| d.join("images"))
}

/// Set by Ctrl-C: finish the run in progress, then write what is done.
static STOP: AtomicBool = AtomicBool::new(false);

fn install_ctrlc() {
    // A second Ctrl-C while the finished rows are being written exits at
    // once; the CSV already holds every finished row.
    let _ = ctrlc::set_handler(|| {
        if STOP.swap(true, Ordering::SeqCst) {
            std::process::exit(130);
        }
        eprintln!(
            "\nhider bench: interrupted; finishing the current run and writing the results so far"
        );
    });
}

/// The command line as typed, for the report, spelled `hider bench ...`
/// whether the facade's `bench` subcommand or the `hider-bench` binary
/// (which takes the same arguments) ran it.
fn command_line() -> String {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) != Some("bench") {
        args.insert(0, "bench".to_owned());
    }
    format!("hider {}", args.join(" "))
}

/// Writes results, plots and report for `results`; prints where.
fn publish(results: &Results, output: &OutputArgs, command: &str) -> Result<()> {
    std::fs::create_dir_all(&output.out)
        .with_context(|| format!("creating {}", output.out.display()))?;
    write_results(&output.out, results)?;
    let images = image_dir(output);
    let report = output
        .docs
        .as_ref()
        .map_or_else(|| output.out.join("report.md"), |d| d.join("report.md"));
    if let Some(d) = &output.docs {
        std::fs::create_dir_all(d)?;
    }
    write_report(results, &report, &images, command)?;
    println!(
        "\nwrote {}, {}, {} and plots in {}",
        output.out.join("results.csv").display(),
        output.out.join("results.json").display(),
        report.display(),
        images.display()
    );
    Ok(())
}

/// Runs `hider bench` with parsed arguments.
pub fn run_command(args: &BenchArgs) -> Result<()> {
    match &args.action {
        None => run_matrix(&args.run),
        Some(Action::Merge(m)) => {
            let merged = merge(&m.inputs)?;
            print!("{}", terminal_table(&merged));
            publish(&merged, &m.output, &command_line())
        }
        Some(Action::Report(r)) => {
            let results = read_results(&r.from)?;
            publish(&results, &r.output, &command_line())
        }
    }
}

fn run_matrix(args: &RunArgs) -> Result<()> {
    let options = args.options();
    if args.dry_run {
        let hiders = select_hiders(&options.matrix)?;
        let cases = options.shard.select(&build_cases(&options.matrix)?);
        for (k, c) in &cases {
            println!(
                "case {k:>3}: {:<17} {:<10} {}",
                c.study.as_str(),
                c.group.as_str(),
                c.label()
            );
        }
        let names: Vec<&str> = hiders.iter().map(|e| e.name).collect();
        println!(
            "{} cases x {} hiders: {}",
            cases.len(),
            hiders.len(),
            names.join(", ")
        );
        return Ok(());
    }
    install_ctrlc();
    let command = command_line();
    let out = run(&options, &STOP, &command)?;
    print!("{}", terminal_table(&out.results));
    let answer = conclusions(&out.results);
    if !answer.is_empty() {
        println!("\nWhat accuracy costs in time (from this run):");
        for line in answer {
            println!("- {}", line.replace('`', ""));
        }
    }
    publish(&out.results, &args.output, &command)?;
    if !out.results.complete {
        bail!(
            "interrupted: the results hold the {} runs finished before Ctrl-C",
            out.results.rows.len()
        );
    }
    Ok(())
}

/// Combines shard results: rows of every input, in matrix order, with every
/// machine and command. Errors on a run present in two inputs (the same
/// shard merged twice, or shards of different matrices).
pub fn merge(inputs: &[PathBuf]) -> Result<Results> {
    let mut merged = Results {
        schema: SCHEMA_VERSION,
        complete: true,
        ..Results::default()
    };
    for dir in inputs {
        let r = read_results(dir)?;
        merged.complete &= r.complete;
        for m in r.machines {
            if !merged.machines.contains(&m) {
                merged.machines.push(m);
            }
        }
        merged.commands.extend(r.commands);
        merged.rows.extend(r.rows);
    }
    check_unique(&merged, inputs)?;
    let order: Vec<&str> = registry::all().iter().map(|e| e.name).collect();
    merged.sort(|h| order.iter().position(|n| *n == h).unwrap_or(usize::MAX));
    Ok(merged)
}

fn check_unique(results: &Results, inputs: &[PathBuf]) -> Result<()> {
    let mut keys: Vec<(u32, &str, &str, u32, &str)> = results
        .rows
        .iter()
        .map(|r| {
            (
                r.case,
                r.study.as_str(),
                r.scene.as_str(),
                r.width,
                r.hider.as_str(),
            )
        })
        .collect();
    keys.sort_unstable();
    if let Some(w) = keys.windows(2).find(|w| w[0] == w[1]) {
        let dirs: Vec<String> = inputs.iter().map(|p| p.display().to_string()).collect();
        bail!(
            "run {} {}@{} {} appears twice in {} (a shard given twice?)",
            w[0].1,
            w[0].2,
            w[0].3,
            w[0].4,
            dirs.join(", ")
        );
    }
    for w in keys.windows(2) {
        if w[0].0 == w[1].0 && (w[0].1, w[0].2, w[0].3) != (w[1].1, w[1].2, w[1].3) {
            bail!(
                "case {} is {} {}@{} in one input and {} {}@{} in another: shards of different matrices",
                w[0].0,
                w[0].1,
                w[0].2,
                w[0].3,
                w[1].1,
                w[1].2,
                w[1].3
            );
        }
    }
    Ok(())
}
