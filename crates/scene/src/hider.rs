//! The `Hider` trait every hidden-surface algorithm implements, and the
//! `Stats` it returns.

use crate::error::Result;
use crate::frame::Frame;
use crate::prepare::ScreenScene;
use hider_geom::Viewport;

/// Work counters that explain a hider's cost (fragments, depth tests,
/// splits, regions, spans, bytes...).
///
/// Each algorithm crate has a typed stats struct with documented fields and
/// converts it into this uniform shape, so the benchmark can tabulate any
/// hider without knowing it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Stats {
    /// Named counters, in the order the hider reports them.
    pub counters: Vec<(&'static str, u64)>,
    /// Peak bytes of working memory (buffers, fragment arenas, lists), not
    /// counting the output frame.
    pub peak_bytes: u64,
}

impl Stats {
    /// The value of a counter, if the hider reports it.
    pub fn get(&self, name: &str) -> Option<u64> {
        self.counters
            .iter()
            .find(|(n, _)| *n == name)
            .map(|&(_, v)| v)
    }

    /// Appends a counter.
    pub fn push(&mut self, name: &'static str, value: u64) {
        self.counters.push((name, value));
    }
}

impl std::fmt::Display for Stats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (k, (name, value)) in self.counters.iter().enumerate() {
            if k > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{name} {value}")?;
        }
        if self.peak_bytes > 0 {
            write!(f, ", peak bytes {}", self.peak_bytes)?;
        }
        Ok(())
    }
}

/// A hidden-surface algorithm.
///
/// `render` draws a [`ScreenScene`] into a [`Frame`] of the same size: it
/// clears the frame and writes, per pixel, the id and window depth of the
/// visible primitive. Hiders that resolve colour themselves (anti-aliasing,
/// transparency) also fill `color` (and `coverage`) and say so through
/// [`Hider::resolves_color`]; for the others the caller shades from the ids
/// with [`crate::shade::shade_frame`].
///
/// `&mut self` lets a hider keep its scratch memory (depth buffers, edge
/// tables, fragment arenas) from one frame to the next.
pub trait Hider {
    /// A short name for tables and messages (`"zbuffer"`, `"warnock"`...).
    fn name(&self) -> &str;

    /// Renders `scene` into `frame`, returning the work done.
    ///
    /// Errors when the frame's size differs from the scene's viewport or a
    /// budget the hider documents is exceeded.
    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<Stats>;

    /// Whether `render` writes the frame's colour itself.
    fn resolves_color(&self) -> bool {
        false
    }
}

/// Checks that a frame matches the scene's viewport: the first thing every
/// hider does.
pub fn check_frame(hider: &str, scene: &ScreenScene, frame: &Frame) -> Result<()> {
    check_frame_size(hider, scene.viewport, frame)
}

/// [`check_frame`] for a scene prepared for `viewport` (a
/// [`crate::DepthScene`], or any other input of that size).
pub fn check_frame_size(hider: &str, viewport: Viewport, frame: &Frame) -> Result<()> {
    let vp = viewport;
    if frame.width() != vp.width || frame.height() != vp.height {
        return Err(crate::error::Error::Render {
            hider: hider.to_owned(),
            message: format!(
                "frame is {}x{} but the scene was prepared for {}x{}",
                frame.width(),
                frame.height(),
                vp.width,
                vp.height
            ),
        });
    }
    Ok(())
}
