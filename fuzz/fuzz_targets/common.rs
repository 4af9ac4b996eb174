// Shared by the fuzz targets: render a prepared scene with every
// registered hider and check the invariants that must hold for any input.

use hider::scene::{Frame, NO_ID, ScreenScene};

/// Renders with every hider; a hider may refuse with an error (budgets),
/// never panic, and what it draws must be well formed.
pub fn render_all(screen: &ScreenScene) {
    let vp = screen.viewport;
    let Ok(mut frame) = Frame::new(vp.width, vp.height) else {
        return;
    };
    for entry in hider::registry::all() {
        let mut h = (entry.make)();
        if h.render(screen, &mut frame).is_ok() {
            for (&id, &d) in frame.ids.iter().zip(&frame.depth) {
                assert!(id == NO_ID || (id as usize) < screen.prims.len(), "{}: id {id}", entry.name);
                assert!(d.is_finite(), "{}: depth {d}", entry.name);
            }
        }
    }
}
