//! The `hider-bench` binary: the benchmark's command line, taking exactly
//! the arguments of `hider bench` (see [`hider_bench::cli`]).
//!
//! ```sh
//! cargo run --release -p hider-bench                 # default matrix -> bench-out/
//! cargo run --release -p hider-bench -- --docs docs  # report -> docs/report.md
//! cargo run --release -p hider-bench -- --quick      # smoke test (seconds)
//! ```

use std::process::ExitCode;

use clap::Parser;
use hider_bench::BenchArgs;

/// Benchmark every registered hider: accuracy against the oracle beside
/// time; writes a table, results.csv/json, a report and plots.
#[derive(Parser, Debug)]
#[command(name = "hider-bench", version, allow_negative_numbers = true)]
struct Cli {
    #[command(flatten)]
    args: BenchArgs,
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            // Usage errors: one line naming the flag and the value, exit
            // status 2, as `hider` prints them; help and version print
            // normally with status 0.
            if !e.use_stderr() {
                let _ = e.print();
                return ExitCode::SUCCESS;
            }
            eprintln!(
                "hider-bench: error: {}",
                hider_cli::cli_error::usage_error_line(&e)
            );
            return ExitCode::from(2);
        }
    };
    match hider_bench::run_command(&cli.args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("hider-bench: error: {}", hider_plan::error_line(e.as_ref()));
            ExitCode::from(2)
        }
    }
}
