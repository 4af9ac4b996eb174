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
//! With several threads the triangle list is cut into as many contiguous
//! chunks, each binned by one thread into its own bins; a tile walks the
//! chunks' bins in chunk order, which is again primitive order.
//!
//! A triangle whose box meets more than [`LARGE_TILES`] tiles goes to its
//! chunk's *large* list instead, visited by every tile (each rejects it
//! from its bounding box in a few instructions). That bounds the bins at
//! `LARGE_TILES` entries per triangle, so their memory is linear in the
//! triangle count whatever the image size.

use hider_scene::ScreenScene;

/// Triangles covering more tiles than this go to the shared large list.
pub(crate) const LARGE_TILES: u32 = 16;

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
    /// Per tile (row-major), indices of the chunk's small triangles meeting
    /// it, ascending.
    pub tiles: Vec<Vec<u32>>,
    /// Indices of the chunk's large triangles, ascending.
    pub large: Vec<u32>,
    /// Triangles with a non-empty box in the viewport.
    pub binned: u64,
    /// Entries appended to `tiles`.
    pub entries: u64,
}

impl ChunkBins {
    /// Bins triangles `range` of `scene` on `grid`, reusing the memory.
    pub(crate) fn fill(&mut self, scene: &ScreenScene, range: std::ops::Range<usize>, grid: Grid) {
        self.tiles.resize_with(grid.tiles(), Vec::new);
        self.tiles.truncate(grid.tiles());
        for bin in &mut self.tiles {
            bin.clear();
        }
        self.large.clear();
        self.binned = 0;
        self.entries = 0;
        let shift = grid.tile.trailing_zeros();
        let pow2 = grid.tile.is_power_of_two();
        let tile_of = |p: u32| if pow2 { p >> shift } else { p / grid.tile };
        for (i, tri) in scene.tris[range.clone()].iter().enumerate() {
            let Some((x0, y0, x1, y1)) = super::tile::pixel_bounds(tri, scene.viewport) else {
                continue;
            };
            self.binned += 1;
            let index = (range.start + i) as u32;
            let (tx0, ty0, tx1, ty1) = (tile_of(x0), tile_of(y0), tile_of(x1), tile_of(y1));
            let count = (tx1 - tx0 + 1) * (ty1 - ty0 + 1);
            if count > LARGE_TILES {
                self.large.push(index);
                continue;
            }
            self.entries += u64::from(count);
            for ty in ty0..=ty1 {
                let row = (ty * grid.cols) as usize;
                for tx in tx0..=tx1 {
                    self.tiles[row + tx as usize].push(index);
                }
            }
        }
    }

    /// Bytes held by the bins.
    pub(crate) fn bytes(&self) -> usize {
        self.tiles.iter().map(|b| b.capacity() * 4).sum::<usize>()
            + self.tiles.capacity() * std::mem::size_of::<Vec<u32>>()
            + self.large.capacity() * 4
    }
}

/// Calls `draw` with the triangles of tile `tile` in primitive order: for
/// each chunk, its tile bin merged with its large list (both ascending).
pub(crate) fn for_each_in_tile(chunks: &[ChunkBins], tile: usize, mut draw: impl FnMut(u32)) {
    for chunk in chunks {
        let small = &chunk.tiles[tile];
        let large = &chunk.large;
        if large.is_empty() {
            small.iter().for_each(|&i| draw(i));
            continue;
        }
        let (mut a, mut b) = (0, 0);
        while a < small.len() || b < large.len() {
            let take_small = b == large.len() || (a < small.len() && small[a] < large[b]);
            if take_small {
                draw(small[a]);
                a += 1;
            } else {
                draw(large[b]);
                b += 1;
            }
        }
    }
}

/// Whether any chunk has a triangle for tile `tile` (large triangles are
/// counted for every tile; the tile's own bounding-box test sorts them out).
pub(crate) fn tile_has_work(chunks: &[ChunkBins], tile: usize) -> bool {
    chunks
        .iter()
        .any(|c| !c.tiles[tile].is_empty() || !c.large.is_empty())
}
