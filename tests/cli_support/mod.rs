//! What the command-line tests share: running the `hider` binary built for
//! this test run, a fresh scratch folder per test, and the checks on what a
//! run printed and how it ended.

#![allow(dead_code, reason = "each test binary uses a different subset")]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs `hider` with `args` and returns what it did.
pub fn hider(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hider"))
        .args(args)
        .output()
        .expect("hider runs")
}

/// Runs `hider render MODEL -o OUTPUT EXTRA...`.
pub fn render(model: &str, output: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["render", model, "-o", output.to_str().unwrap()];
    args.extend_from_slice(extra);
    hider(&args)
}

/// An empty scratch folder for test `name`, unique to this process.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hider-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// What the run wrote to stderr.
pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Asserts that the run succeeded (showing its stderr if not) and returns
/// its stderr.
#[track_caller]
pub fn assert_success(out: &Output) -> String {
    let err = stderr(out);
    assert!(out.status.success(), "{err}");
    err
}

/// Asserts the start of every refusal: exit status 2, no panic, and exactly
/// one line on stderr, which it returns.
#[track_caller]
pub fn assert_one_line_failure(out: &Output) -> String {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(2), "stderr: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    err
}

/// Asserts that `err` contains every one of `needles`.
#[track_caller]
pub fn assert_mentions(err: &str, needles: &[&str]) {
    for n in needles {
        assert!(err.contains(n), "'{n}' missing from: {err}");
    }
}
