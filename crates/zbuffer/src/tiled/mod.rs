//! The fast z-buffer: the same answer as [`crate::ZBuffer`], pixel for
//! pixel, from a binned, tiled, hierarchical, parallel rasteriser.
//!
//! 1. **Binning** ([`bins`]): one pass appends each triangle's index to
//!    the bins of the screen tiles its bounding box meets (in parallel over
//!    contiguous chunks of triangles, keeping primitive order per tile).
//! 2. **Tiles** ([`tile`]): bands of tiles are drawn in parallel (rayon),
//!    each tile into a compact buffer of keys and ids that stays in cache,
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
//! lean [`DepthScene`] of [`hider_scene::prepare_depth_into`].
//!
//! Equality with the reference is by construction: the coverage test is
//! the same exact integer edge functions; a pixel's depth is the same f64
//! expression ([`hider_geom::PlaneEq::eval`], split into a column term
//! plus a row term in the same order of operations); the keys round it as
//! the reference buffer does ([`key`]); and each tile sees its triangles in
//! primitive order, so LESS keeps the same one of two equal keys.
//! Hierarchical rejection only skips pixels that provably fail.

mod bins;
mod bounds;
mod key;
mod options;
mod stats;
mod tile;
mod wide;

#[cfg(test)]
mod tests;

use hider_geom::{FixedPt, PlaneEq, Viewport};
use hider_scene::frame::BACKGROUND;
use hider_scene::{
    DepthFragment, DepthScene, DepthTri, Error, Frame, Hider, Result, ScreenScene, ScreenTri,
    Stats, check_frame, check_frame_size,
};

use crate::options::DepthFormat;
use bins::{ChunkBins, FragmentBins, Grid};
use key::{Fixed16, Fixed24, Reversed};
use tile::{Scratch, TileBuf, TileKey};
use wide::{Avx2, Isa, Portable};

pub use options::TiledZBufferOptions;
pub use stats::TiledZBufferStats;

/// What the tile kernel reads of a triangle; implemented by both
/// [`ScreenTri`] and the lean [`DepthTri`].
pub(crate) trait RasterTri: Sync {
    /// Whether the list may hold triangles that cover no pixel centre
    /// (binning drops them). The lean front end drops them itself; a
    /// screen scene keeps them for the other hiders.
    const MAY_MISS_CENTRES: bool;
    /// Snapped vertices, positively ordered.
    fn v(&self) -> &[FixedPt; 3];
    /// The window-depth plane.
    fn depth(&self) -> &PlaneEq;
    /// The primitive id.
    fn prim(&self) -> u32;
}

/// Both triangle types keep the same three fields under the same names.
macro_rules! raster_tri {
    ($($t:ty: $miss:expr),*) => {$(
        impl RasterTri for $t {
            const MAY_MISS_CENTRES: bool = $miss;
            #[inline]
            fn v(&self) -> &[FixedPt; 3] {
                &self.v
            }
            #[inline]
            fn depth(&self) -> &PlaneEq {
                &self.depth
            }
            #[inline]
            fn prim(&self) -> u32 {
                self.prim
            }
        }
    )*};
}
raster_tri!(ScreenTri: true, DepthTri: false);

/// One band of the frame as the resolve receives it: ((ids, depth),
/// colour) rows of one row of tiles.
type FrameBand<'a> = ((&'a mut [u32], &'a mut [f32]), &'a mut [[u8; 4]]);

/// Triangles per binning chunk below which binning stays on one thread.
const MIN_CHUNK: usize = 4096;

/// The fast depth-buffer hider: binned, tiled, hierarchical and parallel,
/// with exactly [`crate::ZBuffer`]'s output (window depth source).
///
/// Keeps its bins, tile buffers (its framebuffer) and thread pool between
/// frames.
#[derive(Debug)]
pub struct TiledZBuffer {
    options: TiledZBufferOptions,
    name: String,
    pool: Option<rayon::ThreadPool>,
    chunks: Vec<ChunkBins>,
    fragment_bins: Vec<FragmentBins>,
    scratch: Scratch,
    /// The image held in the tiles: its viewport, grid and format.
    drawn: Option<(Viewport, Grid, DepthFormat)>,
    /// Whether the AVX2 kernel may be used (tests turn it off to compare
    /// the two kernels).
    wide_kernel: bool,
}

impl TiledZBuffer {
    /// A tiled z-buffer with the given options (checked when rendering).
    /// Its [`Hider::name`] is `zbuffer-tiled` followed by the depth format
    /// when it is not the default (`zbuffer-tiled-fixed24`...).
    pub fn new(options: TiledZBufferOptions) -> Self {
        let name = match options.depth_format {
            DepthFormat::F32 => "zbuffer-tiled".to_owned(),
            DepthFormat::ReversedF32 => "zbuffer-tiled-reversed".to_owned(),
            f => format!("zbuffer-tiled-{}", f.name()),
        };
        Self {
            options,
            name,
            pool: None,
            chunks: Vec::new(),
            fragment_bins: Vec::new(),
            scratch: Scratch::default(),
            drawn: None,
            wide_kernel: true,
        }
    }

    /// The options in use.
    pub fn options(&self) -> &TiledZBufferOptions {
        &self.options
    }

    /// The number of threads rendering: [`TiledZBufferOptions::threads`],
    /// or the machine's core count for 0.
    pub fn threads(&self) -> usize {
        match self.options.threads {
            0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
            n => n,
        }
    }

    /// Renders a screen scene into `frame` and returns the typed
    /// statistics.
    pub fn render_frame(
        &mut self,
        scene: &ScreenScene,
        frame: &mut Frame,
    ) -> Result<TiledZBufferStats> {
        check_frame(&self.name, scene, frame)?;
        self.run(&[&scene.tris[..]], &[], scene.viewport, Some(frame))
    }

    /// Renders a lean [`DepthScene`] into `frame`: the same frame as
    /// [`Self::render_frame`] on the [`ScreenScene`] of the same scene,
    /// view and options.
    pub fn render_depth_scene(
        &mut self,
        scene: &DepthScene,
        frame: &mut Frame,
    ) -> Result<TiledZBufferStats> {
        self.check_size(scene.viewport, frame)?;
        let parts: Vec<&[DepthTri]> = scene.parts().collect();
        let fragments: Vec<&[DepthFragment]> = scene.fragments().collect();
        self.run(&parts, &fragments, scene.viewport, Some(frame))
    }

    /// Draws a lean [`DepthScene`] into the hider's own tiled framebuffer
    /// and stops, as a GL draw call and `glFinish` do: tiles no triangle
    /// reached are only flagged background. [`Self::read_into`] copies the
    /// image out; [`Self::pixel`] reads one pixel.
    pub fn draw_depth_scene(&mut self, scene: &DepthScene) -> Result<TiledZBufferStats> {
        let parts: Vec<&[DepthTri]> = scene.parts().collect();
        let fragments: Vec<&[DepthFragment]> = scene.fragments().collect();
        self.run(&parts, &fragments, scene.viewport, None)
    }

    /// Copies the image last drawn into `frame` (ids, window depth,
    /// background colour), exactly as [`Self::render_frame`] writes it:
    /// the read-back (`glReadPixels`) step.
    ///
    /// # Errors
    ///
    /// When nothing was drawn yet, or `frame` has another size.
    pub fn read_into(&mut self, frame: &mut Frame) -> Result<()> {
        let Some((vp, grid, format)) = self.drawn else {
            return Err(self.error("nothing has been drawn to read back".to_owned()));
        };
        self.check_size(vp, frame)?;
        match format {
            DepthFormat::F32 => self.read_with::<f32>(vp, grid, frame),
            DepthFormat::F64 => self.read_with::<f64>(vp, grid, frame),
            DepthFormat::Fixed24 => self.read_with::<Fixed24>(vp, grid, frame),
            DepthFormat::Fixed16 => self.read_with::<Fixed16>(vp, grid, frame),
            DepthFormat::ReversedF32 => self.read_with::<Reversed>(vp, grid, frame),
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
        Some(match format {
            DepthFormat::F32 => get::<f32>(&mut self.scratch, t, x, y),
            DepthFormat::F64 => get::<f64>(&mut self.scratch, t, x, y),
            DepthFormat::Fixed24 => get::<Fixed24>(&mut self.scratch, t, x, y),
            DepthFormat::Fixed16 => get::<Fixed16>(&mut self.scratch, t, x, y),
            DepthFormat::ReversedF32 => get::<Reversed>(&mut self.scratch, t, x, y),
        })
    }

    fn error(&self, message: String) -> Error {
        Error::Render {
            hider: self.name.clone(),
            message,
        }
    }

    fn check_size(&self, vp: Viewport, frame: &Frame) -> Result<()> {
        check_frame_size(&self.name, vp, frame)
    }

    /// Validates the options, starts the pool if needed, then draws (and
    /// resolves into `frame` when given).
    fn run<T: RasterTri>(
        &mut self,
        parts: &[&[T]],
        fragments: &[&[DepthFragment]],
        vp: Viewport,
        frame: Option<&mut Frame>,
    ) -> Result<TiledZBufferStats> {
        self.options.validate()?;
        hider_scene::view::check_image_size(vp.width, vp.height)?;
        let threads = self.threads();
        if threads > 1
            && !ambient_pool(threads)
            && self
                .pool
                .as_ref()
                .is_none_or(|p| p.current_num_threads() != threads)
        {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .map_err(|e| self.error(format!("cannot start {threads} threads: {e}")))?;
            self.pool = Some(pool);
        }
        self.drawn = None;
        let stats = match self.options.depth_format {
            DepthFormat::F32 => self.draw_with::<T, f32>((parts, fragments), vp, frame, threads),
            DepthFormat::F64 => self.draw_with::<T, f64>((parts, fragments), vp, frame, threads),
            DepthFormat::Fixed24 => {
                self.draw_with::<T, Fixed24>((parts, fragments), vp, frame, threads)
            }
            DepthFormat::Fixed16 => {
                self.draw_with::<T, Fixed16>((parts, fragments), vp, frame, threads)
            }
            DepthFormat::ReversedF32 => {
                self.draw_with::<T, Reversed>((parts, fragments), vp, frame, threads)
            }
        };
        let grid = Grid::new(vp.width, vp.height, self.options.tile_size);
        self.drawn = Some((vp, grid, self.options.depth_format));
        Ok(stats)
    }

    fn draw_with<T: RasterTri, K: TileKey>(
        &mut self,
        (parts, fragments): (&[&[T]], &[&[DepthFragment]]),
        vp: Viewport,
        frame: Option<&mut Frame>,
        threads: usize,
    ) -> TiledZBufferStats {
        let grid = Grid::new(vp.width, vp.height, self.options.tile_size);
        let pool = workers(self.pool.as_ref(), threads);
        // Wake the other threads now, while this one bins: an idle rayon
        // worker sleeps, and on these virtual machines waking one takes
        // tens of microseconds, a tenth of a small scene's frame. After
        // the empty job it searches for work for a while before sleeping
        // again, and the tiles arrive within that while.
        match pool {
            Some(Some(pool)) => pool.spawn(|| {}),
            Some(None) => rayon::spawn(|| {}),
            None => {}
        }

        // 1. Binning, one chunk per contiguous run of triangles; runs are
        //    cut further so that every thread has one.
        let total: usize = parts.iter().map(|p| p.len()).sum();
        let wanted = if pool.is_some() {
            threads.min(total / MIN_CHUNK).max(1)
        } else {
            1
        };
        let per = total.div_ceil(wanted).max(MIN_CHUNK);
        let tris: Vec<&[T]> = parts
            .iter()
            .flat_map(|p| p.chunks(per))
            .filter(|c| !c.is_empty())
            .collect();
        self.chunks.resize_with(tris.len(), ChunkBins::default);
        self.chunks.truncate(tris.len());
        let hiz = self.options.hierarchical_z;
        let bin = |(bins, chunk): (&mut ChunkBins, &&[T])| bins.fill(chunk, vp, grid, hiz);
        self.fragment_bins
            .resize_with(fragments.len(), FragmentBins::default);
        self.fragment_bins.truncate(fragments.len());
        let bin_fragments = |(bins, run): (&mut FragmentBins, &&[DepthFragment])| {
            bins.fill(run, vp, grid);
        };
        match pool {
            Some(pool) if tris.len() > 1 || fragments.len() > 1 => {
                use rayon::prelude::*;
                install(pool, || {
                    rayon::join(
                        || self.chunks.par_iter_mut().zip(&tris).for_each(bin),
                        || {
                            self.fragment_bins
                                .par_iter_mut()
                                .zip(fragments)
                                .for_each(bin_fragments);
                        },
                    )
                });
            }
            _ => {
                self.chunks.iter_mut().zip(&tris).for_each(bin);
                self.fragment_bins
                    .iter_mut()
                    .zip(fragments)
                    .for_each(bin_fragments);
            }
        }

        // 2. Tiles, band by band (a band is a row of tiles: a contiguous
        //    run of frame rows, so bands can be handed to threads safely).
        let bufs = K::bufs(&mut self.scratch);
        if bufs.first().is_some_and(|b| b.size() != grid.tile) {
            bufs.clear();
        }
        bufs.resize_with(grid.tiles(), || TileBuf::new(grid.tile));
        bufs.truncate(grid.tiles());
        let chunks = &self.chunks;
        let fragment_bins = &self.fragment_bins;
        let wide = self.wide_kernel;
        let cols = grid.cols as usize;
        // The job drawing the run of tiles that starts at tile `first`.
        let job_at = |first: usize| BandJob {
            wide,
            first,
            grid,
            vp,
            tris: &tris,
            chunks,
            fragments: fragment_bins,
            hiz,
        };
        let draw_band = |b: usize, band: &mut [TileBuf<K>]| job_at(b * cols).dispatch(band);
        match frame {
            Some(frame) => {
                let width = vp.width as usize;
                for_each_band(frame, bufs, grid, pool, |b, out, band| {
                    draw_band(b, band);
                    resolve_band(band, out, width, b as u32 * grid.tile);
                });
            }
            // Nothing to resolve: threads take single tiles, which balances
            // a small object in the middle of the image far better than
            // bands do.
            None => match pool {
                Some(pool) => {
                    use rayon::prelude::*;
                    // Tiles nothing reaches are only flagged background,
                    // here; the threads share the others, one task each
                    // (the spider at 1024 reaches 36 of 256 tiles: fewer
                    // tasks to split and steal).
                    let mut busy = Vec::new();
                    for (t, tile) in bufs.iter_mut().enumerate() {
                        if bins::tile_has_work(chunks, fragment_bins, t) {
                            busy.push((bins::tile_load(chunks, fragment_bins, t), t, tile));
                        } else {
                            job_at(t).dispatch(std::slice::from_mut(tile));
                        }
                    }
                    // Heaviest first: the last tasks, which decide when the
                    // threads finish, are then the small ones.
                    busy.sort_unstable_by_key(|&(load, t, _)| (std::cmp::Reverse(load), t));
                    install(pool, || {
                        busy.par_iter_mut()
                            .with_max_len(1)
                            .for_each(|(_, t, tile)| {
                                job_at(*t).dispatch(std::slice::from_mut(*tile))
                            });
                    });
                }
                None => bufs
                    .chunks_mut(cols)
                    .enumerate()
                    .for_each(|(b, band)| draw_band(b, band)),
            },
        }

        let mut stats = TiledZBufferStats::default();
        for buf in bufs.iter() {
            stats.add(&buf.stats);
        }
        for c in &self.chunks {
            stats.triangles_binned += c.binned;
            stats.bin_entries += c.entries;
            stats.large_triangles += c.large.len() as u64;
        }
        stats.scratch_bytes = (K::bufs(&mut self.scratch)
            .iter()
            .map(TileBuf::bytes)
            .sum::<usize>()
            + self.chunks.iter().map(ChunkBins::bytes).sum::<usize>()
            + self
                .fragment_bins
                .iter()
                .map(FragmentBins::bytes)
                .sum::<usize>()) as u64;
        stats
    }

    fn read_with<K: TileKey>(&mut self, vp: Viewport, grid: Grid, frame: &mut Frame) {
        let pool = workers(self.pool.as_ref(), self.threads());
        let width = vp.width as usize;
        for_each_band(
            frame,
            K::bufs(&mut self.scratch),
            grid,
            pool,
            |b, out, band| {
                resolve_band(band, out, width, b as u32 * grid.tile);
            },
        );
    }
}

/// Calls `work` with each band's index, its rows of the frame and its
/// tiles, in parallel on `pool` (see [`workers`]) or in order; clears the
/// frame's coverage (a z-buffer writes none).
fn for_each_band<K: TileKey>(
    frame: &mut Frame,
    bufs: &mut [TileBuf<K>],
    grid: Grid,
    pool: Option<Option<&rayon::ThreadPool>>,
    work: impl Fn(usize, FrameBand<'_>, &mut [TileBuf<K>]) + Sync,
) {
    frame.coverage.clear();
    let band_len = frame.width() as usize * grid.tile as usize;
    let cols = grid.cols as usize;
    let work = |(b, (out, band)): (usize, (FrameBand<'_>, &mut [TileBuf<K>]))| work(b, out, band);
    match pool {
        Some(pool) => {
            use rayon::prelude::*;
            install(pool, || {
                frame
                    .ids
                    .par_chunks_mut(band_len)
                    .zip(frame.depth.par_chunks_mut(band_len))
                    .zip(frame.color.par_chunks_mut(band_len))
                    .zip(bufs.par_chunks_mut(cols))
                    .enumerate()
                    .for_each(work)
            });
        }
        None => frame
            .ids
            .chunks_mut(band_len)
            .zip(frame.depth.chunks_mut(band_len))
            .zip(frame.color.chunks_mut(band_len))
            .zip(bufs.chunks_mut(cols))
            .enumerate()
            .for_each(work),
    }
}

/// Everything drawing a run of tiles (a band, or one tile) needs.
struct BandJob<'a, T> {
    /// Whether the AVX2 kernel may be used.
    wide: bool,
    /// Index of the first tile of the run (row-major).
    first: usize,
    grid: Grid,
    vp: Viewport,
    tris: &'a [&'a [T]],
    chunks: &'a [ChunkBins],
    /// Each run's fragments by tile, applied after the tile's triangles.
    fragments: &'a [FragmentBins],
    hiz: bool,
}

impl<T: RasterTri> BandJob<'_, T> {
    /// Draws the band with the widest vector instructions the CPU has.
    ///
    /// The kernel is compiled twice: for baseline x86-64 (SSE2) and, where
    /// the CPU reports AVX2 and FMA at run time, for those (4 `f64` or 8
    /// `i32` lanes instead of 2 or 4, and blends). Everything the band calls
    /// is `#[inline(always)]`, so all of it is compiled with the features
    /// of the copy it lands in. Same instructions' semantics, same results:
    /// IEEE arithmetic is exact per operation and Rust never contracts
    /// `a * b + c` into an FMA, so both copies give the same bits (the
    /// property tests run whichever this machine picks; CI's machine has
    /// AVX2, and `tests::both_kernels_agree` runs both).
    fn dispatch<K: TileKey>(&self, band: &mut [TileBuf<K>]) {
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = Avx2::detect().filter(|_| self.wide) {
            self.draw_avx2(band, avx2);
            return;
        }
        self.draw(band, Portable);
    }

    /// [`Self::draw`] compiled for AVX2 and FMA.
    ///
    /// One of the project's six `unsafe` sites (listed in
    /// `docs/zbuffer.md`): calling a `target_feature` function is unsafe
    /// only because the CPU might lack the feature, and the [`Avx2`] value
    /// proves it has them.
    #[cfg(target_arch = "x86_64")]
    #[allow(unsafe_code)]
    fn draw_avx2<K: TileKey>(&self, band: &mut [TileBuf<K>], avx2: Avx2) {
        #[target_feature(enable = "avx2,fma")]
        unsafe fn kernel<T: RasterTri, K: TileKey>(
            job: &BandJob<'_, T>,
            band: &mut [TileBuf<K>],
            avx2: Avx2,
        ) {
            job.draw(band, avx2);
        }
        // SAFETY: an `Avx2` value exists only where AVX2 and FMA were
        // detected.
        unsafe { kernel(self, band, avx2) }
    }

    /// Draws the run of tiles `band` (tiles `first..`, row-major) from
    /// their bins.
    #[inline(always)]
    fn draw<K: TileKey, I: Isa>(&self, band: &mut [TileBuf<K>], isa: I) {
        let (grid, vp) = (self.grid, self.vp);
        for (i, buf) in band.iter_mut().enumerate() {
            let t = self.first + i;
            let (tx, ty) = (
                (t % grid.cols as usize) as u32,
                (t / grid.cols as usize) as u32,
            );
            let (x0, y0) = (tx * grid.tile, ty * grid.tile);
            buf.start(
                x0,
                y0,
                grid.tile.min(vp.width - x0),
                grid.tile.min(vp.height - y0),
            );
            if bins::tile_has_work(self.chunks, self.fragments, t) {
                let mut draw = Drawer {
                    isa,
                    buf: &mut *buf,
                    vp,
                    hiz: self.hiz,
                };
                bins::for_each_in_tile(self.tris, self.chunks, t, &mut draw);
                for run in self.fragments {
                    for f in &run.tiles[t] {
                        buf.fragment(f);
                    }
                }
            }
            if !buf.is_active() {
                buf.stats.tiles_skipped += 1;
            }
        }
    }
}

/// A tile buffer drawing binned triangles.
struct Drawer<'a, K, I> {
    isa: I,
    buf: &'a mut TileBuf<K>,
    vp: Viewport,
    hiz: bool,
}

impl<T: RasterTri, K: TileKey, I: Isa> bins::DrawTri<T> for Drawer<'_, K, I> {
    #[inline(always)]
    fn draw(&mut self, tri: &T, low: f32) {
        self.buf.draw(self.isa, tri, low, self.vp, self.hiz);
    }
}

/// Whether the caller's rayon pool (the one `par_iter` would use here:
/// the pool the current thread works for, or the global one) has exactly
/// `threads` workers. Then the hider uses it rather than a pool of its own:
/// two pools on the same cores only take turns (the CLI builds a global
/// pool for the parallel front end, and a caller may run the front end and
/// the hider inside one `install`).
fn ambient_pool(threads: usize) -> bool {
    rayon::current_num_threads() == threads
}

/// The workers for `threads`: `None` to stay on the calling thread,
/// `Some(None)` for the ambient pool, `Some(Some(pool))` for the hider's.
fn workers(own: Option<&rayon::ThreadPool>, threads: usize) -> Option<Option<&rayon::ThreadPool>> {
    if threads <= 1 {
        None
    } else if ambient_pool(threads) {
        Some(None)
    } else {
        own.map(Some)
    }
}

/// Runs `f` in `pool`, or right here in the ambient pool.
fn install<R: Send>(pool: Option<&rayon::ThreadPool>, f: impl FnOnce() -> R + Send) -> R {
    match pool {
        Some(pool) => pool.install(f),
        None => f(),
    }
}

/// Writes a band's tiles into the frame's rows of that band.
fn resolve_band<K: TileKey>(
    band: &[TileBuf<K>],
    ((ids, depth), color): FrameBand<'_>,
    width: usize,
    band_y0: u32,
) {
    for buf in band {
        buf.resolve(ids, depth, width, band_y0);
    }
    color.fill(BACKGROUND);
}

/// One pixel of tile `t` in format `K`, decoded.
fn get<K: TileKey>(scratch: &mut Scratch, t: usize, x: u32, y: u32) -> (u32, f32) {
    let (id, key) = K::bufs(scratch)[t].get(x, y);
    (id, key.decode())
}

impl Default for TiledZBuffer {
    fn default() -> Self {
        Self::new(TiledZBufferOptions::default())
    }
}

impl Hider for TiledZBuffer {
    fn name(&self) -> &str {
        &self.name
    }

    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<Stats> {
        self.render_frame(scene, frame).map(Stats::from)
    }
}
