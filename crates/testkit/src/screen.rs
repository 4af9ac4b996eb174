//! From a world-space scene to what a hider draws: one `screen()` and a
//! render helper, for tests (they panic on errors).

use hider_geom::Camera;
use hider_scene::{Frame, Hider, PrepareOptions, Scene, ScreenScene, View, prepare};

/// Prepares `scene` at `width x height` with its own camera (or the fit
/// camera when it has none) and the default, accurate front-end options.
///
/// Panics when the scene cannot be prepared: this is test code, and
/// generated scenes always can.
pub fn screen(scene: &Scene, width: u32, height: u32) -> ScreenScene {
    let view = View::for_scene(scene, width, height).expect("a valid camera and image size");
    prepare(scene, &view, &PrepareOptions::default()).expect("the scene prepares")
}

/// Like [`screen`], through `camera` instead of the scene's.
pub fn screen_with(scene: &Scene, camera: Camera, width: u32, height: u32) -> ScreenScene {
    let view = View::new(camera, width, height).expect("a valid camera and image size");
    prepare(scene, &view, &PrepareOptions::default()).expect("the scene prepares")
}

/// A cleared frame the size of `screen`'s viewport.
pub fn frame_for(screen: &ScreenScene) -> Frame {
    Frame::new(screen.viewport.width, screen.viewport.height).expect("a valid image size")
}

/// Renders `screen` with `hider` into a fresh frame; panics (naming the
/// hider) when it refuses.
pub fn render<H: Hider>(hider: &mut H, screen: &ScreenScene) -> (Frame, H::Stats) {
    let mut frame = frame_for(screen);
    let stats = hider
        .render(screen, &mut frame)
        .unwrap_or_else(|e| panic!("{} failed: {e}", hider.name()));
    (frame, stats)
}
