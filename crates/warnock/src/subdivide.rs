//! The subdivision loop: classify, cull, decide or split, with an explicit
//! stack and one arena of candidate lists.
//!
//! Warnock's procedure is recursive: look at a window; if what it holds is
//! simple enough, draw it, else split it into four and look at each. Here
//! the recursion is a loop over an explicit stack, so a 16384-pixel window
//! (14 levels to a pixel) or any sub-pixel depth cannot overflow the thread
//! stack, and it costs no allocation per region:
//!
//! - The candidate lists live in one arena (`Vec<u32>` of triangle
//!   indices), used as a stack of lists. A region reads its parent's list
//!   and appends its survivors; its children all read that one survivor
//!   list. The traversal is depth-first, so when a region is popped every
//!   list above its own belongs to a finished sibling subtree and the arena
//!   is truncated back to it. The arena never holds more than one list per
//!   level on the current path.
//! - A list is copied only once a candidate drops out of it: a region all
//!   of whose candidates survive hands its parent's list on as it is. On a
//!   pile of tiny triangles over one pixel every level keeps all of them in
//!   the one quadrant holding that pixel, and nothing is copied.
//! - A region also hands its children the bounding box of its survivors: a
//!   child none of whose samples that box reaches is empty, settled without
//!   looking at a candidate. The quadrants beside a pile are settled so, and
//!   when the box reaches one quadrant only (and cannot surround it), that
//!   quadrant is split in turn without a look at its list.
//! - Lists keep triangle order, so "the earlier triangle wins a depth tie"
//!   stays true at every level.
//!
//! What a decided region means for the output is up to a `Sink`: the
//! pixel-centre frame, a pixel with sub-pixel samples, or a pixel's sample
//! buffer.

use crate::classify::{
    BoundingBox, Class, CornerDepths, Setups, Tri, certainly_behind, classify_in_box,
};
use crate::grid::{Grid, Region, SampleRect};
use crate::stats::{Rule, WarnockStats};
use crate::trace::{Look, Outcome, WindowClasses};

/// Receives the decisions of the subdivision loop.
pub(crate) trait Sink {
    /// `t` covers every sample of `r` and is in front of every other
    /// polygon there: draw it over the whole region.
    fn fill(&mut self, grid: &Grid, r: &Region, t: Tri<'_>, stats: &mut WarnockStats);

    /// `t` is the only polygon reaching `r`: draw the samples it covers.
    fn single(&mut self, grid: &Grid, r: &Region, t: Tri<'_>, stats: &mut WarnockStats);

    /// The one sample of cell `(u, v)` shows primitive `prim` at `depth`.
    fn sample(&mut self, u: u32, v: u32, prim: u32, depth: f64, stats: &mut WarnockStats);

    /// `r` is one cell holding several samples and several polygons remain:
    /// resolve it and say by which rule. Only grids with several samples per
    /// cell reach this; the default resolves the cell at its first sample.
    fn resolve_cell(
        &mut self,
        grid: &Grid,
        r: &Region,
        candidates: &[u32],
        setups: &Setups,
        _level: usize,
        stats: &mut WarnockStats,
    ) -> Rule {
        let (x, y) = (grid.sample_x(r.u0), grid.sample_y(r.v0));
        if let Some((t, d)) = nearest_at(candidates, setups, x, y, stats) {
            self.sample(r.u0, r.v0, setups.get(t).prim(), d, stats);
        }
        Rule::Sample
    }

    /// `r` was decided by `rule` at `level` (for the region record).
    fn leaf(&mut self, _r: &Region, _rule: Rule, _level: usize) {}

    /// `r`, at `level`, was cut: no rule settled it (for the region record).
    fn cut(&mut self, _r: &Region, _level: usize) {}
}

/// A candidate list: a run of the arena.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct List {
    start: usize,
    len: usize,
}

impl List {
    fn end(&self) -> usize {
        self.start + self.len
    }
}

/// A region waiting on the stack, with its candidate list.
#[derive(Clone, Copy, Debug)]
struct Entry {
    region: Region,
    list: List,
    level: usize,
}

/// What classification and culling left of a region's list.
#[derive(Clone, Copy, Debug)]
struct Survivors {
    /// The surviving list: the parent's when nothing dropped out, else a
    /// new list at the end of the arena.
    list: List,
    /// The surrounder nearest at the centre, with its corner depths.
    front: Option<(u32, CornerDepths)>,
    /// How many the surrounder culled.
    culled: u64,
    /// The bounding box of the classified survivors (before culling, so
    /// possibly larger than the culled list needs).
    bounds: BoundingBox,
}

/// Where a subdivision starts: regions of a grid at a level.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Roots<'a> {
    /// The grid the regions are in.
    pub grid: &'a Grid,
    /// The regions, subdivided in order.
    pub regions: &'a [Region],
    /// Their subdivision level (0 is the whole window).
    pub level: usize,
}

/// The reusable state of the loop: the candidate arena and the region
/// stack, kept between frames.
#[derive(Clone, Debug, Default)]
pub(crate) struct Subdivider {
    arena: Vec<u32>,
    stack: Vec<Entry>,
    peak: usize,
    /// The windows and classes, when recording (the pixel pass only).
    pub(crate) record: WindowClasses,
    /// Polled every [`POLL_EVERY`](hider_scene::cancel::POLL_EVERY)
    /// regions: a stopped run leaves its regions undecided (the caller
    /// returns the error).
    pub(crate) cancel: hider_scene::Cancel,
}

impl Subdivider {
    /// Largest number of candidate indices held at once since the last
    /// [`Self::reset_peak`].
    pub(crate) fn peak(&self) -> usize {
        self.peak
    }

    /// Starts a new peak measurement.
    pub(crate) fn reset_peak(&mut self) {
        self.peak = 0;
    }

    /// Bytes held by the arena and the stack.
    pub(crate) fn bytes(&self) -> usize {
        self.arena.capacity() * std::mem::size_of::<u32>()
            + self.stack.capacity() * std::mem::size_of::<Entry>()
            + self.record.bytes()
    }

    /// Subdivides each of the `roots`, starting from the candidate list
    /// `initial` (indices into `setups`, in drawing order), and hands every
    /// decision to `sink`.
    pub(crate) fn run<S: Sink>(
        &mut self,
        roots: Roots<'_>,
        initial: impl IntoIterator<Item = u32>,
        setups: &Setups,
        sink: &mut S,
        stats: &mut WarnockStats,
    ) {
        self.arena.clear();
        self.stack.clear();
        self.arena.extend(initial);
        let list = List {
            start: 0,
            len: self.arena.len(),
        };
        stats.candidates_copied += list.len as u64;
        for &region in roots.regions.iter().rev() {
            self.stack.push(Entry {
                region,
                list,
                level: roots.level,
            });
        }
        let grid = roots.grid;
        let one_sample = grid.one_sample_per_cell();
        let mut regions = 0usize;
        while let Some(e) = self.stack.pop() {
            regions += 1;
            if self.cancel.poll_every(regions).is_err() {
                self.stack.clear();
                break;
            }
            self.arena.truncate(e.list.end());
            stats.visit(e.level);
            if one_sample && e.region.is_single_cell() {
                let list = &self.arena[e.list.start..];
                stats.sample_resolves += 1;
                stats.examined(e.level, list.len());
                let w = self.record.open(&e.region, e.level, Look::Sample);
                let rule =
                    resolve_sample(grid, &e.region, list, setups, sink, stats, &mut self.record);
                self.record.close(w, Outcome::Decided(rule));
                stats.decided[rule as usize] += 1;
                sink.leaf(&e.region, rule, e.level);
                continue;
            }
            let w = self.record.open(&e.region, e.level, Look::Classified);
            let rect = grid.sample_rect(&e.region);
            let (list, front, bounds) = self.classify(&e, &rect, setups, stats);
            let (list, culled) = match front {
                Some((s, sd)) => self.cull_behind(&e, list, s, &sd, &rect, setups, stats),
                None => (list, 0),
            };
            self.peak = self.peak.max(self.arena.len());
            let survivors = Survivors {
                list,
                front,
                culled,
                bounds,
            };
            let decided = self.decide(grid, &e, survivors, setups, sink, stats);
            self.record
                .close(w, decided.map_or(Outcome::Cut, Outcome::Decided));
            if let Some(rule) = decided {
                stats.decided[rule as usize] += 1;
                sink.leaf(&e.region, rule, e.level);
            }
        }
    }

    /// The candidates of `list` that `keep` accepts, in order. A list of
    /// `e`'s own (made by this region, at the end of the arena) is
    /// compacted in place; the list `e` was handed is never written: it is
    /// returned as it is when every candidate is kept, and copied from the
    /// first one dropped (the kept ones before it in one block).
    fn filter(
        arena: &mut Vec<u32>,
        e: &Entry,
        list: List,
        stats: &mut WarnockStats,
        mut keep: impl FnMut(u32, &mut WarnockStats) -> bool,
    ) -> List {
        if list != e.list {
            let mut kept = list.start;
            for k in list.start..list.end() {
                let t = arena[k];
                if keep(t, stats) {
                    arena[kept] = t;
                    kept += 1;
                }
            }
            arena.truncate(kept);
            return List {
                start: list.start,
                len: kept - list.start,
            };
        }
        let Some(first_out) = (list.start..list.end()).find(|&k| !keep(arena[k], stats)) else {
            return list;
        };
        let out = arena.len();
        arena.extend_from_within(list.start..first_out);
        for k in first_out + 1..list.end() {
            let t = arena[k];
            if keep(t, stats) {
                arena.push(t);
            }
        }
        let len = arena.len() - out;
        stats.candidates_copied += len as u64;
        List { start: out, len }
    }

    /// Classifies the candidates `e` was handed against the region's
    /// samples `rect`, keeping all but the disjoint ones; returns them, the
    /// surrounder nearest at the centre, if any (if any surrounder hides
    /// everything, that one does), and the survivors' bounding box.
    fn classify(
        &mut self,
        e: &Entry,
        rect: &SampleRect,
        setups: &Setups,
        stats: &mut WarnockStats,
    ) -> (List, Option<(u32, CornerDepths)>, BoundingBox) {
        let mut front: Option<(u32, CornerDepths)> = None;
        let mut bounds = BoundingBox::EMPTY;
        stats.examined(e.level, e.list.len);
        let list = Self::filter(&mut self.arena, e, e.list, stats, |t, stats| {
            let setup = &setups.tris[t as usize];
            let b = setup.bounding_box();
            let class = classify_in_box(setup, &b, rect);
            stats.classified(class);
            self.record.class(t, class);
            match class {
                Class::Disjoint => return false,
                Class::Surrounding => {
                    let d = CornerDepths::new(&setups.depth[t as usize], rect);
                    stats.depth_evaluations += 4;
                    if front.is_none_or(|(_, f)| d.sum() < f.sum()) {
                        front = Some((t, d));
                    }
                }
                Class::Contained | Class::Intersecting => {}
            }
            bounds = bounds.union(&b);
            true
        });
        if let Some((s, _)) = front {
            self.record.front(s);
        }
        (list, front, bounds)
    }

    /// Culls from `list` what the surrounder `s` (with corner depths `sd`)
    /// hides at every sample of the region: hidden here, hidden in every
    /// subregion too. Returns what is left and how many went.
    #[allow(
        clippy::too_many_arguments,
        reason = "the loop's state, the region and the surrounder, all distinct"
    )]
    fn cull_behind(
        &mut self,
        e: &Entry,
        list: List,
        s: u32,
        sd: &CornerDepths,
        rect: &SampleRect,
        setups: &Setups,
        stats: &mut WarnockStats,
    ) -> (List, u64) {
        let mut culled = 0;
        let list = Self::filter(&mut self.arena, e, list, stats, |t, stats| {
            if t == s {
                return true;
            }
            let d = CornerDepths::new(&setups.depth[t as usize], rect);
            stats.depth_evaluations += 4;
            let behind = certainly_behind(&d, sd);
            if behind {
                self.record.hidden(t);
            }
            culled += u64::from(behind);
            !behind
        });
        stats.culled_behind_surrounder += culled;
        (list, culled)
    }

    /// Decides region `e` from what classification and culling left: the
    /// rule that decided it, or `None` when it was split into children
    /// pushed on the stack (children the survivors' bounding box misses are
    /// settled empty on the spot).
    fn decide<S: Sink>(
        &mut self,
        grid: &Grid,
        e: &Entry,
        survivors: Survivors,
        setups: &Setups,
        sink: &mut S,
        stats: &mut WarnockStats,
    ) -> Option<Rule> {
        let Survivors {
            list,
            front,
            culled,
            bounds,
        } = survivors;
        let candidates = &self.arena[list.start..list.end()];
        let rule = match (list.len, front) {
            (0, _) => Rule::Empty,
            (1, Some((s, _))) => {
                sink.fill(grid, &e.region, setups.get(s), stats);
                if culled > 0 {
                    Rule::SurrounderInFront
                } else {
                    Rule::SurrounderAlone
                }
            }
            (1, None) => {
                sink.single(grid, &e.region, setups.get(candidates[0]), stats);
                Rule::SinglePolygon
            }
            _ => {
                if front.is_some() {
                    stats.surrounder_undecided += 1;
                }
                if e.region.quadrants().1 == 0 {
                    sink.resolve_cell(grid, &e.region, candidates, setups, e.level, stats)
                } else {
                    sink.cut(&e.region, e.level);
                    self.split(grid, e.region, e.level, list, &bounds, sink, stats);
                    return None;
                }
            }
        };
        Some(rule)
    }

    /// Splits `region` (at `level`, holding `list`, whose bounding box is
    /// `bounds`) and pushes the children the box reaches; the others are
    /// settled empty on the spot.
    ///
    /// When the box reaches one child only and cannot hold all of its
    /// samples, that child is split in turn without classifying its list
    /// (counted in [`WarnockStats::passed_through`]). No candidate can
    /// surround it (a surrounder's box holds every sample), so no rule
    /// could settle it whole unless classification left one candidate or
    /// none; and whatever happens below, the region finally pushed
    /// classifies the list against itself, dropping everything the skipped
    /// levels would have dropped (what misses a region by the rectangle
    /// tests misses each of its subregions), so the picture is the same. A
    /// pile over one pixel goes from the window straight down to that
    /// pixel.
    #[allow(
        clippy::too_many_arguments,
        reason = "the loop's state, the region and its list, all distinct"
    )]
    fn split<S: Sink>(
        &mut self,
        grid: &Grid,
        mut region: Region,
        mut level: usize,
        list: List,
        bounds: &BoundingBox,
        sink: &mut S,
        stats: &mut WarnockStats,
    ) {
        loop {
            let (children, n) = region.quadrants();
            level += 1;
            let mut reached = [false; 4];
            for (k, child) in children[..n].iter().enumerate() {
                reached[k] = !bounds.misses(&grid.sample_rect(child));
                if !reached[k] {
                    let handed = &self.arena[list.start..list.end()];
                    self.record.unseen(child, level, Look::ParentBox, handed);
                    stats.visit(level);
                    stats.empty_by_bounds += 1;
                    stats.decided[Rule::Empty as usize] += 1;
                    sink.leaf(child, Rule::Empty, level);
                }
            }
            let mut only = (0..n).filter(|&k| reached[k]);
            if let (Some(k), None) = (only.next(), only.next()) {
                let child = children[k];
                if child.quadrants().1 > 0 && !bounds.holds(&grid.sample_rect(&child)) {
                    stats.visit(level);
                    stats.passed_through += 1;
                    self.record.unseen(&child, level, Look::PassedThrough, &[]);
                    sink.cut(&child, level);
                    region = child;
                    continue;
                }
            }
            for k in (0..n).rev().filter(|&k| reached[k]) {
                self.stack.push(Entry {
                    region: children[k],
                    list,
                    level,
                });
            }
            return;
        }
    }
}

/// Decides a one-sample region: the z-buffer at that sample. Warnock's
/// classification of a polygon against a single sample is exactly the
/// coverage test (it surrounds the sample or is disjoint from it), and
/// "in front of all others" there is exactly the depth test, so this is
/// the same decision as the general loop, without its corner bookkeeping.
fn resolve_sample<S: Sink>(
    grid: &Grid,
    r: &Region,
    candidates: &[u32],
    setups: &Setups,
    sink: &mut S,
    stats: &mut WarnockStats,
    record: &mut WindowClasses,
) -> Rule {
    let (x, y) = (grid.sample_x(r.u0), grid.sample_y(r.v0));
    let mut best: Option<(u32, f64)> = None;
    let mut covering = 0;
    for &t in candidates {
        let s = setups.get(t);
        if s.covers(x, y) {
            stats.classified(Class::Surrounding);
            record.class(t, Class::Surrounding);
            covering += 1;
            let d = s.depth_at(x, y);
            if best.is_none_or(|(_, b)| d < b) {
                best = Some((s.prim(), d));
            }
        } else {
            stats.classified(Class::Disjoint);
            record.class(t, Class::Disjoint);
        }
    }
    stats.depth_evaluations += covering;
    match best {
        None => Rule::Empty,
        Some((prim, d)) => {
            sink.sample(r.u0, r.v0, prim, d, stats);
            if covering == 1 {
                Rule::SurrounderAlone
            } else {
                Rule::Sample
            }
        }
    }
}

/// The candidate nearest at the fixed-point sample `(x, y)`: the z-buffer's
/// test, `LESS` in `f64` over the candidates in drawing order, so an exact
/// tie keeps the earlier triangle. Returns the triangle index and depth.
#[inline]
pub(crate) fn nearest_at(
    candidates: &[u32],
    setups: &Setups,
    x: i64,
    y: i64,
    stats: &mut WarnockStats,
) -> Option<(u32, f64)> {
    let mut best: Option<(u32, f64)> = None;
    for &t in candidates {
        let s = setups.get(t);
        if s.covers(x, y) {
            let d = s.depth_at(x, y);
            stats.depth_evaluations += 1;
            if best.is_none_or(|(_, b)| d < b) {
                best = Some((t, d));
            }
        }
    }
    best
}
