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
    assert_eq!(text.matches("<path data-prim").count(), 2, "{text}");
    // Pixel coordinates, no transform; seamless by default (a clip path
    // of the covered set and each region stroked in its colour).
    assert!(!text.contains("transform"), "{text}");
    assert!(text.contains(r#"clip-path="url(#covered)""#), "{text}");
    assert!(text.contains("<title>gen:intersecting</title>"), "{text}");
    assert!(
        !text.contains("<rect"),
        "no background unless asked: {text}"
    );
    let same = svg_of(
        &dir,
        "gen:intersecting",
        &["--algo", "zbuffer", "--svg-mode", "regions"],
    );
    assert_eq!(text, same);
    // A cube from the fit camera: one path per visible face.
    let cube = svg_of(&dir, "gen:cube", &[]);
    assert!(
        (1..=3).contains(&cube.matches("<path data-prim").count()),
        "{cube}"
    );
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

/// The points of every polyline of a lines SVG.
fn polylines(text: &str) -> Vec<Vec<(f64, f64)>> {
    text.split("points=\"")
        .skip(1)
        .map(|rest| {
            rest[..rest.find('"').unwrap()]
                .split(' ')
                .map(|p| {
                    let (x, y) = p.split_once(',').unwrap();
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect()
        })
        .collect()
}

#[test]
fn a_cube_seen_head_on_draws_only_its_outline() {
    // Issue 38: the cube's side edges project onto the front face's
    // diagonals, exactly under the shared edge of its two triangles, and
    // were drawn (two of 50 px). Only the outline is visible.
    let dir = temp_dir("cube-head-on");
    let cube = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/cube.obj");
    let png = dir.join("c.png");
    let svg = dir.join("c.svg");
    let out = hider(&[
        "render",
        cube,
        "-o",
        png.to_str().unwrap(),
        "--size",
        "256",
        "--svg",
        svg.to_str().unwrap(),
        "--svg-mode",
        "lines",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    for line in polylines(&text) {
        for w in line.windows(2) {
            let axis = w[0].0 == w[1].0 || w[0].1 == w[1].1;
            assert!(axis, "a diagonal segment {:?} is drawn: {text}", w);
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_vector_flags_reach_the_svg() {
    let dir = temp_dir("vector-flags");
    // Hidden lines dashed, in layers of their own; a background; a page.
    let text = svg_of(
        &dir,
        "gen:cube",
        &[
            "--svg-mode",
            "lines",
            "--hidden",
            "dashed",
            "--background",
            "white",
            "--page-size",
            "A4",
            "--stroke-width",
            "0.5mm",
        ],
    );
    assert!(text.contains(r#"id="hidden""#), "{text}");
    assert!(text.contains("stroke-dasharray"), "{text}");
    assert!(text.contains(r#"<rect id="background" width="64" height="64" fill="white"/>"#));
    assert!(text.contains(r#"width="210mm" height="297mm" viewBox="0 0 64 64""#));
    // 0.5 mm on A4 at 64 pixels across 210 mm: 64 / 210 * 0.5 pixels.
    let width = 64.0 / 210.0 * 0.5;
    assert!(
        text.contains(&format!(r#"stroke-width="{width}""#)),
        "{width}: {text}"
    );
    // Creases: none above 100 degrees on a cube (its are 90), seen from
    // a corner where three of them show.
    let corner = ["--svg-mode", "lines", "--eye", "3.1,2.3,4.2"];
    let with = svg_of(&dir, "gen:cube", &corner);
    let mut flat = corner.to_vec();
    flat.extend_from_slice(&["--crease-angle", "100"]);
    let without = svg_of(&dir, "gen:cube", &flat);
    assert!(with.contains(r#"class="crease""#), "{with}");
    assert!(!without.contains(r#"class="crease""#), "{without}");
    // Seams off: the bare regions, no clip and no stroke.
    let bare = svg_of(&dir, "gen:cube", &["--seams", "off"]);
    assert!(!bare.contains("clip-path"), "{bare}");
    assert!(!bare.contains("stroke=\"#"), "{bare}");
    // Bad values are refused.
    for bad in [
        ["--stroke-width", "-1"],
        ["--crease-angle", "200"],
        ["--page-size", "B9"],
        ["--background", "red\"/>"],
    ] {
        let png = dir.join("bad.png");
        let svg = dir.join("bad.svg");
        let mut args = vec!["render", "gen:cube", "-o", png.to_str().unwrap()];
        args.extend_from_slice(&["--svg", svg.to_str().unwrap()]);
        args.extend_from_slice(&bad);
        let out = hider(&args);
        assert!(!out.status.success(), "{bad:?} was accepted");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn textured_scenes_are_told_their_region_fills_are_flat() {
    let dir = temp_dir("textured");
    let spider = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/spider/spider.obj");
    let png = dir.join("s.png");
    let svg = dir.join("s.svg");
    let out = hider(&[
        "render",
        spider,
        "-o",
        png.to_str().unwrap(),
        "--size",
        "64",
        "--svg",
        svg.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("region fills are flat colours"), "{stderr}");
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("textures are not written</desc>"), "{text}");
    // One layer per OBJ group.
    assert!(text.contains(r#"inkscape:label="Bein1Li""#), "{text}");
    std::fs::remove_dir_all(&dir).unwrap();
}
