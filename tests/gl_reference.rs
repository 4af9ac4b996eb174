//! Pixel-by-pixel agreement with a real OpenGL implementation.
//!
//! `tests/data/gl/` holds renders by Mesa's llvmpipe, made by the `peers/`
//! harness from the cases of `tests/data/gl/cases.txt` (the data folder's
//! README says how to regenerate them): per pixel, the visible triangle's
//! index and GL's window depth. This test renders every case with hider's
//! GL-compatible front end (`PrepareOptions::gl_compatible`) and every
//! exact pixel-centre hider of the registry, plus the two z-buffers with
//! GL's own depth test (`DepthTest::GlLess`), and checks:
//!
//! - coverage identical to llvmpipe on every pixel (the front end snaps and
//!   fills as llvmpipe does: docs/conventions.md);
//! - ids identical on every pixel that is not a depth tie. Where ids
//!   differ, the pixel is a tie when the oracle's tie criterion holds there
//!   ([`Reference::compare`]'s: relative gap below
//!   [`DEFAULT_TIE_TOLERANCE`] or window-depth gap below
//!   [`WINDOW_TIE_TOLERANCE`]) or when hider's and GL's triangles both
//!   cover the centre at window depths closer than
//!   [`WINDOW_TIE_TOLERANCE`] (coincident coplanar faces). A third kind is
//!   counted apart, as a *set-up tie*: both triangles cover the centre and
//!   their depths there differ by less than moving their vertices half a
//!   snapping step (1/512 pixel in x and y) can change them. llvmpipe
//!   interpolates depth from its own float set-up, hider from the snapped
//!   vertices, so two interpenetrating surfaces that close may be ordered
//!   either way (one pixel of the close spider view). Every other
//!   differing pixel fails the test.
//!
//! Missing reference data fails the test: it is part of the repository.
//! Run with `--nocapture` for the agreement table.

use std::path::{Path, PathBuf};

use hider::geom::Camera;
use hider::geom::glam::DVec3;
use hider::oracle::{DEFAULT_TIE_TOLERANCE, RayCastOracle, Reference, WINDOW_TIE_TOLERANCE};
use hider::scene::{
    DynHider, Frame, Hider, NO_ID, PrepareOptions, Scene, ScreenScene, View, load_obj, prepare,
    procedural,
};
use hider::zbuffer::{
    DepthFormat, DepthTest, TiledZBuffer, TiledZBufferOptions, ZBuffer, ZBufferOptions,
};
use hider_plan::registry;

/// One case of the manifest.
struct Case {
    name: String,
    size: u32,
    scene: String,
    camera: Vec<String>,
}

fn data_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/gl")
}

/// The manifest, `NAME SIZE SCENE CAMERA...` per line (the data folder's
/// README).
fn cases() -> Vec<Case> {
    let path = data_dir().join("cases.txt");
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (the GL reference data is missing)", path.display()));
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let w: Vec<&str> = line.split_whitespace().collect();
        assert!(w.len() >= 4, "cases.txt line {}: too few words", n + 1);
        out.push(Case {
            name: w[0].to_owned(),
            size: w[1]
                .parse()
                .unwrap_or_else(|_| panic!("cases.txt line {}: bad size", n + 1)),
            scene: w[2].to_owned(),
            camera: w[3..].iter().map(|s| (*s).to_owned()).collect(),
        });
    }
    out
}

fn load_scene(spec: &str) -> Scene {
    if let Some(file) = spec.strip_prefix("obj:") {
        return load_obj(data_dir().join(file)).expect("reference model loads");
    }
    let n = spec
        .strip_prefix("sphere:")
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("scene `{spec}` is neither obj:FILE nor sphere:N"));
    procedural::uv_sphere(n)
}

fn view(case: &Case, scene: &Scene) -> View {
    let point = |w: &str| {
        let v: Vec<f64> = w.split(',').map(|c| c.parse().expect("x,y,z")).collect();
        DVec3::new(v[0], v[1], v[2])
    };
    match case.camera.as_slice() {
        [fit] if fit == "fit" => View::for_scene(scene, case.size, case.size).unwrap(),
        [look, eye, target, near, far] if look == "look" => {
            let camera = Camera::perspective(
                point(eye),
                point(target),
                near.parse().expect("near"),
                far.parse().expect("far"),
            );
            View::new(camera, case.size, case.size).unwrap()
        }
        other => panic!("{}: camera `{}` not understood", case.name, other.join(" ")),
    }
}

/// llvmpipe's ids (`NO_ID` for background) and window depths, top row
/// first.
fn gl_buffers(case: &Case) -> (Vec<u32>, Vec<f32>) {
    let open = |suffix: &str| {
        let path = data_dir().join(format!("{}.{suffix}.png", case.name));
        image::open(&path).unwrap_or_else(|e| {
            panic!(
                "{}: {e} (GL reference data missing: run tests/data/gl/regen.sh)",
                path.display()
            )
        })
    };
    let ids = open("ids").to_rgb8();
    let depth = open("depth").to_rgba8();
    for (what, (w, h)) in [("ids", ids.dimensions()), ("depth", depth.dimensions())] {
        assert_eq!((w, h), (case.size, case.size), "{} {what}: size", case.name);
    }
    let ids = ids
        .pixels()
        .map(|p| {
            let v = u32::from_le_bytes([p[0], p[1], p[2], 0]);
            v.checked_sub(1).unwrap_or(NO_ID)
        })
        .collect();
    let depth = depth.pixels().map(|p| f32::from_le_bytes(p.0)).collect();
    (ids, depth)
}

/// The hiders checked: every exact pixel-centre hider of the registry,
/// and the plain and tiled z-buffers with GL's depth test and 24-bit
/// depth.
fn hiders() -> Vec<(String, Box<dyn DynHider>)> {
    let mut out: Vec<(String, Box<dyn DynHider>)> = registry::pixel_centre_hiders()
        .into_iter()
        .map(|h| (h.name().to_owned(), h))
        .collect();
    let gl = ZBufferOptions::default()
        .with_depth_test(DepthTest::GlLess)
        .with_depth_format(DepthFormat::Fixed24);
    out.push(("zbuffer gl-less z24".into(), Box::new(ZBuffer::new(gl))));
    let tiled = TiledZBufferOptions::default()
        .with_depth_test(DepthTest::GlLess)
        .with_depth_format(DepthFormat::Fixed24);
    out.push((
        "zbuffer-tiled gl-less z24".into(),
        Box::new(TiledZBuffer::new(tiled)),
    ));
    out
}

/// How one hider's ids agree with llvmpipe's on one case.
#[derive(Default)]
struct Tally {
    pixels: usize,
    coverage_mismatches: usize,
    id_same: usize,
    ties: usize,
    setup_ties: usize,
    wrong: Vec<(u32, u32, u32, u32)>,
}

/// Window depth of primitive `prim` at pixel `(x, y)` if one of its
/// screen pieces covers the centre.
fn depth_of(screen: &ScreenScene, prim: u32, x: u32, y: u32) -> Option<f64> {
    let first = screen.tris.partition_point(|t| t.prim < prim);
    screen.tris[first..]
        .iter()
        .take_while(|t| t.prim == prim)
        .find(|t| {
            let px = i64::from(hider::geom::fixed::pixel_center(x as i32));
            let py = i64::from(hider::geom::fixed::pixel_center(y as i32));
            t.edges().iter().all(|e| e.contains(px, py))
        })
        .map(|t| t.depth.at_pixel(x, y))
}

/// The depth plane's slope of the first piece of `prim`: the change of
/// window depth per pixel in x and y, summed in absolute value.
fn slope_of(screen: &ScreenScene, prim: u32) -> f64 {
    let first = screen.tris.partition_point(|t| t.prim < prim);
    screen
        .tris
        .get(first)
        .map_or(0.0, |t| t.depth.dx.abs() + t.depth.dy.abs())
}

/// Why ids differ at a covered pixel.
enum Difference {
    /// The oracle's tie criterion, or coincident coplanar faces.
    Tie,
    /// Within what half a snapping step of the vertices can change.
    SetupTie,
    /// Neither: a real difference.
    Wrong,
}

/// Classifies differing ids at pixel `k`.
fn classify(
    screen: &ScreenScene,
    oracle: &Reference,
    k: usize,
    ours: u32,
    theirs: u32,
) -> Difference {
    let width = screen.viewport.width;
    let (x, y) = (k as u32 % width, k as u32 / width);
    let both = depth_of(screen, ours, x, y).zip(depth_of(screen, theirs, x, y));
    let gap = both.map(|(a, b)| (a - b).abs());
    if oracle.gap[k] < DEFAULT_TIE_TOLERANCE
        || oracle.window_gap[k] < WINDOW_TIE_TOLERANCE
        || gap.is_some_and(|g| g < WINDOW_TIE_TOLERANCE)
    {
        return Difference::Tie;
    }
    let half_step = 0.5 / f64::from(hider::geom::fixed::SUBPIXEL_SCALE);
    let movable = (slope_of(screen, ours) + slope_of(screen, theirs)) * half_step;
    if gap.is_some_and(|g| g < movable) {
        Difference::SetupTie
    } else {
        Difference::Wrong
    }
}

fn compare(screen: &ScreenScene, oracle: &mut Option<Reference>, ids: &[u32], gl: &[u32]) -> Tally {
    let mut t = Tally {
        pixels: ids.len(),
        ..Tally::default()
    };
    let width = screen.viewport.width;
    for (k, (&ours, &theirs)) in ids.iter().zip(gl).enumerate() {
        if ours == theirs {
            t.id_same += 1;
        } else if (ours == NO_ID) != (theirs == NO_ID) {
            t.coverage_mismatches += 1;
        } else {
            let reference = oracle
                .get_or_insert_with(|| RayCastOracle::new(Default::default()).evaluate(screen));
            match classify(screen, reference, k, ours, theirs) {
                Difference::Tie => t.ties += 1,
                Difference::SetupTie => t.setup_ties += 1,
                Difference::Wrong => {
                    t.wrong
                        .push((k as u32 % width, k as u32 / width, ours, theirs));
                }
            }
        }
    }
    t
}

fn percent(n: usize, of: usize) -> f64 {
    100.0 * n as f64 / of.max(1) as f64
}

/// Checks one case with every hider; returns the failures.
fn check_case(case: &Case, table: &mut Vec<String>) -> Vec<String> {
    let scene = load_scene(&case.scene);
    let view = view(case, &scene);
    let options = PrepareOptions::gl_compatible();
    let reference_screen = prepare(&scene, &view, &options).expect("prepares");
    let (gl_ids, gl_depth) = gl_buffers(case);
    let gl_covered = gl_ids.iter().filter(|&&id| id != NO_ID).count();
    assert!(gl_covered > 0, "{}: llvmpipe covered nothing", case.name);
    assert_eq!(gl_ids.len(), gl_depth.len());
    let mut oracle = None;
    let mut failures = Vec::new();
    for (name, mut hider) in hiders() {
        let mut screen = reference_screen.clone();
        let mut frame = Frame::new(case.size, case.size).unwrap();
        hider
            .render_scene(&scene, &view, &options, &mut screen, &mut frame)
            .unwrap_or_else(|e| panic!("{name} on {}: {e}", case.name));
        let t = compare(&reference_screen, &mut oracle, &frame.ids, &gl_ids);
        let coverage = percent(t.pixels - t.coverage_mismatches, t.pixels);
        table.push(format!(
            "| {} | {} | {name} | {coverage:.4}% | {:.4}% | {} | {} | {} |",
            case.name,
            case.size,
            percent(t.id_same, t.pixels),
            t.ties,
            t.setup_ties,
            t.wrong.len()
        ));
        if t.coverage_mismatches > 0 || !t.wrong.is_empty() {
            failures.push(format!(
                "{name} on {} at {}: {} coverage mismatches, {} non-tie id differences (first: {:?})",
                case.name,
                case.size,
                t.coverage_mismatches,
                t.wrong.len(),
                t.wrong.first()
            ));
        }
    }
    failures
}

#[test]
fn every_reference_case_matches_llvmpipe() {
    let cases = cases();
    assert!(
        cases.len() >= 10,
        "the manifest lists {} cases",
        cases.len()
    );
    let mut table = vec![
        "| case | size | hider | coverage | ids | ties | set-up ties | other differences |"
            .to_owned(),
        "|---|---|---|---|---|---|---|---|".to_owned(),
    ];
    let mut failures = Vec::new();
    for case in &cases {
        failures.extend(check_case(case, &mut table));
    }
    println!("{}", table.join("\n"));
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The data folder holds exactly the files the manifest needs, so a
/// reference cannot silently go missing or stay behind.
#[test]
fn every_case_has_its_two_images() {
    for case in cases() {
        for suffix in ["ids", "depth"] {
            let path: &Path = &data_dir().join(format!("{}.{suffix}.png", case.name));
            assert!(path.is_file(), "{} is missing", path.display());
        }
    }
}

/// The comparison can fail: llvmpipe's strips at 512 with one covered
/// pixel cleared and one id replaced by a triangle that does not cover the
/// pixel are one coverage mismatch and one wrong id, not ties.
#[test]
fn a_coverage_hole_and_a_wrong_id_are_caught() {
    let case = cases()
        .into_iter()
        .find(|c| c.name == "strips_512")
        .expect("strips_512 is a case");
    let scene = load_scene(&case.scene);
    let screen = prepare(
        &scene,
        &view(&case, &scene),
        &PrepareOptions::gl_compatible(),
    )
    .unwrap();
    let (mut gl, _) = gl_buffers(&case);
    let covered: Vec<usize> = (0..gl.len()).filter(|&k| gl[k] != NO_ID).collect();
    let (hole, wrong) = (covered[100], covered[covered.len() / 2]);
    gl[hole] = NO_ID;
    let other = (gl[wrong] + 600) % 1200;
    gl[wrong] = other;
    let mut frame = Frame::new(case.size, case.size).unwrap();
    Hider::render(&mut ZBuffer::default(), &screen, &mut frame).unwrap();
    let t = compare(&screen, &mut None, &frame.ids, &gl);
    assert_eq!(t.coverage_mismatches, 1);
    assert_eq!(t.ties + t.setup_ties, 0);
    assert_eq!(t.wrong.len(), 1, "{:?}", t.wrong);
    assert_eq!(t.wrong[0].3, other);
}
