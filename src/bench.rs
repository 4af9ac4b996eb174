//! `hider bench ARGS...`: the benchmark is the `hider-bench` program (so
//! `hider` does not link its plotting and reporting); this runs the one
//! built beside the `hider` executable with the same arguments.

use std::ffi::OsString;
use std::path::PathBuf;
use std::process::{Command, ExitCode};

/// The `hider-bench` executable in the folder of the running one, if it is
/// there.
fn beside_this_one() -> Option<PathBuf> {
    let exe = std::env::current_exe().ok()?;
    let bench = exe.with_file_name(format!("hider-bench{}", std::env::consts::EXE_SUFFIX));
    bench.is_file().then_some(bench)
}

/// Runs `hider-bench` with `args`, passing its exit status through; when
/// it is not built, says how to run it and exits with status 2.
pub fn run(args: &[OsString]) -> ExitCode {
    let Some(bench) = beside_this_one() else {
        let shown: Vec<String> = args
            .iter()
            .map(|a| a.to_string_lossy().into_owned())
            .collect();
        let tail = if shown.is_empty() {
            String::new()
        } else {
            format!(" {}", shown.join(" "))
        };
        crate::progress::eprint_line(&format!(
            "hider: the benchmark is its own program, not built here: run \
             `cargo run --release -p hider-bench --{tail}`"
        ));
        return ExitCode::from(2);
    };
    match Command::new(&bench).args(args).status() {
        // A run ended by a signal has no code: report it as a failure.
        Ok(status) => ExitCode::from(status.code().map_or(1, |c| c.clamp(0, 255) as u8)),
        Err(e) => {
            crate::progress::eprint_line(&format!(
                "hider: error: cannot run {}: {e}",
                bench.display()
            ));
            ExitCode::from(2)
        }
    }
}
