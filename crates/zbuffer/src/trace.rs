//! The z-buffer's step trace: what the depth test decided at every pixel
//! of every triangle, in drawing order, for the explorable page's
//! step-through (`crates/web`) and for anyone who wants to watch it.
//!
//! [`ZBuffer::render_traced`] renders the frame
//! [`Hider::render`](hider_scene::Hider::render) renders
//! (the same code: the drawing loop is generic over the sink, and the
//! untraced render's sink does nothing, so it costs nothing) and records a
//! [`TriangleStep`] per triangle drawn. [`ZBufferTrace::replay`] rebuilds
//! the id and depth buffers after any number of steps; after the last one
//! they are the frame's, bit for bit.

use hider_scene::{Frame, NO_ID, Result, ScreenScene};

use crate::raster::{ZBuffer, ZBufferStats};

/// Receives the depth test's outcomes while the z-buffer draws.
pub(crate) trait DepthTestSink {
    /// A triangle (primitive `prim`) starts.
    fn triangle(&mut self, prim: u32);
    /// The depth test at pixel `pixel` (row-major index); `depth` is the
    /// window depth stored if it `passed`.
    fn test(&mut self, pixel: usize, depth: f32, passed: bool);
}

/// The sink of an untraced frame: nothing.
pub(crate) struct NoTrace;

impl DepthTestSink for NoTrace {
    #[inline(always)]
    fn triangle(&mut self, _prim: u32) {}
    #[inline(always)]
    fn test(&mut self, _pixel: usize, _depth: f32, _passed: bool) {}
}

/// One depth test.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PixelTest {
    /// Row-major pixel index.
    pub pixel: u32,
    /// The fragment's window depth as the frame stores it (for the
    /// linear-depth demonstration, the stored value's window depth on a
    /// pass, the fragment's plane value on a failure).
    pub depth: f32,
    /// Whether it was nearer than what the buffer held (id and depth
    /// written).
    pub passed: bool,
}

/// One triangle drawn: its id and the depth test at every pixel centre it
/// covers, in traversal order (row by row).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TriangleStep {
    /// The primitive id.
    pub prim: u32,
    /// The depth tests.
    pub tests: Vec<PixelTest>,
}

/// Every triangle's step of one frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ZBufferTrace {
    /// Frame width in pixels.
    pub width: u32,
    /// Frame height in pixels.
    pub height: u32,
    /// The steps, in drawing order (triangles that cover no pixel centre
    /// have an empty step; triangles off screen have none).
    pub steps: Vec<TriangleStep>,
}

impl DepthTestSink for ZBufferTrace {
    fn triangle(&mut self, prim: u32) {
        self.steps.push(TriangleStep {
            prim,
            tests: Vec::new(),
        });
    }

    fn test(&mut self, pixel: usize, depth: f32, passed: bool) {
        if let Some(step) = self.steps.last_mut() {
            step.tests.push(PixelTest {
                pixel: pixel as u32,
                depth,
                passed,
            });
        }
    }
}

impl ZBufferTrace {
    /// The id and depth buffers after the first `steps` steps (all of them
    /// when `steps` is larger): [`NO_ID`] and 1.0 where nothing passed.
    pub fn replay(&self, steps: usize) -> (Vec<u32>, Vec<f32>) {
        let n = self.width as usize * self.height as usize;
        let mut ids = vec![NO_ID; n];
        let mut depth = vec![hider_scene::frame::BACKGROUND_DEPTH; n];
        for step in self.steps.iter().take(steps) {
            for t in step.tests.iter().filter(|t| t.passed) {
                ids[t.pixel as usize] = step.prim;
                depth[t.pixel as usize] = t.depth;
            }
        }
        (ids, depth)
    }
}

impl ZBuffer {
    /// [`Hider::render`](hider_scene::Hider::render), recording every depth test into `trace`
    /// (cleared first).
    pub fn render_traced(
        &mut self,
        scene: &ScreenScene,
        frame: &mut Frame,
        trace: &mut ZBufferTrace,
    ) -> Result<ZBufferStats> {
        *trace = ZBufferTrace {
            width: frame.width(),
            height: frame.height(),
            steps: Vec::new(),
        };
        let stats = self.render_with(scene, frame, trace)?;
        debug_assert_eq!(trace.replay(usize::MAX).0, frame.ids);
        Ok(stats)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{DepthFormat, ZBufferOptions};
    use hider_scene::{Hider, PrepareOptions, View, prepare, procedural};

    #[test]
    fn the_last_step_is_the_frame_and_the_first_steps_are_not() {
        for (scene, format) in [
            (procedural::intersecting_pair(), DepthFormat::F32),
            (procedural::uv_sphere(12), DepthFormat::Fixed16),
            (procedural::cyclic_triple(), DepthFormat::F64),
        ] {
            let view = View::for_scene(&scene, 40, 32).unwrap();
            let screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
            let options = ZBufferOptions::default().with_depth_format(format);
            let mut plain = Frame::new(40, 32).unwrap();
            ZBuffer::new(options).render(&screen, &mut plain).unwrap();
            let mut traced = Frame::new(40, 32).unwrap();
            let mut trace = ZBufferTrace::default();
            ZBuffer::new(options)
                .render_traced(&screen, &mut traced, &mut trace)
                .unwrap();
            assert!(traced == plain, "tracing changed the frame");
            let (ids, depth) = trace.replay(trace.steps.len());
            assert_eq!(ids, plain.ids);
            assert_eq!(
                depth.iter().map(|d| d.to_bits()).collect::<Vec<_>>(),
                plain.depth.iter().map(|d| d.to_bits()).collect::<Vec<_>>()
            );
            assert_ne!(trace.replay(1).0, plain.ids);
            let tests: usize = trace.steps.iter().map(|s| s.tests.len()).sum();
            assert!(
                trace
                    .steps
                    .iter()
                    .any(|s| s.tests.iter().any(|t| !t.passed))
            );
            assert!(tests > 0);
        }
    }
}
