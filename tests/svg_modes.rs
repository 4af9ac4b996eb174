//! `hider render --svg out.svg --svg-mode regions|lines`: the exact
//! visible regions (the default) and the hidden-line drawing. The
//! painter's ordered polygon list (`--svg-mode painter`), and its refusal
//! by hiders without one, are tested with the other output errors in
//! `tests/cli.rs`.

mod cli_support;
use cli_support::{hider, temp_dir};

/// Renders `model` with `extra` arguments and returns the SVG written.
fn svg_of(dir: &std::path::Path, model: &str, extra: &[&str]) -> String {
    let png = dir.join("out.png");
    let svg = dir.join("out.svg");
    let mut args = vec!["render", model, "-o", png.to_str().unwrap(), "--size", "64"];
    args.extend_from_slice(&["--svg", svg.to_str().unwrap()]);
    args.extend_from_slice(extra);
    let out = hider(&args);
    assert!(
        out.status.success(),
        "{:?}: {}",
        args,
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    std::fs::remove_file(&svg).unwrap();
    text
}

#[test]
fn regions_are_the_default_and_need_no_painter() {
    let dir = temp_dir("regions");
    // The intersecting pair: two primitives, each visible in one piece.
    let text = svg_of(&dir, "gen:intersecting", &["--algo", "zbuffer"]);
    assert_eq!(text.matches("<path").count(), 2, "{text}");
    assert!(text.contains("transform=\"scale("), "{text}");
    let same = svg_of(
        &dir,
        "gen:intersecting",
        &["--algo", "zbuffer", "--svg-mode", "regions"],
    );
    assert_eq!(text, same);
    // A cube from the fit camera: one path per visible face.
    let cube = svg_of(&dir, "gen:cube", &[]);
    assert!((1..=3).contains(&cube.matches("<path").count()), "{cube}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn lines_mode_writes_polylines() {
    let dir = temp_dir("lines");
    let text = svg_of(&dir, "gen:intersecting", &["--svg-mode", "lines"]);
    assert!(text.contains("<polyline"), "{text}");
    assert!(!text.contains("<path"), "{text}");
    // The pair pierces itself: its intersection line is drawn (red).
    assert!(text.contains("#b03030"), "{text}");
    std::fs::remove_dir_all(&dir).unwrap();
}
