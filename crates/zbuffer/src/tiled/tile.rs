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
//! cannot pass LESS anywhere there. Maxima only fall as depths are
//! written, so a stale maximum is still a valid bound: they are refreshed
//! lazily, after enough passes to be worth it.

use hider_geom::Viewport;
use hider_geom::fixed::{HALF_PIXEL, SUBPIXEL_SCALE};
use hider_scene::{DepthFragment, NO_ID};

use super::RasterTri;
use super::bounds::DepthBounds;
use super::key::{DepthKey, Fixed16, Fixed24, Reversed};
use super::stats::TiledZBufferStats;
use super::wide::{Block8, Isa};

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
            keys: vec![K::FAR; n],
            ids: vec![NO_ID; n],
            block_max: vec![K::FAR; blocks],
            block_passes: vec![0; blocks],
            tile_max: K::FAR,
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
        self.tile_max = K::FAR;
        self.tile_passes = 0;
        self.stats = TiledZBufferStats::default();
    }

    /// Whether a triangle met the tile this frame (otherwise it is all
    /// background and its buffers hold stale values).
    pub(crate) fn is_active(&self) -> bool {
        self.active
    }

    /// The id and stored depth key at pixel `(x, y)` (image coordinates,
    /// inside the tile).
    pub(crate) fn get(&self, x: u32, y: u32) -> (u32, K) {
        if self.active {
            let i = self.at(x, y);
            (self.id(i), self.keys[i])
        } else {
            (NO_ID, K::FAR)
        }
    }

    /// Clears the tile for its first triangle of the frame. The ids are
    /// left as they are: a pixel's key is below the far key once anything
    /// wrote it (LESS against the far key, and keys only fall), so a far
    /// key means background whatever its id slot holds ([`Self::id`]). That
    /// halves the clear (the spider at 1024 activates 36 tiles a frame).
    #[inline(always)]
    fn activate(&mut self) {
        self.active = true;
        self.stats.tiles_drawn += 1;
        self.keys.fill(K::FAR);
        self.block_max.fill(K::FAR);
        self.block_passes.fill(0);
    }

    /// The id of the pixel at storage index `i` of an active tile:
    /// [`NO_ID`] where nothing was written (see [`Self::activate`]).
    #[inline(always)]
    fn id(&self, i: usize) -> u32 {
        if self.keys[i] == K::FAR {
            NO_ID
        } else {
            self.ids[i]
        }
    }

    /// Draws one triangle into the tile; `low` is a lower bound of its
    /// computed depths (from its bin entry).
    #[inline(always)]
    pub(crate) fn draw<T: RasterTri, I: Isa>(
        &mut self,
        isa: I,
        tri: &T,
        low: f32,
        viewport: Viewport,
        hiz: bool,
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
        let Some((bx0, by0, bx1, by1)) = viewport.pixel_bounds(tri.v()) else {
            return;
        };
        let (x0, y0) = (bx0.max(self.x0), by0.max(self.y0));
        let (x1, y1) = (bx1.min(self.x0 + self.w - 1), by1.min(self.y0 + self.h - 1));
        if x0 > x1 || y0 > y1 {
            return;
        }
        if !self.active {
            self.activate();
        }
        self.stats.triangle_tiles += 1;
        let small = (x1 - x0 + 1) * (y1 - y0 + 1) <= SMALL_AREA;
        // Block bounds cost a few plane evaluations: only for triangles
        // that have blocks.
        let bounds = if hiz && !small {
            DepthBounds::new(tri.v(), tri.depth())
        } else {
            None
        };
        if small {
            self.small(tri, x0, y0, x1, y1);
            return;
        }
        // Large: walk the tile's aligned 8x8 blocks the box meets.
        let ox = self.x0 + (x0 - self.x0) / BLOCK * BLOCK;
        let oy = self.y0 + (y0 - self.y0) / BLOCK * BLOCK;
        let span_end = (self.x0 + (x1 - self.x0) / BLOCK * BLOCK + BLOCK).min(self.x0 + self.w);
        // Column terms of the depth plane: PlaneEq::eval computes
        // `value + dx * (x - x0) + dy * (y - y0)` left to right, so adding
        // the row term to this column term gives the same f64, bit for bit.
        let p = tri.depth();
        for (i, c) in self.col[..(span_end - ox) as usize].iter_mut().enumerate() {
            *c = p.value + p.dx * ((f64::from(ox + i as u32) + 0.5) - p.x0);
        }
        let edges = hider_geom::edge::triangle_edges(tri.v());
        let unit = i64::from(SUBPIXEL_SCALE);
        let px = i64::from(ox) * unit + i64::from(HALF_PIXEL);
        let py = i64::from(oy) * unit + i64::from(HALF_PIXEL);
        let (sx, sy) = (edges.map(|e| e.a * unit), edges.map(|e| e.b * unit));
        // Over a whole block, an edge function ranges from its value at
        // the first centre plus `reach_lo` to that plus `reach_hi` (its
        // extremes are at the corners, seven steps away).
        let reach_lo = [0, 1, 2].map(|k| (sx[k] * 7).min(0) + (sy[k] * 7).min(0));
        let reach_hi = [0, 1, 2].map(|k| (sx[k] * 7).max(0) + (sy[k] * 7).max(0));
        let setup = Setup {
            ox,
            oy,
            e00: edges.map(|e| e.eval(px, py)),
            sx,
            sy,
            reach_lo,
            reach_hi,
            // An edge crossing a block spans `reach_hi - reach_lo` there:
            // i32 lanes are exact when that fits.
            narrow: [0, 1, 2].map(|k| reach_hi[k] - reach_lo[k] < i64::from(i32::MAX)),
            lanes: [0, 1, 2].map(|k| std::array::from_fn(|i| (sx[k] * i as i64) as i32)),
            prim: tri.prim(),
            bbox: (x0, y0, x1, y1),
        };
        self.blocks(isa, &setup, tri, bounds.as_ref());
    }

    /// One pixel fragment of a triangle too small to rasterise, applied
    /// after the tile's triangles. Out of primitive order, so the test is
    /// LESS on `(key, prim)` (see [`DepthFragment`]): it wins over an
    /// equal key written by a later primitive, never over the background.
    #[inline(always)]
    pub(crate) fn fragment(&mut self, f: &DepthFragment) {
        if !self.active {
            self.activate();
        }
        let i = self.at(u32::from(f.x), u32::from(f.y));
        let key = K::encode(f.depth);
        let (old, id) = (self.keys[i], self.id(i));
        let wins = key < old || (key == old && f.prim < id && id != NO_ID);
        if wins {
            self.keys[i] = key;
            self.ids[i] = f.prim;
        }
        self.stats.fragments += 1;
        self.stats.depth_passes += u64::from(wins);
    }

    /// A triangle whose box in the tile is a few pixels: a plain scan of
    /// the box, scalar (too short to vectorise), evaluating the depth only
    /// where the edges pass.
    #[inline(always)]
    fn small<T: RasterTri>(&mut self, tri: &T, x0: u32, y0: u32, x1: u32, y1: u32) {
        let edges = hider_geom::edge::triangle_edges(tri.v());
        let unit = i64::from(SUBPIXEL_SCALE);
        let px = i64::from(x0) * unit + i64::from(HALF_PIXEL);
        let sx = edges.map(|e| e.a * unit);
        let p = tri.depth();
        let (mut inside, mut passes) = (0u32, 0u32);
        // Half-open ranges: `a..=b` loops carry an extra exhausted flag
        // (a tenth of the sphere's small-triangle instructions).
        for y in y0..y1 + 1 {
            let py = i64::from(y) * unit + i64::from(HALF_PIXEL);
            // Biased by one: inside iff all three are >= 0, i.e. the OR of
            // the three has no sign bit (exact; |E| < 2^50).
            let [mut e0, mut e1, mut e2] = edges.map(|e| e.eval(px, py) - 1);
            let ty = p.dy * ((f64::from(y) + 0.5) - p.y0);
            for x in x0..x1 + 1 {
                if (e0 | e1 | e2) >= 0 {
                    inside += 1;
                    let key = K::encode(p.value + p.dx * ((f64::from(x) + 0.5) - p.x0) + ty);
                    let i = self.at(x, y);
                    if key < self.keys[i] {
                        self.keys[i] = key;
                        self.ids[i] = tri.prim();
                        passes += 1;
                    }
                }
                e0 += sx[0];
                e1 += sx[1];
                e2 += sx[2];
            }
        }
        self.stats.pixels_tested += u64::from((x1 - x0 + 1) * (y1 - y0 + 1));
        self.stats.depth_tests += u64::from(inside);
        self.stats.depth_passes += u64::from(passes);
        if passes > 0 {
            self.note_passes_in_rect(x0, y0, x1, y1, passes);
        }
    }

    /// Visits the aligned 8x8 blocks of the tile that the triangle's box
    /// meets. The edge functions at each block's first centre are stepped
    /// from block to block (exact integer additions), and a block is
    /// rejected when one edge is at most 0 over the whole 8x8 block (its
    /// maximum, `c + reach_hi`): exactly `block`'s outside test for a full
    /// block, and a valid one for a block cut by the image's edge, which
    /// `block` then tests pixel by pixel.
    #[inline(always)]
    fn blocks<T: RasterTri, I: Isa>(
        &mut self,
        isa: I,
        s: &Setup,
        tri: &T,
        bounds: Option<&DepthBounds>,
    ) {
        let per_row = (self.size / BLOCK) as usize;
        let (_, _, x1, y1) = s.bbox;
        let (tile_x1, tile_y1) = (self.x0 + self.w - 1, self.y0 + self.h - 1);
        let step = i64::from(BLOCK);
        let (right, down) = (s.sx.map(|a| a * step), s.sy.map(|b| b * step));
        let (mut visited, mut outside) = (0u64, 0u64);
        let mut row = s.e00;
        let mut by = s.oy;
        while by <= y1 {
            let yb = (by + BLOCK - 1).min(tile_y1);
            let mut c = row;
            let mut bx = s.ox;
            while bx <= x1 {
                visited += 1;
                let out = (c[0] + s.reach_hi[0] <= 0)
                    | (c[1] + s.reach_hi[1] <= 0)
                    | (c[2] + s.reach_hi[2] <= 0);
                if out {
                    outside += 1;
                } else {
                    let xb = (bx + BLOCK - 1).min(tile_x1);
                    self.block(isa, s, tri, bounds, (bx, by, xb, yb), c, per_row);
                }
                for (c, r) in c.iter_mut().zip(right) {
                    *c += r;
                }
                bx += BLOCK;
            }
            for (r, d) in row.iter_mut().zip(down) {
                *r += d;
            }
            by += BLOCK;
        }
        self.stats.blocks_visited += visited;
        self.stats.blocks_outside += outside;
    }

    /// One block `(bx, by)..=(xb, yb)` (aligned; clipped to the image)
    /// that no edge rejects whole; `corner` holds the edge functions at
    /// its first centre.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn block<T: RasterTri, I: Isa>(
        &mut self,
        isa: I,
        s: &Setup,
        tri: &T,
        bounds: Option<&DepthBounds>,
        (bx, by, xb, yb): (u32, u32, u32, u32),
        corner: [i64; 3],
        per_row: usize,
    ) {
        let lo = [0, 1, 2].map(|k| corner[k] + s.reach_lo[k]);
        let inside = (lo[0] > 0) & (lo[1] > 0) & (lo[2] > 0);
        let block = ((by - self.y0) / BLOCK) as usize * per_row + ((bx - self.x0) / BLOCK) as usize;
        let (x0, y0, x1, y1) = s.bbox;
        if let Some(b) = bounds {
            if self.block_passes[block] >= BLOCK_REFRESH {
                self.refresh_block(block);
            }
            let max = self.block_max[block];
            if max < K::FAR
                && K::encode(b.rect_low(bx.max(x0), by.max(y0), xb.min(x1), yb.min(y1))) >= max
            {
                self.stats.hiz_block_rejects += 1;
                return;
            }
        }
        let full = xb - bx + 1 == BLOCK && yb - by + 1 == BLOCK;
        let fits = (0..3).all(|k| lo[k] > 0 || s.narrow[k]);
        let (passes, max) = if full && inside {
            self.stats.blocks_inside += 1;
            self.block8::<T, I, false>(isa, s, tri, bx, by, [0; 3], [[0; 8]; 3], [0; 3])
        } else if full && fits {
            // Biased by one so "inside" is ">= 0" (see `small`); edges the
            // whole block is inside of are replaced by the constant 0.
            let mut e = [0i32; 3];
            let mut lanes = [[0i32; 8]; 3];
            let mut down = [0i32; 3];
            for k in 0..3 {
                if lo[k] <= 0 {
                    e[k] = (corner[k] - 1) as i32;
                    lanes[k] = s.lanes[k];
                    down[k] = s.sy[k] as i32;
                }
            }
            self.block8::<T, I, true>(isa, s, tri, bx, by, e, lanes, down)
        } else {
            // At the image's edge, or edges too long for i32 lanes.
            let xy = (bx.max(x0), by.max(y0), xb.min(x1), yb.min(y1));
            (self.rows::<T, true>(s, tri, xy.0, xy.1, xy.2, xy.3), None)
        };
        self.tile_passes += passes;
        match max {
            // A whole block was just merged in registers: its exact
            // maximum came with it, so it never needs a refresh.
            Some(max) => {
                self.block_max[block] = max;
                self.block_passes[block] = 0;
            }
            None => self.block_passes[block] += passes,
        }
    }

    /// A full 8x8 block as 64 contiguous lanes: the compiler vectorises
    /// each of the three simple passes (depth keys, edge signs, LESS and
    /// select). Edge lanes are i32: `e` at the block corner (biased by -1),
    /// `lanes` the offsets along a row, `down` the step per row. Returns
    /// the passes and the block's greatest key after the merge.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn block8<T: RasterTri, I: Isa, const EDGES: bool>(
        &mut self,
        isa: I,
        s: &Setup,
        tri: &T,
        bx: u32,
        by: u32,
        e: [i32; 3],
        lanes: [[i32; 8]; 3],
        down: [i32; 3],
    ) -> (u32, Option<K>) {
        let p = tri.depth();
        let c0 = (bx - s.ox) as usize;
        let Ok(col) = <[f64; 8]>::try_from(&self.col[c0..c0 + 8]) else {
            return (0, None);
        };
        let base = self.at(bx, by);
        let (Ok(keys), Ok(ids)) = (
            <&mut [K; 64]>::try_from(&mut self.keys[base..base + 64]),
            <&mut [u32; 64]>::try_from(&mut self.ids[base..base + 64]),
        ) else {
            return (0, None);
        };
        if let Some(avx2) = isa.avx2() {
            let b = Block8 {
                col: &col,
                dy: p.dy,
                y0: p.y0,
                by,
                e,
                lanes,
                down,
                prim: s.prim,
            };
            if let Some((inside, passes, max)) = K::wide_block8::<EDGES>(avx2, keys, ids, &b) {
                if EDGES {
                    self.stats.pixels_tested += 64;
                }
                self.stats.depth_tests += u64::from(inside);
                self.stats.depth_passes += u64::from(passes);
                return (passes, Some(max));
            }
        }
        let mut new = [K::FAR; 64];
        for (r, row) in new.chunks_exact_mut(8).enumerate() {
            let ty = p.dy * ((f64::from(by + r as u32) + 0.5) - p.y0);
            for (key, &c) in row.iter_mut().zip(&col) {
                *key = K::encode(c + ty);
            }
        }
        // Sign bit set = outside some edge.
        let mut out = [0i32; 64];
        if EDGES {
            for r in 0..8 {
                let row = [0, 1, 2].map(|k| e[k] + r as i32 * down[k]);
                for c in 0..8 {
                    out[r * 8 + c] =
                        (row[0] + lanes[0][c]) | (row[1] + lanes[1][c]) | (row[2] + lanes[2][c]);
                }
            }
        }
        let (mut inside, mut passes) = (0u32, 0u32);
        let prim = s.prim;
        // Read the block, merge in registers, count, then write it back
        // whole. Written as `keys[i] = select(mask, new, keys[i])`, LLVM 22
        // folds the load-select-store into AVX masked stores
        // (`vmaskmovps`), which AMD's Zen cores run in microcode: they took
        // a third of the spider's draw time. The counter stores between the
        // reads and the writes keep the fold from applying (it needs a
        // store's memory chain to reach the load with no other store in
        // between; llvm-project #145176, undone for Zen by #214187).
        let (old_keys, old_ids) = (*keys, *ids);
        let mut merged_keys = old_keys;
        let mut merged_ids = old_ids;
        for i in 0..64 {
            let ok = out[i] >= 0;
            let mask = 0u32.wrapping_sub(u32::from(ok & (new[i] < old_keys[i])));
            merged_keys[i] = K::select(mask, new[i], old_keys[i]);
            merged_ids[i] = (prim & mask) | (old_ids[i] & !mask);
            inside += u32::from(ok);
            passes += mask & 1;
        }
        if EDGES {
            self.stats.pixels_tested += 64;
        }
        self.stats.depth_tests += u64::from(inside);
        self.stats.depth_passes += u64::from(passes);
        // After the counters: see above.
        *keys = merged_keys;
        *ids = merged_ids;
        // Eight running maxima, then their maximum (vectorised).
        let mut max: [K; 8] = std::array::from_fn(|c| merged_keys[c]);
        for row in merged_keys[8..].chunks_exact(8) {
            for (m, &k) in max.iter_mut().zip(row) {
                *m = m.max_key(k);
            }
        }
        (passes, Some(max.iter().fold(max[0], |m, &k| m.max_key(k))))
    }

    /// Rasterises rows `ya..=yb`, columns `xa..=xb` (inside the triangle's
    /// box); `EDGES` = false when the block is known to be inside.
    /// Returns the passes.
    #[inline(always)]
    fn rows<T: RasterTri, const EDGES: bool>(
        &mut self,
        s: &Setup,
        tri: &T,
        xa: u32,
        ya: u32,
        xb: u32,
        yb: u32,
    ) -> u32 {
        let p = tri.depth();
        let n = (xb - xa + 1) as usize;
        let c0 = (xa - s.ox) as usize;
        let col = &self.col[c0..c0 + n];
        let dx = i64::from(xa - s.ox);
        let dy = i64::from(ya - s.oy);
        let mut e = [0, 1, 2].map(|k| s.e00[k] + s.sx[k] * dx + s.sy[k] * dy);
        let (mut inside_total, mut pass_total) = (0u32, 0u32);
        for y in ya..yb + 1 {
            let ty = p.dy * ((f64::from(y) + 0.5) - p.y0);
            let at = self.at(xa, y);
            let (inside, passes) = raster_row::<K, EDGES>(
                &mut self.keys[at..at + n],
                &mut self.ids[at..at + n],
                col,
                ty,
                e,
                s.sx,
                s.prim,
            );
            inside_total += inside;
            pass_total += passes;
            for (e, step) in e.iter_mut().zip(s.sy) {
                *e += step;
            }
        }
        let rows = u64::from(yb - ya + 1);
        if EDGES {
            self.stats.pixels_tested += rows * n as u64;
            self.stats.depth_tests += u64::from(inside_total);
        } else {
            self.stats.depth_tests += rows * n as u64;
        }
        self.stats.depth_passes += u64::from(pass_total);
        pass_total
    }

    /// Credits `passes` to every block of a rectangle (an over-count for
    /// blocks it only partly covers: that only refreshes them sooner).
    #[inline(always)]
    fn note_passes_in_rect(&mut self, x0: u32, y0: u32, x1: u32, y1: u32, passes: u32) {
        let per_row = (self.size / BLOCK) as usize;
        for br in (y0 - self.y0) / BLOCK..(y1 - self.y0) / BLOCK + 1 {
            for bc in (x0 - self.x0) / BLOCK..(x1 - self.x0) / BLOCK + 1 {
                self.block_passes[br as usize * per_row + bc as usize] += passes;
            }
        }
        self.tile_passes += passes;
    }

    /// Recomputes a block's maximum key from its pixels.
    #[inline(always)]
    fn refresh_block(&mut self, block: usize) {
        let per_row = (self.size / BLOCK) as usize;
        let (br, bc) = ((block / per_row) as u32, (block % per_row) as u32);
        let (ya, xa) = (br * BLOCK, bc * BLOCK);
        let (yb, xb) = ((ya + BLOCK).min(self.h), (xa + BLOCK).min(self.w));
        let base = block * 64;
        let mut m = self.keys[base];
        if let (8, 8, Ok(keys)) = (
            yb - ya,
            xb - xa,
            <&[K; 64]>::try_from(&self.keys[base..base + 64]),
        ) {
            // A whole block: a fixed-length, branch-free reduction the
            // compiler vectorises (eight running maxima).
            let mut lanes = [m; 8];
            for row in keys.chunks_exact(8) {
                for (l, &k) in lanes.iter_mut().zip(row) {
                    *l = l.max_key(k);
                }
            }
            m = lanes.iter().fold(m, |m, &l| m.max_key(l));
        } else {
            for r in 0..(yb - ya) as usize {
                for &k in &self.keys[base + r * 8..base + r * 8 + (xb - xa) as usize] {
                    m = m.max_key(k);
                }
            }
        }
        self.block_max[block] = m;
        self.block_passes[block] = 0;
    }

    /// Recomputes the tile's maximum once enough has been drawn since the
    /// last time (half the tile's pixels' worth of passes).
    #[inline(always)]
    fn refresh_tile_max(&mut self) {
        if self.tile_passes < self.w * self.h / 2 {
            return;
        }
        let per_row = (self.size / BLOCK) as usize;
        let mut m: Option<K> = None;
        for br in 0..self.h.div_ceil(BLOCK) as usize {
            for bc in 0..self.w.div_ceil(BLOCK) as usize {
                let block = br * per_row + bc;
                if self.block_passes[block] > 0 {
                    self.refresh_block(block);
                }
                let b = self.block_max[block];
                m = Some(m.map_or(b, |m| m.max_key(b)));
            }
        }
        self.tile_max = m.unwrap_or(K::FAR);
        self.tile_passes = 0;
    }

    /// Writes the tile into the band's rows of the frame (`band_y0` is the
    /// band's first image row): ids, and the window depth the reference
    /// z-buffer would have written; background where nothing was drawn.
    pub(crate) fn resolve(&self, ids: &mut [u32], depth: &mut [f32], width: usize, band_y0: u32) {
        let w = self.w as usize;
        for r in 0..self.h as usize {
            let at = (self.y0 - band_y0) as usize * width + r * width + self.x0 as usize;
            let (ids_out, depth_out) = (&mut ids[at..at + w], &mut depth[at..at + w]);
            if self.active {
                // Blocks are stored one after the other (64 pixels each):
                // a tile row is a run of 8 pixels from each block of the row.
                let y = self.y0 + r as u32;
                for c in (0..w).step_by(BLOCK as usize) {
                    let n = (w - c).min(BLOCK as usize);
                    let from = self.at(self.x0 + c as u32, y);
                    for ((id, d), (&i, k)) in ids_out[c..c + n]
                        .iter_mut()
                        .zip(&mut depth_out[c..c + n])
                        .zip(
                            self.ids[from..from + n]
                                .iter()
                                .zip(&self.keys[from..from + n]),
                        )
                    {
                        // See `activate`: a far key is background.
                        *id = if *k == K::FAR { NO_ID } else { i };
                        *d = k.decode();
                    }
                }
            } else {
                ids_out.fill(NO_ID);
                depth_out.fill(1.0);
            }
        }
    }
}

/// Per (triangle, tile) set-up of a large triangle: the edge functions at
/// the pixel centre `(ox, oy)` (the first block's corner) and their exact
/// integer steps per pixel; the depth column terms start at `ox` too.
struct Setup {
    ox: u32,
    oy: u32,
    e00: [i64; 3],
    sx: [i64; 3],
    sy: [i64; 3],
    /// Per edge, the least and greatest change of the edge function over
    /// an 8x8 block from its first centre.
    reach_lo: [i64; 3],
    reach_hi: [i64; 3],
    /// Per edge, whether its values over a block it crosses fit `i32`.
    narrow: [bool; 3],
    /// Per edge, its value's offsets along a row of eight pixels.
    lanes: [[i32; 8]; 3],
    prim: u32,
    /// The triangle's pixel box clipped to the tile.
    bbox: (u32, u32, u32, u32),
}

/// One row of pixels: edge tests (when `EDGES`), depth, LESS, write.
/// Branch-free so that the compiler can vectorise it: the edge values step
/// by exact integer increments, the depth is the column term plus the row
/// term (the reference's own f64 expression), and the writes are selects.
/// Returns (pixels inside, passes).
#[inline(always)]
fn raster_row<K: DepthKey, const EDGES: bool>(
    keys: &mut [K],
    ids: &mut [u32],
    col: &[f64],
    ty: f64,
    e: [i64; 3],
    step: [i64; 3],
    prim: u32,
) -> (u32, u32) {
    let n = keys.len();
    let (ids, col) = (&mut ids[..n], &col[..n]);
    let (mut e0, mut e1, mut e2) = (e[0], e[1], e[2]);
    let (mut inside_n, mut passes) = (0u32, 0u32);
    for i in 0..n {
        let inside = !EDGES || ((e0 > 0) & (e1 > 0) & (e2 > 0));
        e0 += step[0];
        e1 += step[1];
        e2 += step[2];
        let key = K::encode(col[i] + ty);
        let mask = 0u32.wrapping_sub(u32::from(inside & (key < keys[i])));
        keys[i] = K::select(mask, key, keys[i]);
        ids[i] = (prim & mask) | (ids[i] & !mask);
        inside_n += u32::from(inside);
        passes += mask & 1;
    }
    (inside_n, passes)
}

/// The tile buffers (one per tile), one vector per depth format so each
/// holds its format's own key type.
#[derive(Clone, Debug, Default)]
pub(crate) struct Scratch {
    pub(crate) f32: Vec<TileBuf<f32>>,
    pub(crate) f64: Vec<TileBuf<f64>>,
    pub(crate) fixed24: Vec<TileBuf<Fixed24>>,
    pub(crate) fixed16: Vec<TileBuf<Fixed16>>,
    pub(crate) reversed: Vec<TileBuf<Reversed>>,
}

/// A key type with its place in [`Scratch`].
pub(crate) trait TileKey: DepthKey {
    /// The tile buffers of this format.
    fn bufs(s: &mut Scratch) -> &mut Vec<TileBuf<Self>>;
}

impl TileKey for f32 {
    fn bufs(s: &mut Scratch) -> &mut Vec<TileBuf<Self>> {
        &mut s.f32
    }
}

impl TileKey for f64 {
    fn bufs(s: &mut Scratch) -> &mut Vec<TileBuf<Self>> {
        &mut s.f64
    }
}

impl TileKey for Fixed24 {
    fn bufs(s: &mut Scratch) -> &mut Vec<TileBuf<Self>> {
        &mut s.fixed24
    }
}

impl TileKey for Fixed16 {
    fn bufs(s: &mut Scratch) -> &mut Vec<TileBuf<Self>> {
        &mut s.fixed16
    }
}

impl TileKey for Reversed {
    fn bufs(s: &mut Scratch) -> &mut Vec<TileBuf<Self>> {
        &mut s.reversed
    }
}
