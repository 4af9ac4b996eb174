//! Bad input gives typed errors, never a panic, and leaves the frame alone.

use hider_scanline::{Scanline, ScanlineOptions};
use hider_scene::{Error, Frame, Hider, procedural};

fn sphere() -> hider_scene::ScreenScene {
    hider_testkit::screen(&procedural::uv_sphere(8), 32, 32)
}

#[test]
fn wrong_frame_size_is_refused() {
    let mut frame = Frame::new(31, 32).unwrap();
    let err = Scanline::default()
        .render(&sphere(), &mut frame)
        .unwrap_err();
    assert!(matches!(err, Error::Render { .. }), "{err}");
    assert!(err.to_string().contains("31x32"), "{err}");
}

#[test]
fn budget_is_checked_before_allocating() {
    let mut frame = Frame::new(32, 32).unwrap();
    let mut hider = Scanline::new(ScanlineOptions::default().with_max_bytes(1000));
    let err = hider.render(&sphere(), &mut frame).unwrap_err();
    assert!(matches!(err, Error::Budget { limit: 1000, .. }), "{err}");
    assert_eq!(hider.bytes(), 0, "nothing allocated");
}

#[test]
fn unusable_triangles_are_named_and_the_frame_is_untouched() {
    let mut frame = Frame::new(32, 32).unwrap();
    frame.ids[5] = 77;
    let good = sphere();

    let mut flipped = good.clone();
    flipped.tris[3].v.swap(1, 2);
    let err = Scanline::default()
        .render(&flipped, &mut frame)
        .unwrap_err();
    assert!(
        err.to_string().contains("triangle 3") && err.to_string().contains("orientation"),
        "{err}"
    );

    let mut far = good.clone();
    far.tris[0].v[0].x = i32::MIN;
    let err = Scanline::default().render(&far, &mut frame).unwrap_err();
    assert!(err.to_string().contains("beyond"), "{err}");

    let mut nan = good;
    nan.tris[1].depth.dx = f64::NAN;
    let err = Scanline::default().render(&nan, &mut frame).unwrap_err();
    assert!(err.to_string().contains("not finite"), "{err}");

    assert_eq!(frame.ids[5], 77);
}

#[test]
fn empty_scene_gives_background() {
    let mut s = sphere();
    s.tris.clear();
    let mut frame = Frame::new(32, 32).unwrap();
    frame.ids[0] = 3;
    let stats = Scanline::default().render(&s, &mut frame).unwrap();
    assert_eq!(frame.covered_count(), 0);
    assert_eq!((stats.polygons, stats.spans), (0, 0));
}
