//! [`NaivePainter`]: sort far to near and paint, nothing more.
//!
//! This is the painter's algorithm of the renderer-tutorial seed (chapter
//! 8): draw the farther triangle first and the nearer one over it. The
//! seed shows where it breaks: two triangles that intersect each other
//! have no single "farther" one, so whichever is drawn second wrongly
//! covers part of the first; three triangles overlapping in a cycle break
//! it the same way. It is kept to show that failure, which the tests
//! assert and the benchmark counts in wrong pixels.

use std::path::Path;

use hider_scene::{Frame, Hider, Result, ScreenScene, ShadeMode, Stats, check_frame};

use crate::options::{NaiveOptions, SortKey};
use crate::piece::Piece;
use crate::raster::{paint, validate};
use crate::stats::PainterStats;
use crate::svg::write_svg;

/// The naive painter's algorithm: one depth per triangle
/// ([`NaiveOptions::sort_key`]), a stable sort farthest first (equal keys
/// paint the lower primitive id first), and overwrite. Coverage is the
/// shared exact one; only the visibility can be wrong.
#[derive(Clone, Debug, Default)]
pub struct NaivePainter {
    options: NaiveOptions,
    pieces: Vec<Piece>,
    keys: Vec<(f64, u32)>,
    order: Vec<u32>,
}

impl NaivePainter {
    /// The name under which it reports (`"painter-naive"`).
    pub const NAME: &'static str = "painter-naive";

    /// A naive painter with the given options.
    pub fn new(options: NaiveOptions) -> Self {
        Self {
            options,
            ..Self::default()
        }
    }

    /// The options.
    pub fn options(&self) -> &NaiveOptions {
        &self.options
    }

    /// Sorts the scene's triangles, farthest first, into
    /// [`NaivePainter::ordered_pieces`].
    pub fn order(&mut self, scene: &ScreenScene) -> Result<PainterStats> {
        validate(Self::NAME, scene)?;
        self.pieces.clear();
        self.keys.clear();
        self.order.clear();
        for (k, tri) in scene.tris.iter().enumerate() {
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

    /// The triangles of the last [`NaivePainter::order`] (or render) in
    /// paint order, farthest first.
    pub fn ordered_pieces(&self) -> impl ExactSizeIterator<Item = &Piece> + '_ {
        self.order.iter().map(|&k| &self.pieces[k as usize])
    }

    /// Renders into `frame` and returns the typed counters.
    pub fn render_with_stats(
        &mut self,
        scene: &ScreenScene,
        frame: &mut Frame,
    ) -> Result<PainterStats> {
        check_frame(Self::NAME, scene, frame)?;
        let mut stats = self.order(scene)?;
        frame.clear();
        stats.pixels_painted = paint(scene, &self.pieces, &self.order, frame, None);
        Ok(stats)
    }

    /// Sorts the scene and writes the triangles in paint order to `path`
    /// as SVG, atomically: the vector output of a plain depth sort, with
    /// its errors.
    pub fn render_svg(
        &mut self,
        scene: &ScreenScene,
        path: &Path,
        mode: ShadeMode,
    ) -> Result<Stats> {
        let stats = self.order(scene)?;
        write_svg(scene, self.ordered_pieces(), path, mode, 0.0)?;
        Ok(stats.into())
    }
}

impl Hider for NaivePainter {
    fn name(&self) -> &str {
        Self::NAME
    }

    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<Stats> {
        self.render_with_stats(scene, frame).map(Stats::from)
    }
}
