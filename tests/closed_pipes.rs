//! A closed pipe ends a run quietly: a reader that went away (`hider
//! analyze FILE | head -1`, `hider list | ...`) is not a panic (exit 101),
//! and a closed stderr does not lose the PNG.

use std::process::{Command, Stdio};

mod cli_support;
use cli_support::temp_dir;

/// Runs `hider ARGS` with stdout and/or stderr a pipe whose reading end
/// is closed right after the start (long before the run prints: the scene
/// is large enough to take a while), and returns the exit code and what
/// the open stream got.
fn with_closed(args: &[&str], close_stdout: bool, close_stderr: bool) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_hider"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("hider runs");
    if close_stdout {
        drop(child.stdout.take());
    }
    if close_stderr {
        drop(child.stderr.take());
    }
    let out = child.wait_with_output().unwrap();
    let open = if close_stderr {
        &out.stdout
    } else {
        &out.stderr
    };
    (
        out.status.code(),
        String::from_utf8_lossy(open).into_owned(),
    )
}

#[test]
fn analyze_with_its_stdout_closed_ends_quietly() {
    let (code, err) = with_closed(&["analyze", "gen:sphere:300", "--size", "64"], true, false);
    assert_eq!(code, Some(0), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn list_with_its_stdout_closed_ends_quietly() {
    let (code, err) = with_closed(&["list"], true, false);
    assert_eq!(code, Some(0), "{err}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn an_error_with_stderr_closed_still_exits_2() {
    let (code, _) = with_closed(&["analyze", "no-such-file.obj"], false, true);
    assert_eq!(code, Some(2));
    let (code, _) = with_closed(&["analyze", "gen:cube", "--size", "0"], false, true);
    assert_eq!(code, Some(2));
}

#[test]
fn render_with_stderr_closed_still_writes_the_png() {
    let dir = temp_dir("closed-stderr");
    let png = dir.join("out.png");
    let png_arg = png.to_string_lossy().into_owned();
    let args = ["render", "gen:sphere:300", "-o", &png_arg, "--size", "64"];
    let (code, _) = with_closed(&args, false, true);
    assert_eq!(code, Some(0));
    assert!(png.exists(), "the PNG is written");
}
