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

#[cfg(test)]
mod tests;

use hider_scene::frame::BACKGROUND;
use hider_scene::{Error, Frame, Hider, Result, ScreenScene, Stats, check_frame};

use crate::options::DepthFormat;
use bins::{ChunkBins, Grid};
use key::{Fixed16, Fixed24, Reversed};
use tile::{Scratch, TileBuf, TileKey};

pub use options::TiledZBufferOptions;
pub use stats::TiledZBufferStats;

/// One band's share of the frame and its tile buffer, as the band loop
/// receives it: (band index, (((ids, depth), colour), buffer)).
type BandWork<'a, K> = (
    usize,
    (
        ((&'a mut [u32], &'a mut [f32]), &'a mut [[u8; 4]]),
        &'a mut TileBuf<K>,
    ),
);

/// Triangles per binning chunk below which binning stays on one thread.
const MIN_CHUNK: usize = 4096;

/// The fast depth-buffer hider: binned, tiled, hierarchical and parallel,
/// with exactly [`crate::ZBuffer`]'s output (window depth source).
///
/// Keeps its bins, tile buffers and thread pool between frames.
#[derive(Debug)]
pub struct TiledZBuffer {
    options: TiledZBufferOptions,
    name: String,
    pool: Option<rayon::ThreadPool>,
    chunks: Vec<ChunkBins>,
    scratch: Scratch,
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
            scratch: Scratch::default(),
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

    /// Renders and returns the typed statistics.
    pub fn render_frame(
        &mut self,
        scene: &ScreenScene,
        frame: &mut Frame,
    ) -> Result<TiledZBufferStats> {
        check_frame(&self.name, scene, frame)?;
        self.options.validate()?;
        let threads = self.threads();
        if threads > 1
            && self
                .pool
                .as_ref()
                .is_none_or(|p| p.current_num_threads() != threads)
        {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .map_err(|e| Error::Render {
                    hider: self.name.clone(),
                    message: format!("cannot start {threads} threads: {e}"),
                })?;
            self.pool = Some(pool);
        }
        match self.options.depth_format {
            DepthFormat::F32 => self.render_with::<f32>(scene, frame, threads),
            DepthFormat::F64 => self.render_with::<f64>(scene, frame, threads),
            DepthFormat::Fixed24 => self.render_with::<Fixed24>(scene, frame, threads),
            DepthFormat::Fixed16 => self.render_with::<Fixed16>(scene, frame, threads),
            DepthFormat::ReversedF32 => self.render_with::<Reversed>(scene, frame, threads),
        }
    }

    fn render_with<K: TileKey>(
        &mut self,
        scene: &ScreenScene,
        frame: &mut Frame,
        threads: usize,
    ) -> Result<TiledZBufferStats> {
        let vp = scene.viewport;
        let grid = Grid::new(vp.width, vp.height, self.options.tile_size);
        let pool = self.pool.as_ref().filter(|_| threads > 1);

        // 1. Binning, in contiguous chunks of triangles.
        let n = scene.tris.len();
        let chunks = if pool.is_some() {
            threads.min(n / MIN_CHUNK).max(1)
        } else {
            1
        };
        let per = n.div_ceil(chunks).max(1);
        self.chunks.resize_with(chunks, ChunkBins::default);
        self.chunks.truncate(chunks);
        let bin = |(c, bins): (usize, &mut ChunkBins)| {
            bins.fill(scene, (c * per).min(n)..((c + 1) * per).min(n), grid);
        };
        match pool {
            Some(pool) if chunks > 1 => {
                use rayon::prelude::*;
                pool.install(|| self.chunks.par_iter_mut().enumerate().for_each(bin));
            }
            _ => self.chunks.iter_mut().enumerate().for_each(bin),
        }

        // 2. Tiles, band by band (a band is a row of tiles: a contiguous
        //    run of frame rows, so bands can be handed to threads safely).
        let bufs = K::bufs(&mut self.scratch);
        if bufs.first().is_some_and(|b| b.size() != grid.tile) {
            bufs.clear();
        }
        bufs.resize_with(grid.rows as usize, || TileBuf::new(grid.tile));
        bufs.truncate(grid.rows as usize);
        let width = vp.width as usize;
        let band_len = width * grid.tile as usize;
        frame.coverage.clear();
        let chunks = &self.chunks;
        let hiz = self.options.hierarchical_z;
        let band = |(b, (((ids, depth), color), buf)): BandWork<'_, K>| {
            buf.stats = TiledZBufferStats::default();
            let y0 = b as u32 * grid.tile;
            let h = grid.tile.min(vp.height - y0);
            for tx in 0..grid.cols {
                let x0 = tx * grid.tile;
                let w = grid.tile.min(vp.width - x0);
                let t = b * grid.cols as usize + tx as usize;
                if !bins::tile_has_work(chunks, t) {
                    tile::clear_tile(ids, depth, width, (x0, 0, w, h));
                    buf.stats.tiles_skipped += 1;
                    continue;
                }
                buf.start(x0, y0, w, h);
                bins::for_each_in_tile(chunks, t, |i| buf.draw(&scene.tris[i as usize], vp, hiz));
                buf.resolve(ids, depth, width, y0);
            }
            color.fill(BACKGROUND);
        };
        match pool {
            Some(pool) => {
                use rayon::prelude::*;
                pool.install(|| {
                    frame
                        .ids
                        .par_chunks_mut(band_len)
                        .zip(frame.depth.par_chunks_mut(band_len))
                        .zip(frame.color.par_chunks_mut(band_len))
                        .zip(bufs.par_iter_mut())
                        .enumerate()
                        .for_each(band)
                });
            }
            None => frame
                .ids
                .chunks_mut(band_len)
                .zip(frame.depth.chunks_mut(band_len))
                .zip(frame.color.chunks_mut(band_len))
                .zip(bufs.iter_mut())
                .enumerate()
                .for_each(band),
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
            + self.chunks.iter().map(ChunkBins::bytes).sum::<usize>())
            as u64;
        Ok(stats)
    }
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
