//! Pixels held whole: Carpenter's plain pixel, one opaque surface over
//! the whole pixel and in front of everything there, kept as that one
//! primitive (its centre depth, near and far keys and an index of its
//! plane) without its 32 sample depths; an unwritten 8 x 8 block a
//! triangle covers whole, held so a row of 8 at a time; and the expansion
//! of a whole pixel into samples when a later fragment shares it.

use hider_geom::PlaneEq;
use hider_geom::isa::Avx2;
use hider_scene::NO_ID;

#[cfg(target_arch = "x86_64")]
use super::avx2;
use super::{BLOCK, BLOCKS_X, EMPTY, SampleBuffer, Tri};
use crate::coverage::Coverage;
use crate::depth::plane_depth;
use crate::pattern::{CENTRE, MAX_SAMPLES, SamplePattern};
use crate::stats::ABufferStats;

/// What [`SampleBuffer::whole_block`] needs of a triangle.
pub(crate) struct Held {
    /// Its depth plane.
    pub(super) plane: PlaneEq,
    /// Its primitive.
    pub(super) prim: u32,
    /// Its near and far corners of the sample hull.
    pub(super) corners: ((i32, i32), (i32, i32)),
    /// Its plane's index in [`SampleBuffer::planes`].
    pub(super) index: u32,
}

impl SampleBuffer {
    /// The index of `tri`'s plane in [`Self::planes`], added on its first
    /// whole pixel in the pass.
    #[inline(always)]
    pub(super) fn own_plane(&mut self, tri: &mut Tri) -> u32 {
        *tri.own_plane.get_or_insert_with(|| {
            self.planes.push(tri.plane);
            self.planes.len() as u32 - 1
        })
    }

    /// Whether no pixel of the 8 x 8 block whose top-left pixel is
    /// `(i0, j0)` has been written this pass.
    #[inline(always)]
    pub(super) fn unwritten(&self, i0: u32, j0: u32) -> bool {
        let (row, shift) = ((j0 - self.rect.1) as usize, i0 - self.rect.0);
        self.touched[row..row + BLOCK as usize]
            .iter()
            .all(|&bits| (bits >> shift) & 0xff == 0)
    }

    /// Holds the 8 x 8 unwritten pixels from `(i0, j0)` on (one block,
    /// covered whole by the triangle `held` describes) whole, as
    /// [`Self::pixel`]'s common case does each (nothing there to cull),
    /// a row at a time: the same keys and depths, its plane evaluated for
    /// 8 pixels together, stored 8 at a time. One by one such a pixel was
    /// 7 ns, and a large triangle's frame 6.7 times the tiled z-buffer's.
    // Out of line, given copies rather than the walk's `Tri`, and tested
    // per block rather than per row: each of those, in the loop over rows,
    // made the walk of every triangle 1.5 to 4 % dearer in instructions.
    #[inline(never)]
    pub(super) fn whole_block(&mut self, held: Held, ij: (u32, u32), stats: &mut ABufferStats) {
        #[cfg(target_arch = "x86_64")]
        if let Some(isa) = self.avx2 {
            // Compiled for AVX2, so that the row evaluations inline.
            avx2::whole_block(isa, self, held, ij, stats);
            return;
        }
        self.whole_block_with(held, ij, stats);
    }

    /// [`Self::whole_block`], inlined into its AVX2 and portable callers.
    #[inline(always)]
    pub(crate) fn whole_block_with(
        &mut self,
        held: Held,
        (i0, j0): (u32, u32),
        stats: &mut ABufferStats,
    ) {
        const N: usize = BLOCK as usize;
        let (px0, py0) = (self.rect.0, self.rect.1);
        let plane = held.plane;
        let (near_corner, far_corner) = held.corners;
        let mut block_far = i32::MIN;
        for j in j0..j0 + BLOCK {
            let p0 = self.index(i0, j);
            let far = self.row_keys(&plane, (i0, j), far_corner);
            block_far = far.iter().fold(block_far, |m, &f| m.max(f));
            let near = self.row_keys(&plane, (i0, j), near_corner);
            let centre: [f64; N] =
                std::array::from_fn(|k| plane_depth(&plane, i0 + k as u32, j, CENTRE));
            self.centre_z[p0..p0 + N].copy_from_slice(&centre);
            self.centre_prim[p0..p0 + N].fill(held.prim);
            self.far[p0..p0 + N].copy_from_slice(&far);
            self.near[p0..p0 + N].copy_from_slice(&near);
            self.plane_of[p0..p0 + N].fill(held.index);
            let (row, shift) = ((j - py0) as usize, i0 - px0);
            self.touched[row] |= 0xff << shift;
            self.whole[row] |= 0xff << shift;
        }
        let pixels = (N * N) as u64;
        stats.fragments += pixels;
        stats.full_coverage += pixels;
        stats.whole_pixels += pixels;
        let b = ((j0 - py0) / BLOCK * BLOCKS_X + (i0 - px0) / BLOCK) as usize;
        self.open[b] = 0;
        // Every pixel of the block was written here: its bound is exact
        // (recomputing it from the 64 pixels was a seventh of a large
        // triangle's frame).
        self.block_far[b] = block_far;
        self.stale &= !(1 << b);
    }

    /// Turns whole pixel `p` (at `ij`) into samples: its primitive's
    /// depth at every sample, as its write to the empty pixel (or over
    /// the whole primitive it beat everywhere) would have left them.
    #[inline(always)]
    pub(super) fn expand(
        &mut self,
        p: usize,
        ij: (u32, u32),
        (pattern, grid): (SamplePattern, Option<Avx2>),
    ) {
        let plane = self.planes[self.plane_of[p] as usize];
        let full = Coverage {
            mask: pattern.full_mask(),
            centre: true,
            full: true,
        };
        self.keys[p] = [EMPTY; MAX_SAMPLES];
        self.prims[p] = [NO_ID; MAX_SAMPLES];
        // The centre already holds this primitive's depth: the write
        // leaves it (no primitive is in front of itself).
        self.write(p, ij, &plane, self.centre_prim[p], full, (pattern, grid));
    }
}
