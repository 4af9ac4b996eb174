//! Newell, Newell & Sancha's list priority algorithm: sort, test, move,
//! split.
//!
//! Newell, Newell & Sancha, "A solution to the hidden surface problem",
//! Proc. ACM National Conference 1972; the form followed here is the one in
//! Sutherland, Sproull & Schumacker's survey (1974) and Foley, van Dam et
//! al. §15.5:
//!
//! 1. Sort all polygons by their farthest depth, farthest first.
//! 2. Take the head P. Compare it with every Q whose depth extent overlaps
//!    P's ([`crate::newell`], tests 1-6). If P passes against all of them,
//!    paint P and repeat.
//! 3. If some Q blocks P, and Q may itself be painted before P (tests 4-5
//!    with the roles swapped), move Q to the head and mark it.
//! 4. If Q cannot go first either (the polygons intersect), or Q is marked
//!    (it was moved before: a cycle), split one by the plane of the other
//!    and put the pieces back in sorted position.
//!
//! Two things are added to make it total. A cycle of polygons that pairwise
//! do not cut each other's planes (three sticks) has no plane to split
//! along; there the candidate is cut along an edge line of the blocker, or
//! bisected, which shrinks the overlaps until the cycle disappears. And
//! every split is counted against [`crate::PainterOptions::max_splits`]:
//! each step outputs a piece, moves a never-moved piece, or splits, so the
//! loop always ends.
//!
//! The list is kept as a stack of moved pieces (`front`, must all be
//! compared) over a B-tree sorted by farthest depth (`sorted`, farthest
//! last, cheap insertion of split pieces), which is scanned from the end
//! only while depth extents overlap: with a sorted list, test 1 settles the
//! whole remainder at once. Past the first few entries of that run, a
//! screen-space bin grid (`bins.rs`, each bin sorted the same way) yields
//! only the entries whose bounding boxes can meet the candidate's, in the
//! same order, so the blocker found (`blocker.rs`) is the same as with a
//! full scan. Splitting a pair is in `resolve.rs`; this file holds the list
//! and the loop.

use std::cell::RefCell;
use std::collections::BTreeMap;

use hider_geom::star::{NO_STAR, fixed_star_pairs, fixed_stars};
use hider_scene::{Error, Result, ScreenScene};

use crate::bins::{Grid, Key, depth_bits};
use crate::centres::{CentreIndex, Centres};
use crate::cull::HiZ;
use crate::newell::Extent;
use crate::options::{PainterOptions, SPLIT_BUDGET};
use crate::piece::Piece;
use crate::stats::PainterStats;
use crate::trace::{PainterTrace, TraceEvent};

/// Where a piece sits in the list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Slot {
    /// Index into `front`.
    Front(usize),
    /// Key in `sorted`.
    Sorted(Key),
}

/// A piece and where it sits.
pub(crate) type At = (Slot, u32);

/// The ordering stage and its scratch memory, kept between frames.
#[derive(Clone, Debug, Default)]
pub(crate) struct Orderer {
    /// Every piece made this frame (split parents stay, unused, with
    /// their outline and cuts freed).
    pub pieces: Vec<Piece>,
    /// Paint order, indices into `pieces`, farthest first.
    pub order: Vec<u32>,
    /// The extents of every piece, by piece index (tests 1-3 read these
    /// without touching the arena).
    pub extents: Vec<Extent>,
    /// Pieces not yet painted nor moved, by key (farthest last).
    pub sorted: BTreeMap<Key, u32>,
    /// The same pieces by screen bin, those covering several centres only
    /// (the others are in `index`).
    pub grid: Grid,
    /// Which centres each piece covers, by piece index.
    pub centres: Vec<Centres>,
    /// The pieces covering exactly one centre, not yet painted, by centre.
    pub index: CentreIndex,
    /// Each piece's key in `sorted` (meaningful while it is there).
    pub keys: Vec<Key>,
    /// Next tie-break for an insertion (decreasing).
    next_tie: i64,
    /// Moved pieces, the last moved on top.
    pub front: Vec<u32>,
    /// Scratch for the bin query.
    pub near: Vec<(Key, u32)>,
    /// The occluder depths of the frame's triangles.
    pub hiz: HiZ,
    /// Per piece index, whether it was culled (hidden everywhere).
    pub hidden: Vec<bool>,
    /// The trace being recorded (only with [`PainterOptions::trace`]).
    pub tracer: Option<RefCell<PainterTrace>>,
    /// The trace of the last frame ordered with [`PainterOptions::trace`].
    pub traced: Option<PainterTrace>,
    /// Entries compared one by one before the grid takes over (tests
    /// only; `None` is the default prefix of the blocker search).
    pub linear_scan: Option<usize>,
    /// Per triangle (the first pieces), the stars it belongs to
    /// ([`hider_geom::star`]): its mates are kept apart in the bins.
    pub stars_of: Vec<[u32; 3]>,
    /// Where each triangle's star partners start in `partners` (one more
    /// than the triangles of stars; empty without stars).
    pub partners_start: Vec<usize>,
    /// The star partners of every triangle, triangle after triangle: the
    /// mates whose sectors meet its own at a shared star vertex, the only
    /// mates that can overlap it on the screen.
    pub partners: Vec<u32>,
    /// Star mates from the bins like any other piece, no partners (tests
    /// set it to compare with the bins alone).
    pub no_stars: bool,
}

/// Width of a grid bin in mean piece bounding boxes. Each bin a candidate
/// meets costs a cache miss or two at its end (bins are separate lists,
/// visited in depth order, not screen order), while the entries scanned
/// within a bin are contiguous and mostly settled by their inline extents:
/// on two intersecting 100 x 100 height fields (the `surfaces` example)
/// bins three boxes wide order about 15% faster than bins one box wide,
/// and random soups and spheres are as fast either way.
const BIN_BOXES: f64 = 3.0;

/// Bytes of the piece arena now and at its peak.
#[derive(Clone, Copy, Debug)]
struct Arena {
    now: u64,
    peak: u64,
}

impl Orderer {
    /// Orders the scene's triangles, splitting where needed, into
    /// `self.order`, within the budgets of `options`.
    pub fn run(
        &mut self,
        scene: &ScreenScene,
        options: &PainterOptions,
        stats: &mut PainterStats,
    ) -> Result<()> {
        let max_splits = options.split_budget(scene.tris.len() as u64);
        self.tracer = options.trace.then(|| {
            let mut t = self.traced.take().unwrap_or_default();
            t.clear();
            RefCell::new(t)
        });
        self.traced = None;
        let mut arena = self.start(scene, options, stats)?;
        let mut steps = 0u32;
        loop {
            // Every 16 steps (blocker searches, moves, splits): a poll with
            // a deadline reads the clock, 1% of the steps' instructions on
            // small scenes when made at every step.
            if steps.is_multiple_of(16) {
                options.cancel.poll()?;
            }
            steps = steps.wrapping_add(1);
            let (cslot, p) = match (self.front.last(), self.sorted.last_key_value()) {
                (Some(&c), _) => (Slot::Front(self.front.len() - 1), c),
                (None, Some((&key, &id))) => (Slot::Sorted(key), id),
                (None, None) => break,
            };
            let Some((qslot, q, blocked)) = self.find_blocker(cslot, p, scene, stats) else {
                self.remove(cslot);
                self.unindex(p);
                self.order.push(p);
                self.note(|| TraceEvent::Painted { piece: p });
                continue;
            };
            if blocked.reverse_ok() && !self.pieces[q as usize].moved {
                self.remove(qslot);
                self.pieces[q as usize].moved = true;
                self.front.push(q);
                stats.moves += 1;
                self.note(|| TraceEvent::Move { piece: q });
                continue;
            }
            if self.pieces[q as usize].moved {
                self.note(|| TraceEvent::CycleBroken { p, q });
            }
            if stats.plane_splits + stats.line_splits >= max_splits {
                return Err(Error::Limit {
                    what: SPLIT_BUDGET,
                    value: max_splits.saturating_add(1),
                    limit: max_splits,
                });
            }
            let before = self.pieces.len();
            let freed = self.split((cslot, p), (qslot, q), &blocked, scene, stats)?;
            arena.now += self.pieces[before..]
                .iter()
                .map(|p| p.bytes() as u64)
                .sum::<u64>();
            arena.peak = arena.peak.max(arena.now);
            arena.now -= freed;
            if arena.now > options.max_bytes {
                return Err(Error::Budget {
                    what: "painter piece memory in bytes",
                    value: arena.now,
                    limit: options.max_bytes,
                });
            }
        }
        stats.splits = stats.plane_splits + stats.line_splits;
        stats.pieces_out = self.order.len() as u64;
        // The tree's nodes hold about one key and id per entry.
        let lists = self.extents.capacity()
            * (std::mem::size_of::<Extent>()
                + std::mem::size_of::<Centres>()
                + std::mem::size_of::<Key>())
            + self.grid.bytes()
            + (self.front.capacity() + self.order.capacity()) * 4;
        stats.peak_bytes = arena.peak + lists as u64;
        if let Some(t) = self.tracer.take() {
            let mut t = t.into_inner();
            t.order.clone_from(&self.order);
            t.prims.extend(self.pieces.iter().map(|p| p.prim));
            self.traced = Some(t);
        }
        Ok(())
    }

    /// Records an event when tracing (the closure runs only then).
    #[inline]
    pub(crate) fn note(&self, event: impl FnOnce() -> TraceEvent) {
        if let Some(t) = &self.tracer {
            t.borrow_mut().events.push(event());
        }
    }

    /// Fills the arena with the scene's triangles, sorted and binned, and
    /// returns its size.
    fn start(
        &mut self,
        scene: &ScreenScene,
        options: &PainterOptions,
        stats: &mut PainterStats,
    ) -> Result<Arena> {
        self.pieces.clear();
        self.order.clear();
        self.extents.clear();
        self.sorted.clear();
        self.front.clear();
        self.centres.clear();
        self.index.clear();
        self.keys.clear();
        if scene.tris.len() >= u32::MAX as usize {
            return Err(Error::Limit {
                what: "painter triangles",
                value: scene.tris.len() as u64,
                limit: u64::from(u32::MAX) - 1,
            });
        }
        self.pieces.reserve(scene.tris.len());
        for (k, tri) in scene.tris.iter().enumerate() {
            self.pieces.push(Piece::from_tri(tri, k as u32));
        }
        self.extents.extend(self.pieces.iter().map(Extent::of));
        self.hiz.build(scene, options.cull_hidden, options.cancel);
        options.cancel.poll()?;
        self.hidden.clear();
        for (k, p) in self.pieces.iter().enumerate() {
            options.cancel.poll_every(k)?;
            self.hidden.push(self.hiz.hides(p));
        }
        stats.culled = self.hidden.iter().filter(|&&h| h).count() as u64;
        for (k, _) in self.hidden.iter().enumerate().filter(|(_, h)| **h) {
            self.note(|| TraceEvent::Culled { piece: k as u32 });
        }
        self.index_all(scene);
        self.find_stars(scene);
        stats.triangles = scene.tris.len() as u64;
        let bytes: u64 = self.pieces.iter().map(|p| p.bytes() as u64).sum();
        // Bins a few mean bounding boxes wide ([`BIN_BOXES`]), so that a
        // typical piece meets one to four of them.
        let n = self.extents.len().max(1) as f64;
        let side = self
            .extents
            .iter()
            .map(|e| (e.max.x - e.min.x) + (e.max.y - e.min.y))
            .sum::<f64>()
            / (2.0 * n)
            * BIN_BOXES;
        self.grid
            .reset(scene.viewport.width, scene.viewport.height, side);
        self.keys.extend(
            self.extents
                .iter()
                .enumerate()
                .map(|(k, e)| (depth_bits(e.zmax), -(k as i64))),
        );
        self.grid.insert_all(
            self.extents
                .iter()
                .zip(&self.keys)
                .zip(0..)
                .filter(|&(_, k)| self.centres[k as usize] == Centres::Many)
                .map(|((e, &key), k)| {
                    let group = self.stars_of.get(k as usize).map_or(NO_STAR, |s| s[0]);
                    (key, k, e, group)
                }),
        );
        // Bulk-loaded from the keys (sorted first): no search per entry.
        self.sorted = self
            .keys
            .iter()
            .zip(0..)
            .filter(|&(_, k)| !self.hidden[k as usize])
            .map(|(&key, k)| (key, k))
            .collect();
        self.next_tie = -(self.pieces.len() as i64) - 1;
        Ok(Arena {
            now: bytes,
            peak: bytes,
        })
    }

    /// Takes the piece at `slot` out of the list.
    pub fn remove(&mut self, slot: Slot) {
        match slot {
            Slot::Front(k) => {
                self.front.remove(k);
            }
            Slot::Sorted(key) => {
                // Most often the farthest entry, painted next.
                let last = self.sorted.last_key_value().is_some_and(|(&k, _)| k == key);
                let removed = if last {
                    self.sorted.pop_last().map(|(_, id)| id)
                } else {
                    self.sorted.remove(&key)
                };
                if let Some(id) = removed
                    && self.centres[id as usize] == Centres::Many
                {
                    let group = self.group(id);
                    self.grid.remove(key, &self.extents[id as usize], group);
                }
            }
        }
    }

    /// The star whose list in the bins holds piece `id`, or [`NO_STAR`].
    pub(crate) fn group(&self, id: u32) -> u32 {
        self.stars_of.get(id as usize).map_or(NO_STAR, |s| s[0])
    }

    /// The star partners of piece `id` (none for a cut piece).
    pub(crate) fn partners_of(&self, id: u32) -> &[u32] {
        let k = id as usize;
        if k + 1 < self.partners_start.len() {
            &self.partners[self.partners_start[k]..self.partners_start[k + 1]]
        } else {
            &[]
        }
    }

    /// The stars of the triangles that cover several centres, and each
    /// one's partners ([`hider_geom::star::fixed_star_pairs`]). Only
    /// uncut triangles are members: two of them sharing a vertex whose
    /// sectors do not meet have disjoint interiors, which test 6 settles
    /// exactly, so such a mate never blocks and the bins may skip it.
    fn find_stars(&mut self, scene: &ScreenScene) {
        self.stars_of.clear();
        self.partners_start.clear();
        self.partners.clear();
        if self.no_stars {
            return;
        }
        let n = scene.tris.len();
        let mut stars = fixed_stars(n, |k| {
            (self.centres[k] == Centres::Many).then_some(scene.tris[k].v)
        });
        // Dense stars are dissolved first.
        let pairs = fixed_star_pairs(&mut stars, |t| scene.tris[t as usize].v);
        if stars.is_empty() {
            return;
        }
        self.stars_of.extend((0..n).map(|k| stars.stars_of(k)));
        self.partners_start.resize(n + 1, 0);
        for &(a, b) in &pairs {
            self.partners_start[a as usize + 1] += 1;
            self.partners_start[b as usize + 1] += 1;
        }
        for k in 0..n {
            self.partners_start[k + 1] += self.partners_start[k];
        }
        let mut fill = self.partners_start.clone();
        self.partners.resize(self.partners_start[n], 0);
        for &(a, b) in &pairs {
            for (x, y) in [(a, b), (b, a)] {
                self.partners[fill[x as usize]] = y;
                fill[x as usize] += 1;
            }
        }
    }

    /// Puts piece `id` back into the sorted list, before the entries of
    /// equal depth.
    pub fn insert_sorted(&mut self, id: u32) {
        let extent = self.extents[id as usize];
        let key = (depth_bits(extent.zmax), self.next_tie);
        self.next_tie -= 1;
        self.sorted.insert(key, id);
        if self.keys.len() <= id as usize {
            self.keys.resize(id as usize + 1, key);
        }
        self.keys[id as usize] = key;
        if self.centres[id as usize] == Centres::Many {
            // A moved triangle put back keeps its star's list.
            let group = self.group(id);
            self.grid.insert(key, id, &extent, group);
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use hider_scene::{PrepareOptions, View, prepare, procedural};

    /// Orders `scene` with the blocker search's linear prefix
    /// `linear_scan`, and star partners unless `no_stars`: the pieces in
    /// painting order and the counters.
    pub(crate) fn ordered(
        scene: &ScreenScene,
        linear_scan: usize,
        no_stars: bool,
    ) -> (Vec<Piece>, PainterStats) {
        let mut o = Orderer {
            linear_scan: Some(linear_scan),
            no_stars,
            ..Orderer::default()
        };
        let mut stats = PainterStats::default();
        o.run(scene, &PainterOptions::default(), &mut stats)
            .unwrap();
        let pieces = o
            .order
            .iter()
            .map(|&k| o.pieces[k as usize].clone())
            .collect();
        (pieces, stats)
    }

    /// The bin grid visits exactly the entries of the depth-overlapping
    /// run that tests 2-3 could not settle, in the same order: the grid
    /// from the first entry on, after the default linear prefix, or never
    /// (a full scan, the algorithm before the grid) give the same pieces in
    /// the same order, with the same splits.
    #[test]
    fn bin_grid_gives_the_same_order_as_a_full_scan() {
        for (scene, size) in [
            (procedural::random_soup(1500, 7), 96),
            (procedural::random_soup(400, 11), 40),
            (procedural::uv_sphere(20), 64),
        ] {
            let view = View::for_scene(&scene, size, size).unwrap();
            let s = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
            let (full, full_stats) = ordered(&s, usize::MAX, false);
            for linear in [0, 1, crate::blocker::LINEAR_SCAN] {
                let (binned, stats) = ordered(&s, linear, false);
                assert_eq!(binned.len(), full.len());
                assert!(binned == full, "linear prefix {linear}: order differs");
                assert_eq!(stats.splits, full_stats.splits);
                assert_eq!(stats.moves, full_stats.moves);
                assert!(stats.comparisons <= full_stats.comparisons);
            }
        }
    }
}
