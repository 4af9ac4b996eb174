//! Exact occlusion culling, at three levels.
//!
//! Per pixel an *opaque bound*: a depth such that every sample and the
//! centre is covered by opaque fragments of the list no farther than it (a
//! full opaque fragment's `zmax`, or the farthest `zmax` of partial opaque
//! fragments gathered until their masks cover everything). A fragment
//! whose `zmin` is beyond it is strictly behind at every sample and the
//! centre: culled on arrival, or pruned when the bound drops. Per 8 x 8
//! block, the farthest bound of its pixels: a triangle whose plane is
//! beyond it over the block (one evaluation, the plane being monotonic)
//! makes no fragment there, and a triangle with no live block is not even
//! set up. Per partial pixel, the plane at the hull corner bounds `zmin`
//! from below before the mask is computed (that last test is in the
//! rasteriser).
//!
//! When a list overflows, [`hidden_in_every_sample`] finds the fragments
//! that nearer opaque ones hide in every sample: pruning them is exact too.

use crate::bins::TILE;
use crate::fragment::{Fragment, Shaded};
use crate::pool::FragmentPool;

/// Side of the blocks of the hierarchical occlusion test, in pixels.
pub(crate) const BLOCK: u32 = 8;
/// Blocks per tile side.
pub(crate) const BLOCKS: usize = (TILE / BLOCK) as usize;
// A tile's blocks are the bits of a `u64`.
const _: () = assert!(BLOCKS * BLOCKS <= 64 && TILE % BLOCK == 0);

/// Per 8 x 8 block of the current tile: an upper bound of the opaque
/// bounds of its pixels. While some pixel of the block has no bound yet
/// (`open > 0`) it is infinite; after that it is their maximum, recomputed
/// only when a test needs it and a bound dropped since (`stale`). Bounds
/// only decrease, so a stale value is still an upper bound.
#[derive(Clone, Debug)]
struct BlockFar {
    far: [f32; BLOCKS * BLOCKS],
    open: [u8; BLOCKS * BLOCKS],
    stale: u64,
}

impl BlockFar {
    /// The blocks of a tile whose pixels `x0..=x1`, `y0..=y1` (tile-local)
    /// exist: every one open.
    fn reset(&mut self, x1: u32, y1: u32) {
        self.far = [f32::INFINITY; BLOCKS * BLOCKS];
        self.stale = 0;
        for (b, open) in self.open.iter_mut().enumerate() {
            let (bx, by) = ((b % BLOCKS) as u32 * BLOCK, (b / BLOCKS) as u32 * BLOCK);
            let w = (x1 + 1).saturating_sub(bx).min(BLOCK);
            let h = (y1 + 1).saturating_sub(by).min(BLOCK);
            *open = (w * h) as u8;
        }
    }
}

impl Default for BlockFar {
    fn default() -> Self {
        Self {
            far: [f32::INFINITY; BLOCKS * BLOCKS],
            open: [(BLOCK * BLOCK) as u8; BLOCKS * BLOCKS],
            stale: 0,
        }
    }
}

/// The opaque fragments gathered towards a new opaque bound of one pixel:
/// the samples (and centre) they cover and their farthest `zmax`.
#[derive(Clone, Copy, Debug)]
struct Gather {
    mask: u32,
    centre: bool,
    far: f32,
}

impl Gather {
    const EMPTY: Gather = Gather {
        mask: 0,
        centre: false,
        far: f32::NEG_INFINITY,
    };
}

/// The culling state of the current tile: what each pixel gathered towards
/// its next opaque bound, and the bound of each block.
#[derive(Clone, Debug, Default)]
pub(crate) struct Culling {
    /// Per pixel of the tile (row-major, `TILE` per row).
    gather: Vec<Gather>,
    blocks: BlockFar,
}

impl Culling {
    /// Starts a tile whose last pixel is `(x1, y1)` (tile-local): nothing
    /// gathered, every block open.
    pub(crate) fn begin_tile(&mut self, x1: u32, y1: u32) {
        self.gather.resize((TILE * TILE) as usize, Gather::EMPTY);
        self.gather.fill(Gather::EMPTY);
        self.blocks.reset(x1, y1);
    }

    /// Forgets what tile pixel `g` gathered (a fragment it counted may have
    /// left the list).
    pub(crate) fn forget(&mut self, g: usize) {
        self.gather[g] = Gather::EMPTY;
    }

    /// Whether every fragment that a triangle could make in block `b` of
    /// the tile at `(tx0, ty0)`, all with `zmin >= near`, would be culled:
    /// `near` is beyond the opaque bound of every pixel of the block (whose
    /// entries are in `pool`, for a frame of `(w, h)` pixels).
    #[inline]
    pub(crate) fn block_hidden(
        &mut self,
        pool: &FragmentPool,
        (w, h): (u32, u32),
        b: usize,
        near: f32,
        (tx0, ty0): (u32, u32),
    ) -> bool {
        let blocks = &mut self.blocks;
        if near > blocks.far[b] {
            return true;
        }
        if blocks.stale >> b & 1 == 0 || blocks.open[b] > 0 {
            return false;
        }
        // Tighten the stale bound to the current maximum and test again.
        blocks.stale &= !(1u64 << b);
        let x0 = tx0 + (b % BLOCKS) as u32 * BLOCK;
        let y0 = ty0 + (b / BLOCKS) as u32 * BLOCK;
        let (x1, y1) = ((x0 + BLOCK).min(w), (y0 + BLOCK).min(h));
        let mut far = f32::NEG_INFINITY;
        for j in y0..y1 {
            let row = j as usize * w as usize;
            for p in row + x0 as usize..row + x1 as usize {
                let z = pool.pixel(p).occluder;
                if z > far {
                    far = z;
                }
            }
        }
        blocks.far[b] = far;
        near > far
    }

    /// After opaque fragment `f` entered pixel `p` (tile pixel `g`) as
    /// itself or merged into `m`: lowers the pixel's opaque bound when `m`
    /// covers every sample (`full`) and the centre, or when the opaque
    /// fragments gathered since the last bound now do, and prunes the
    /// fragments entirely behind the new bound; returns how many.
    ///
    /// The bound `B` means: every sample and the centre is covered by an
    /// opaque fragment of the list whose depth there is at most `B`. A
    /// fragment with `zmin > B` is then strictly behind an opaque surface
    /// at each of its samples and its centre, so it changes no sample, no
    /// coverage and no id: culling and pruning it is exact. Fragments
    /// supporting `B` have `zmin <= zmax <= B`, so pruning never removes
    /// them; a merge keeps every sample's depth.
    pub(crate) fn note_opaque(
        &mut self,
        pool: &mut FragmentPool,
        full: u32,
        (p, g): (usize, usize),
        f: &Fragment,
        m: &Fragment,
    ) -> u64 {
        let e = *pool.pixel(p);
        let mut bound = e.occluder;
        if m.mask == full && m.covers_centre() && m.zmax < bound {
            bound = m.zmax;
        }
        if f.zmax < e.occluder {
            let gather = &mut self.gather[g];
            gather.mask |= f.mask;
            gather.centre |= f.covers_centre();
            gather.far = gather.far.max(f.zmax);
            if gather.mask == full && gather.centre {
                bound = bound.min(gather.far);
            }
        }
        let mut pruned = 0;
        if bound < e.occluder {
            pool.set_occluder(p, bound);
            let (gi, gj) = (g % TILE as usize, g / TILE as usize);
            let b = gj / BLOCK as usize * BLOCKS + gi / BLOCK as usize;
            self.blocks.stale |= 1 << b;
            if e.occluder == f32::INFINITY {
                self.blocks.open[b] -= 1;
            }
            self.gather[g] = Gather::EMPTY;
            if e.far > bound {
                pruned = pool.remove_where(p, |h| h.zmin > bound);
            }
        }
        pruned
    }
}

/// Whether fragment `g` is hidden in every sample it covers, and at the
/// centre if it covers that, by opaque fragments of `list` lying entirely
/// in front of it (`full`: the mask of every sample). Exact: the depth
/// ranges are strict bounds.
pub(crate) fn hidden_in_every_sample(g: &Shaded, list: &[Shaded], full: u32) -> bool {
    let mut cover = 0u32;
    let mut centre = !g.frag.covers_centre();
    for h in list {
        if h.alpha >= 1.0 && h.frag.zmax < g.frag.zmin {
            cover |= h.frag.mask;
            centre |= h.frag.covers_centre();
        }
    }
    centre && (g.frag.mask & full) & !cover == 0
}

#[cfg(test)]
mod tests {

    use super::*;

    fn frag(mask: u32, zmin: f32, zmax: f32, alpha: f32) -> Shaded {
        let f = Fragment::with_mask(mask, zmin, zmax);
        Shaded::new(f, [0.0, 0.0, 0.0, alpha], 0)
    }

    #[test]
    fn hidden_fragments_are_found_exactly() {
        let full = u32::MAX;
        let a = frag(0xffff, 0.1, 0.2, 1.0);
        let b = frag(0xffff_0000, 0.1, 0.3, 1.0);
        let behind = frag(0x00ff_ff00, 0.35, 0.4, 1.0);
        let touching = frag(0x00ff_ff00, 0.3, 0.4, 1.0);
        let list = [a, b, behind, touching];
        assert!(hidden_in_every_sample(&behind, &list, full));
        assert!(
            !hidden_in_every_sample(&touching, &list, full),
            "equal depth is not hidden"
        );
        assert!(!hidden_in_every_sample(&a, &list, full));
        let glass = frag(0xffff_0000, 0.1, 0.3, 0.5);
        assert!(!hidden_in_every_sample(&behind, &[a, glass], full));
    }
}
