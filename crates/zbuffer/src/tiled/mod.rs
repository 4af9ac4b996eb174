//! The fast z-buffer: the same answer as [`crate::ZBuffer`], pixel for
//! pixel, from a binned, tiled, hierarchical, parallel rasteriser.
//!
//! 1. **Binning** ([`bins`]): one pass appends each triangle's index to
//!    the bins of the screen tiles its bounding box meets (in parallel over
//!    contiguous chunks of triangles, keeping primitive order per tile).
//! 2. **Tiles** ([`tile`], [`band`]): bands of tiles are drawn in
//!    parallel (rayon), each tile into a compact buffer of keys and ids
//!    that stays in cache,
//!    by 8x8 blocks with trivial accept/reject from the edge functions at
//!    their corners and hierarchical depth rejection of triangles and
//!    blocks ([`bounds`]); inner rows are branch-free so they vectorise.
//! 3. **Resolve**: each tile writes its ids and depths into the frame
//!    once. A tile no triangle met is never cleared: background is written
//!    straight into the frame (the per-tile clear flag).
//!
//! The tiles are the hider's own framebuffer, one buffer per tile kept
//! between frames. [`TiledZBuffer::draw_depth_scene`] stops there, as a GL
//! draw call followed by `glFinish` does (tiles no triangle reached are
//! flagged background and never touched), and
//! [`TiledZBuffer::read_into`] is the read-back (`glReadPixels`);
//! [`Hider::render`] does both, resolving each band while it is in cache.
//! Input is either a [`ScreenScene`] (what every hider consumes) or the
//! lean [`DepthScene`] of [`prepare_depth_into`], the hider's own front
//! end, which [`Hider::render_scene`] runs.
//!
//! Equality with the reference is by construction: the coverage test is
//! the same exact integer edge functions; a pixel's depth is the same f64
//! expression ([`hider_geom::PlaneEq::eval`], split into a column term
//! plus a row term in the same order of operations); the keys round it as
//! the reference buffer does ([`key`]); and each tile sees its triangles in
//! primitive order, so LESS keeps the same one of two equal keys.
//! Hierarchical rejection only skips pixels that provably fail.

mod band;
mod bins;
mod bounds;
mod draw;
pub(crate) mod key;
mod options;
mod raster_tri;
mod scratch;
mod stats;
mod tile;
#[cfg_attr(
    not(target_arch = "x86_64"),
    expect(
        dead_code,
        reason = "the AVX2 kernels' inputs: only the x86_64 build has the kernels"
    )
)]
pub(crate) mod wide;

#[cfg(test)]
mod readback_tests;
#[cfg(test)]
mod setup_tests;
#[cfg(test)]
mod tests;

use hider_geom::Viewport;
use hider_scene::{
    Error, Frame, Hider, PrepareOptions, Result, Scene, ScreenScene, View, check_frame,
    check_frame_size,
};

use hider_scene::pool::{OwnPool, thread_count};

use crate::depth_scene::{DepthFragment, DepthScene, DepthTri, prepare_depth_into};
use crate::options::{DepthFormat, DepthTest};
use bins::Grid;
use key::{Fixed16, Fixed24, Reversed};
use scratch::Scratch;

pub(crate) use tile::SMALL_AREA;

pub use options::TiledZBufferOptions;
pub use stats::TiledZBufferStats;

/// The fast depth-buffer hider: binned, tiled, hierarchical and parallel,
/// with exactly [`crate::ZBuffer`]'s output (window depth source).
///
/// Keeps its bins, tile buffers (its framebuffer), lean depth scene and
/// thread pool between frames.
#[derive(Debug)]
pub struct TiledZBuffer {
    options: TiledZBufferOptions,
    name: String,
    pool: OwnPool,
    bins: bins::Bins,
    scratch: Scratch,
    /// The lean front end's output, for [`Hider::render_scene`].
    lean: DepthScene,
    /// The image held in the tiles: its viewport, grid and format.
    drawn: Option<(Viewport, Grid, DepthFormat)>,
    /// Whether the AVX2 kernel may be used (tests turn it off to compare
    /// the two kernels; the output is the same).
    wide_kernel: bool,
}

impl TiledZBuffer {
    /// The number of threads rendering: [`TiledZBufferOptions::threads`],
    /// or the machine's core count for 0.
    pub fn threads(&self) -> usize {
        thread_count(self.options.threads)
    }

    /// Draws a lean [`DepthScene`] into the hider's own tiled framebuffer
    /// and stops, as a GL draw call and `glFinish` do: tiles no triangle
    /// reached are only flagged background. [`Self::read_into`] copies the
    /// image out; [`Self::pixel`] reads one pixel. [`Hider::render_scene`]
    /// is the same draw with the read-back done band by band while the
    /// tiles are in cache.
    ///
    /// # Errors
    ///
    /// Invalid options, or a depth scene never prepared (no image size).
    pub fn draw_depth_scene(&mut self, scene: &DepthScene) -> Result<TiledZBufferStats> {
        let parts: Vec<&[DepthTri]> = scene.parts().collect();
        let fragments: Vec<&[DepthFragment]> = scene.fragments().collect();
        self.run(
            (&parts, &fragments),
            (scene.viewport, scene.setups_valid()),
            None,
        )
    }

    /// Copies the image last drawn into `frame` (ids, window depth,
    /// background colour), exactly as [`Hider::render`] writes it: the
    /// read-back (`glReadPixels`) step.
    ///
    /// # Errors
    ///
    /// When nothing was drawn yet, or `frame` has another size.
    pub fn read_into(&mut self, frame: &mut Frame) -> Result<()> {
        let Some((vp, grid, format)) = self.drawn else {
            return Err(self.error("nothing has been drawn to read back".to_owned()));
        };
        check_frame_size(&self.name, vp, frame)?;
        match format {
            DepthFormat::F32 => self.read_with::<f32>(grid, frame),
            DepthFormat::F64 => self.read_with::<f64>(grid, frame),
            DepthFormat::Fixed24 => self.read_with::<Fixed24>(grid, frame),
            DepthFormat::Fixed16 => self.read_with::<Fixed16>(grid, frame),
            DepthFormat::ReversedF32 => self.read_with::<Reversed>(grid, frame),
        }
        Ok(())
    }

    /// The visible primitive id ([`hider_scene::NO_ID`] for background)
    /// and window depth of pixel `(x, y)` of the image last drawn, or
    /// `None` outside it or before anything was drawn.
    pub fn pixel(&mut self, x: u32, y: u32) -> Option<(u32, f32)> {
        let (vp, grid, format) = self.drawn?;
        if x >= vp.width || y >= vp.height {
            return None;
        }
        let t = (y / grid.tile * grid.cols + x / grid.tile) as usize;
        let s = &mut self.scratch;
        Some(match format {
            DepthFormat::F32 => s.pixel::<f32>(t, x, y),
            DepthFormat::F64 => s.pixel::<f64>(t, x, y),
            DepthFormat::Fixed24 => s.pixel::<Fixed24>(t, x, y),
            DepthFormat::Fixed16 => s.pixel::<Fixed16>(t, x, y),
            DepthFormat::ReversedF32 => s.pixel::<Reversed>(t, x, y),
        })
    }

    fn error(&self, message: String) -> Error {
        Error::Render {
            hider: self.name.clone(),
            message,
        }
    }
}

impl Default for TiledZBuffer {
    fn default() -> Self {
        Self::new(TiledZBufferOptions::default())
    }
}

impl Hider for TiledZBuffer {
    type Options = TiledZBufferOptions;
    type Stats = TiledZBufferStats;

    /// A tiled z-buffer with the given options (checked when rendering).
    /// Its [`Hider::name`] is `zbuffer-tiled` followed by the depth format
    /// and test when they are not the defaults (`zbuffer-tiled-fixed24`,
    /// `zbuffer-tiled-gl-less`...).
    fn new(options: TiledZBufferOptions) -> Self {
        let mut name = match options.depth_format {
            DepthFormat::F32 => "zbuffer-tiled".to_owned(),
            DepthFormat::ReversedF32 => "zbuffer-tiled-reversed".to_owned(),
            f => format!("zbuffer-tiled-{}", f.name()),
        };
        if options.depth_test == DepthTest::GlLess {
            name.push_str("-gl-less");
        }
        Self {
            options,
            name,
            pool: OwnPool::default(),
            bins: bins::Bins::default(),
            scratch: Scratch::default(),
            lean: DepthScene::new(),
            drawn: None,
            wide_kernel: true,
        }
    }

    fn options(&self) -> &TiledZBufferOptions {
        &self.options
    }

    fn name(&self) -> &str {
        &self.name
    }

    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<TiledZBufferStats> {
        check_frame(&self.name, scene, frame)?;
        self.run(
            (&[&scene.tris[..]], &[]),
            (scene.viewport, false),
            Some(frame),
        )
    }

    /// The hider's own pipeline: the lean front end
    /// ([`prepare_depth_into`], into a depth scene the hider keeps), then
    /// the draw, each band resolved into `frame` while it is in cache.
    /// The same frame as [`Hider::render`] on `prepare`'s screen scene;
    /// `screen` is left as it was.
    fn render_scene(
        &mut self,
        scene: &Scene,
        view: &View,
        options: &PrepareOptions,
        _screen: &mut ScreenScene,
        frame: &mut Frame,
    ) -> Result<TiledZBufferStats> {
        let mut lean = std::mem::take(&mut self.lean);
        let stats = prepare_depth_into(scene, view, options, &mut lean).and_then(|()| {
            check_frame_size(&self.name, lean.viewport, frame)?;
            let parts: Vec<&[DepthTri]> = lean.parts().collect();
            let fragments: Vec<&[DepthFragment]> = lean.fragments().collect();
            self.run(
                (&parts, &fragments),
                (lean.viewport, lean.setups_valid()),
                Some(frame),
            )
        });
        self.lean = lean;
        stats
    }
}
