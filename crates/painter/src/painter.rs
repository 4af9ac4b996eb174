//! [`Painter`]: the correct painter's algorithm (Newell, Newell & Sancha
//! 1972, with splitting) as a [`Hider`].

use std::path::Path;

use hider_scene::{Frame, Hider, Result, ScreenScene, ShadeMode, Stats, check_frame};

use crate::options::PainterOptions;
use crate::order::Orderer;
use crate::piece::Piece;
use crate::raster::{NO_OWNER, paint, validate};
use crate::stats::PainterStats;
use crate::svg::write_svg;

/// The painter's algorithm done right: Newell, Newell & Sancha's ordering
/// tests, moving polygons that must go first, and splitting polygons by
/// each other's planes where no order exists (intersections, cyclic
/// overlaps). Its raster output equals the z-buffer's on every pixel that
/// is not a depth tie; its vector output ([`Painter::render_svg`]) is the
/// ordered, split polygon list.
///
/// The piece arena and lists are kept between frames.
#[derive(Clone, Debug, Default)]
pub struct Painter {
    options: PainterOptions,
    orderer: Orderer,
    owner: Vec<u32>,
    stats: PainterStats,
}

impl Painter {
    /// The name under which it reports (`"painter"`).
    pub const NAME: &'static str = "painter";

    /// A painter with the given options.
    pub fn new(options: PainterOptions) -> Self {
        Self {
            options,
            ..Self::default()
        }
    }

    /// The options.
    pub fn options(&self) -> &PainterOptions {
        &self.options
    }

    /// Orders the scene's triangles back to front, splitting where needed,
    /// without painting. The result is [`Painter::ordered_pieces`].
    ///
    /// Errors when a triangle is not set up (non-finite depth plane, wrong
    /// orientation) or the split budget runs out.
    pub fn order(&mut self, scene: &ScreenScene) -> Result<PainterStats> {
        validate(Self::NAME, scene)?;
        let mut stats = PainterStats::default();
        self.orderer.run(
            scene,
            (self.options.max_splits, self.options.max_bytes),
            self.options.depth_epsilon,
            &mut stats,
        )?;
        self.stats = stats;
        Ok(stats)
    }

    /// The pieces of the last [`Painter::order`] (or render), in paint
    /// order: farthest first, each to be painted over the ones before.
    pub fn ordered_pieces(&self) -> impl ExactSizeIterator<Item = &Piece> + '_ {
        self.orderer
            .order
            .iter()
            .map(|&id| &self.orderer.pieces[id as usize])
    }

    /// Renders into `frame` and returns the typed counters.
    pub fn render_with_stats(
        &mut self,
        scene: &ScreenScene,
        frame: &mut Frame,
    ) -> Result<PainterStats> {
        check_frame(Self::NAME, scene, frame)?;
        self.order(scene)?;
        frame.clear();
        self.stats.pixels_painted = paint(
            scene,
            &self.orderer.pieces,
            &self.orderer.order,
            frame,
            None,
        );
        Ok(self.stats)
    }

    /// Orders the scene and writes the ordered, split polygon list to
    /// `path` as SVG (one path per piece, farthest first, coloured with
    /// `mode`), atomically. With [`PainterOptions::svg_drop_hidden`] the
    /// scene is also rasterised and pieces owning no pixel are left out.
    pub fn render_svg(
        &mut self,
        scene: &ScreenScene,
        path: &Path,
        mode: ShadeMode,
    ) -> Result<Stats> {
        self.order(scene)?;
        let stroke = self.options.svg_seam_stroke;
        if self.options.svg_drop_hidden {
            let vp = scene.viewport;
            let mut frame = Frame::new(vp.width, vp.height)?;
            self.stats.pixels_painted = paint(
                scene,
                &self.orderer.pieces,
                &self.orderer.order,
                &mut frame,
                Some(&mut self.owner),
            );
            let mut visible = vec![false; self.orderer.order.len()];
            for &rank in &self.owner {
                if rank != NO_OWNER {
                    visible[rank as usize] = true;
                }
            }
            let pieces = self
                .ordered_pieces()
                .zip(&visible)
                .filter_map(|(p, &v)| v.then_some(p));
            write_svg(scene, pieces, path, mode, stroke)?;
        } else {
            write_svg(scene, self.ordered_pieces(), path, mode, stroke)?;
        }
        Ok(self.stats.into())
    }
}

impl Hider for Painter {
    fn name(&self) -> &str {
        Self::NAME
    }

    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<Stats> {
        self.render_with_stats(scene, frame).map(Stats::from)
    }
}
