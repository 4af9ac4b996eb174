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
//! compared) over a vector sorted by farthest depth (`sorted`, farthest at
//! the end), which is scanned from the end only while depth extents
//! overlap: with a sorted list, test 1 settles the whole remainder at once.

use glam::DVec2;
use hider_geom::PlaneEq;
use hider_scene::{Error, Result, ScreenScene};

use crate::newell::{Blocked, Decided, Extent, Outcome, extents_decide, may_precede_by_planes};
use crate::piece::{Piece, depth_difference, edge_line};
use crate::stats::PainterStats;

/// Where a piece sits in the list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Slot {
    /// Index into `front`.
    Front(usize),
    /// Index into `sorted`.
    Sorted(usize),
}

/// A sorted-list entry: the keys scanned most, kept inline so that the scan
/// does not chase the piece arena.
#[derive(Clone, Copy, Debug)]
struct Entry {
    extent: Extent,
    id: u32,
}

/// The ordering stage and its scratch memory, kept between frames.
#[derive(Clone, Debug, Default)]
pub(crate) struct Orderer {
    /// Every piece made this frame (split parents stay, unused).
    pub pieces: Vec<Piece>,
    /// Paint order, indices into `pieces`, farthest first.
    pub order: Vec<u32>,
    sorted: Vec<Entry>,
    front: Vec<u32>,
}

impl Orderer {
    /// Orders the scene's triangles, splitting where needed, into
    /// `self.order`.
    pub fn run(
        &mut self,
        scene: &ScreenScene,
        (max_splits, max_bytes): (u64, u64),
        eps: f64,
        stats: &mut PainterStats,
    ) -> Result<()> {
        let max_splits = max_splits.min(
            crate::options::SPLITS_BASE
                + crate::options::SPLITS_PER_TRIANGLE * scene.tris.len() as u64,
        );
        self.pieces.clear();
        self.order.clear();
        self.sorted.clear();
        self.front.clear();
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
        stats.triangles = scene.tris.len() as u64;
        let mut arena_bytes: u64 = self.pieces.iter().map(|p| p.bytes() as u64).sum();
        self.sorted
            .extend(self.pieces.iter().enumerate().map(|(k, p)| Entry {
                extent: Extent::of(p),
                id: k as u32,
            }));
        // Ascending, so the farthest is popped from the end; equal depths
        // paint the lower primitive id first.
        self.sorted.sort_by(|a, b| {
            a.extent
                .zmax
                .total_cmp(&b.extent.zmax)
                .then(b.id.cmp(&a.id))
        });
        loop {
            let candidate = match (self.front.last(), self.sorted.last()) {
                (Some(&c), _) => Slot::Front(self.front.len() - 1).with(c),
                (None, Some(e)) => Slot::Sorted(self.sorted.len() - 1).with(e.id),
                (None, None) => break,
            };
            let (cslot, p) = candidate;
            match self.find_blocker(cslot, p, eps, stats) {
                None => {
                    self.remove(cslot);
                    self.order.push(p);
                }
                Some((qslot, q, blocked)) => {
                    let moved = self.pieces[q as usize].moved;
                    if blocked.reverse_ok(eps) && !moved {
                        self.remove(qslot);
                        self.pieces[q as usize].moved = true;
                        self.front.push(q);
                        stats.moves += 1;
                    } else {
                        if stats.splits() >= max_splits {
                            return Err(Error::Render {
                                hider: "painter".into(),
                                message: format!(
                                    "split budget of {max_splits} used up with {} pieces still \
                                     unordered (intersecting or cyclic polygons need more \
                                     splits; raise PainterOptions::max_splits)",
                                    self.front.len() + self.sorted.len()
                                ),
                            });
                        }
                        let before = self.pieces.len();
                        self.split(cslot, p, qslot, q, &blocked, eps, stats)?;
                        arena_bytes += self.pieces[before..]
                            .iter()
                            .map(|p| p.bytes() as u64)
                            .sum::<u64>();
                        if arena_bytes > max_bytes {
                            return Err(Error::Limit {
                                what: "painter piece memory in bytes",
                                value: arena_bytes,
                                limit: max_bytes,
                            });
                        }
                    }
                }
            }
        }
        stats.pieces_out = self.order.len() as u64;
        let lists = (self.sorted.capacity() * std::mem::size_of::<Entry>())
            + (self.front.capacity() + self.order.capacity()) * 4;
        // Pieces are never freed during a frame: the arena's final size is
        // its peak.
        let arena = self.pieces.iter().map(Piece::bytes).sum::<usize>();
        stats.peak_bytes = (arena + lists) as u64;
        Ok(())
    }

    /// The first polygon that P may not be painted before, if any.
    fn find_blocker(
        &self,
        cslot: Slot,
        p: u32,
        eps: f64,
        stats: &mut PainterStats,
    ) -> Option<(Slot, u32, Blocked)> {
        let pp = &self.pieces[p as usize];
        let pe = Extent::of(pp);
        let check = |q: u32, qe: &Extent, stats: &mut PainterStats| -> Option<Blocked> {
            stats.comparisons += 1;
            let outcome = match extents_decide(&pe, qe, eps) {
                Some(d) => Outcome::Ok(d),
                None => may_precede_by_planes(pp, &self.pieces[q as usize], eps),
            };
            match outcome {
                Outcome::Ok(d) => {
                    *match d {
                        Decided::Depth => &mut stats.decided_depth,
                        Decided::X => &mut stats.decided_x,
                        Decided::Y => &mut stats.decided_y,
                        Decided::PBehind => &mut stats.decided_p_behind,
                        Decided::QInFront => &mut stats.decided_q_in_front,
                        Decided::Projection => &mut stats.decided_projection,
                    } += 1;
                    None
                }
                Outcome::Blocked(b) => {
                    stats.blocked += 1;
                    Some(b)
                }
            }
        };
        // Moved pieces are out of depth order: compare with all of them.
        for (k, &q) in self.front.iter().enumerate().rev() {
            if Slot::Front(k) == cslot {
                continue;
            }
            if let Some(b) = check(q, &Extent::of(&self.pieces[q as usize]), stats) {
                return Some((Slot::Front(k), q, b));
            }
        }
        let limit = pp.zmin + eps;
        for k in (0..self.sorted.len()).rev() {
            if Slot::Sorted(k) == cslot {
                continue;
            }
            let e = self.sorted[k];
            if e.extent.zmax <= limit {
                // Test 1 for this entry and everything nearer.
                stats.decided_depth += 1;
                break;
            }
            if let Some(b) = check(e.id, &e.extent, stats) {
                return Some((Slot::Sorted(k), e.id, b));
            }
        }
        None
    }

    fn remove(&mut self, slot: Slot) {
        match slot {
            Slot::Front(k) => {
                self.front.remove(k);
            }
            Slot::Sorted(k) => {
                self.sorted.remove(k);
            }
        }
    }

    fn insert_sorted(&mut self, id: u32) {
        let extent = Extent::of(&self.pieces[id as usize]);
        let at = self.sorted.partition_point(|e| e.extent.zmax < extent.zmax);
        self.sorted.insert(at, Entry { extent, id });
    }

    /// Resolves a pair with no order by splitting: by the other's plane
    /// when it really cuts (intersections, most cycles), else by the plane
    /// of another member of the cycle, else along a screen line.
    #[allow(clippy::too_many_arguments)]
    fn split(
        &mut self,
        pslot: Slot,
        p: u32,
        qslot: Slot,
        q: u32,
        blocked: &Blocked,
        eps: f64,
        stats: &mut PainterStats,
    ) -> Result<()> {
        let (pp, qq) = (&self.pieces[p as usize], &self.pieces[q as usize]);
        // (slot, piece, line, whether it is a plane split)
        let mut attempts: Vec<(Slot, u32, PlaneEq, bool)> = Vec::with_capacity(8);
        if blocked.q_plane_cuts_p(eps) {
            attempts.push((pslot, p, depth_difference(&pp.depth, &qq.depth), true));
        }
        if blocked.p_plane_cuts_q(eps) {
            attempts.push((qslot, q, depth_difference(&qq.depth, &pp.depth), true));
        }
        if attempts.is_empty() {
            // A cycle through moved pieces whose two ends do not cut each
            // other's planes. Polygons none of whose planes cuts another
            // always have an order (a BSP tree on their own planes needs
            // no split), so look for a cut anywhere in the cycle: Q, the
            // pieces moved after it, and P.
            // (Q is marked, so it is on the moved stack, and P, the
            // candidate, is the stack's top.)
            if let Slot::Front(first) = qslot {
                let members: Vec<(Slot, u32)> = (first..self.front.len())
                    .map(|k| (Slot::Front(k), self.front[k]))
                    .collect();
                if let Some((slot, id, line)) = self.plane_cut_among(&members, eps) {
                    attempts.push((slot, id, line, true));
                }
            }
        }
        // No plane cuts: cut along the other's outline, so that the pieces
        // outside it lose the constraint, or bisect.
        let (pp, qq) = (&self.pieces[p as usize], &self.pieces[q as usize]);
        attempts.extend(edge_lines_cutting(qq, pp).map(|l| (pslot, p, l, false)));
        attempts.extend(edge_lines_cutting(pp, qq).map(|l| (qslot, q, l, false)));
        attempts.push((pslot, p, bisector(pp), false));
        attempts.push((qslot, q, bisector(qq), false));
        for (slot, id, line, plane) in attempts {
            if let Some((a, b)) = self.pieces[id as usize].split(line) {
                self.remove(slot);
                if id != p {
                    // The moved stack is a chain (each entry must precede
                    // the one beneath it, the bottom one the head of the
                    // sorted list); splitting any piece but the candidate
                    // on top may break a link, and a stale chain would
                    // report cycles that do not exist. Start the chain
                    // afresh: between two splits every piece still moves
                    // at most once, so the loop still ends.
                    for k in std::mem::take(&mut self.front) {
                        self.pieces[k as usize].moved = false;
                        self.insert_sorted(k);
                    }
                }
                let base = self.pieces.len() as u32;
                self.pieces.push(a);
                self.pieces.push(b);
                self.insert_sorted(base);
                self.insert_sorted(base + 1);
                if plane {
                    stats.plane_splits += 1;
                } else {
                    stats.line_splits += 1;
                }
                return Ok(());
            }
        }
        let (pp, qq) = (&self.pieces[p as usize], &self.pieces[q as usize]);
        Err(Error::Render {
            hider: "painter".into(),
            message: format!(
                "primitives {} and {} overlap with no depth order and neither can be split \
                 (degenerate pieces)",
                pp.prim, qq.prim
            ),
        })
    }

    /// The first member of `members` whose polygon the plane of another
    /// member with an overlapping bounding box really cuts, and that plane.
    fn plane_cut_among(&self, members: &[(Slot, u32)], eps: f64) -> Option<(Slot, u32, PlaneEq)> {
        for &(slot, y) in members {
            let py = &self.pieces[y as usize];
            for &(_, x) in members {
                let px = &self.pieces[x as usize];
                let boxes_meet = px.min.x < py.max.x
                    && py.min.x < px.max.x
                    && px.min.y < py.max.y
                    && py.min.y < px.max.y;
                if x == y || px.source == py.source || !boxes_meet {
                    continue;
                }
                let line = depth_difference(&py.depth, &px.depth);
                let (lo, hi) = crate::split::range_over(&py.polygon, &line);
                if lo < -eps && hi > eps {
                    return Some((slot, y, line));
                }
            }
        }
        None
    }
}

impl Slot {
    fn with(self, id: u32) -> (Slot, u32) {
        (self, id)
    }
}

/// Lines along the edges of `by` that strictly cut the polygon of `target`.
fn edge_lines_cutting<'a>(by: &'a Piece, target: &'a Piece) -> impl Iterator<Item = PlaneEq> + 'a {
    let n = by.polygon.len();
    (0..n).filter_map(move |k| {
        let (a, b) = (by.polygon[k], by.polygon[(k + 1) % n]);
        let length = (b - a).length();
        if length < 1e-3 {
            return None;
        }
        let line = edge_line(a, b);
        let (lo, hi) = crate::split::range_over(&target.polygon, &line);
        let tol = crate::newell::CUT_MARGIN * length;
        (lo < -tol && hi > tol).then_some(line)
    })
}

/// The line through the centre of a piece's bounding box, across its
/// longer side.
fn bisector(p: &Piece) -> PlaneEq {
    let c = (p.min + p.max) * 0.5;
    let size = p.max - p.min;
    let dir = if size.x >= size.y { DVec2::X } else { DVec2::Y };
    PlaneEq {
        x0: c.x,
        y0: c.y,
        value: 0.0,
        dx: dir.x,
        dy: dir.y,
    }
}
