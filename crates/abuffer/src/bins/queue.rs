//! One thread's queue of a tile's triangles: the tile's bin sorted front
//! to back, its items gathered in that order, and the coincident ones
//! among them; and which tiles of the thread's pixel table hold lists.

use hider_geom::FixedPt;
use hider_geom::isa::prefetch;

use super::{BinItem, Bins};

/// [`TileQueue::twin`]: no earlier item of the tile has the same geometry.
pub(crate) const SOLE: u32 = u32::MAX;
/// [`TileQueue::twin`]: the first item of the tile with its geometry, and later
/// ones share it.
pub(crate) const LEADER: u32 = u32::MAX - 1;

/// Runs of equal nearest depth up to this length are searched for
/// coincident items pair by pair; longer ones are sorted by geometry.
const PAIRWISE_RUN: usize = 16;

/// What makes two triangles coincident: the same snapped vertices in the
/// same order and the same depth plane, bit for bit. Such triangles cover
/// the same samples and centres (same edges, same fill rule) at the same
/// depths (same expression).
type Geometry = ([FixedPt; 3], [u64; 5]);

impl BinItem {
    fn geometry(&self) -> Geometry {
        let p = &self.plane;
        (self.v, [p.x0, p.y0, p.value, p.dx, p.dy].map(f64::to_bits))
    }
}

/// How many items ahead of the one being copied into a tile's order
/// the next is prefetched ([`prefetch`]): a tile's items, in depth order,
/// are scattered through the item array (500 sphere: -2 to -3 % of the
/// frame).
const PREFETCH_AHEAD: usize = 8;

/// One thread's view of the tiles it takes: the current tile's items in
/// processing order, the coincident ones among them, and which tiles of
/// the thread's pixel table hold lists.
#[derive(Clone, Debug, Default)]
pub(crate) struct TileQueue {
    /// The current tile's items in processing order, as their sort keys
    /// (see [`super::Chunk::refs`]; the low half is the position in the bins).
    order: Vec<u64>,
    /// The current tile's items themselves, in processing order.
    items: Vec<BinItem>,
    /// Per position of `order`: [`SOLE`], [`LEADER`] (the first of
    /// several coincident items), or the position of its leader.
    twin: Vec<u32>,
    /// Geometry keys of a long run of equal nearest depth, with positions.
    run: Vec<(Geometry, u32)>,
    /// Tiles whose entries in this thread's pixel table may hold lists of
    /// an earlier frame.
    dirty: Vec<bool>,
    /// Frame size the dirty flags refer to.
    dims: (u32, u32),
}

impl TileQueue {
    /// Starts tracking which tiles hold lists, for a frame of `dims` pixels
    /// and `tiles` tiles whose pixel table is `fresh` (just allocated,
    /// empty). A table kept from an earlier frame of another shape may
    /// hold lists anywhere: every tile is then taken as dirty.
    pub(crate) fn track(&mut self, fresh: bool, dims: (u32, u32), tiles: usize) {
        if fresh || self.dims != dims {
            self.dirty.clear();
            self.dirty.resize(tiles, !fresh);
            self.dims = dims;
        }
    }

    /// Whether tile `t`'s pixels may hold lists of an earlier frame.
    pub(crate) fn is_dirty(&self, t: usize) -> bool {
        self.dirty[t]
    }

    /// Records whether tile `t`'s pixels hold lists after this frame.
    pub(crate) fn set_dirty(&mut self, t: usize, dirty: bool) {
        self.dirty[t] = dirty;
    }

    /// Puts the items of tile `t` in processing order, front to back
    /// (nearest vertex depth, then triangle index) or in submission order,
    /// and finds the coincident ones ([`Self::twin`]); returns how many
    /// items the tile has.
    pub(crate) fn order_tile(&mut self, bins: &Bins, t: usize, front_to_back: bool) -> usize {
        self.order.clear();
        self.order.extend(bins.tile_refs(t));
        if front_to_back {
            // Items are binned in submission order, so the tile's items
            // are in index order: a stable sort by the depth half of the
            // key alone gives the order of the whole key (depth, then
            // index). A radix sort (4 passes of 8 bits) instead of a
            // comparison sort: 6 % of the instructions of the 500 sphere's
            // frame went to sorting tiles of about 2,000 items.
            radsort::sort_by_key(&mut self.order, |&key| (key >> 32) as u32);
        }
        self.items.clear();
        let order = &self.order;
        self.items.extend(order.iter().enumerate().map(|(k, &key)| {
            if let Some(&ahead) = order.get(k + PREFETCH_AHEAD) {
                prefetch(bins.item(ahead));
            }
            *bins.item(key)
        }));
        self.find_twins();
        self.order.len()
    }

    /// Item `k` of the current tile in processing order.
    #[inline]
    pub(crate) fn item(&self, k: usize) -> &BinItem {
        &self.items[k]
    }

    /// Item `k`'s index in the frame's triangles ([`Bins::items`]).
    #[inline]
    pub(crate) fn index(&self, k: usize) -> u32 {
        self.order[k] as u32
    }

    /// Item `k`'s place among coincident items: [`SOLE`], [`LEADER`], or
    /// the position of the earlier item it coincides with.
    #[inline]
    pub(crate) fn twin(&self, k: usize) -> u32 {
        self.twin[k]
    }

    /// Marks coincident items of the current tile. Coincident triangles
    /// have the same nearest vertex depth, so they sit in one run of equal
    /// depth keys (front to back: in triangle order within the run); only
    /// runs are searched, pair by pair when short, by sorting their
    /// geometry when long, so the cost stays `O(n log n)` per tile.
    fn find_twins(&mut self) {
        let n = self.order.len();
        self.twin.clear();
        self.twin.resize(n, SOLE);
        let mut a = 0;
        while a < n {
            let depth = self.order[a] >> 32;
            let mut b = a + 1;
            while b < n && self.order[b] >> 32 == depth {
                b += 1;
            }
            if b - a <= PAIRWISE_RUN {
                for k in a + 1..b {
                    // The vertices first (24 bytes, and they differ for
                    // all but coincident triangles), the plane only then.
                    let v = self.item(k).v;
                    let same = |l: usize| {
                        self.twin[l] >= LEADER
                            && self.item(l).v == v
                            && self.item(l).geometry() == self.item(k).geometry()
                    };
                    if let Some(l) = (a..k).find(|&l| same(l)) {
                        self.twin[k] = l as u32;
                        self.twin[l] = LEADER;
                    }
                }
            } else {
                let mut run = std::mem::take(&mut self.run);
                run.clear();
                run.extend((a..b).map(|k| (self.item(k).geometry(), k as u32)));
                run.sort_unstable();
                for w in 1..run.len() {
                    let ((g, k), (h, l)) = (run[w], run[w - 1]);
                    if g == h {
                        let l = self.leader(l);
                        self.twin[k as usize] = l;
                        self.twin[l as usize] = LEADER;
                    }
                }
                self.run = run;
            }
            a = b;
        }
    }

    /// The leader of the group of position `k`, during [`Self::find_twins`].
    fn leader(&self, k: u32) -> u32 {
        match self.twin[k as usize] {
            SOLE | LEADER => k,
            l => l,
        }
    }
}

#[cfg(test)]
mod tests {
    /// The stable radix sort by the depth half of the keys, on items in
    /// index order, is the order of the whole keys (ties in depth, the
    /// case that matters for coincident triangles, included).
    #[test]
    fn radix_order_is_key_order() {
        let mut next = crate::test_rng::xorshift();
        for n in [0usize, 1, 7, 300, 5000] {
            // Few distinct depths: many ties. Keys as the refs hold them:
            // depth above, index below.
            let mut order: Vec<u64> = (0..n as u64).map(|b| (next() % 37) << 32 | b).collect();
            let mut want = order.clone();
            want.sort_unstable();
            radsort::sort_by_key(&mut order, |&key| (key >> 32) as u32);
            assert_eq!(order, want, "{n} items");
        }
    }
}
