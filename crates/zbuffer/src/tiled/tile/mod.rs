//! One screen tile: its depth and ids in a compact buffer that stays in
//! cache, 8x8 blocks with trivial accept/reject from the edge functions at
//! their corners, hierarchical depth, and the resolve into the frame.
//!
//! Block traversal is Greene's hierarchical rasterisation reduced to one
//! level (Greene, "Hierarchical Polygon Tiling with Coverage Masks",
//! SIGGRAPH 1996; McCormack and McNamara, "Tiled Polygon Traversal Using
//! Half-Plane Edge Functions", 2000): an edge function is affine, so its
//! extreme values over a block are at the block's corners, and a block is
//! outside the triangle when one edge is non-positive at all four, inside
//! when all three are positive at all four.
//!
//! Hierarchical depth is Greene, Kass and Miller's z-pyramid ("Hierarchical
//! Z-Buffer Visibility", SIGGRAPH 1993) with two levels: the maximum key of
//! each block and of the whole tile. A triangle or block whose depth lower
//! bound (see [`super::bounds`]) encodes to a key not below that maximum
//! cannot pass LESS anywhere there. A triangle meets three tests: the
//! tile's maximum, the greatest maximum of the blocks its box meets, and
//! each block's. Maxima only fall as depths are
//! written, so a stale maximum is still a valid bound: they are refreshed
//! lazily, after enough passes to be worth it.

mod blocks;
mod hiz;
mod small;

use hider_geom::Viewport;
use hider_scene::NO_ID;

use super::bounds::DepthBounds;
use super::key::DepthKey;
use super::raster_tri::RasterTri;
use super::scratch::TileKey;
use super::stats::TiledZBufferStats;
use super::wide::{Isa, WideBlock};
use crate::depth_scene::DepthFragment;
use crate::options::DepthTest;

/// Side of a block, pixels.
const BLOCK: u32 = 8;
/// Triangles whose box in the tile is at most this many pixels are drawn
/// by a plain box scan: for them block set-up costs more than it saves.
pub(crate) const SMALL_AREA: u32 = 32;
/// Passes into a block after which its maximum is recomputed.
const BLOCK_REFRESH: u32 = 16;

/// A tile's buffers, reused for every tile of a band and every frame.
#[derive(Clone, Debug)]
pub(crate) struct TileBuf<K> {
    /// Tile side (stride of `keys` and `ids`).
    size: u32,
    keys: Vec<K>,
    ids: Vec<u32>,
    /// Per block (row-major, `size / 8` per row): an upper bound of its
    /// keys, and the passes since it was last recomputed.
    block_max: Vec<K>,
    block_passes: Vec<u32>,
    /// Upper bound of every key of the tile, and passes since recomputed.
    tile_max: K,
    /// The key of a pixel nothing has written: [`DepthKey::BLANK`] or,
    /// under GL's test, [`DepthKey::FAR`] (see [`Self::set_test`]).
    clear: K,
    tile_passes: u32,
    /// Per column of the current triangle, `value + dx * (x - x0)`.
    col: Vec<f64>,
    /// The current tile: origin and size in pixels (clipped to the image).
    x0: u32,
    y0: u32,
    w: u32,
    h: u32,
    /// Whether a triangle met the tile (its buffers were cleared).
    active: bool,
    /// Counters of the band this buffer renders.
    pub(crate) stats: TiledZBufferStats,
}

impl<K: DepthKey> TileBuf<K> {
    pub(crate) fn new(size: u32) -> Self {
        let n = (size * size) as usize;
        let blocks = ((size / BLOCK) * (size / BLOCK)) as usize;
        Self {
            size,
            keys: vec![K::BLANK; n],
            ids: vec![NO_ID; n],
            block_max: vec![K::BLANK; blocks],
            block_passes: vec![0; blocks],
            tile_max: K::BLANK,
            clear: K::BLANK,
            tile_passes: 0,
            col: vec![0.0; size as usize],
            x0: 0,
            y0: 0,
            w: 0,
            h: 0,
            active: false,
            stats: TiledZBufferStats::default(),
        }
    }

    pub(crate) fn size(&self) -> u32 {
        self.size
    }

    /// Sets the depth test of the frames to come: the key a pixel is
    /// cleared to. Under [`DepthTest::ViewVolume`] it is the blank key,
    /// above every encoded depth, so the one LESS test accepts any
    /// fragment on a pixel nothing has written; under
    /// [`DepthTest::GlLess`] it is the far plane's key, as GL clears it.
    pub(crate) fn set_test(&mut self, test: DepthTest) {
        self.clear = match test {
            DepthTest::ViewVolume => K::BLANK,
            DepthTest::GlLess => K::FAR,
        };
    }

    pub(crate) fn bytes(&self) -> usize {
        self.keys.capacity() * std::mem::size_of::<K>()
            + self.ids.capacity() * 4
            + self.block_max.capacity() * std::mem::size_of::<K>()
            + self.block_passes.capacity() * 4
            + self.col.capacity() * 8
    }

    /// Index of pixel `(x, y)` (image coordinates, inside the tile) in the
    /// tile's block-linear storage: 8x8 blocks of 64 consecutive values,
    /// blocks row by row, so a block is one 256-byte run (f32) and its
    /// depth test works on contiguous memory.
    #[inline(always)]
    fn at(&self, x: u32, y: u32) -> usize {
        let (lx, ly) = (x - self.x0, y - self.y0);
        let blocks = ((ly >> 3) * (self.size >> 3) + (lx >> 3)) as usize;
        blocks * 64 + ((ly & 7) * 8 + (lx & 7)) as usize
    }

    /// Starts the tile at `(x0, y0)` of `w x h` pixels for a new frame.
    /// Nothing is cleared until a triangle meets it: until then the tile
    /// reads as background (the per-tile clear flag), so a tile no
    /// triangle reaches costs no memory traffic at all.
    pub(crate) fn start(&mut self, x0: u32, y0: u32, w: u32, h: u32) {
        (self.x0, self.y0, self.w, self.h) = (x0, y0, w, h);
        self.active = false;
        self.tile_max = self.clear;
        self.tile_passes = 0;
        self.stats = TiledZBufferStats::default();
    }

    /// Whether a triangle met the tile this frame (otherwise it is all
    /// background and its buffers hold stale values).
    pub(crate) fn is_active(&self) -> bool {
        self.active
    }

    /// The id and window depth at pixel `(x, y)` (image coordinates,
    /// inside the tile), as the frame gets them: depth 1 for background.
    pub(crate) fn get(&self, x: u32, y: u32) -> (u32, f32) {
        if self.active {
            let i = self.at(x, y);
            match self.id(i) {
                NO_ID => (NO_ID, 1.0),
                id => (id, self.keys[i].decode()),
            }
        } else {
            (NO_ID, 1.0)
        }
    }

    /// Clears the tile for its first triangle of the frame. The ids are
    /// left as they are: a pixel's key is below the clear key once anything
    /// wrote it (LESS against the clear key, and keys only fall), so the
    /// clear key means background whatever its id slot holds
    /// ([`Self::id`]). That halves the clear (the spider at 1024 activates
    /// 36 tiles a frame).
    #[inline(always)]
    fn activate(&mut self) {
        self.active = true;
        self.stats.tiles_drawn += 1;
        self.keys.fill(self.clear);
        self.block_max.fill(self.clear);
        self.block_passes.fill(0);
    }

    /// The id of the pixel at storage index `i` of an active tile:
    /// [`NO_ID`] where nothing was written (see [`Self::activate`]).
    #[inline(always)]
    fn id(&self, i: usize) -> u32 {
        if self.keys[i] == self.clear {
            NO_ID
        } else {
            self.ids[i]
        }
    }

    /// One pixel fragment of a triangle too small to rasterise, applied
    /// after the tile's triangles. Out of primitive order, so the test is
    /// LESS on `(key, prim)` (see [`DepthFragment`]): it wins over an
    /// equal key written by a later primitive, never over the background.
    #[cfg(test)]
    pub(crate) fn fragment(&mut self, f: &DepthFragment) {
        self.fragments(std::slice::from_ref(f));
    }

    /// [`Self::fragment`] for each of a run of fragments. The counters are
    /// kept in locals and added once: the stores into the key and id
    /// buffers could alias `self.stats` for all the compiler knows, so a
    /// field increment per fragment was a load and a store each (about a
    /// sixth of the tile kernel's samples on the UV sphere 500).
    #[inline(always)]
    pub(crate) fn fragments(&mut self, run: &[DepthFragment]) {
        if run.is_empty() {
            return;
        }
        if !self.active {
            self.activate();
        }
        let mut passes = 0u64;
        for f in run {
            let i = self.at(u32::from(f.x), u32::from(f.y));
            let key = K::encode(f.depth);
            let (old, id) = (self.keys[i], self.id(i));
            let wins = key < old || (key == old && f.prim < id && id != NO_ID);
            if wins {
                self.keys[i] = key;
                self.ids[i] = f.prim;
            }
            passes += u64::from(wins);
        }
        self.stats.fragments += run.len() as u64;
        self.stats.depth_passes += passes;
    }

    /// The tile's first column and width in pixels.
    pub(crate) fn columns(&self) -> (usize, usize) {
        (self.x0 as usize, self.w as usize)
    }
}

impl<K: TileKey> TileBuf<K> {
    /// Writes an active tile into the band's rows of the frame
    /// (`band_y0` is the band's first image row): the ids if `IDS`, the
    /// window depth the reference z-buffer would have written if `DEPTH`;
    /// background where nothing was drawn. Only what the caller asked for
    /// is written (a frame request of ids alone halves the traffic).
    #[inline(always)]
    pub(crate) fn resolve<I: Isa, const IDS: bool, const DEPTH: bool>(
        &self,
        isa: I,
        ids: &mut [u32],
        depth: &mut [f32],
        width: usize,
        band_y0: u32,
    ) {
        debug_assert!(self.active);
        let w = self.w as usize;
        let clear = self.clear;
        // See `activate`: the clear key is background, at depth 1
        // whichever key the test clears to.
        let id_of = |k: K, i: u32| if k == clear { NO_ID } else { i };
        let depth_of = |k: K| if k == clear { 1.0 } else { k.decode() };
        for r in 0..self.h as usize {
            let at = (self.y0 - band_y0) as usize * width + r * width + self.x0 as usize;
            // Blocks are stored one after the other (64 pixels each): a
            // tile row is a run of 8 pixels from each block of the row.
            let from = self.at(self.x0, self.y0 + r as u32);
            let (keys, src_ids) = (&self.keys[from..], &self.ids[from..]);
            let (ids, depth) = (&mut ids[at..at + w], &mut depth[at..at + w]);
            // Whole runs of eight as fixed-size arrays, which the compiler
            // turns into a few vector instructions each (a run of
            // run-time length was about six instructions a pixel).
            let runs = w / BLOCK as usize;
            for b in 0..runs {
                let (o, s) = (b * BLOCK as usize, b * 64);
                let k: &[K; 8] = keys[s..s + 8].try_into().expect("a block row");
                if let Some(avx2) = isa.avx2() {
                    let i: &[u32; 8] = src_ids[s..s + 8].try_into().expect("a block row");
                    let out = (
                        (&mut ids[o..o + 8]).try_into().expect("8 pixels"),
                        (&mut depth[o..o + 8]).try_into().expect("8 pixels"),
                    );
                    if K::wide_resolve8::<IDS, DEPTH>(avx2, k, i, clear, out) {
                        continue;
                    }
                }
                if IDS {
                    let i: &[u32; 8] = src_ids[s..s + 8].try_into().expect("a block row");
                    let out: &mut [u32; 8] = (&mut ids[o..o + 8]).try_into().expect("8 pixels");
                    for c in 0..8 {
                        out[c] = id_of(k[c], i[c]);
                    }
                }
                if DEPTH {
                    let out: &mut [f32; 8] = (&mut depth[o..o + 8]).try_into().expect("8 pixels");
                    for c in 0..8 {
                        out[c] = depth_of(k[c]);
                    }
                }
            }
            let (o, s) = (runs * BLOCK as usize, runs * 64);
            let n = w - o;
            if IDS {
                for c in 0..n {
                    ids[o + c] = id_of(keys[s + c], src_ids[s + c]);
                }
            }
            if DEPTH {
                for c in 0..n {
                    depth[o + c] = depth_of(keys[s + c]);
                }
            }
        }
    }
}

impl<K: WideBlock> TileBuf<K> {
    /// Draws one triangle into the tile; `low` is a lower bound of its
    /// computed depths (from its bin entry). With `setups`, a triangle's
    /// [`SmallSetup`](crate::depth_scene::SmallSetup) is used when it has
    /// one and its box lies in the tile.
    #[inline(always)]
    pub(crate) fn draw<T: RasterTri, I: Isa>(
        &mut self,
        isa: I,
        tri: &T,
        low: f32,
        (viewport, hiz, setups): (Viewport, bool, bool),
    ) {
        // Hierarchical depth, triangle level, before the triangle itself is
        // read: nothing it could write is nearer than what the whole tile
        // holds.
        if hiz && self.active && low > f32::NEG_INFINITY {
            self.refresh_tile_max();
            if K::encode(f64::from(low)) >= self.tile_max {
                self.stats.hiz_triangle_rejects += 1;
                return;
            }
        }
        let setup = tri.setup();
        let ready = if setups { setup.ready() } else { None };
        // Most triangle-tiles of a dense mesh: a front-end set-up whose
        // box (at most `SMALL_AREA` pixels) lies in this tile, which then
        // needs no clipping (wrapping differences: a box left of or above
        // the tile wraps to a large value).
        if let Some((bx0, by0, bx1, by1)) = ready {
            let (x0, y0, w, h) = (self.x0, self.y0, self.w, self.h);
            if bx0.wrapping_sub(x0) < w
                && bx1.wrapping_sub(x0) < w
                && by0.wrapping_sub(y0) < h
                && by1.wrapping_sub(y0) < h
            {
                if !self.active {
                    self.activate();
                }
                self.stats.triangle_tiles += 1;
                self.small(isa, tri, (bx0, by0, bx1, by1), Some(setup.e));
                return;
            }
        }
        let Some((bx0, by0, bx1, by1)) = ready.or_else(|| viewport.pixel_bounds(tri.v())) else {
            return;
        };
        let (x0, y0) = (bx0.max(self.x0), by0.max(self.y0));
        let (x1, y1) = (bx1.min(self.x0 + self.w - 1), by1.min(self.y0 + self.h - 1));
        if x0 > x1 || y0 > y1 {
            return;
        }
        // Hierarchical depth between the tile's level and the blocks': the
        // maxima of the blocks the triangle's box meets here. A triangle in
        // front of the tile's farthest key can still be behind everything
        // in its own corner of the tile; rejecting it here saves its set-up
        // and its walk over blocks that would each be rejected in turn.
        // (On the soup of 100k triangles, 43 % of the triangle-tiles that
        // pass the tile's test; the stale maxima of an inactive tile are
        // not read.)
        if hiz && self.active && low > f32::NEG_INFINITY {
            let max = self.box_max((x0, y0, x1, y1));
            if max < self.clear && K::encode(f64::from(low)) >= max {
                self.stats.hiz_box_rejects += 1;
                return;
            }
        }
        if !self.active {
            self.activate();
        }
        self.stats.triangle_tiles += 1;
        let small = (x1 - x0 + 1) * (y1 - y0 + 1) <= SMALL_AREA;
        if small {
            // Here the box is cut by the tile (a whole one took the path
            // above): the front end's set-up does not hold.
            self.small(isa, tri, (x0, y0, x1, y1), None);
            return;
        }
        // Block bounds cost a few plane evaluations: only for triangles
        // that have blocks.
        let bounds = if hiz {
            DepthBounds::new(tri.v(), tri.depth())
        } else {
            None
        };
        self.large(isa, tri, (x0, y0, x1, y1), bounds.as_ref());
    }
}
