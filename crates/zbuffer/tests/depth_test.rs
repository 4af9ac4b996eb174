//! Fragments whose window depth is exactly 1, the value a depth buffer is
//! cleared to: by default every z-buffer (every format, tiled included)
//! draws them where the exact oracle does; `DepthTest::GlLess` drops them
//! as GL does.

use hider_scene::{Frame, Hider, NO_ID, PrepareOptions, Scene, ScreenScene, View, procedural};
use hider_testkit::{cameras, hard_cases, reference, render, screen_with};
use hider_zbuffer::{
    DepthFormat, DepthTest, TiledZBuffer, TiledZBufferOptions, ZBuffer, ZBufferOptions,
};

/// The two scenes of the regression: one triangle on the far plane of its
/// camera at 128 px, and a unit sphere through the fit camera with its
/// near plane moved to `1e-7` (every window depth within `1e-8` of 1, so
/// `f32` and the fixed formats round all of it to 1).
fn cases() -> Vec<(&'static str, Scene, View)> {
    let triangle = hard_cases::far_plane_triangle();
    let triangle_view = View::for_scene(&triangle, 128, 128).unwrap();
    let sphere = procedural::uv_sphere(32);
    let camera = cameras::with_near(hider_scene::view::fit_camera(&sphere), 1e-7);
    let sphere_view = View::new(camera, 128, 128).unwrap();
    vec![
        ("far-plane triangle", triangle, triangle_view),
        ("sphere at near 1e-7", sphere, sphere_view),
    ]
}

fn covered(frame: &Frame) -> Vec<bool> {
    frame.ids.iter().map(|&id| id != NO_ID).collect()
}

/// The tiled z-buffer through its own front end (`render_scene`) and on
/// the shared screen scene (`render`), with and without hierarchical
/// depth, single-threaded.
fn tiled_frames(options: TiledZBufferOptions, scene: &Scene, view: &View) -> Vec<Frame> {
    let mut out = Vec::new();
    for hiz in [true, false] {
        let mut tiled = TiledZBuffer::new(options.with_threads(1).with_hierarchical_z(hiz));
        let mut screen = prepare(scene, view);
        let (frame, _) = render(&mut tiled, &screen);
        out.push(frame);
        let mut frame = Frame::new(view.viewport.width, view.viewport.height).unwrap();
        tiled
            .render_scene(
                scene,
                view,
                &PrepareOptions::default(),
                &mut screen,
                &mut frame,
            )
            .unwrap();
        out.push(frame);
    }
    out
}

fn prepare(scene: &Scene, view: &View) -> ScreenScene {
    screen_with(
        scene,
        view.camera,
        view.viewport.width,
        view.viewport.height,
    )
}

#[test]
fn every_format_draws_what_the_oracle_draws_at_window_depth_one() {
    for (name, scene, view) in cases() {
        let s = prepare(&scene, &view);
        // The ray cast's coverage (which pixel centres any triangle covers).
        let oracle = reference::ray_cast(&s);
        let want: Vec<bool> = oracle.ids.iter().map(|&id| id != NO_ID).collect();
        let count = want.iter().filter(|&&c| c).count();
        assert!(count > 10, "{name}: the oracle covers {count} pixels");
        for format in DepthFormat::ALL {
            let options = ZBufferOptions::default().with_depth_format(format);
            let (plain, _) = render(&mut ZBuffer::new(options), &s);
            assert_eq!(covered(&plain), want, "{name}: zbuffer {format:?}");
            let tiled = TiledZBufferOptions::default().with_depth_format(format);
            for frame in tiled_frames(tiled, &scene, &view) {
                assert!(
                    frame == plain,
                    "{name}: tiled {format:?} differs from plain"
                );
            }
        }
    }
}

#[test]
fn gl_less_drops_window_depth_one_in_every_format_tiled_included() {
    // GL's behaviour, kept on request: the triangle lies exactly on the far
    // plane, so no format lets any of it through the strict LESS against
    // the clear value.
    let (_, scene, view) = cases().swap_remove(0);
    let s = prepare(&scene, &view);
    for format in DepthFormat::ALL {
        let options = ZBufferOptions::default()
            .with_depth_format(format)
            .with_depth_test(DepthTest::GlLess);
        let (plain, _) = render(&mut ZBuffer::new(options), &s);
        assert_eq!(plain.covered_count(), 0, "zbuffer {format:?}");
        let tiled = TiledZBufferOptions::default()
            .with_depth_format(format)
            .with_depth_test(DepthTest::GlLess);
        for frame in tiled_frames(tiled, &scene, &view) {
            assert!(frame == plain, "tiled {format:?} differs from plain");
        }
    }
}

#[test]
fn a_written_pixel_still_keeps_the_first_of_equal_depths() {
    // Two copies of the far-plane triangle: both at window depth 1, the
    // first (lower id) stays under either test's LESS between fragments.
    let mut scene = hard_cases::far_plane_triangle();
    let copy = scene.meshes[0].clone();
    scene.push_mesh(copy, None);
    let view = View::for_scene(&scene, 64, 64).unwrap();
    let s = prepare(&scene, &view);
    for format in DepthFormat::ALL {
        let options = ZBufferOptions::default().with_depth_format(format);
        let (plain, _) = render(&mut ZBuffer::new(options), &s);
        assert!(plain.covered_count() > 0);
        assert!(
            plain.ids.iter().all(|&id| id == NO_ID || id == 0),
            "{format:?}"
        );
        let tiled = TiledZBufferOptions::default().with_depth_format(format);
        for frame in tiled_frames(tiled, &scene, &view) {
            assert!(frame == plain, "tiled {format:?} differs from plain");
        }
    }
}

#[test]
fn names_say_when_the_test_is_gls() {
    let gl = ZBufferOptions::default().with_depth_test(DepthTest::GlLess);
    assert_eq!(ZBuffer::new(gl).name(), "zbuffer-gl-less");
    assert_eq!(ZBuffer::default().name(), "zbuffer");
    let tiled = TiledZBufferOptions::default().with_depth_test(DepthTest::GlLess);
    assert_eq!(TiledZBuffer::new(tiled).name(), "zbuffer-tiled-gl-less");
    assert_eq!(DepthTest::from_name("gl-less"), Some(DepthTest::GlLess));
    assert_eq!(DepthTest::default(), DepthTest::ViewVolume);
}
