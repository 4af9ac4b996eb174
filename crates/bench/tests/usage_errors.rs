//! A bad argument to `hider-bench` (and so to `hider bench`) is one line
//! naming the flag and the value, exit status 2, as `hider` prints it; not
//! clap's multi-line usage, and a negative number is a value, not a flag.

use std::process::Command;

fn bench(args: &[&str]) -> (i32, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_hider-bench"))
        .args(args)
        .output()
        .expect("hider-bench runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn bad_arguments_are_one_line_naming_the_flag_and_value() {
    for (args, flag, value) in [
        (&["--sizes", "-5"][..], "--sizes", "-5"),
        (&["--sizes", "big"][..], "--sizes", "big"),
        (&["--repeats", "x"][..], "--repeats", "x"),
    ] {
        let (code, stderr) = bench(args);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert_eq!(stderr.lines().count(), 1, "{args:?}: {stderr}");
        assert!(
            stderr.starts_with("hider-bench: error: ")
                && stderr.contains(flag)
                && stderr.contains(value),
            "{args:?}: {stderr}"
        );
    }
    let (code, stderr) = bench(&["--no-such-flag"]);
    assert_eq!((code, stderr.lines().count()), (2, 1), "{stderr}");
}
