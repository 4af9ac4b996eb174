//! What a library user writes to get the command line's coloured frame:
//! a registered hider built with one thread and Lambert shading, then
//! `render_frame` (the hider's pipeline, the cut-out stage, the colour
//! pass) with the stages the scene calls for.

use hider::plan::{HiderConfig, registry};
use hider::scene::shade::{Stages, render_frame};
use hider::scene::{Frame, PrepareOptions, Scene, ScreenScene, ShadeMode, View};

/// `scene` through its own (or the fit) camera at `size` x `size` with the
/// registered hider `name`.
pub fn library_frame(name: &str, scene: &Scene, size: u32) -> Frame {
    let view = View::for_scene(scene, size, size).unwrap();
    let mut hider = registry::find(name)
        .unwrap()
        .build(
            &HiderConfig::default()
                .with_threads(1)
                .with_shade(ShadeMode::Lambert),
        )
        .unwrap();
    let mut screen = ScreenScene::empty(&view);
    let mut frame = Frame::new(size, size).unwrap();
    render_frame(
        hider.as_mut(),
        scene,
        &view,
        &PrepareOptions::default(),
        &Stages::for_scene(scene, true),
        ShadeMode::Lambert,
        &mut screen,
        &mut frame,
    )
    .unwrap();
    frame
}
