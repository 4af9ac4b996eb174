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
//! - Lists keep triangle order, so "the earlier triangle wins a depth tie"
//!   stays true at every level.
//!
//! What a decided region means for the output is up to a `Sink`: the
//! pixel-centre frame, a pixel with sub-pixel samples, or a pixel's sample
//! buffer.

use crate::classify::{Class, CornerDepths, TriSetup, certainly_behind, classify};
use crate::grid::{Grid, Region, SampleRect};
use crate::stats::{Rule, WarnockStats};

/// Receives the decisions of the subdivision loop.
pub(crate) trait Sink {
    /// `t` covers every sample of `r` and is in front of every other
    /// polygon there: draw it over the whole region.
    fn fill(&mut self, grid: &Grid, r: &Region, t: &TriSetup, stats: &mut WarnockStats);

    /// `t` is the only polygon reaching `r`: draw the samples it covers.
    fn single(&mut self, grid: &Grid, r: &Region, t: &TriSetup, stats: &mut WarnockStats);

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
        setups: &[TriSetup],
        _level: usize,
        stats: &mut WarnockStats,
    ) -> Rule {
        let (x, y) = (grid.sample_x(r.u0), grid.sample_y(r.v0));
        if let Some((t, d)) = nearest_at(candidates, setups, x, y, stats) {
            self.sample(r.u0, r.v0, setups[t as usize].prim, d, stats);
        }
        Rule::Sample
    }

    /// `r` was decided by `rule` at `level` (for the region record).
    fn leaf(&mut self, _r: &Region, _rule: Rule, _level: usize) {}
}

/// A region waiting on the stack, with where its candidate list is.
#[derive(Clone, Copy, Debug)]
struct Entry {
    region: Region,
    start: usize,
    len: usize,
    level: usize,
}

/// What classification and culling left of a region's list.
#[derive(Clone, Copy, Debug)]
struct Survivors {
    /// Where the surviving list starts in the arena (it runs to the end).
    out: usize,
    /// The surrounder nearest at the centre, with its corner depths.
    front: Option<(u32, CornerDepths)>,
    /// How many the surrounder culled.
    culled: u64,
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
}

impl Subdivider {
    /// Largest number of candidate indices held at once since the last
    /// [`Self::reset_peak`].
    pub fn peak(&self) -> usize {
        self.peak
    }

    /// Starts a new peak measurement.
    pub fn reset_peak(&mut self) {
        self.peak = 0;
    }

    /// Bytes held by the arena and the stack.
    pub fn bytes(&self) -> usize {
        self.arena.capacity() * std::mem::size_of::<u32>()
            + self.stack.capacity() * std::mem::size_of::<Entry>()
    }

    /// Subdivides each of the `roots`, starting from the candidate list
    /// `initial` (indices into `setups`, in drawing order), and hands every
    /// decision to `sink`.
    pub fn run<S: Sink>(
        &mut self,
        roots: Roots<'_>,
        initial: impl IntoIterator<Item = u32>,
        setups: &[TriSetup],
        sink: &mut S,
        stats: &mut WarnockStats,
    ) {
        self.arena.clear();
        self.stack.clear();
        self.arena.extend(initial);
        let len = self.arena.len();
        stats.candidates_copied += len as u64;
        for &region in roots.regions.iter().rev() {
            self.stack.push(Entry {
                region,
                start: 0,
                len,
                level: roots.level,
            });
        }
        let grid = roots.grid;
        let one_sample = grid.one_sample_per_cell();
        while let Some(e) = self.stack.pop() {
            self.arena.truncate(e.start + e.len);
            stats.visit(e.level);
            if one_sample && e.region.is_single_cell() {
                let list = &self.arena[e.start..];
                stats.sample_resolves += 1;
                stats.examined(e.level, list.len());
                let rule = resolve_sample(grid, &e.region, list, setups, sink, stats);
                stats.decided[rule as usize] += 1;
                sink.leaf(&e.region, rule, e.level);
                continue;
            }
            let rect = grid.sample_rect(&e.region);
            let out = self.arena.len();
            let front = self.classify(&e, &rect, setups, stats);
            let culled = match front {
                Some((s, sd)) => self.cull_behind(out, s, &sd, &rect, setups, stats),
                None => 0,
            };
            self.peak = self.peak.max(self.arena.len());
            let survivors = Survivors { out, front, culled };
            if let Some(rule) = self.decide(grid, &e, survivors, setups, sink, stats) {
                stats.decided[rule as usize] += 1;
                sink.leaf(&e.region, rule, e.level);
            }
        }
    }

    /// Classifies the parent's survivors (the list of `e`) against the
    /// region's samples `rect`, appending all but the disjoint ones to the
    /// arena; returns the surrounder nearest at the centre, if any: if any
    /// surrounder hides everything, that one does.
    fn classify(
        &mut self,
        e: &Entry,
        rect: &SampleRect,
        setups: &[TriSetup],
        stats: &mut WarnockStats,
    ) -> Option<(u32, CornerDepths)> {
        let mut front: Option<(u32, CornerDepths)> = None;
        stats.examined(e.level, e.len);
        let out = self.arena.len();
        for k in e.start..e.start + e.len {
            let t = self.arena[k];
            let setup = &setups[t as usize];
            let class = classify(setup, rect);
            stats.classified(class);
            match class {
                Class::Disjoint => continue,
                Class::Surrounding => {
                    let d = CornerDepths::new(&setup.depth, rect);
                    stats.depth_evaluations += 4;
                    if front.is_none_or(|(_, f)| d.sum() < f.sum()) {
                        front = Some((t, d));
                    }
                }
                Class::Contained | Class::Intersecting => {}
            }
            self.arena.push(t);
        }
        stats.candidates_copied += (self.arena.len() - out) as u64;
        front
    }

    /// Culls from the list starting at `out` what the surrounder `s` (with
    /// corner depths `sd`) hides at every sample of the region: hidden
    /// here, hidden in every subregion too. Returns how many went.
    fn cull_behind(
        &mut self,
        out: usize,
        s: u32,
        sd: &CornerDepths,
        rect: &SampleRect,
        setups: &[TriSetup],
        stats: &mut WarnockStats,
    ) -> u64 {
        let mut culled = 0;
        let mut kept = out;
        for k in out..self.arena.len() {
            let t = self.arena[k];
            if t != s {
                let d = CornerDepths::new(&setups[t as usize].depth, rect);
                stats.depth_evaluations += 4;
                if certainly_behind(&d, sd) {
                    culled += 1;
                    continue;
                }
            }
            self.arena[kept] = t;
            kept += 1;
        }
        self.arena.truncate(kept);
        stats.culled_behind_surrounder += culled;
        culled
    }

    /// Decides region `e` from what classification and culling left: the
    /// rule that decided it, or `None` when it was split into children
    /// pushed on the stack.
    fn decide<S: Sink>(
        &mut self,
        grid: &Grid,
        e: &Entry,
        Survivors { out, front, culled }: Survivors,
        setups: &[TriSetup],
        sink: &mut S,
        stats: &mut WarnockStats,
    ) -> Option<Rule> {
        let list = &self.arena[out..];
        let rule = match (list.len(), front) {
            (0, _) => Rule::Empty,
            (1, Some((s, _))) => {
                sink.fill(grid, &e.region, &setups[s as usize], stats);
                if culled > 0 {
                    Rule::SurrounderInFront
                } else {
                    Rule::SurrounderAlone
                }
            }
            (1, None) => {
                sink.single(grid, &e.region, &setups[list[0] as usize], stats);
                Rule::SinglePolygon
            }
            _ => {
                if front.is_some() {
                    stats.surrounder_undecided += 1;
                }
                let (children, n) = e.region.quadrants();
                if n == 0 {
                    sink.resolve_cell(grid, &e.region, list, setups, e.level, stats)
                } else {
                    let len = list.len();
                    for &region in children[..n].iter().rev() {
                        self.stack.push(Entry {
                            region,
                            start: out,
                            len,
                            level: e.level + 1,
                        });
                    }
                    return None;
                }
            }
        };
        Some(rule)
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
    setups: &[TriSetup],
    sink: &mut S,
    stats: &mut WarnockStats,
) -> Rule {
    let (x, y) = (grid.sample_x(r.u0), grid.sample_y(r.v0));
    let mut best: Option<(u32, f64)> = None;
    let mut covering = 0;
    for &t in candidates {
        let s = &setups[t as usize];
        if s.covers(x, y) {
            stats.classified(Class::Surrounding);
            covering += 1;
            let d = s.depth_at(x, y);
            if best.is_none_or(|(_, b)| d < b) {
                best = Some((s.prim, d));
            }
        } else {
            stats.classified(Class::Disjoint);
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
    setups: &[TriSetup],
    x: i64,
    y: i64,
    stats: &mut WarnockStats,
) -> Option<(u32, f64)> {
    let mut best: Option<(u32, f64)> = None;
    for &t in candidates {
        let s = &setups[t as usize];
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
