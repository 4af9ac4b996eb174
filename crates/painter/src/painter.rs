//! [`Painter`]: the correct painter's algorithm (Newell, Newell & Sancha
//! 1972, with splitting) as a [`Hider`].

use std::path::Path;

use hider_scene::{Frame, Hider, OrderedPolygons, Result, ScreenScene, ShadeMode, check_frame};

use crate::options::PainterOptions;
use crate::order::Orderer;
use crate::piece::Piece;
use crate::raster::{NO_OWNER, paint, validate};
use crate::stats::PainterStats;
use crate::svg::{LastFrame, write_svg};
use crate::trace::PainterTrace;

/// The painter's algorithm done right: Newell, Newell & Sancha's ordering
/// tests, moving polygons that must go first, and splitting polygons by
/// each other's planes where no order exists (intersections, cyclic
/// overlaps). Its raster output equals the z-buffer's on every pixel that
/// is not a depth tie; its vector output ([`Hider::ordered_polygons`]) is the
/// ordered, split polygon list of the last frame.
///
/// The piece arena and lists are kept between frames.
#[derive(Clone, Debug, Default)]
pub struct Painter {
    options: PainterOptions,
    orderer: Orderer,
    /// Per pixel, the rank of the piece painted last (only with
    /// [`PainterOptions::svg_drop_hidden`]).
    owner: Vec<u32>,
    /// Per ranked piece, whether it owns a pixel (only with
    /// [`PainterOptions::svg_drop_hidden`]).
    visible: Vec<bool>,
    /// The scene of the last successful render or [`Self::order`].
    last: Option<LastFrame>,
}

impl Painter {
    /// The name under which it reports (`"painter"`).
    pub const NAME: &'static str = "painter";

    /// The pieces of the last successful render (or [`Self::order`]) in
    /// paint order: farthest first, each painted over the ones before.
    /// Empty before the first render and after a failed one.
    pub fn ordered_pieces(&self) -> impl ExactSizeIterator<Item = &Piece> + '_ {
        let n = if self.last.is_some() {
            self.orderer.order.len()
        } else {
            0
        };
        self.orderer.order[..n]
            .iter()
            .map(|&id| &self.orderer.pieces[id as usize])
    }

    /// What the ordering of the last successful render (or
    /// [`Self::order`]) did, step by step, when
    /// [`PainterOptions::trace`] was on; `None` otherwise. Its
    /// [`PainterTrace::order`] is the drawing order of
    /// [`Self::ordered_pieces`].
    pub fn trace(&self) -> Option<&PainterTrace> {
        self.last.as_ref().and(self.orderer.traced.as_ref())
    }

    /// Orders the scene's triangles back to front, splitting where needed,
    /// without painting them: [`Self::ordered_pieces`] then lists the
    /// pieces, and [`OrderedPolygons::write_svg`] writes them. This is all a
    /// caller that draws the pieces itself needs (a vector drawing, a plot
    /// library's polygons), and it skips the raster pass and the frame.
    /// The statistics have no pixel writes.
    ///
    /// Errors when a triangle is not set up (non-finite depth plane, wrong
    /// orientation), or the split or memory budget runs out.
    pub fn order(&mut self, scene: &ScreenScene) -> Result<PainterStats> {
        self.last = None;
        self.visible.clear();
        validate(Self::NAME, scene)?;
        let mut stats = PainterStats::default();
        self.orderer.run(scene, &self.options, &mut stats)?;
        self.last = Some(LastFrame::of(scene));
        Ok(stats)
    }

    /// Marks the ranked pieces that own at least one pixel in `owner`.
    fn mark_visible(&mut self) {
        self.visible.clear();
        self.visible.resize(self.orderer.order.len(), false);
        for &rank in &self.owner {
            if rank != NO_OWNER {
                self.visible[rank as usize] = true;
            }
        }
    }
}

impl Hider for Painter {
    type Options = PainterOptions;
    type Stats = PainterStats;

    fn new(options: PainterOptions) -> Self {
        Self {
            options,
            ..Self::default()
        }
    }

    fn options(&self) -> &PainterOptions {
        &self.options
    }

    fn name(&self) -> &str {
        Self::NAME
    }

    /// Orders the scene's triangles back to front, splitting where needed,
    /// and paints the pieces into `frame`.
    ///
    /// Errors when the frame's size differs from the scene's, a triangle is
    /// not set up (non-finite depth plane, wrong orientation), or the split
    /// or memory budget runs out.
    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<PainterStats> {
        check_frame(Self::NAME, scene, frame)?;
        let mut stats = self.order(scene)?;
        frame.clear();
        let drop_hidden = self.options.svg_drop_hidden;
        stats.pixels_painted = paint(
            scene,
            (&self.orderer.pieces, Some(&self.orderer.centres)),
            &self.orderer.order,
            frame,
            drop_hidden.then_some(&mut self.owner),
        );
        if drop_hidden {
            self.mark_visible();
        }
        Ok(stats)
    }

    fn ordered_polygons(&self) -> Option<&dyn OrderedPolygons> {
        Some(self)
    }
}

impl OrderedPolygons for Painter {
    /// Writes the ordered, split pieces of the last render of `scene` to
    /// `path` as SVG (one path per piece, farthest first, coloured with
    /// `mode`), atomically. With [`PainterOptions::svg_drop_hidden`] pieces
    /// owning no pixel are left out; [`PainterOptions::svg_seam_stroke`]
    /// strokes each path.
    ///
    /// Errors before any render, after a failed one, or when `scene` is
    /// not the one last rendered (another size or triangle count).
    fn write_svg(&self, scene: &ScreenScene, path: &Path, mode: ShadeMode) -> Result<()> {
        LastFrame::check(self.last.as_ref(), Self::NAME, scene)?;
        let stroke = self.options.svg_seam_stroke;
        if self.options.svg_drop_hidden {
            if self.visible.len() != self.orderer.order.len() {
                return Err(hider_scene::Error::Render {
                    hider: Self::NAME.into(),
                    message: "the last frame was ordered without painting, so which pieces \
                              are hidden is unknown; render it to drop hidden pieces"
                        .into(),
                });
            }
            let pieces = self
                .ordered_pieces()
                .zip(&self.visible)
                .filter_map(|(p, &v)| v.then_some(p));
            write_svg(scene, pieces, path, mode, stroke)
        } else {
            write_svg(scene, self.ordered_pieces(), path, mode, stroke)
        }
    }
}
