//! The step-through views' traces, recorded by the algorithm crates
//! themselves: the page only replays them.

use hider_scene::frame::id_to_i32;
use hider_scene::{Frame, Hider, PrepareOptions, ScreenScene, View, prepare};
use hider_zbuffer::{ZBuffer, ZBufferOptions, ZBufferTrace};

use crate::session::Session;

/// Largest side of a step-through image: every depth test is recorded.
pub const MAX_STEP_SIDE: u32 = 128;

/// The session's scene prepared through its camera at `side` x `side`
/// and a frame of that size: what every step-through records from.
/// Refuses a size outside 1 to [`MAX_STEP_SIDE`].
pub(crate) fn step_scene(session: &Session, side: u32) -> Result<(ScreenScene, Frame), String> {
    if side == 0 || side > MAX_STEP_SIDE {
        return Err(format!(
            "step-through size {side}: 1 to {MAX_STEP_SIDE} pixels a side"
        ));
    }
    let camera = session.camera().apply(session.scene());
    let view = View::new(camera, side, side).map_err(|e| e.to_string())?;
    let screen =
        prepare(session.scene(), &view, &PrepareOptions::default()).map_err(|e| e.to_string())?;
    let frame = Frame::new(side, side).map_err(|e| e.to_string())?;
    Ok((screen, frame))
}

/// The plain z-buffer's trace of the session's scene and camera at
/// `side` x `side` ([`ZBuffer::render_traced`]), with the frame it drew.
pub fn zbuffer_trace(session: &Session, side: u32) -> Result<(ZBufferTrace, Frame), String> {
    let (screen, mut frame) = step_scene(session, side)?;
    let mut trace = ZBufferTrace::default();
    ZBuffer::new(ZBufferOptions::default())
        .render_traced(&screen, &mut frame, &mut trace)
        .map_err(|e| e.to_string())?;
    Ok((trace, frame))
}

/// What the page draws for step `k` of a z-buffer trace (0: nothing drawn
/// yet; `k` triangles drawn).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ZStep {
    /// Ids after `k` steps, -1 for background.
    pub ids: Vec<i32>,
    /// Depth after `k` steps, 1.0 for background.
    pub depth: Vec<f32>,
    /// Step `k`'s depth tests: 0 none, 1 passed, 2 failed, per pixel.
    pub outcome: Vec<u8>,
    /// Step `k`'s primitive id (-1 at step 0).
    pub prim: i32,
}

/// Step `k` of `trace`.
pub fn zbuffer_step(trace: &ZBufferTrace, k: usize) -> ZStep {
    let (ids, depth) = trace.replay(k);
    let mut outcome = vec![0u8; ids.len()];
    let mut prim = -1;
    if let Some(step) = k.checked_sub(1).and_then(|i| trace.steps.get(i)) {
        prim = id_to_i32(step.prim);
        for t in &step.tests {
            outcome[t.pixel as usize] = if t.passed { 1 } else { 2 };
        }
    }
    ZStep {
        ids: ids.into_iter().map(id_to_i32).collect(),
        depth,
        outcome,
        prim,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_last_step_is_the_zbuffer_frame() {
        let mut session = Session::new();
        session.set_scene(crate::scenes::from_spec("gen:cyclic").unwrap());
        session.set_size(40, 40).unwrap();
        let (trace, _) = zbuffer_trace(&session, 40).unwrap();
        let last = zbuffer_step(&trace, trace.steps.len());
        assert_eq!(last.ids, session.render("zbuffer").unwrap().ids());
        assert_eq!(zbuffer_step(&trace, 0).prim, -1);
        assert!(zbuffer_trace(&session, 1000).is_err());
    }
}
