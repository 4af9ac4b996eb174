//! What a new user hits at the edges of `hider`: outputs that are not
//! regular files, bad flag values, and a picture with nothing in it. Each
//! test starts from an example an outside tester found.

use std::process::{Command, Output};

mod cli_support;
use cli_support::{
    assert_mentions, assert_one_line_failure, assert_success, hider, render, stderr, temp_dir,
};

/// Asserts exit status 2 with exactly one line on stderr holding every
/// needle.
fn assert_one_line_error(out: &Output, needles: &[&str]) {
    let err = assert_one_line_failure(out);
    assert!(err.starts_with("hider: error: "), "{err}");
    assert_mentions(&err, needles);
}

#[test]
fn every_bad_flag_value_is_one_line_naming_flag_and_value() {
    let dir = temp_dir("flags");
    let png = dir.join("out.png");
    let cases: &[(&[&str], &[&str])] = &[
        (&["--size", "-5"], &["--size", "'-5'", "1 to 16384"]),
        (&["--size", "1e3"], &["--size", "'1e3'"]),
        (&["--width", "-1", "--height", "4"], &["--width", "'-1'"]),
        (&["--fovy", "-30"], &["--fovy", "'-30'", "180"]),
        (&["--fovy", "180"], &["--fovy", "'180'"]),
        (&["--near", "-1"], &["--near", "'-1'", "more than 0"]),
        (&["--far", "0"], &["--far", "'0'"]),
        (&["--eye", "1,2"], &["--eye", "'1,2'", "x,y,z"]),
        (&["--target", "1,2,x"], &["--target", "'x'"]),
        (&["--up", "-1,-2,nan"], &["--up", "'nan'"]),
        (&["--width", "10"], &["--width 10", "--height"]),
        (&["--height", "10"], &["--height 10", "--width"]),
        (&["--threads", "-1"], &["--threads", "'-1'", "1 to 1024"]),
        (&["--threads", "0"], &["--threads", "'0'"]),
        (&["--repeat", "-3"], &["--repeat", "'-3'"]),
        (
            &["--shade", "phong"],
            &["--shade", "'phong'", "lambert, ids"],
        ),
        (
            &["--depth-format", "f16"],
            &["--depth-format", "'f16'", "fixed24"],
        ),
        (&["--precision", "f128"], &["--precision", "'f128'"]),
        (&["--eye"], &["--eye", "needs a value"]),
        (
            &["--size", "5", "--width", "4"],
            &["--size cannot be used with --width"],
        ),
        (
            &["--algo", "zbuffer", "--algo", "scanline"],
            &["--algo is given more than once"],
        ),
        (&["--frobnicate"], &["--frobnicate"]),
        (&["--aa", "--algo", "zbuffer"], &["--aa", "--algo zbuffer"]),
        (&["--svg-mode", "painter"], &["--svg-mode painter", "--svg"]),
        (
            &[
                "--svg",
                "/tmp/unwritten.svg",
                "--svg-mode",
                "painter",
                "--stroke-width",
                "2",
            ],
            &["--stroke-width applies to --svg-mode regions or lines"],
        ),
    ];
    for (extra, needles) in cases {
        let out = render("gen:cube", &png, extra);
        assert_one_line_error(&out, needles);
        assert!(!png.exists(), "{extra:?} wrote an image");
    }
    let out = hider(&["render", "gen:cube"]);
    assert_one_line_error(&out, &["--output"]);
    let out = hider(&["analyze", "gen:cube", "--size", "-5"]);
    assert_one_line_error(&out, &["--size", "'-5'"]);
    let out = hider(&["analyze", "gen:cube", "--pair-budget", "-1"]);
    assert_one_line_error(&out, &["--pair-budget", "'-1'"]);
    let out = hider(&["lsit"]);
    assert_one_line_error(&out, &["'lsit'", "list"]);
    let out = hider(&["list", "extra"]);
    assert_one_line_error(&out, &["'extra'"]);
    let out = hider(&[]);
    assert_one_line_error(&out, &["no subcommand", "render"]);
    // Help is not an error.
    let out = hider(&["render", "--help"]);
    assert_eq!(out.status.code(), Some(0));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[cfg(target_os = "linux")]
#[test]
fn a_full_device_is_written_through_and_reported() {
    use std::os::unix::fs::FileTypeExt;
    let is_device =
        || std::fs::symlink_metadata("/dev/full").is_ok_and(|m| m.file_type().is_char_device());
    if !is_device() {
        eprintln!("no /dev/full here: skipped");
        return;
    }
    let dir = temp_dir("full");
    let png = dir.join("out.png");
    let png = png.to_str().unwrap();
    // A named hider, so that stderr holds only the error.
    for (flag, algo) in [
        ("-o", "zbuffer"),
        ("--ids-out", "zbuffer-tiled"),
        ("--depth-out", "scanline"),
        ("--svg", "painter"),
    ] {
        let output = if flag == "-o" { "/dev/full" } else { png };
        let mut args = vec!["render", "gen:cube", "--size", "16", "-o", output];
        if flag != "-o" {
            args.extend([flag, "/dev/full"]);
        }
        args.extend(["--algo", algo]);
        let out = hider(&args);
        assert_one_line_error(&out, &["/dev/full", "No space left on device"]);
        assert!(is_device(), "{flag} replaced /dev/full");
    }
    // /dev/null takes the output and stays a device.
    let out = hider(&["render", "gen:cube", "--size", "16", "-o", "/dev/null"]);
    assert_success(&out);
    assert!(std::fs::symlink_metadata("/dev/null").is_ok_and(|m| m.file_type().is_char_device()));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[cfg(unix)]
#[test]
fn outputs_through_a_symbolic_link_keep_the_link() {
    let dir = temp_dir("link");
    let real = dir.join("real.png");
    std::fs::write(&real, "old").unwrap();
    let link = dir.join("link.png");
    std::os::unix::fs::symlink("real.png", &link).unwrap();
    let out = hider(&[
        "render",
        "gen:cube",
        "--size",
        "16",
        "-o",
        link.to_str().unwrap(),
    ]);
    assert_success(&out);
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert!(std::fs::read(&real).unwrap().starts_with(b"\x89PNG"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_plane_seen_edge_on_warns_and_suggests_an_eye() {
    let dir = temp_dir("edge-on");
    // A square in the plane y = 0: the fit camera's eye sits in that plane.
    let obj = dir.join("floor.obj");
    std::fs::write(&obj, "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nf 1 2 3 4\n").unwrap();
    let obj = obj.to_str().unwrap();
    let png = dir.join("floor.png");
    let out = render(obj, &png, &["--size", "64"]);
    let err = assert_success(&out);
    let warning = err
        .lines()
        .find(|l| l.starts_with("hider: warning: nothing on screen"))
        .unwrap_or_else(|| panic!("no warning: {err}"));
    assert!(
        warning.contains("edge-on") && warning.contains("--eye"),
        "{warning}"
    );
    // The suggested eye sees the square.
    let eye = warning
        .split("--eye ")
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .unwrap();
    let out = render(obj, &png, &["--size", "64", "--eye", eye]);
    let err = assert_success(&out);
    assert!(!err.contains("nothing on screen"), "--eye {eye}: {err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_empty_picture_says_why() {
    let dir = temp_dir("empty");
    let png = dir.join("empty.png");

    // Everything behind the eye: outside the view.
    let out = render(
        "gen:cube",
        &png,
        &["--size", "32", "--eye", "0,0,10", "--target", "0,0,20"],
    );
    let err = assert_success(&out);
    assert!(
        err.contains("nothing on screen") && err.contains("outside the view"),
        "{err}"
    );
    // A triangle far smaller than the snapping step: zero area on screen.
    let tiny = dir.join("tiny.obj");
    std::fs::write(&tiny, "v 0 0 0\nv 1e-4 0 0\nv 0 1e-4 0\nf 1 2 3\n").unwrap();
    let out = render(
        tiny.to_str().unwrap(),
        &png,
        &[
            "--size",
            "16",
            "--eye",
            "0.3,0.3,10",
            "--target",
            "0.3,0.3,0",
            "--near",
            "0.1",
            "--far",
            "100",
        ],
    );
    let err = assert_success(&out);
    assert!(
        err.contains("nothing on screen: the triangle has zero area on screen"),
        "{err}"
    );
    // A picture with something in it has no such warning.
    let out = render("gen:cube", &png, &["--size", "32"]);
    assert!(!stderr(&out).contains("nothing on screen"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A render that takes over a second here, so past the spinner's delay.
const LONG_RENDER: [&str; 8] = [
    "render",
    "gen:sphere:1000",
    "--size",
    "2048",
    "--algo",
    "scanline",
    "-o",
    "",
];

#[test]
fn the_spinner_shows_on_a_terminal_only() {
    let dir = temp_dir("spinner");
    let png = dir.join("long.png");
    let mut args = LONG_RENDER;
    args[7] = png.to_str().unwrap();
    // Not a terminal: nothing but whole lines, however long the run.
    let out = hider(&args);
    let err = assert_success(&out);
    assert!(!err.contains('\r') && !err.contains('\u{1b}'), "{err:?}");
    // On a terminal (a pseudo-terminal from `script`, where there is one),
    // with the delay set to 0 so that the check does not hang on timing:
    // the stage is named.
    let command = format!(
        "{} render gen:cube --size 16 -o {}",
        env!("CARGO_BIN_EXE_hider"),
        png.display()
    );
    let typescript = dir.join("typescript");
    let on_terminal = Command::new("script")
        .args(["-qec", &command, typescript.to_str().unwrap()])
        .env("HIDER_SPINNER_DELAY_MS", "0")
        .output();
    match on_terminal {
        Ok(out) if out.status.success() => {
            let seen = String::from_utf8_lossy(&std::fs::read(&typescript).unwrap()).into_owned();
            assert!(seen.contains("loading the model"), "{seen:?}");
        }
        _ => eprintln!("no `script` to make a terminal with: the terminal half skipped"),
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
