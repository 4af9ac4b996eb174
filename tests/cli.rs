//! The `hider` command line: bad input gives one line on stderr and exit
//! status 2, never a panic and never a partial output file.

use std::path::Path;
use std::process::Output;

mod cli_support;
use cli_support::{assert_mentions, assert_one_line_failure, assert_success, render, temp_dir};

/// Asserts a failed run: status 2, exactly one line on stderr that contains
/// every `needles`, no panic, and no output file left behind.
fn assert_fails(out: &Output, needles: &[&str], png: &Path) {
    let stderr = assert_one_line_failure(out);
    assert_mentions(&stderr, needles);
    assert!(!png.exists(), "no output file after an error");
    let dir = png.parent().unwrap();
    let leftovers: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".tmp") || n.ends_with(".png"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_string_lossy().into_owned()
}

#[test]
fn bad_inputs_exit_2_with_one_line() {
    let dir = temp_dir("bad");
    let png = dir.join("out.png");
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

    let missing = dir.join("missing.obj");
    let out = render(missing.to_str().unwrap(), &png, &[]);
    assert_fails(&out, &["missing.obj", "No such file"], &png);

    let bad = write(&dir, "malformed.obj", &format!("{tri}f 1 2 three\n"));
    let out = render(&bad, &png, &[]);
    assert_fails(&out, &["malformed.obj:4", "'three'"], &png);

    let range = write(&dir, "range.obj", &format!("{tri}f 1 2 9\n"));
    let out = render(&range, &png, &[]);
    assert_fails(&out, &["range.obj:4", "index 9 out of range"], &png);

    let nan = write(&dir, "nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
    let out = render(&nan, &png, &[]);
    assert_fails(&out, &["nan.obj:2", "NaN"], &png);

    let good = write(&dir, "good.obj", &format!("{tri}f 1 2 3\n"));
    let out = render(&good, &png, &["--size", "0"]);
    assert_fails(&out, &["--size", "'0'", "1 to 16384"], &png);
    let out = render(&good, &png, &["--size", "16385"]);
    assert_fails(&out, &["16385", "16384"], &png);
    let out = render(&good, &png, &["--algo", "nonesuch"]);
    assert_fails(&out, &["nonesuch", "zbuffer"], &png);
    let out = render(&good, &png, &["--eye", "0,0,nan"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(!png.exists());

    let nowhere = dir.join("no/such/dir/out.png");
    let out = render(&good, &nowhere, &[]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no/such/dir/out.png"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn render_writes_png_and_gl_format_dumps() {
    let dir = temp_dir("good");
    let png = dir.join("cube.png");
    let ids = dir.join("cube.i32");
    let depth = dir.join("cube.f32");
    let out = render(
        "gen:cube",
        &png,
        &[
            "--width",
            "40",
            "--height",
            "30",
            "--ids-out",
            ids.to_str().unwrap(),
            "--depth-out",
            depth.to_str().unwrap(),
            "--shade",
            "ids",
            "--repeat",
            "2",
        ],
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_success(&out);
    assert!(
        stdout.contains("median") && stdout.contains("min"),
        "{stdout}"
    );
    assert_eq!(std::fs::read(&ids).unwrap().len(), 40 * 30 * 4);
    assert_eq!(std::fs::read(&depth).unwrap().len(), 40 * 30 * 4);
    let id_values = hider::scene::frame::read_ids(&ids, 40, 30).unwrap();
    let depth_values = hider::scene::frame::read_depth(&depth, 40, 30).unwrap();
    // The cube fills the centre; the corners are background with depth 1.
    assert!(id_values[15 * 40 + 20] < 12);
    assert_eq!(id_values[0], hider::scene::NO_ID);
    assert_eq!(depth_values[0], 1.0);
    assert!(depth_values[15 * 40 + 20] < 1.0);
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn tiled_repeat_times_its_own_pipeline_and_writes_the_same_ids() {
    let dir = temp_dir("tiled");
    let mut ids = Vec::new();
    for (algo, threads) in [
        ("zbuffer", "1"),
        ("zbuffer-tiled", "1"),
        ("zbuffer-tiled", "2"),
    ] {
        let file = dir.join(format!("{algo}-{threads}.i32"));
        let out = render(
            "gen:sphere:24",
            &dir.join("s.png"),
            &[
                "--size",
                "70",
                "--algo",
                algo,
                "--threads",
                threads,
                "--precision",
                "f32",
                "--ids-out",
                file.to_str().unwrap(),
                "--repeat",
                "3",
            ],
        );
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert_success(&out);
        assert!(
            stdout.contains("median") && stdout.contains("over 3 runs"),
            "{stdout}"
        );
        // Every hider's timed span is its whole pipeline (`render_scene`):
        // for the tiled z-buffer its own lean front end, draw and read-back.
        assert!(stdout.contains("prepare + clear + rasterise"), "{stdout}");
        ids.push(std::fs::read(&file).unwrap());
    }
    assert!(ids.windows(2).all(|w| w[0] == w[1]));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn painter_writes_svg_and_other_hiders_refuse_it() {
    let dir = temp_dir("svg");
    let png = dir.join("pair.png");
    let svg = dir.join("pair.svg");
    let out = render(
        "gen:intersecting",
        &png,
        &[
            "--size",
            "64",
            "--algo",
            "painter",
            "--svg",
            svg.to_str().unwrap(),
            "--svg-mode",
            "painter",
        ],
    );
    assert_success(&out);
    let text = std::fs::read_to_string(&svg).unwrap();
    // The pair pierces itself: splitting leaves three pieces, one path each.
    assert_eq!(text.matches("<path").count(), 3, "{text}");
    std::fs::remove_file(&png).unwrap();
    std::fs::remove_file(&svg).unwrap();
    let out = render(
        "gen:cube",
        &png,
        &[
            "--algo",
            "zbuffer",
            "--svg",
            svg.to_str().unwrap(),
            "--svg-mode",
            "painter",
        ],
    );
    assert_fails(&out, &["--svg", "painter"], &png);
    assert!(!svg.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
