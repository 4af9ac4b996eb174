//! Pixel-by-pixel agreement with a real OpenGL implementation.
//!
//! `shared/gl-reference/` (beside the project folder) holds renders of real
//! models by Mesa's llvmpipe at 512 x 512 with the *fit* camera: the visible
//! triangle id and the 24-bit window depth per pixel. This test renders the
//! same models through hider's front end (in GL-compatible f32 arithmetic)
//! and the z-buffer, and compares.
//!
//! Tolerances, and why:
//! - coverage (background vs covered) must agree on >= 99.999% of pixels:
//!   with 8 sub-pixel bits and the top-left rule both rasterisers decide
//!   coverage identically; the slack (2 pixels of 262,144) absorbs a vertex
//!   whose f32 transform rounds to the other side of a 1/512-pixel boundary
//!   in our arithmetic and llvmpipe's.
//! - ids must agree on >= 99.99% of pixels: the remaining differences are
//!   depth ties, where GL's 24-bit buffer cannot separate two nearly
//!   coplanar surfaces and keeps the first drawn.
//! - window depth on pixels with the same id must agree within 1e-5: hider
//!   sets up the depth plane in f64 from the *snapped* vertices, llvmpipe in
//!   f32 from its own; up to half a snapping step (1/512 pixel) times the
//!   steepest depth slope of these models, plus f32 setup rounding, gives the
//!   measured maximum of about 6e-6 (100 steps of the 24-bit buffer).
//!
//! Where the shared folder is absent the test prints that it skipped.

use std::path::PathBuf;

use hider_scene::frame::{read_depth, read_ids};
use hider_scene::{Frame, Hider, NO_ID, PrepareOptions, View, load_obj, prepare};
use hider_zbuffer::{DepthFormat, ZBuffer, ZBufferOptions};

const SIZE: u32 = 512;

fn reference_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/gl-reference");
    dir.join("README.md").exists().then_some(dir)
}

struct Agreement {
    coverage_same: usize,
    ids_same: usize,
    max_depth_diff: f32,
    both_covered: usize,
}

fn compare(model: &str, name: &str) -> Option<Agreement> {
    let Some(dir) = reference_dir() else {
        eprintln!("skipped: shared/gl-reference not found beside the project");
        return None;
    };
    let scene = load_obj(dir.join("models").join(model)).expect("model loads");
    let view = View::for_scene(&scene, SIZE, SIZE).unwrap();
    let screen = prepare(&scene, &view, &PrepareOptions::gl_compatible()).unwrap();
    let mut frame = Frame::new(SIZE, SIZE).unwrap();
    // GL's buffer is 24-bit fixed point: the same format decides ties the
    // same way.
    let options = ZBufferOptions::default().with_depth_format(DepthFormat::Fixed24);
    ZBuffer::new(options).render(&screen, &mut frame).unwrap();
    let gl_ids = read_ids(&dir.join(format!("{name}_512.i32")), SIZE, SIZE).unwrap();
    let gl_depth = read_depth(&dir.join(format!("{name}_512.f32")), SIZE, SIZE).unwrap();
    let mut a = Agreement {
        coverage_same: 0,
        ids_same: 0,
        max_depth_diff: 0.0,
        both_covered: 0,
    };
    for i in 0..frame.len() {
        let (ours, theirs) = (frame.ids[i], gl_ids[i]);
        a.coverage_same += usize::from((ours == NO_ID) == (theirs == NO_ID));
        a.ids_same += usize::from(ours == theirs);
        if ours != NO_ID && ours == theirs {
            a.both_covered += 1;
            a.max_depth_diff = a.max_depth_diff.max((frame.depth[i] - gl_depth[i]).abs());
        }
    }
    let n = frame.len() as f64;
    eprintln!(
        "{model}: coverage agrees on {}/{} ({:.5}%), ids on {} ({:.5}%), max |depth diff| {:.3e} on {} pixels",
        a.coverage_same,
        frame.len(),
        100.0 * a.coverage_same as f64 / n,
        a.ids_same,
        100.0 * a.ids_same as f64 / n,
        a.max_depth_diff,
        a.both_covered
    );
    Some(a)
}

fn check(model: &str, name: &str) {
    let Some(a) = compare(model, name) else {
        return;
    };
    let n = f64::from(SIZE * SIZE);
    assert!(
        a.coverage_same as f64 / n >= 0.99999,
        "coverage agreement too low"
    );
    assert!(a.ids_same as f64 / n >= 0.9999, "id agreement too low");
    assert!(a.both_covered > 10_000);
    assert!(
        a.max_depth_diff <= 1e-5,
        "depth differs by {}",
        a.max_depth_diff
    );
}

#[test]
fn spider_matches_llvmpipe() {
    check("spider.obj", "spider");
}

#[test]
fn sphere_200_matches_llvmpipe() {
    check("sphere_200.obj", "sphere_200");
}
