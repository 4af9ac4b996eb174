//! The read-back writes what the frame asks for ([`FrameBuffers`]) and
//! nothing else, through `render`, `render_scene` and `read_into`,
//! for every combination, thread count and tile size.

use hider_scene::{Frame, FrameBuffers, Hider, PrepareOptions, ScreenScene, View, procedural};

use crate::{TiledZBuffer, TiledZBufferOptions, ZBuffer};

/// Every combination of the three buffers.
fn requests() -> impl Iterator<Item = FrameBuffers> {
    (0..8).map(|m| FrameBuffers {
        ids: m & 1 != 0,
        depth: m & 2 != 0,
        color: m & 4 != 0,
    })
}

/// A frame of garbage asking for `wanted`.
fn dirty(w: u32, h: u32, wanted: FrameBuffers) -> Frame {
    let mut f = Frame::new(w, h).unwrap().with_buffers(wanted);
    f.ids.fill(7);
    f.depth.fill(0.25);
    f.color.fill([1, 2, 3, 4]);
    f
}

/// The requested buffers are the reference's, the others untouched.
fn assert_request(got: &Frame, want: &Frame, wanted: FrameBuffers, what: &str) {
    let garbage = dirty(got.width(), got.height(), wanted);
    let pick = |asked: bool| if asked { want } else { &garbage };
    assert!(got.ids == pick(wanted.ids).ids, "ids, {wanted:?}, {what}");
    let bits = |f: &Frame| f.depth.iter().map(|d| d.to_bits()).collect::<Vec<_>>();
    assert!(
        bits(got) == bits(pick(wanted.depth)),
        "depth, {wanted:?}, {what}"
    );
    assert!(
        got.color == pick(wanted.color).color,
        "colour, {wanted:?}, {what}"
    );
}

/// A sphere in one corner of a wide frame: bands with drawn and untouched
/// tiles, and bands no triangle meets.
fn corner_sphere(w: u32, h: u32) -> (hider_scene::Scene, View, ScreenScene) {
    let scene = procedural::uv_sphere(24);
    let mut view = View::for_scene(&scene, w, h).unwrap();
    view.camera.target += glam::DVec3::new(0.9, -0.6, 0.0);
    let screen = hider_scene::prepare(&scene, &view, &PrepareOptions::default()).unwrap();
    (scene, view, screen)
}

#[test]
fn only_the_requested_buffers_are_written() {
    let (w, h) = (150, 97);
    let (scene, view, screen) = corner_sphere(w, h);
    let mut want = Frame::new(w, h).unwrap();
    ZBuffer::default().render(&screen, &mut want).unwrap();
    assert!(want.covered_count() > 100, "the sphere is on screen");
    for threads in [1, 2] {
        for tile in [16, 64] {
            let options = TiledZBufferOptions::default()
                .with_threads(threads)
                .with_tile_size(tile);
            let mut hider = TiledZBuffer::new(options);
            for wanted in requests() {
                let what = format!("{threads} threads, tiles of {tile}");
                let mut got = dirty(w, h, wanted);
                hider.render(&screen, &mut got).unwrap();
                assert_request(&got, &want, wanted, &format!("render, {what}"));
                let mut got = dirty(w, h, wanted);
                let mut unused = ScreenScene::empty(&view);
                let options = PrepareOptions::default();
                hider
                    .render_scene(&scene, &view, &options, &mut unused, &mut got)
                    .unwrap();
                assert_request(&got, &want, wanted, &format!("render_scene, {what}"));
                let mut got = dirty(w, h, wanted);
                hider.read_into(&mut got).unwrap();
                assert_request(&got, &want, wanted, &format!("read_into, {what}"));
            }
        }
    }
}
