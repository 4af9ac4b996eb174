//! Drawing the tiles of a frame: a job per band of tiles (a row of tiles,
//! a contiguous run of frame rows, so bands can be handed to threads
//! safely) or per single tile, each with the widest vector instructions
//! the CPU has, and the resolve of a band into the frame.

use hider_geom::Viewport;
use hider_scene::frame::{BACKGROUND, BACKGROUND_DEPTH};
use hider_scene::pool::Workers;
use hider_scene::{Frame, FrameBuffers, NO_ID};

use super::bins::{self, ChunkBins, FragmentBins, Grid};
use super::raster_tri::RasterTri;
use super::scratch::TileKey;
use super::tile::TileBuf;
#[cfg(target_arch = "x86_64")]
use super::wide::Avx2;
use super::wide::{Isa, Portable};
use crate::depth_scene::DepthFragment;
#[cfg(target_arch = "x86_64")]
use crate::simd::{self, Kernel};

/// One band of the frame as the resolve receives it: ((ids, depth),
/// colour) rows of one row of tiles.
type FrameBand<'a> = ((&'a mut [u32], &'a mut [f32]), &'a mut [[u8; 4]]);

/// Everything drawing a run of tiles (a band, or one tile) needs.
pub(super) struct Jobs<'a, T> {
    /// Whether the AVX2 kernel may be used.
    #[cfg_attr(
        not(target_arch = "x86_64"),
        expect(dead_code, reason = "only the x86_64 build has an AVX2 kernel")
    )]
    pub(super) wide: bool,
    pub(super) grid: Grid,
    pub(super) vp: Viewport,
    pub(super) tris: &'a [&'a [T]],
    pub(super) chunks: &'a [ChunkBins],
    /// Each run's fragments by tile, applied after the tile's triangles.
    pub(super) fragments: &'a [FragmentBins],
    /// The runs of fragments those bins index, in the same order.
    pub(super) fragment_runs: &'a [&'a [DepthFragment]],
    pub(super) hiz: bool,
    /// Whether the triangles' small-box set-ups hold (see
    /// [`DepthScene::setups_valid`](crate::DepthScene)).
    pub(super) setups: bool,
    /// Polled per tile: a stopped render draws no more triangles.
    pub(super) cancel: hider_scene::Cancel,
}

/// Where a band drawn by [`Jobs::dispatch`] is then resolved: its rows of
/// the frame, the frame's width, the band's first row and the buffers
/// asked for.
struct Resolve<'a> {
    out: FrameBand<'a>,
    width: usize,
    band_y0: u32,
    wanted: FrameBuffers,
}

/// [`Jobs::draw`] of a run of tiles as a [`Kernel`], for
/// [`simd::with_avx2`].
#[cfg(target_arch = "x86_64")]
struct DrawBand<'a, 'b, T, K> {
    jobs: &'a Jobs<'b, T>,
    first: usize,
    band: &'a mut [TileBuf<K>],
    resolve: Option<Resolve<'a>>,
}

#[cfg(target_arch = "x86_64")]
impl<T: RasterTri, K: TileKey> Kernel for DrawBand<'_, '_, T, K> {
    type Output = ();

    #[inline(always)]
    fn run<I: Isa>(self, isa: I) {
        self.jobs.draw(self.first, self.band, isa);
        if let Some(r) = self.resolve {
            resolve_band(isa, self.band, r.out, r.width, r.band_y0, r.wanted);
        }
    }
}

impl<T: RasterTri> Jobs<'_, T> {
    /// Draws every tile and resolves each band into `frame` while it is in
    /// cache, band by band on `pool`'s threads.
    pub(super) fn draw_and_resolve<K: TileKey>(
        &self,
        frame: &mut Frame,
        bufs: &mut [TileBuf<K>],
        pool: Workers<'_>,
    ) {
        let (width, cols, tile) = (
            self.vp.width as usize,
            self.grid.cols as usize,
            self.grid.tile,
        );
        let wanted = frame.buffers();
        for_each_band(frame, bufs, self.grid, pool, |b, out, band| {
            let band_y0 = b as u32 * tile;
            let resolve = Resolve {
                out,
                width,
                band_y0,
                wanted,
            };
            self.dispatch(b * cols, band, Some(resolve));
        });
    }

    /// Draws every tile and stops (nothing to resolve): on a pool, threads
    /// take single tiles, which balances a small object in the middle of
    /// the image far better than bands do.
    pub(super) fn draw_tiles<K: TileKey>(&self, bufs: &mut [TileBuf<K>], pool: Workers<'_>) {
        if !pool.is_parallel() {
            let cols = self.grid.cols as usize;
            for (b, band) in bufs.chunks_mut(cols).enumerate() {
                self.dispatch(b * cols, band, None);
            }
            return;
        }
        use rayon::prelude::*;
        // Tiles nothing reaches are only flagged background, here; the
        // threads share the others, one task each (the spider at 1024
        // reaches 36 of 256 tiles: fewer tasks to split and steal).
        let mut busy = Vec::new();
        for (t, tile) in bufs.iter_mut().enumerate() {
            if bins::tile_has_work(self.chunks, self.fragments, t) {
                busy.push((bins::tile_load(self.chunks, self.fragments, t), t, tile));
            } else {
                self.dispatch(t, std::slice::from_mut(tile), None);
            }
        }
        // Heaviest first: the last tasks, which decide when the threads
        // finish, are then the small ones.
        busy.sort_unstable_by_key(|&(load, t, _)| (std::cmp::Reverse(load), t));
        pool.install(|| {
            busy.par_iter_mut()
                .with_max_len(1)
                .for_each(|(_, t, tile)| self.dispatch(*t, std::slice::from_mut(*tile), None));
        });
    }

    /// Draws the run of tiles `band`, which starts at tile `first`
    /// (row-major), with the widest vector instructions the CPU has.
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
    fn dispatch<K: TileKey>(
        &self,
        first: usize,
        band: &mut [TileBuf<K>],
        resolve: Option<Resolve<'_>>,
    ) {
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = Avx2::detect().filter(|_| self.wide) {
            let jobs = self;
            simd::with_avx2(
                DrawBand {
                    jobs,
                    first,
                    band,
                    resolve,
                },
                avx2,
            );
            return;
        }
        self.draw(first, band, Portable);
        if let Some(r) = resolve {
            resolve_band(Portable, band, r.out, r.width, r.band_y0, r.wanted);
        }
    }

    /// Draws the run of tiles `band` (tiles `first..`, row-major) from
    /// their bins.
    #[inline(always)]
    fn draw<K: TileKey, I: Isa>(&self, first: usize, band: &mut [TileBuf<K>], isa: I) {
        let (grid, vp) = (self.grid, self.vp);
        for (i, buf) in band.iter_mut().enumerate() {
            let t = first + i;
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
            if bins::tile_has_work(self.chunks, self.fragments, t) && self.cancel.check().is_ok() {
                let mut draw = Drawer {
                    isa,
                    buf: &mut *buf,
                    vp,
                    hiz: self.hiz,
                    setups: self.setups,
                };
                bins::for_each_in_tile(self.tris, self.chunks, t, &mut draw);
                for (bins, run) in self.fragments.iter().zip(self.fragment_runs) {
                    for stretch in bins.tile(run, t) {
                        buf.fragments(stretch);
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
    setups: bool,
}

impl<T: RasterTri, K: TileKey, I: Isa> bins::DrawTri<T> for Drawer<'_, K, I> {
    #[inline(always)]
    fn draw(&mut self, tri: &T, low: f32) {
        self.buf
            .draw(self.isa, tri, low, (self.vp, self.hiz, self.setups));
    }
}

/// Copies the tiles `bufs` into `frame`, band by band on `pool`'s threads:
/// the read-back.
pub(super) fn resolve<K: TileKey>(
    frame: &mut Frame,
    bufs: &mut [TileBuf<K>],
    grid: Grid,
    pool: Workers<'_>,
) {
    let width = frame.width() as usize;
    let wanted = frame.buffers();
    for_each_band(frame, bufs, grid, pool, |b, out, band| {
        let band_y0 = b as u32 * grid.tile;
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = Avx2::detect() {
            let r = Resolve {
                out,
                width,
                band_y0,
                wanted,
            };
            simd::with_avx2(ResolveBand { band, r }, avx2);
            return;
        }
        resolve_band(Portable, band, out, width, band_y0, wanted);
    });
}

/// [`resolve_band`] as a [`Kernel`], for [`simd::with_avx2`].
#[cfg(target_arch = "x86_64")]
struct ResolveBand<'a, K> {
    band: &'a [TileBuf<K>],
    r: Resolve<'a>,
}

#[cfg(target_arch = "x86_64")]
impl<K: TileKey> Kernel for ResolveBand<'_, K> {
    type Output = ();

    #[inline(always)]
    fn run<I: Isa>(self, isa: I) {
        let r = self.r;
        resolve_band(isa, self.band, r.out, r.width, r.band_y0, r.wanted);
    }
}

/// Calls `work` with each band's index, its rows of the frame and its
/// tiles, in parallel on `pool` or in order; clears the frame's coverage
/// (a z-buffer writes none).
fn for_each_band<K: TileKey>(
    frame: &mut Frame,
    bufs: &mut [TileBuf<K>],
    grid: Grid,
    pool: Workers<'_>,
    work: impl Fn(usize, FrameBand<'_>, &mut [TileBuf<K>]) + Sync,
) {
    frame.coverage.clear();
    let band_len = frame.width() as usize * grid.tile as usize;
    let cols = grid.cols as usize;
    let work = |(b, (out, band)): (usize, (FrameBand<'_>, &mut [TileBuf<K>]))| work(b, out, band);
    /// The bands, numbered: each band's rows of the frame's ids, depths
    /// and colours with its row of tiles, split by `$chunks` (the slices'
    /// `chunks_mut`, or rayon's `par_chunks_mut` for the pool): one
    /// pairing of rows and tiles for both ways of running.
    macro_rules! bands {
        ($chunks:ident) => {
            frame
                .ids
                .$chunks(band_len)
                .zip(frame.depth.$chunks(band_len))
                .zip(frame.color.$chunks(band_len))
                .zip(bufs.$chunks(cols))
                .enumerate()
        };
    }
    match pool {
        Workers::Here => bands!(chunks_mut).for_each(work),
        pool => {
            use rayon::prelude::*;
            pool.install(|| bands!(par_chunks_mut).for_each(work));
        }
    }
}

/// Writes a band's tiles into the frame's rows of that band: only the
/// buffers the frame asks for ([`Frame::buffers`]); the tiles no triangle
/// met, and the colour (a z-buffer resolves none), as background in runs
/// as long as the frame allows. Inlined into the drawing kernel's copies
/// (the AVX2 one resolves 8 lanes at a time).
#[inline(always)]
fn resolve_band<K: TileKey, I: Isa>(
    isa: I,
    band: &[TileBuf<K>],
    ((ids, depth), color): FrameBand<'_>,
    width: usize,
    band_y0: u32,
    wanted: FrameBuffers,
) {
    for buf in band.iter().filter(|b| b.is_active()) {
        match (wanted.ids, wanted.depth) {
            (true, true) => buf.resolve::<I, true, true>(isa, ids, depth, width, band_y0),
            (true, false) => buf.resolve::<I, true, false>(isa, ids, depth, width, band_y0),
            (false, true) => buf.resolve::<I, false, true>(isa, ids, depth, width, band_y0),
            (false, false) => {}
        }
    }
    // Runs of untouched tiles, in columns; a band no triangle met is one
    // contiguous run of rows.
    let mut runs: Vec<(usize, usize)> = Vec::new();
    for buf in band.iter().filter(|b| !b.is_active()) {
        let (x0, w) = buf.columns();
        match runs.last_mut() {
            Some((_, end)) if *end == x0 => *end = x0 + w,
            _ => runs.push((x0, x0 + w)),
        }
    }
    let clear = |ids: &mut [u32], depth: &mut [f32]| {
        if wanted.ids {
            ids.fill(NO_ID);
        }
        if wanted.depth {
            depth.fill(BACKGROUND_DEPTH);
        }
    };
    if runs == [(0, width)] {
        clear(ids, depth);
    } else if !runs.is_empty() && (wanted.ids || wanted.depth) {
        for row in 0..ids.len() / width {
            for &(x0, x1) in &runs {
                let at = row * width;
                clear(&mut ids[at + x0..at + x1], &mut depth[at + x0..at + x1]);
            }
        }
    }
    // Plain stores, not streaming ones: `movntdq` for these fills was
    // measured slower on this machine at 1024 (the frame stays in the
    // last-level cache, where the caller reads it next) and at 2048 alike
    // (docs/zbuffer.md, "Frame delivery").
    if wanted.color {
        color.fill(BACKGROUND);
    }
}
