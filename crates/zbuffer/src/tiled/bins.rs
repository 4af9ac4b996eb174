//! Binning: which triangles each screen tile must draw, in drawing order.
//!
//! Sort-middle rendering (Molnar et al., "A Sorting Classification of
//! Parallel Rendering", 1994; the tiler of llvmpipe and of every mobile GPU):
//! one pass over the triangles appends each one's index to the bin of every
//! tile its bounding box meets, then tiles are drawn independently. Bins
//! are appended in primitive order, so a tile sees its triangles in the
//! same order as the reference z-buffer and LESS keeps the same one of two
//! equal depths.
//!
//! The triangle list arrives as contiguous chunks (the runs of a
//! [`DepthScene`](crate::DepthScene), or a screen scene's list cut into one
//! chunk per thread), each binned by one thread into its own bins; a tile
//! walks the chunks' bins in chunk order, which is again primitive order.
//!
//! A triangle whose box meets more than [`LARGE_TILES`] tiles goes to its
//! chunk's *large* list instead, visited by every tile (each rejects it
//! from its bounding box in a few instructions). That bounds the bins at
//! `LARGE_TILES` entries per triangle, so their memory is linear in the
//! triangle count whatever the image size.

use hider_geom::Viewport;
use hider_geom::isa::prefetch;
use hider_scene::pool::Workers;

use super::bounds::DepthBounds;
use super::raster_tri::RasterTri;
use super::tile::SMALL_AREA;
use crate::depth_scene::DepthFragment;

/// Triangles per binning chunk below which binning stays on one thread.
const MIN_CHUNK: usize = 4096;

/// The triangles to draw, in primitive order: contiguous runs of
/// triangles, and per run the pixel fragments of the lean front end.
pub(crate) type Input<'a, T> = (&'a [&'a [T]], &'a [&'a [DepthFragment]]);

/// The bins of a frame: one set per chunk of triangles, and one per run
/// of fragments.
#[derive(Clone, Debug, Default)]
pub(crate) struct Bins {
    /// Per chunk of triangles, in primitive order.
    pub chunks: Vec<ChunkBins>,
    /// Per run of fragments, in primitive order.
    pub fragments: Vec<FragmentBins>,
}

impl Bins {
    /// Bins the input, one chunk per contiguous run of triangles; runs are
    /// cut further so that every thread has one. Bins hold depth bounds
    /// when `hiz`. Returns the chunks, in primitive order.
    pub(crate) fn fill<'a, T: RasterTri>(
        &mut self,
        (parts, fragments): Input<'a, T>,
        (vp, grid, hiz, setups): (Viewport, Grid, bool, bool),
        (pool, threads): (Workers<'_>, usize),
    ) -> Vec<&'a [T]> {
        let total: usize = parts.iter().map(|p| p.len()).sum();
        let wanted = if pool.is_parallel() {
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
        let bin =
            |(bins, chunk): (&mut ChunkBins, &&[T])| bins.fill(chunk, vp, grid, (hiz, setups));
        self.fragments
            .resize_with(fragments.len(), FragmentBins::default);
        self.fragments.truncate(fragments.len());
        let bin_fragments = |(bins, run): (&mut FragmentBins, &&[DepthFragment])| {
            bins.fill(run, vp, grid);
        };
        match pool {
            pool if pool.is_parallel() && (tris.len() > 1 || fragments.len() > 1) => {
                use rayon::prelude::*;
                pool.install(|| {
                    rayon::join(
                        || self.chunks.par_iter_mut().zip(&tris).for_each(bin),
                        || {
                            self.fragments
                                .par_iter_mut()
                                .zip(fragments)
                                .for_each(bin_fragments);
                        },
                    )
                });
            }
            _ => {
                self.chunks.iter_mut().zip(&tris).for_each(bin);
                self.fragments
                    .iter_mut()
                    .zip(fragments)
                    .for_each(bin_fragments);
            }
        }
        tris
    }

    /// Bytes held by the bins.
    pub(crate) fn bytes(&self) -> usize {
        self.chunks.iter().map(ChunkBins::bytes).sum::<usize>()
            + self
                .fragments
                .iter()
                .map(FragmentBins::bytes)
                .sum::<usize>()
    }
}

/// A bin entry: the triangle's index in its chunk and a lower bound of
/// its computed depths, rounded down to `f32` (see
/// [`DepthBounds::low_f32`]). With the bound in the entry a tile rejects a
/// triangle hidden behind everything it holds without reading the
/// triangle: on an overdrawn soup that read is a cache miss, and most
/// triangle-tiles end there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct BinEntry {
    pub index: u32,
    pub low: f32,
}

/// Triangles covering more tiles than this go to the shared large list.
pub(crate) const LARGE_TILES: u32 = 16;

/// The most tiles a box of at most [`SMALL_AREA`] pixels meets when tiles
/// are 8 pixels (the smallest): a box `w` pixels wide spans at most
/// `(w + 6) / 8 + 1` columns of tiles, and over `w * h <= 32` that peaks at
/// 16 x 2 or 10 x 3 pixels, 3 x 2 tiles. Such a box is never a large
/// triangle.
const SETUP_TILES: u32 = 6;
const _: () = assert!(SMALL_AREA <= 32 && SETUP_TILES <= LARGE_TILES);

/// The tile grid over the viewport.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Grid {
    /// Tile side in pixels.
    pub tile: u32,
    /// Tiles across.
    pub cols: u32,
    /// Tiles down.
    pub rows: u32,
}

impl Grid {
    pub(crate) fn new(width: u32, height: u32, tile: u32) -> Self {
        Self {
            tile,
            cols: width.div_ceil(tile),
            rows: height.div_ceil(tile),
        }
    }

    pub(crate) fn tiles(&self) -> usize {
        self.cols as usize * self.rows as usize
    }
}

/// The bins of one contiguous chunk of triangles.
#[derive(Clone, Debug, Default)]
pub(crate) struct ChunkBins {
    /// Per tile (row-major), the chunk's small triangles meeting it, by
    /// ascending index.
    pub tiles: Vec<Vec<BinEntry>>,
    /// The chunk's large triangles, by ascending index.
    pub large: Vec<BinEntry>,
    /// Triangles with a non-empty box in the viewport.
    pub binned: u64,
    /// Entries appended to `tiles`.
    pub entries: u64,
}

impl ChunkBins {
    /// Bins the triangles of `chunk` on `grid`, reusing the memory; bins
    /// hold indices into `chunk`, and depth bounds when `hiz` (minus
    /// infinity otherwise). With `setups`, the boxes of the triangles'
    /// small-box set-ups are used where they have one.
    pub(crate) fn fill<T: RasterTri>(
        &mut self,
        chunk: &[T],
        viewport: Viewport,
        grid: Grid,
        (hiz, setups): (bool, bool),
    ) {
        self.tiles.resize_with(grid.tiles(), Vec::new);
        self.tiles.truncate(grid.tiles());
        for bin in &mut self.tiles {
            bin.clear();
        }
        self.large.clear();
        // One loop per way to find a tile (a shift for the default
        // sizes): the choice out of the per-triangle loop.
        if grid.tile.is_power_of_two() {
            let shift = grid.tile.trailing_zeros();
            self.bin(chunk, (viewport, grid.cols), (hiz, setups), |p| p >> shift);
        } else {
            self.bin(chunk, (viewport, grid.cols), (hiz, setups), |p| {
                p / grid.tile
            });
        }
    }

    /// The loop of [`Self::fill`], `tile_of` giving a pixel coordinate's
    /// tile coordinate.
    #[inline(always)]
    fn bin<T: RasterTri>(
        &mut self,
        chunk: &[T],
        (viewport, cols): (Viewport, u32),
        (hiz, setups): (bool, bool),
        tile_of: impl Fn(u32) -> u32,
    ) {
        // Counters in locals: the pushes below store through pointers the
        // compiler cannot tell from `self`'s fields, so a field increment
        // per triangle was a load and a store.
        let (mut binned, mut entries) = (0u64, 0u64);
        for (i, tri) in chunk.iter().enumerate() {
            let ready = if setups { tri.setup().ready() } else { None };
            // A front-end set-up's box holds at most `SMALL_AREA` pixels,
            // so it gets no depth bound (below) and meets at most six tiles
            // even of the smallest size (see `SETUP_TILES`): the most
            // common triangle of a dense mesh skips both tests.
            let small_setup = ready.is_some();
            let Some((x0, y0, x1, y1)) = ready.or_else(|| viewport.pixel_bounds(tri.v())) else {
                continue;
            };
            // Triangles that cover no pixel centre write nothing; drop them
            // before they cost a bin entry and a set-up per tile.
            if T::MAY_MISS_CENTRES && viewport.misses_every_centre(tri.v(), 1) {
                continue;
            }
            binned += 1;
            // A bound costs about 80 instructions; a triangle of a few
            // pixels costs little more to draw than to reject, so only
            // larger ones get one (the others can never be rejected unread).
            let low = if hiz && !small_setup && (x1 - x0 + 1) * (y1 - y0 + 1) > SMALL_AREA {
                DepthBounds::low_f32(tri.v(), tri.depth())
            } else {
                f32::NEG_INFINITY
            };
            let entry = BinEntry {
                index: i as u32,
                low,
            };
            let (tx0, ty0, tx1, ty1) = (tile_of(x0), tile_of(y0), tile_of(x1), tile_of(y1));
            // Most triangles of a dense mesh meet one tile (56k entries
            // for 52k triangles on the sphere 200 at 1024): no loops.
            if (tx0, ty0) == (tx1, ty1) {
                entries += 1;
                self.tiles[(ty0 * cols + tx0) as usize].push(entry);
                continue;
            }
            let count = (tx1 - tx0 + 1) * (ty1 - ty0 + 1);
            if !small_setup && count > LARGE_TILES {
                self.large.push(entry);
                continue;
            }
            entries += u64::from(count);
            for ty in ty0..ty1 + 1 {
                let row = (ty * cols) as usize;
                for tx in tx0..tx1 + 1 {
                    self.tiles[row + tx as usize].push(entry);
                }
            }
        }
        self.binned = binned;
        self.entries = entries;
    }

    /// Bytes held by the bins.
    pub(crate) fn bytes(&self) -> usize {
        let entry = std::mem::size_of::<BinEntry>();
        self.tiles
            .iter()
            .map(|b| b.capacity() * entry)
            .sum::<usize>()
            + self.tiles.capacity() * std::mem::size_of::<Vec<BinEntry>>()
            + self.large.capacity() * entry
    }
}

/// The pixel fragments of one run of a depth scene, by tile: per tile,
/// the ranges of the run whose fragments lie in it.
///
/// The front end emits fragments in primitive order, and a mesh's
/// consecutive triangles are neighbours on screen, so fragments come in
/// long stretches within one tile (a UV sphere's rings cross a tile in
/// dozens of them). A tile then reads its stretches of the run in place,
/// in order, and binning costs a comparison per fragment and a range per
/// stretch, where copying each fragment into its tile's list cost about
/// 42 instructions a fragment (the UV sphere 500 at 1024, 231k
/// fragments). A scattered run (a soup) costs one range per fragment, 8
/// bytes against the 16 of a copy.
#[derive(Clone, Debug, Default)]
pub(crate) struct FragmentBins {
    /// Per tile (row-major), the ranges `[start, end)` of the run's
    /// fragments in it, in primitive order.
    pub tiles: Vec<Vec<[u32; 2]>>,
}

impl FragmentBins {
    /// Bins `fragments` on `grid`, reusing the memory. Fragments outside
    /// the viewport (only if a caller shrank a depth scene's viewport by
    /// hand) are dropped.
    pub(crate) fn fill(&mut self, fragments: &[DepthFragment], viewport: Viewport, grid: Grid) {
        self.tiles.resize_with(grid.tiles(), Vec::new);
        self.tiles.truncate(grid.tiles());
        for bin in &mut self.tiles {
            bin.clear();
        }
        // One loop per way to find a tile (a shift for the default
        // sizes): the choice out of the per-fragment loop.
        if grid.tile.is_power_of_two() {
            let shift = grid.tile.trailing_zeros();
            self.stretches(fragments, viewport, grid.cols, |p| p >> shift);
        } else {
            self.stretches(fragments, viewport, grid.cols, |p| p / grid.tile);
        }
    }

    /// Appends the stretches of `fragments` to the tiles' lists, `tile_of`
    /// giving a pixel coordinate's tile coordinate.
    #[inline(always)]
    fn stretches(
        &mut self,
        fragments: &[DepthFragment],
        viewport: Viewport,
        cols: u32,
        tile_of: impl Fn(u32) -> u32,
    ) {
        // The open stretch: its tile (`usize::MAX` for none) and start.
        // Indices as u32, as the triangles' bin entries (a run of 2^32
        // fragments would be 64 GB).
        let (mut tile, mut start) = (usize::MAX, 0u32);
        let len = fragments.len() as u32;
        for (i, f) in (0..len).zip(fragments) {
            let (x, y) = (u32::from(f.x), u32::from(f.y));
            let inside = (x < viewport.width) & (y < viewport.height);
            let t = if inside {
                (tile_of(y) * cols + tile_of(x)) as usize
            } else {
                usize::MAX
            };
            if t != tile {
                if tile != usize::MAX {
                    self.tiles[tile].push([start, i]);
                }
                (tile, start) = (t, i);
            }
        }
        if tile != usize::MAX {
            self.tiles[tile].push([start, len]);
        }
    }

    /// The fragments of `run` (the run binned) in tile `tile`, stretch by
    /// stretch, in primitive order.
    #[inline]
    pub(crate) fn tile<'a>(
        &'a self,
        run: &'a [DepthFragment],
        tile: usize,
    ) -> impl Iterator<Item = &'a [DepthFragment]> + 'a {
        self.tiles[tile]
            .iter()
            .map(move |&[a, b]| &run[a as usize..b as usize])
    }

    /// Bytes held by the bins.
    pub(crate) fn bytes(&self) -> usize {
        self.tiles
            .iter()
            .map(|b| b.capacity() * std::mem::size_of::<[u32; 2]>())
            .sum::<usize>()
            + self.tiles.capacity() * std::mem::size_of::<Vec<[u32; 2]>>()
    }
}

/// How many entries ahead of the one being drawn a triangle is prefetched:
/// a tile's triangles are scattered through the triangle list, and
/// without it every one is a cache miss.
const PREFETCH_AHEAD: usize = 6;

/// What [`for_each_in_tile`] hands each triangle to. A trait with an
/// `#[inline(always)]` method rather than a closure, so that the whole
/// kernel inlines into each of its target-feature copies (a closure is
/// compiled on its own, with baseline features).
pub(crate) trait DrawTri<T> {
    /// Draws `tri`, whose depths are at least `low`.
    fn draw(&mut self, tri: &T, low: f32);
}

/// Calls `draw` with the triangles of tile `tile` in primitive order, each
/// with its entry's depth bound: for each chunk (`tris[c]` binned into
/// `chunks[c]`), its tile bin merged with its large list (both ascending).
#[inline(always)]
pub(crate) fn for_each_in_tile<T, D: DrawTri<T>>(
    tris: &[&[T]],
    chunks: &[ChunkBins],
    tile: usize,
    draw: &mut D,
) {
    for (chunk, tris) in chunks.iter().zip(tris) {
        let small = &chunk.tiles[tile];
        let large = &chunk.large;
        if large.is_empty() {
            for (i, e) in small.iter().enumerate() {
                if let Some(ahead) = small.get(i + PREFETCH_AHEAD) {
                    prefetch(&tris[ahead.index as usize]);
                }
                draw.draw(&tris[e.index as usize], e.low);
            }
            continue;
        }
        let (mut a, mut b) = (0, 0);
        while a < small.len() || b < large.len() {
            let take_small =
                b == large.len() || (a < small.len() && small[a].index < large[b].index);
            let e = if take_small {
                a += 1;
                small[a - 1]
            } else {
                b += 1;
                large[b - 1]
            };
            draw.draw(&tris[e.index as usize], e.low);
        }
    }
}

/// A rough cost of tile `tile`, for ordering the tiles threads take: its
/// bin entries, and its fragments at an eighth each.
#[inline]
pub(crate) fn tile_load(chunks: &[ChunkBins], fragments: &[FragmentBins], tile: usize) -> usize {
    chunks.iter().map(|c| c.tiles[tile].len()).sum::<usize>()
        + fragments
            .iter()
            .flat_map(|f| &f.tiles[tile])
            .map(|&[a, b]| (b - a) as usize)
            .sum::<usize>()
            / 8
}

/// Whether any chunk has a triangle for tile `tile` (large triangles are
/// counted for every tile; the tile's own bounding-box test sorts them
/// out), or any run a fragment.
#[inline]
pub(crate) fn tile_has_work(chunks: &[ChunkBins], fragments: &[FragmentBins], tile: usize) -> bool {
    chunks
        .iter()
        .any(|c| !c.tiles[tile].is_empty() || !c.large.is_empty())
        || fragments.iter().any(|f| !f.tiles[tile].is_empty())
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::{FragmentBins, Grid};
    use crate::depth_scene::DepthFragment;
    use hider_geom::Viewport;

    proptest! {
        /// A tile's stretches hold exactly the run's fragments in that
        /// tile, in order, whether the run walks the screen coherently or
        /// jumps, some fragments outside the viewport, on tiles of every
        /// kind (a power of two or not).
        #[test]
        fn stretches_are_the_fragments_of_each_tile_in_order(
            steps in prop::collection::vec((0u16..3, 0u16..3, 0u8..8), 0..400),
            tile in prop::sample::select(vec![8u32, 24, 64]),
            size in (1u32..200, 1u32..200),
        ) {
            let viewport = Viewport::new(size.0, size.1);
            let grid = Grid::new(size.0, size.1, tile);
            // Mostly small steps (a mesh's neighbours), now and then a
            // jump anywhere, some past the viewport's right or lower edge.
            let (mut x, mut y) = (0u16, 0u16);
            let run: Vec<DepthFragment> = steps
                .iter()
                .enumerate()
                .map(|(i, &(dx, dy, jump))| {
                    if jump == 0 {
                        (x, y) = ((i * 37 % 230) as u16, (i * 53 % 230) as u16);
                    } else {
                        (x, y) = ((x + dx) % 230, (y + dy) % 230);
                    }
                    DepthFragment { depth: 0.5, x, y, prim: i as u32 }
                })
                .collect();
            let mut bins = FragmentBins::default();
            bins.fill(&run, viewport, grid);
            for t in 0..grid.tiles() {
                let got: Vec<DepthFragment> = bins.tile(&run, t).flatten().copied().collect();
                let want: Vec<DepthFragment> = run
                    .iter()
                    .filter(|f| {
                        let (fx, fy) = (u32::from(f.x), u32::from(f.y));
                        fx < size.0
                            && fy < size.1
                            && (fy / tile * grid.cols + fx / tile) as usize == t
                    })
                    .copied()
                    .collect();
                prop_assert_eq!(got, want, "tile {}", t);
            }
        }
    }
}
