//! Exact occlusion culling, at four levels.
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
//! set up. Per tile, the farthest bound of its blocks: a triangle over
//! several blocks whose plane is beyond it over its part of the tile is
//! rejected before the block tests, which would each reject it. Per
//! partial pixel, the plane at the hull corner bounds `zmin` from below
//! before the mask is computed (the tile, block and pixel tests are in the
//! rasteriser).
//!
//! When a list overflows, [`hidden_fragments`] finds the fragments
//! that nearer opaque ones hide in every sample: pruning them is exact too.

use crate::bins::TILE;
use crate::fragment::{Fragment, Shaded};
use crate::pool::FragmentPool;

/// Side of the blocks of the hierarchical occlusion test, in pixels.
pub(crate) const BLOCK: u32 = 8;
/// Blocks per tile side.
pub(crate) const BLOCKS: usize = (TILE / BLOCK) as usize;
// A tile's blocks are the bits of a `u64`.
const _: () = assert!(BLOCKS * BLOCKS <= 64 && TILE.is_multiple_of(BLOCK));

/// The pixels of block `(bx, by)`, of the blocks laid from pixel `origin`,
/// that lie inside the pixels `(x0, y0)` to `(x1, y1)`: its part of the
/// rectangle, inclusive (empty, `x0 > x1` or `y0 > y1`, if they miss).
#[inline(always)]
pub(crate) fn block_part(
    origin: (u32, u32),
    (bx, by): (u32, u32),
    (x0, y0, x1, y1): (u32, u32, u32, u32),
) -> (u32, u32, u32, u32) {
    let (i, j) = (origin.0 + bx * BLOCK, origin.1 + by * BLOCK);
    (
        i.max(x0),
        j.max(y0),
        (i + BLOCK - 1).min(x1),
        (j + BLOCK - 1).min(y1),
    )
}

/// Per 8 x 8 block of the current tile: an upper bound of the opaque
/// bounds of its pixels. While some pixel of the block has no bound yet
/// (`open > 0`) it is infinite; after that it is their maximum, recomputed
/// only when a test needs it and a bound dropped since (`stale`). Bounds
/// only decrease, so a stale value is still an upper bound.
///
/// The tile's bound is the maximum of its blocks' (infinite while a block
/// is open), cached and recomputed from `far` when a block's value changed
/// (`tile_dirty`): an upper bound of every pixel's bound in the tile.
#[derive(Clone, Debug)]
struct BlockFar {
    far: [f32; BLOCKS * BLOCKS],
    open: [u8; BLOCKS * BLOCKS],
    stale: u64,
    /// The blocks with pixels in the frame.
    exists: u64,
    /// How many of them are open.
    open_blocks: u32,
    tile_far: f32,
    tile_dirty: bool,
}

impl BlockFar {
    /// The blocks of a tile whose pixels `x0..=x1`, `y0..=y1` (tile-local)
    /// exist: every one open.
    fn reset(&mut self, x1: u32, y1: u32) {
        self.far = [f32::INFINITY; BLOCKS * BLOCKS];
        self.stale = 0;
        self.exists = 0;
        for (b, open) in self.open.iter_mut().enumerate() {
            let (bx, by) = ((b % BLOCKS) as u32 * BLOCK, (b / BLOCKS) as u32 * BLOCK);
            let w = (x1 + 1).saturating_sub(bx).min(BLOCK);
            let h = (y1 + 1).saturating_sub(by).min(BLOCK);
            *open = (w * h) as u8;
            self.exists |= u64::from(w * h > 0) << b;
        }
        self.open_blocks = self.exists.count_ones();
        self.tile_far = f32::INFINITY;
        self.tile_dirty = false;
    }

    /// An upper bound of the opaque bounds of every pixel of the tile
    /// (infinite while a pixel has none).
    fn tile_far(&mut self) -> f32 {
        if self.open_blocks > 0 {
            return f32::INFINITY;
        }
        if self.tile_dirty {
            self.tile_dirty = false;
            let mut bits = self.exists;
            let mut far = f32::NEG_INFINITY;
            while bits != 0 {
                far = far.max(self.far[bits.trailing_zeros() as usize]);
                bits &= bits - 1;
            }
            self.tile_far = far;
        }
        self.tile_far
    }
}

impl Default for BlockFar {
    fn default() -> Self {
        Self {
            far: [f32::INFINITY; BLOCKS * BLOCKS],
            open: [(BLOCK * BLOCK) as u8; BLOCKS * BLOCKS],
            stale: 0,
            exists: u64::MAX,
            open_blocks: (BLOCKS * BLOCKS) as u32,
            tile_far: f32::INFINITY,
            tile_dirty: false,
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
    /// Whether pruning the pixel's list may remove something: an opaque
    /// fragment entered it since the last pruning (only opaque fragments
    /// hide others). A full list of translucent layers is pruned once,
    /// not at every fragment that arrives.
    prune: bool,
    /// Whether [`Culling::far_key`] holds a bound for the pixel.
    far_known: bool,
}

impl Gather {
    const EMPTY: Gather = Gather {
        mask: 0,
        centre: false,
        far: f32::NEG_INFINITY,
        prune: true,
        far_known: false,
    };
}

/// The culling state of the current tile: what each pixel gathered towards
/// its next opaque bound, and the bound of each block.
#[derive(Clone, Debug, Default)]
pub(crate) struct Culling {
    /// Per pixel of the tile (row-major, `TILE` per row).
    gather: Vec<Gather>,
    /// Per pixel of the tile: an upper bound of the resolve order key
    /// (`zmin`, primitive) of the fragments of its list, where
    /// `Gather::far_known` says so. A full list drops the farthest
    /// fragment; when the new one is at or beyond this bound it is that
    /// fragment, found without walking the list.
    far_key: Vec<(f32, u32)>,
    blocks: BlockFar,
}

/// Whether order key `a` is at or beyond `b` (the resolve order of
/// [`Fragment::order`]).
#[inline]
pub(crate) fn key_at_or_beyond(a: (f32, u32), b: (f32, u32)) -> bool {
    a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).is_ge()
}

impl Culling {
    /// Starts a tile whose last pixel is `(x1, y1)` (tile-local): nothing
    /// gathered, every block open.
    pub(crate) fn begin_tile(&mut self, x1: u32, y1: u32) {
        self.gather.resize((TILE * TILE) as usize, Gather::EMPTY);
        self.gather.fill(Gather::EMPTY);
        self.far_key.resize((TILE * TILE) as usize, (0.0, 0));
        self.blocks.reset(x1, y1);
    }

    /// Records that an opaque fragment entered the list of tile pixel `g`
    /// (as itself or merged): pruning it may now remove something.
    #[inline]
    pub(crate) fn opaque_entered(&mut self, g: usize) {
        self.gather[g].prune = true;
    }

    /// Whether pruning the list of tile pixel `g` may remove something;
    /// the caller prunes it now, so the next call says no until an opaque
    /// fragment enters.
    pub(crate) fn take_prune(&mut self, g: usize) -> bool {
        std::mem::replace(&mut self.gather[g].prune, false)
    }

    /// An upper bound of the order keys of the list of tile pixel `g`,
    /// when one is known.
    #[inline]
    pub(crate) fn far_bound(&self, g: usize) -> Option<(f32, u32)> {
        self.gather[g].far_known.then(|| self.far_key[g])
    }

    /// Records `key` as an upper bound of the order keys of the list of
    /// tile pixel `g` (removing fragments or merging keeps it one).
    pub(crate) fn set_far_bound(&mut self, g: usize, key: (f32, u32)) {
        self.gather[g].far_known = true;
        self.far_key[g] = key;
    }

    /// Keeps the bound of tile pixel `g` one after a fragment with order
    /// key `key` entered its list.
    #[inline]
    pub(crate) fn entered(&mut self, g: usize, key: (f32, u32)) {
        if self.gather[g].far_known && !key_at_or_beyond(self.far_key[g], key) {
            self.far_key[g] = key;
        }
    }

    /// Forgets what tile pixel `g` gathered (a fragment it counted may have
    /// left the list).
    pub(crate) fn forget(&mut self, g: usize) {
        self.gather[g] = Gather::EMPTY;
    }

    /// An upper bound of the opaque bounds of every pixel of the tile
    /// (infinite while a pixel has none): a triangle whose fragments all
    /// have `zmin` beyond it would be culled in every block
    /// ([`Self::block_hidden`] would say so for each), so the tile test is
    /// that test for all blocks at once.
    #[inline]
    pub(crate) fn tile_far(&mut self) -> f32 {
        self.blocks.tile_far()
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
        blocks.tile_dirty = true;
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
                if self.blocks.open[b] == 0 {
                    self.blocks.open_blocks -= 1;
                    self.blocks.tile_dirty = true;
                }
            }
            self.gather[g] = Gather::EMPTY;
            if e.far > bound {
                pruned = pool.remove_where(p, |h| h.zmin > bound);
            }
        }
        pruned
    }
}

/// Scratch of [`hidden_fragments`], kept between calls.
#[derive(Clone, Debug, Default)]
pub(crate) struct HiddenScratch {
    /// Opaque fragments: `zmax`, mask, whether they cover the centre.
    occluders: Vec<(f32, u32, bool)>,
    /// Positions in the list, by `zmin`.
    by_zmin: Vec<(f32, u32)>,
}

/// For each fragment `g` of `list`, whether it is hidden in every sample
/// it covers, and at the centre if it covers that, by opaque fragments of
/// `list` lying entirely in front of it (`full`: the mask of every
/// sample; exact, the depth ranges being strict bounds), in `O(L log L)`
/// instead of the `O(L^2)` of testing each against all the others: fragments taken by increasing
/// `zmin` see a growing set of opaque fragments lying entirely in front
/// (`zmax < zmin`), taken by increasing `zmax`, whose masks accumulate. A
/// full list is pruned at every insertion, so its cost is what bounds the
/// time of a pixel with hundreds of coplanar layers.
pub(crate) fn hidden_fragments(
    list: &[Shaded],
    full: u32,
    scratch: &mut HiddenScratch,
    hidden: &mut Vec<bool>,
) {
    let HiddenScratch { occluders, by_zmin } = scratch;
    occluders.clear();
    occluders.extend(
        list.iter()
            .filter(|h| h.alpha >= 1.0)
            .map(|h| (h.frag.zmax, h.frag.mask, h.frag.covers_centre())),
    );
    occluders.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    by_zmin.clear();
    by_zmin.extend(
        list.iter()
            .enumerate()
            .map(|(k, g)| (g.frag.zmin, k as u32)),
    );
    by_zmin.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    hidden.clear();
    hidden.resize(list.len(), false);
    let (mut cover, mut centre, mut next) = (0u32, false, 0);
    for &(zmin, k) in by_zmin.iter() {
        while next < occluders.len() && occluders[next].0 < zmin {
            cover |= occluders[next].1;
            centre |= occluders[next].2;
            next += 1;
        }
        let g = &list[k as usize].frag;
        hidden[k as usize] = (centre || !g.covers_centre()) && (g.mask & full) & !cover == 0;
    }
}

/// The definition [`hidden_fragments`] implements, fragment by fragment:
/// whether fragment `g` is hidden in every sample it covers, and at the
/// centre if it covers that, by opaque fragments of `list` lying entirely
/// in front of it (`full`: the mask of every sample). Exact: the depth
/// ranges are strict bounds.
#[cfg(test)]
fn hidden_in_every_sample(g: &Shaded, list: &[Shaded], full: u32) -> bool {
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

    /// The sweep finds exactly what the pairwise definition finds, on
    /// lists with repeated depths (ties are never hidden), translucent
    /// fragments and partial masks.
    #[test]
    fn sweep_equals_the_pairwise_definition() {
        let mut next = crate::test_rng::xorshift();
        let (mut scratch, mut hidden) = (HiddenScratch::default(), Vec::new());
        for case in 0..2000 {
            let len = 1 + (next() % 40) as usize;
            let list: Vec<Shaded> = (0..len)
                .map(|_| {
                    let zmin = (next() % 8) as f32 / 8.0;
                    let zmax = zmin + (next() % 3) as f32 / 8.0;
                    let mask = match next() % 3 {
                        0 => u32::MAX,
                        _ => next() as u32,
                    };
                    let alpha = if next().is_multiple_of(4) { 0.5 } else { 1.0 };
                    let mut s = frag(mask, zmin, zmax, alpha);
                    if next().is_multiple_of(2) {
                        s.frag.centre_z = f64::from(zmin);
                    }
                    s
                })
                .collect();
            hidden_fragments(&list, u32::MAX, &mut scratch, &mut hidden);
            for (k, g) in list.iter().enumerate() {
                assert_eq!(
                    hidden[k],
                    hidden_in_every_sample(g, &list, u32::MAX),
                    "case {case}, fragment {k}"
                );
            }
        }
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
