//! The sort key of the unpainted list and a screen-space bin grid over it.
//!
//! The ordering stage keeps its unpainted pieces sorted by farthest depth
//! ([`Key`]). A candidate is compared only with the pieces whose depth
//! extent overlaps its own, and past the first few of those only with the
//! ones whose bounding box can meet its own: the [`Grid`] lists, per
//! screen bin and in key order, the pieces whose box meets that bin.
//!
//! The triangles of a star (a fan, a cone, the pole of a UV sphere: many
//! triangles around one vertex) all meet the bins of that vertex, so a
//! candidate of the star would list all of its mates; they are kept in
//! per-star lists in each bin ([`Grid::star_bins`]), which a candidate of
//! the same star skips (its mates that can overlap it come from the
//! star's sector pairs instead, see `order.rs`).

use hider_geom::star::NO_STAR;

use crate::newell::{Extent, TOUCH};

/// Position of a piece in the sorted list: its farthest depth (as an
/// order-preserving bit pattern), then a tie-break. Initial pieces of equal
/// depth put the higher triangle index first (so the lower one is painted
/// first); every later insertion gets a tie-break below all earlier ones,
/// which places it before the entries of equal depth, as an insertion at
/// the partition point of a sorted vector would.
pub(crate) type Key = (u64, i64);

/// The bit pattern of `z` as an unsigned integer in the order of
/// [`f64::total_cmp`].
pub(crate) fn depth_bits(z: f64) -> u64 {
    let b = z.to_bits();
    if b >> 63 == 1 { !b } else { b | (1 << 63) }
}

/// Largest number of bins along a side of the grid.
const MAX_BINS: usize = 256;

/// A screen-space bin grid over the sorted pieces: each bin lists, sorted
/// by [`Key`], the sorted pieces whose bounding box meets it.
#[derive(Clone, Debug, Default)]
pub(crate) struct Grid {
    /// Bins per row.
    pub cols: usize,
    /// Bins per column.
    rows: usize,
    /// Bins per pixel.
    scale: f64,
    /// The bins, row-major: the pieces of no star.
    pub bins: Vec<Vec<BinEntry>>,
    /// The bins, row-major: the pieces of stars, one list per star (the
    /// piece's first star), each sorted by [`Key`]. Empty when the frame
    /// has no star.
    pub star_bins: Vec<Vec<(u32, Vec<BinEntry>)>>,
}

/// A piece in a bin, with what the query needs kept inline so that bins
/// are scanned without touching the arena or the extent table.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BinEntry {
    /// The piece's key in the sorted list.
    pub key: Key,
    /// The piece's extents.
    pub extent: Extent,
    /// The piece's index in the arena.
    pub id: u32,
    /// The first bin (column, row) of the piece, to report it once.
    pub first: (u16, u16),
}

/// Bins as (first column, last column, first row, last row), inclusive.
pub(crate) type Span = (usize, usize, usize, usize);

impl BinEntry {
    /// The entry of piece `id` under `key` with box `e`, which meets the
    /// bins `span`.
    fn new(key: Key, id: u32, e: &Extent, (x0, _, y0, _): Span) -> Self {
        BinEntry {
            key,
            extent: *e,
            id,
            first: (x0 as u16, y0 as u16),
        }
    }
}

impl Grid {
    /// Empties the grid and sizes it for `width` x `height` pixels with
    /// bins about `side` pixels wide.
    pub fn reset(&mut self, width: u32, height: u32, side: f64) {
        let side = if side.is_finite() { side.max(1.0) } else { 1.0 };
        let extent = f64::from(width.max(height).max(1));
        let n = ((extent / side).ceil() as usize).clamp(1, MAX_BINS);
        self.scale = n as f64 / extent;
        self.cols = ((f64::from(width) * self.scale).ceil() as usize).clamp(1, n);
        self.rows = ((f64::from(height) * self.scale).ceil() as usize).clamp(1, n);
        for b in &mut self.bins {
            b.clear();
        }
        self.bins.resize_with(self.cols * self.rows, Vec::new);
        self.star_bins.clear();
    }

    /// The list of bin `b` that holds the pieces of star `group`
    /// ([`NO_STAR`]: the pieces of no star).
    fn list(&mut self, b: usize, group: u32) -> &mut Vec<BinEntry> {
        if group == NO_STAR {
            return &mut self.bins[b];
        }
        if self.star_bins.is_empty() {
            self.star_bins.resize_with(self.bins.len(), Vec::new);
        }
        let lists = &mut self.star_bins[b];
        let at = match lists.iter().position(|(g, _)| *g == group) {
            Some(at) => at,
            None => {
                lists.push((group, Vec::new()));
                lists.len() - 1
            }
        };
        &mut lists[at].1
    }

    /// The bins a box widened by [`TOUCH`] meets: columns and rows,
    /// inclusive. Clamping keeps it a superset: boxes whose bin ranges are
    /// disjoint are more than [`TOUCH`] apart, which tests 2 and 3 settle
    /// for cut pieces too.
    pub fn span(&self, e: &Extent) -> Span {
        let at =
            |v: f64, n: usize| ((v * self.scale).floor() as i64).clamp(0, n as i64 - 1) as usize;
        (
            at(e.min.x - TOUCH, self.cols),
            at(e.max.x + TOUCH, self.cols),
            at(e.min.y - TOUCH, self.rows),
            at(e.max.y + TOUCH, self.rows),
        )
    }

    /// Calls `f` on the list of star `group` in each bin of `span`.
    fn for_each_bin(
        &mut self,
        (x0, x1, y0, y1): Span,
        group: u32,
        mut f: impl FnMut(&mut Vec<BinEntry>),
    ) {
        for y in y0..=y1 {
            for x in x0..=x1 {
                let b = y * self.cols + x;
                f(self.list(b, group));
            }
        }
    }

    /// Lists piece `id` of star `group` ([`NO_STAR`]: of none) under `key`
    /// in every bin its box `e` meets.
    pub fn insert(&mut self, key: Key, id: u32, e: &Extent, group: u32) {
        let span = self.span(e);
        let entry = BinEntry::new(key, id, e, span);
        self.for_each_bin(span, group, |bin| {
            let at = bin.partition_point(|b| b.key < key);
            bin.insert(at, entry);
        });
    }

    /// Lists many pieces at once, `(key, id, box, star)` in any order
    /// (star [`NO_STAR`] for a piece of none): each bin is sorted once at
    /// the end instead of searched per entry.
    pub fn insert_all<'a>(&mut self, entries: impl Iterator<Item = (Key, u32, &'a Extent, u32)>) {
        for (key, id, e, group) in entries {
            let span = self.span(e);
            let entry = BinEntry::new(key, id, e, span);
            self.for_each_bin(span, group, |bin| bin.push(entry));
        }
        for bin in &mut self.bins {
            bin.sort_unstable_by_key(|b| b.key);
        }
        for (_, bin) in self.star_bins.iter_mut().flatten() {
            bin.sort_unstable_by_key(|b| b.key);
        }
    }

    /// Removes the piece of star `group` listed under `key` with box `e`.
    pub fn remove(&mut self, key: Key, e: &Extent, group: u32) {
        self.for_each_bin(self.span(e), group, |bin| {
            // The piece painted next is the farthest left, the last entry of
            // each of its bins: no search, no shift.
            if bin.last().is_some_and(|b| b.key == key) {
                bin.pop();
            } else if let Ok(at) = bin.binary_search_by(|b| b.key.cmp(&key)) {
                bin.remove(at);
            }
        });
    }

    /// Bytes held (capacity).
    pub fn bytes(&self) -> usize {
        self.bins.capacity() * std::mem::size_of::<Vec<BinEntry>>()
            + self
                .bins
                .iter()
                .map(|b| b.capacity() * std::mem::size_of::<BinEntry>())
                .sum::<usize>()
            + self
                .star_bins
                .iter()
                .map(|b| {
                    b.capacity() * std::mem::size_of::<(u32, Vec<BinEntry>)>()
                        + b.iter()
                            .map(|(_, l)| l.capacity() * std::mem::size_of::<BinEntry>())
                            .sum::<usize>()
                })
                .sum::<usize>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn depth_bits_follow_the_total_order() {
        let zs = [-1.5, -0.0, 0.0, 1e-300, 0.25, 0.5, 1.0, f64::INFINITY];
        for w in zs.windows(2) {
            assert!(depth_bits(w[0]) < depth_bits(w[1]), "{w:?}");
        }
    }
}
