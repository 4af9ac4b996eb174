//! The tile's hierarchical depth: the maximum key of each 8x8 block and of
//! the whole tile, refreshed lazily (a stale maximum is still an upper
//! bound, since keys only fall as depths are written).

use super::super::key::DepthKey;
use super::{BLOCK, TileBuf};

impl<K: DepthKey> TileBuf<K> {
    /// Credits a small box's `passes` to the block of its first pixel and
    /// to the tile. The counts only decide when a maximum is recomputed (a
    /// stale maximum is still an upper bound), so the other blocks a box
    /// meets may go uncredited; on a dense mesh every block holds the first
    /// pixel of boxes of its own. A loop over the box's blocks cost the
    /// sphere 200 at 1024 2.2 % of its frame's instructions, and crediting
    /// the last pixel's block as well 0.6 %, and neither changed a
    /// rejection on the spider.
    #[inline(always)]
    pub(super) fn note_small_passes(&mut self, x0: u32, y0: u32, passes: u32) {
        let per_row = (self.size / BLOCK) as usize;
        let block = ((y0 - self.y0) / BLOCK) as usize * per_row + ((x0 - self.x0) / BLOCK) as usize;
        self.block_passes[block] += passes;
        self.tile_passes += passes;
    }

    /// An upper bound of the keys of the blocks that the box
    /// `(x0, y0)..=(x1, y1)` (image pixels, inside the tile) meets: the
    /// greatest of their maxima, as they stand (a stale one is still a
    /// bound, and refreshing them here would cost more than it saves).
    #[inline(always)]
    pub(super) fn box_max(&self, (x0, y0, x1, y1): (u32, u32, u32, u32)) -> K {
        let per_row = (self.size / BLOCK) as usize;
        let (c0, c1) = (
            ((x0 - self.x0) / BLOCK) as usize,
            ((x1 - self.x0) / BLOCK) as usize,
        );
        let (r0, r1) = ((y0 - self.y0) / BLOCK, (y1 - self.y0) / BLOCK);
        let mut m = self.block_max[r0 as usize * per_row + c0];
        for r in r0..=r1 {
            let row = &self.block_max[r as usize * per_row..][c0..=c1];
            m = row.iter().fold(m, |m, &k| m.max_key(k));
        }
        m
    }

    /// Recomputes a block's maximum key from its pixels.
    #[inline(always)]
    pub(super) fn refresh_block(&mut self, block: usize) {
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
    pub(super) fn refresh_tile_max(&mut self) {
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
        self.tile_max = m.unwrap_or(self.clear);
        self.tile_passes = 0;
    }
}
