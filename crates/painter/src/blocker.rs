//! Finding the blocker: the first polygon Q that the candidate P may not
//! be painted before.
//!
//! The moved pieces are out of depth order and are all compared. The sorted
//! pieces are scanned from the farthest only while their depth extents
//! overlap P's (test 1 settles the rest of the list at once). The first
//! [`LINEAR_SCAN`] of that run are compared one by one; for the rest, the
//! bin grid yields only the entries whose bounding boxes can meet P's, in
//! the same order, so the blocker found is the same as with a full scan.

use hider_geom::star::NO_STAR;
use hider_scene::ScreenScene;

use crate::bins::{BinEntry, Key};
use crate::centres::{Centres, centre_test};
use crate::newell::{Blocked, Decided, Extent, Outcome, extents_decide, may_precede_by_planes};
use crate::order::{At, Orderer, Slot};
use crate::stats::PainterStats;
use crate::trace::{TraceEvent, TraceTest};

/// How many entries of the depth-overlapping run are compared one by one
/// before the bin grid is used for the rest. Closed meshes rarely get
/// past it; soups do, and there the grid skips every entry whose screen
/// box cannot meet the candidate's.
pub(crate) const LINEAR_SCAN: usize = 8;

/// What the one-by-one part of the sorted scan found.
enum Linear {
    /// A blocker.
    Found(At, Blocked),
    /// Test 1 settles the rest of the list: no blocker.
    Settled,
    /// The prefix passed; the rest of the run starts at this key and
    /// nearer.
    Rest(Key),
}

impl Orderer {
    /// The first polygon that P (at `cslot`) may not be painted before, if
    /// any: the moved pieces from the top of the stack, then the sorted
    /// pieces from the farthest, as long as their depth extents overlap
    /// P's.
    pub(crate) fn find_blocker(
        &mut self,
        cslot: Slot,
        p: u32,
        scene: &ScreenScene,
        stats: &mut PainterStats,
    ) -> Option<(Slot, u32, Blocked)> {
        if self.centres[p as usize] == Centres::None {
            // It shows nowhere: no order matters.
            return None;
        }
        let pe = self.extents[p as usize];
        // Moved pieces are out of depth order: compare with all of them.
        for (k, &q) in self.front.iter().enumerate().rev() {
            if Slot::Front(k) == cslot {
                continue;
            }
            if let Some(b) = self.test_pair((p, &pe), (q, &self.extents[q as usize]), scene, stats)
            {
                return Some((Slot::Front(k), q, b));
            }
        }
        match self.scan_linear(cslot, p, scene, stats) {
            Linear::Found((slot, q), b) => Some((slot, q, b)),
            Linear::Settled => None,
            Linear::Rest(upper) => self
                .scan_bins(cslot, p, upper, scene, stats)
                .or_else(|| self.index_blocker(p, scene, stats)),
        }
    }

    /// The rest of the small pieces (those covering one centre, kept out
    /// of the bin grid): the farthest on a centre P covers, if farther
    /// than P there.
    fn index_blocker(
        &self,
        p: u32,
        scene: &ScreenScene,
        stats: &mut PainterStats,
    ) -> Option<(Slot, u32, Blocked)> {
        let q = self.centre_blocker(p, scene)?;
        stats.comparisons += 1;
        stats.blocked += 1;
        self.note(|| TraceEvent::Test {
            p,
            q,
            test: TraceTest::Blocked,
        });
        let slot = if self.pieces[q as usize].moved {
            let k = self.front.iter().position(|&f| f == q)?;
            Slot::Front(k)
        } else {
            Slot::Sorted(self.keys[q as usize])
        };
        Some((slot, q, Blocked::by_centre()))
    }

    /// The first entries of the sorted list one by one, farthest first.
    fn scan_linear(
        &self,
        cslot: Slot,
        p: u32,
        scene: &ScreenScene,
        stats: &mut PainterStats,
    ) -> Linear {
        let pe = self.extents[p as usize];
        let limit = pe.zmin;
        let mut scanned = 0;
        for (&key, &q) in self.sorted.iter().rev() {
            if Slot::Sorted(key) == cslot {
                continue;
            }
            let qe = &self.extents[q as usize];
            if qe.zmax <= limit {
                // Test 1 for this entry and everything nearer.
                stats.decided_depth += 1;
                return Linear::Settled;
            }
            if scanned == self.linear_scan.unwrap_or(LINEAR_SCAN) {
                return Linear::Rest(key);
            }
            scanned += 1;
            if let Some(b) = self.test_pair((p, &pe), (q, qe), scene, stats) {
                return Linear::Found((Slot::Sorted(key), q), b);
            }
        }
        // The whole list passed one by one: no blocker, nothing counted.
        Linear::Settled
    }

    /// The rest of the depth-overlapping run (keys up to `upper`), through
    /// the bins P's box meets: an entry in no such bin has a box disjoint
    /// from P's, which tests 2-3 settle. Visited in the same order
    /// (farthest first), so the blocker found is the one the full scan
    /// would find.
    fn scan_bins(
        &mut self,
        cslot: Slot,
        p: u32,
        upper: Key,
        scene: &ScreenScene,
        stats: &mut PainterStats,
    ) -> Option<(Slot, u32, Blocked)> {
        let pe = self.extents[p as usize];
        let limit = pe.zmin;
        let mut near = std::mem::take(&mut self.near);
        near.clear();
        let (x0, x1, y0, y1) = self.grid.span(&pe);
        // P's stars: their lists in the bins hold P's mates, which can block
        // P only if they are its partners (listed below).
        let own = self
            .stars_of
            .get(p as usize)
            .copied()
            .unwrap_or([NO_STAR; 3]);
        let mut visit = |bin: &[BinEntry], x: usize, y: usize| {
            // Only the entries above the linear prefix (at most its
            // length) sort after `upper`: look from the end rather
            // than bisect, which touches one cache line, not several.
            let end = bin
                .iter()
                .rposition(|b| b.key <= upper)
                .map_or(0, |k| k + 1);
            for b in bin[..end].iter().rev() {
                let qe = &b.extent;
                if qe.zmax <= limit {
                    break;
                }
                // Each entry once: from the first bin both boxes meet.
                if x != x0.max(usize::from(b.first.0)) || y != y0.max(usize::from(b.first.1)) {
                    continue;
                }
                self.extents_first(p, &pe, (b.key, b.id), qe, stats, &mut near);
            }
        };
        for y in y0..=y1 {
            for x in x0..=x1 {
                let at = y * self.grid.cols + x;
                visit(&self.grid.bins[at], x, y);
                for (group, bin) in self.grid.star_bins.get(at).into_iter().flatten() {
                    if !own.contains(group) {
                        visit(bin, x, y);
                    }
                }
            }
        }
        for &q in self.partners_of(p) {
            let (key, qe) = (self.keys[q as usize], &self.extents[q as usize]);
            // Still unpainted and unmoved, in the depth-overlapping run.
            if key <= upper && qe.zmax > limit && self.sorted.get(&key) == Some(&q) {
                self.extents_first(p, &pe, (key, q), qe, stats, &mut near);
            }
        }
        near.sort_unstable_by_key(|e| std::cmp::Reverse(e.0));
        // A partner sharing a second star with P is also in the bins.
        near.dedup_by_key(|e| e.0);
        let mut found = None;
        for &(key, q) in &near {
            if Slot::Sorted(key) == cslot {
                continue;
            }
            if let Some(b) = self.test_pair((p, &pe), (q, &self.extents[q as usize]), scene, stats)
            {
                found = Some((Slot::Sorted(key), q, b));
                break;
            }
        }
        if found.is_none() {
            stats.decided_depth += 1;
        }
        self.near = near;
        found
    }
}

impl Orderer {
    /// Tests 1 to 3 on the pair (P, Q) of the bin scan, counted when they
    /// settle it; otherwise Q (`(key, id)`) goes to `near`, for the
    /// ordered pass. Tests 1-3 never block.
    fn extents_first(
        &self,
        p: u32,
        pe: &Extent,
        (key, q): (Key, u32),
        qe: &Extent,
        stats: &mut PainterStats,
        near: &mut Vec<(Key, u32)>,
    ) {
        match extents_decide(pe, qe) {
            Some(d) => {
                stats.comparisons += 1;
                self.note(|| TraceEvent::Test {
                    p,
                    q,
                    test: d.into(),
                });
                match d {
                    Decided::Depth => stats.decided_depth += 1,
                    Decided::X => stats.decided_x += 1,
                    _ => stats.decided_y += 1,
                }
            }
            None => near.push((key, q)),
        }
    }

    /// Tests 1 to 6 on the pair (P, Q), or the centre test when one of
    /// them covers at most one pixel centre, counting the comparison and
    /// the test that settled it; the blocked outcome when none did.
    fn test_pair(
        &self,
        (p, pe): (u32, &Extent),
        (q, qe): (u32, &Extent),
        scene: &ScreenScene,
        stats: &mut PainterStats,
    ) -> Option<Blocked> {
        stats.comparisons += 1;
        let (pp, qq) = (&self.pieces[p as usize], &self.pieces[q as usize]);
        let outcome = match extents_decide(pe, qe) {
            Some(d) => Outcome::Ok(d),
            None => {
                let (pt, qt) = (
                    &scene.tris[pp.source as usize],
                    &scene.tris[qq.source as usize],
                );
                match centre_test(
                    (pp, self.centres[p as usize], pt),
                    (qq, self.centres[q as usize], qt),
                ) {
                    Some(true) => Outcome::Ok(Decided::Centre),
                    Some(false) => Outcome::Blocked(Blocked::by_centre()),
                    None => may_precede_by_planes(pp, qq, scene),
                }
            }
        };
        self.note(|| TraceEvent::Test {
            p,
            q,
            test: match &outcome {
                Outcome::Ok(d) => (*d).into(),
                Outcome::Blocked(_) => TraceTest::Blocked,
            },
        });
        match outcome {
            Outcome::Ok(d) => {
                *match d {
                    Decided::Depth => &mut stats.decided_depth,
                    Decided::X => &mut stats.decided_x,
                    Decided::Y => &mut stats.decided_y,
                    Decided::PBehind => &mut stats.decided_p_behind,
                    Decided::QInFront => &mut stats.decided_q_in_front,
                    Decided::Projection => &mut stats.decided_projection,
                    Decided::Centre => &mut stats.decided_centre,
                } += 1;
                None
            }
            Outcome::Blocked(b) => {
                stats.blocked += 1;
                Some(b)
            }
        }
    }
}
