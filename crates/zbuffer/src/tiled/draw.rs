//! A frame of the tiled z-buffer: the options checked and the pool
//! started, then binning, the tiles, and the frame's counters.

use hider_geom::Viewport;
use hider_scene::{Frame, Result};

use super::TiledZBuffer;
use super::band::{self, Jobs};
use super::bins::{Grid, Input};
use super::key::{Fixed16, Fixed24, Reversed};
use super::raster_tri::RasterTri;
use super::scratch::{Scratch, TileKey};
use super::stats::TiledZBufferStats;
use super::tile::TileBuf;
use crate::options::{DepthFormat, DepthTest};

impl TiledZBuffer {
    /// Validates the options, starts the pool if needed, then draws (and
    /// resolves into `frame` when given).
    pub(super) fn run<T: RasterTri>(
        &mut self,
        input: Input<'_, T>,
        (vp, setups): (Viewport, bool),
        frame: Option<&mut Frame>,
    ) -> Result<TiledZBufferStats> {
        self.options.validate()?;
        hider_scene::view::check_image_size(vp.width, vp.height)?;
        let threads = self.threads();
        self.pool.start(threads, &self.name)?;
        self.drawn = None;
        let stats = match self.options.depth_format {
            DepthFormat::F32 => self.draw_with::<T, f32>(input, (vp, setups), frame, threads),
            DepthFormat::F64 => self.draw_with::<T, f64>(input, (vp, setups), frame, threads),
            DepthFormat::Fixed24 => {
                self.draw_with::<T, Fixed24>(input, (vp, setups), frame, threads)
            }
            DepthFormat::Fixed16 => {
                self.draw_with::<T, Fixed16>(input, (vp, setups), frame, threads)
            }
            DepthFormat::ReversedF32 => {
                self.draw_with::<T, Reversed>(input, (vp, setups), frame, threads)
            }
        };
        // The tiles skip their triangles once the token stops them.
        self.options.cancel.poll()?;
        let grid = Grid::new(vp.width, vp.height, self.options.tile_size);
        self.drawn = Some((vp, grid, self.options.depth_format));
        Ok(stats)
    }

    /// One frame in format `K`: bins, then tiles (resolved into `frame`
    /// when given), then the counters.
    fn draw_with<T: RasterTri, K: TileKey>(
        &mut self,
        (parts, fragments): Input<'_, T>,
        (vp, setups): (Viewport, bool),
        frame: Option<&mut Frame>,
        threads: usize,
    ) -> TiledZBufferStats {
        let grid = Grid::new(vp.width, vp.height, self.options.tile_size);
        let pool = self.pool.workers(threads);
        pool.wake();
        let hiz = self.options.hierarchical_z;
        let tris = self
            .bins
            .fill((parts, fragments), (vp, grid, hiz, setups), (pool, threads));
        let bufs = tile_bufs::<K>(&mut self.scratch, grid, self.options.depth_test);
        let jobs = Jobs {
            wide: self.wide_kernel,
            grid,
            vp,
            tris: &tris,
            chunks: &self.bins.chunks,
            fragments: &self.bins.fragments,
            fragment_runs: fragments,
            hiz,
            setups,
            cancel: self.options.cancel,
        };
        match frame {
            Some(frame) => jobs.draw_and_resolve(frame, bufs, pool),
            None => jobs.draw_tiles(bufs, pool),
        }
        self.frame_stats::<K>()
    }

    /// The frame's counters: the tiles' and the bins', and the bytes held.
    fn frame_stats<K: TileKey>(&mut self) -> TiledZBufferStats {
        let mut stats = TiledZBufferStats::default();
        let bufs = K::bufs(&mut self.scratch);
        for buf in bufs.iter() {
            stats.add(&buf.stats);
        }
        for c in &self.bins.chunks {
            stats.triangles_binned += c.binned;
            stats.bin_entries += c.entries;
            stats.large_triangles += c.large.len() as u64;
        }
        stats.scratch_bytes =
            (bufs.iter().map(TileBuf::bytes).sum::<usize>() + self.bins.bytes()) as u64;
        stats
    }

    /// Copies the image held in format `K`'s tiles into `frame`.
    pub(super) fn read_with<K: TileKey>(&mut self, grid: Grid, frame: &mut Frame) {
        let pool = self.pool.workers(self.threads());
        band::resolve(frame, K::bufs(&mut self.scratch), grid, pool);
    }
}

/// Format `K`'s tile buffers, one per tile of `grid`, reusing the memory
/// (all dropped when the tile size changed), set to the depth `test`.
fn tile_bufs<K: TileKey>(formats: &mut Scratch, grid: Grid, test: DepthTest) -> &mut [TileBuf<K>] {
    let bufs = K::bufs(formats);
    if bufs.first().is_some_and(|b| b.size() != grid.tile) {
        bufs.clear();
    }
    bufs.resize_with(grid.tiles(), || TileBuf::new(grid.tile));
    bufs.truncate(grid.tiles());
    for b in bufs.iter_mut() {
        b.set_test(test);
    }
    bufs
}
