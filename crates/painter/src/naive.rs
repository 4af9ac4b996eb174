//! [`NaivePainter`]: sort far to near and paint, nothing more.
//!
//! This is the painter's algorithm of the software-renderer tutorial,
//! chapter 8: draw the farther triangle first and the nearer one over it.
//! The tutorial shows where it breaks: two triangles that intersect each other
//! have no single "farther" one, so whichever is drawn second wrongly
//! covers part of the first; three triangles overlapping in a cycle break
//! it the same way. It is kept to show that failure, which the tests
//! assert and the benchmark counts in wrong pixels.

use std::path::Path;

use hider_scene::{Frame, Hider, OrderedPolygons, Result, ScreenScene, ShadeMode, check_frame};

use crate::options::{NaivePainterOptions, SortKey};
use crate::piece::Piece;
use crate::raster::{paint, validate};
use crate::stats::PainterStats;
use crate::svg::{LastFrame, write_svg};

/// The naive painter's algorithm: one depth per triangle
/// ([`NaivePainterOptions::sort_key`]), a stable sort farthest first (equal
/// keys paint the lower primitive id first), and overwrite. Coverage is the
/// shared exact one; only the visibility can be wrong. Its vector output
/// ([`Hider::ordered_polygons`]) is the triangles of the last frame in paint
/// order, with the same errors.
#[derive(Clone, Debug, Default)]
pub struct NaivePainter {
    options: NaivePainterOptions,
    pieces: Vec<Piece>,
    keys: Vec<(f64, u32)>,
    order: Vec<u32>,
    /// The scene of the last successful render.
    last: Option<LastFrame>,
}

impl NaivePainter {
    /// The name under which it reports (`"painter-naive"`).
    pub const NAME: &'static str = "painter-naive";

    /// Sorts the scene's triangles, farthest first, into `self.order`.
    fn sort(&mut self, scene: &ScreenScene) -> Result<PainterStats> {
        validate(Self::NAME, scene)?;
        self.pieces.clear();
        self.keys.clear();
        self.order.clear();
        for (k, tri) in scene.tris.iter().enumerate() {
            self.options.cancel.poll_every(k)?;
            let key = match self.options.sort_key {
                SortKey::FarthestVertex => tri.z.iter().copied().fold(f64::MIN, f64::max),
                SortKey::Centroid => (tri.z[0] + tri.z[1] + tri.z[2]) / 3.0,
            };
            self.keys.push((key, k as u32));
            self.pieces.push(Piece::from_tri(tri, k as u32));
        }
        // Farthest (largest window depth) first; the sort is stable and the
        // triangles are in primitive order, so ties keep the lower id first.
        self.keys.sort_by(|a, b| b.0.total_cmp(&a.0));
        self.options.cancel.poll()?;
        self.order.extend(self.keys.iter().map(|&(_, k)| k));
        let bytes = self.pieces.iter().map(Piece::bytes).sum::<usize>()
            + self.keys.capacity() * std::mem::size_of::<(f64, u32)>()
            + self.order.capacity() * 4;
        Ok(PainterStats {
            triangles: scene.tris.len() as u64,
            pieces_out: self.order.len() as u64,
            peak_bytes: bytes as u64,
            ..PainterStats::default()
        })
    }

    /// The triangles of the last successful render in paint order,
    /// farthest first. Empty before the first render and after a failed
    /// one.
    pub fn ordered_pieces(&self) -> impl ExactSizeIterator<Item = &Piece> + '_ {
        let n = if self.last.is_some() {
            self.order.len()
        } else {
            0
        };
        self.order[..n].iter().map(|&k| &self.pieces[k as usize])
    }
}

impl Hider for NaivePainter {
    type Options = NaivePainterOptions;
    type Stats = PainterStats;

    fn new(options: NaivePainterOptions) -> Self {
        Self {
            options,
            ..Self::default()
        }
    }

    fn options(&self) -> &NaivePainterOptions {
        &self.options
    }

    fn name(&self) -> &str {
        Self::NAME
    }

    /// Sorts the scene's triangles and paints them into `frame`.
    ///
    /// Errors when the frame's size differs from the scene's or a triangle
    /// is not set up (non-finite depth plane, wrong orientation).
    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<PainterStats> {
        check_frame(Self::NAME, scene, frame)?;
        self.last = None;
        let mut stats = self.sort(scene)?;
        frame.clear();
        stats.pixels_painted = paint(scene, (&self.pieces, None), &self.order, frame, None);
        self.last = Some(LastFrame::of(scene));
        Ok(stats)
    }

    fn ordered_polygons(&self) -> Option<&dyn OrderedPolygons> {
        Some(self)
    }
}

impl OrderedPolygons for NaivePainter {
    /// Writes the triangles of the last render of `scene` in paint order to
    /// `path` as SVG, atomically: the vector output of a plain depth sort,
    /// with its errors.
    ///
    /// Errors before any render, after a failed one, or when `scene` is
    /// not the one last rendered (another size or triangle count).
    fn write_svg(&self, scene: &ScreenScene, path: &Path, mode: ShadeMode) -> Result<()> {
        LastFrame::check(self.last.as_ref(), Self::NAME, scene)?;
        write_svg(scene, self.ordered_pieces(), path, mode, 0.0)
    }
}
