//! What the command-line tests share: running the `hider` binary built for
//! this test run, and a fresh scratch folder per test.

#![allow(dead_code, reason = "each test binary uses a different subset")]

use std::path::PathBuf;
use std::process::{Command, Output};

/// Runs `hider` with `args` and returns what it did.
pub fn hider(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hider"))
        .args(args)
        .output()
        .expect("hider runs")
}

/// An empty scratch folder for test `name`, unique to this process.
pub fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hider-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
