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
use hider_plan::registry;

use crate::matrix::{build_cases, select_hiders};
use crate::record::{Results, SCHEMA_VERSION, read_results, write_results};
use crate::report::{conclusions, terminal_table, write_report};
use crate::run::run;

mod args;
#[cfg(test)]
mod tests;

use args::image_dir;
pub use args::{Action, BenchArgs, MergeArgs, OutputArgs, ReportArgs, RunArgs};

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

/// What identifies a run: case, study, scene, (width, height), hider.
type RunKey<'a> = (u32, &'a str, &'a str, (u32, u32), &'a str);

fn check_unique(results: &Results, inputs: &[PathBuf]) -> Result<()> {
    let mut keys: Vec<RunKey<'_>> = results
        .rows
        .iter()
        .map(|r| {
            (
                r.case,
                r.study.as_str(),
                r.scene.as_str(),
                (r.width, r.height),
                r.hider.as_str(),
            )
        })
        .collect();
    keys.sort_unstable();
    if let Some(w) = keys.windows(2).find(|w| w[0] == w[1]) {
        let dirs: Vec<String> = inputs.iter().map(|p| p.display().to_string()).collect();
        bail!(
            "run {} {}@{}x{} {} appears twice in {} (a shard given twice?)",
            w[0].1,
            w[0].2,
            w[0].3.0,
            w[0].3.1,
            w[0].4,
            dirs.join(", ")
        );
    }
    for w in keys.windows(2) {
        if w[0].0 == w[1].0 && (w[0].1, w[0].2, w[0].3) != (w[1].1, w[1].2, w[1].3) {
            bail!(
                "case {} is {} {}@{}x{} in one input and {} {}@{}x{} in another: shards of different matrices",
                w[0].0,
                w[0].1,
                w[0].2,
                w[0].3.0,
                w[0].3.1,
                w[1].1,
                w[1].2,
                w[1].3.0,
                w[1].3.1
            );
        }
    }
    Ok(())
}
