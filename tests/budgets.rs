//! Every budget a render can run into is a flag: the painter's splits
//! (`--max-splits`), the A-buffers' fragment lists (`--max-list-len`,
//! `--overflow`) and the exact vector geometry's pairs (`--max-pairs`).
//! A budget used up fails in one line naming the flag that raises it; a
//! budget flag given to a hider without that budget is refused naming the
//! hiders that have it; under `--algo auto` it applies when the plan picks
//! such a hider.

use std::process::Output;

mod cli_support;
use cli_support::{assert_one_line_failure, assert_success, hider, temp_dir};

fn run(args: &[&str]) -> Output {
    hider(&[&["render"][..], args].concat())
}

fn error_line(out: &Output) -> String {
    let line = assert_one_line_failure(out);
    assert!(line.starts_with("hider: error: "), "{line}");
    line
}

#[test]
fn a_used_up_budget_names_the_flag_that_raises_it() {
    let dir = temp_dir("budgets");
    let png = dir.join("out.png");
    let png = png.to_str().unwrap();
    let svg = dir.join("out.svg");
    let svg = svg.to_str().unwrap();
    let base = ["gen:intersecting", "--size", "32", "-o", png];

    // The painter with no splits allowed: the intersecting pair needs one.
    let out = run(&[&base[..], &["--algo", "painter", "--max-splits", "0"]].concat());
    let line = error_line(&out);
    assert!(line.contains("painter splits"), "{line}");
    assert!(line.contains("raise it with --max-splits"), "{line}");
    assert_success(&run(&[
        &base[..],
        &["--algo", "painter", "--max-splits", "100"],
    ]
    .concat()));

    // One fragment per pixel, and fail rather than drop: two panes of
    // glass, one behind the other, put two surfaces in each pixel's list.
    std::fs::write(
        dir.join("glass.mtl"),
        "newmtl glass\nKd 0.2 0.6 0.9\nd 0.5\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("glass.obj"),
        "mtllib glass.mtl\nusemtl glass\nv -1 -1 0\nv 1 -1 0\nv 0 1 0\n\
         v -1 -1 -1\nv 1 -1 -1\nv 0 1 -1\nf 1 2 3\nf 4 5 6\n",
    )
    .unwrap();
    let glass = dir.join("glass.obj");
    let panes = [glass.to_str().unwrap(), "--size", "32", "-o", png];
    let base = panes;
    let out = run(&[
        &base[..],
        &[
            "--algo",
            "abuffer",
            "--max-list-len",
            "1",
            "--overflow",
            "error",
        ],
    ]
    .concat());
    let line = error_line(&out);
    assert!(line.contains("max_list_len"), "{line}");
    let dropped = run(&[&base[..], &["--algo", "abuffer", "--max-list-len", "1"]].concat());
    assert_success(&dropped);
    assert!(
        String::from_utf8_lossy(&dropped.stderr).contains("dropped"),
        "the default policy drops and says so"
    );

    // The exact regions of three bars overlapping in a cycle, one pair
    // allowed.
    let base = ["gen:cyclic", "--algo", "zbuffer", "--size", "32", "-o", png];
    std::fs::remove_file(dir.join("out.png")).unwrap();
    let out = run(&[&base[..], &["--svg", svg, "--max-pairs", "1"]].concat());
    let line = error_line(&out);
    assert!(line.contains("raise it with --max-pairs"), "{line}");
    assert!(!dir.join("out.png").exists(), "no output of a failed run");
    assert_success(&run(
        &[&base[..], &["--svg", svg, "--max-pairs", "1000"]].concat()
    ));
    // The same regions, ten region vertices allowed: refused in one
    // line naming the flag, before the map-wide booleans.
    std::fs::remove_file(dir.join("out.png")).unwrap();
    let out = run(&[&base[..], &["--svg", svg, "--max-region-points", "10"]].concat());
    let line = error_line(&out);
    assert!(line.contains("raise it with --max-region-points"), "{line}");
    assert!(!dir.join("out.png").exists(), "no output of a failed run");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_budget_flag_goes_to_the_hiders_that_have_that_budget() {
    let dir = temp_dir("budget-flags");
    let png = dir.join("out.png");
    let png = png.to_str().unwrap();
    let base = ["gen:cube", "--size", "16", "-o", png];
    for (flags, needles) in [
        (
            &["--algo", "zbuffer", "--max-splits", "5"][..],
            &["--max-splits", "--algo painter only", "splits no polygons"][..],
        ),
        (
            &["--algo", "painter", "--max-list-len", "4"],
            &["--max-list-len", "abuffer", "keeps no fragment lists"],
        ),
        (
            &["--algo", "zbuffer-tiled", "--overflow", "error"],
            &["--overflow", "abuffer-carpenter"],
        ),
        (
            &[
                "--max-pairs",
                "5",
                "--svg",
                "x.svg",
                "--svg-mode",
                "painter",
            ],
            &["--max-pairs", "regions or lines"],
        ),
        (
            &[
                "--max-region-points",
                "5",
                "--svg",
                "x.svg",
                "--svg-mode",
                "lines",
            ],
            &["--max-region-points", "--svg-mode lines", "regions only"],
        ),
        (
            &[
                "--max-region-points",
                "5",
                "--svg",
                "x.svg",
                "--svg-mode",
                "painter",
            ],
            &["--max-region-points", "--svg-mode painter", "regions only"],
        ),
    ] {
        let line = error_line(&run(&[&base[..], flags].concat()));
        for needle in needles {
            assert!(line.contains(needle), "{flags:?}: {line}");
        }
    }
    // Under auto a budget is a limit for the hider the plan picks: the
    // cube's plan is a z-buffer, which has none of them.
    assert_success(&run(&[
        &base[..],
        &[
            "--max-splits",
            "5",
            "--max-list-len",
            "2",
            "--overflow",
            "error",
        ],
    ]
    .concat()));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_timeout_stops_the_render_with_one_line_naming_the_flag() {
    let dir = temp_dir("timeout");
    let png = dir.join("out.png");
    let png = png.to_str().unwrap();
    let svg = dir.join("out.svg");
    let svg = svg.to_str().unwrap();
    // 0 seconds: every hider stops at its first poll, whatever the machine.
    for algo in ["zbuffer-tiled", "painter", "abuffer", "warnock"] {
        let args = [
            "gen:intersecting",
            "--size",
            "32",
            "-o",
            png,
            "--algo",
            algo,
        ];
        let out = run(&[&args[..], &["--timeout", "0"]].concat());
        let line = error_line(&out);
        assert!(
            line.contains("render timed out after 0ns; raise it with --timeout"),
            "{algo}: {line}"
        );
        assert!(!dir.join("out.png").exists(), "no output of a failed run");
        assert_success(&run(&[&args[..], &["--timeout", "60"]].concat()));
        std::fs::remove_file(dir.join("out.png")).unwrap();
    }
    // `auto` prints its plan first, then the same line.
    let auto = [
        "gen:intersecting",
        "--size",
        "32",
        "-o",
        png,
        "--algo",
        "auto",
    ];
    let out = run(&[&auto[..], &["--timeout", "0"]].concat());
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr
            .trim_end()
            .ends_with("hider: error: render timed out after 0ns; raise it with --timeout"),
        "{stderr}"
    );
    // With --svg as well.
    let args = ["gen:cyclic", "--algo", "zbuffer", "--size", "32", "-o", png];
    let out = run(&[&args[..], &["--svg", svg, "--timeout", "0"]].concat());
    assert!(error_line(&out).contains("--timeout"));
    for bad in ["-1", "nan", "x"] {
        let line = error_line(&run(&["gen:cube", "-o", png, "--timeout", bad]));
        assert!(line.contains("--timeout"), "{line}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_size_over_a_hiders_memory_budget_fails_before_the_model_is_read() {
    // The supersampled z-buffer at 16384 x 16384 would need 72 GB: the
    // hider refuses the size when it is built, before the model is read
    // (the missing file is never reported) and before a frame of gigabytes
    // is allocated; nothing is written.
    let dir = temp_dir("size_budget");
    let png = dir.join("out.png");
    let missing = dir.join("missing.obj");
    for algo in ["ssaa-32", "ssaa-sorted", "abuffer", "oracle"] {
        let out = run(&[
            missing.to_str().unwrap(),
            "--size",
            "16384",
            "--algo",
            algo,
            "-o",
            png.to_str().unwrap(),
        ]);
        let line = error_line(&out);
        assert!(line.contains("is over the limit of"), "{algo}: {line}");
        assert!(!line.contains("missing.obj"), "{algo}: {line}");
        assert!(!png.exists(), "{algo}");
    }
}
