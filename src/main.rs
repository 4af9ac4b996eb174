//! The `hider` command-line tool: render a model with any hider, analyse
//! what a model calls for, list the hiders, and start the benchmark.

mod analyze;
mod args;
mod bench;
mod camera_args;
mod empty;
mod model;
mod outputs;
mod progress;
mod render;
mod render_args;

use std::ffi::OsString;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Classic hidden-surface algorithms side by side.
#[derive(Parser, Debug)]
#[command(name = "hider", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Render a model (an OBJ file, or a generated scene `gen:NAME`) to PNG
    /// and optional id/depth dumps.
    #[command(allow_negative_numbers = true)]
    Render(Box<render::RenderArgs>),
    /// Benchmark every registered hider: accuracy against the oracle beside
    /// time; writes a table, results.csv/json, a report and plots.
    ///
    /// Runs the `hider-bench` program beside this one with the same
    /// arguments (`hider bench --help` shows them).
    #[command(disable_help_flag = true)]
    Bench {
        /// Arguments of `hider-bench`.
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<OsString>,
    },
    /// List the registered hiders.
    List,
    /// Report which effects a model calls for (transparency, textures,
    /// lighting, intersections, cyclic overlaps, back faces...) and what
    /// `--algo auto` would pick.
    #[command(allow_negative_numbers = true)]
    Analyze(analyze::AnalyzeArgs),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if e.use_stderr() => {
            // Usage errors: one line naming the flag and value, status 2.
            progress::eprint_line(&format!("hider: error: {}", args::usage_error_line(&e)));
            return ExitCode::from(2);
        }
        Err(e) => {
            // Help and version print normally with status 0.
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
    };
    let result = match cli.command {
        Command::Render(args) => render::run(&args).map_err(args::budget_error),
        Command::Analyze(args) => analyze::run(&args),
        Command::Bench { args } => return bench::run(&args),
        Command::List => list().map_err(Into::into),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            progress::eprint_line(&format!(
                "hider: error: {}",
                hider_plan::error_line(e.as_ref())
            ));
            ExitCode::from(2)
        }
    }
}

/// `hider list`: one line per registered hider (a closed pipe ends it
/// quietly, see [`progress::print_line`]).
fn list() -> std::io::Result<()> {
    for e in hider::registry::all() {
        progress::print_line(&format!("{:<20} {:?}: {}", e.name, e.kind, e.description))?;
    }
    Ok(())
}
