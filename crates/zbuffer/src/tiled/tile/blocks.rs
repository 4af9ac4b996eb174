//! Triangles larger than a few pixels: the tile's aligned 8x8 blocks their
//! box meets, each rejected or accepted whole from the edge functions at
//! its corners, rejected by its maximum depth, or drawn as 64 lanes (the
//! portable block here, the AVX2 one in `wide`) or row by row at the
//! image's edge.

use hider_geom::fixed::{SUBPIXEL_SCALE, pixel_center};

use super::super::bounds::DepthBounds;
use super::super::key::DepthKey;
use super::super::raster_tri::RasterTri;
use super::super::wide::{Block8, Isa, WideBlock};
use super::{BLOCK, BLOCK_REFRESH, TileBuf};

impl<K: WideBlock> TileBuf<K> {
    /// Draws a triangle whose box in the tile, `(x0, y0)..=(x1, y1)`, is
    /// more than a few pixels: sets up its edge functions and depth column
    /// terms at the first block's corner, then walks the blocks.
    #[inline(always)]
    pub(super) fn large<T: RasterTri, I: Isa>(
        &mut self,
        isa: I,
        tri: &T,
        (x0, y0, x1, y1): (u32, u32, u32, u32),
        bounds: Option<&DepthBounds>,
    ) {
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
        let (px, py) = (
            i64::from(pixel_center(ox as i32)),
            i64::from(pixel_center(oy as i32)),
        );
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
        self.blocks(isa, &setup, tri, bounds);
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
    #[allow(
        clippy::too_many_arguments,
        reason = "the kernel's hot path: plain arguments stay in registers"
    )]
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
            if max < self.clear
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
            self.block8::<T, I, false>(isa, s, tri, bx, by, [0; 3], [0; 3], [0; 3])
        } else if full && fits {
            // Biased by one so "inside" is ">= 0" (see `small`); edges the
            // whole block is inside of are replaced by the constant 0, by
            // masks (`keep`), not branches, and the triangle's lane offsets
            // are passed by reference and masked in registers. A block's
            // own copy of the lanes (96 bytes, copied edge by edge when
            // the edge was kept) cost the spider's draw 0.41 ms against
            // 0.32 now, the soup's 12.2 against 11.2, for 1.5 % more
            // instructions: which edges a sliver's block is inside of
            // changes from block to block (the branches were mispredicted,
            // 34.9k → 32.4k a frame in callgrind's simulation), and, the
            // likelier cost, three 256-bit loads of an array just written
            // in narrower stores cannot be forwarded from them.
            let keep = lo.map(|l| -i32::from(l <= 0));
            let e = [0, 1, 2].map(|k| ((corner[k] - 1) as i32) & keep[k]);
            let down = [0, 1, 2].map(|k| (s.sy[k] as i32) & keep[k]);
            self.block8::<T, I, true>(isa, s, tri, bx, by, e, keep, down)
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
    #[allow(
        clippy::too_many_arguments,
        reason = "the kernel's hot path: plain arguments stay in registers"
    )]
    #[inline(always)]
    fn block8<T: RasterTri, I: Isa, const EDGES: bool>(
        &mut self,
        isa: I,
        s: &Setup,
        tri: &T,
        bx: u32,
        by: u32,
        e: [i32; 3],
        keep: [i32; 3],
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
                lanes: &s.lanes,
                keep,
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
                    let lane = |k: usize| row[k] + (s.lanes[k][c] & keep[k]);
                    out[r * 8 + c] = lane(0) | lane(1) | lane(2);
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
        // between; LLVM issue 145176, undone for Zen by LLVM pull request
        // 214187).
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
