//! Resolving a pair with no order by splitting.
//!
//! When P is blocked by Q and Q cannot go first either (the polygons
//! intersect), or Q was moved before (a cycle), one of them is split and
//! the pieces go back into the sorted list. The cut is, in order of
//! preference: the other polygon's plane where it really cuts
//! (intersections, most cycles); the plane of another member of the cycle;
//! a line along the other polygon's outline, so that the pieces outside it
//! lose the constraint; a bisector of the piece's bounding box.

use glam::DVec2;
use hider_geom::PlaneEq;
use hider_scene::{Error, Result};

use hider_scene::{ScreenScene, ScreenTri};

use crate::centres::Centres;
use crate::newell::{Blocked, CUT_MARGIN, Extent};
use crate::order::{At, Orderer, Slot};
use crate::piece::{Piece, depth_difference, edge_line};
use crate::sides::sides;
use crate::split::range_over;
use crate::stats::PainterStats;
use crate::trace::TraceEvent;

/// One way to split: which piece, along which line, and the triangle whose
/// plane meets the piece's along that line (counted in
/// [`PainterStats::plane_splits`]) or `None` for a screen line
/// ([`PainterStats::line_splits`]).
type Attempt = (Slot, u32, PlaneEq, Option<u32>);

impl Orderer {
    /// Resolves the pair (P, Q) by splitting one of them, trying the cuts
    /// in order of preference. Returns the bytes freed (the parent's
    /// outline and cuts).
    pub(crate) fn split(
        &mut self,
        (pslot, p): At,
        (qslot, q): At,
        blocked: &Blocked,
        scene: &ScreenScene,
        stats: &mut PainterStats,
    ) -> Result<u64> {
        let attempts = self.attempts((pslot, p), (qslot, q), blocked, &scene.tris);
        for (slot, id, line, plane) in attempts {
            if let Some((a, b)) = self.pieces[id as usize].split_on(line, plane) {
                let base = self.pieces.len() as u32;
                self.note(|| TraceEvent::Split {
                    piece: id,
                    halves: [base, base + 1],
                    plane,
                });
                let freed = self.replace((slot, id), p, (a, b), scene, stats);
                if plane.is_some() {
                    stats.plane_splits += 1;
                } else {
                    stats.line_splits += 1;
                }
                return Ok(freed);
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

    /// The cuts to try for the pair (P, Q), best first.
    fn attempts(
        &self,
        (pslot, p): At,
        (qslot, q): At,
        blocked: &Blocked,
        tris: &[ScreenTri],
    ) -> Vec<Attempt> {
        let (pp, qq) = (&self.pieces[p as usize], &self.pieces[q as usize]);
        let mut attempts: Vec<Attempt> = Vec::with_capacity(8);
        if blocked.q_plane_cuts_p() {
            let line = depth_difference(&pp.depth, &qq.depth);
            attempts.push((pslot, p, line, Some(qq.source)));
        }
        if blocked.p_plane_cuts_q() {
            let line = depth_difference(&qq.depth, &pp.depth);
            attempts.push((qslot, q, line, Some(pp.source)));
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
                let members: Vec<At> = (first..self.front.len())
                    .map(|k| (Slot::Front(k), self.front[k]))
                    .collect();
                if let Some((slot, id, line, plane)) = self.plane_cut_among(&members, tris) {
                    attempts.push((slot, id, line, Some(plane)));
                }
            }
        }
        // No plane cuts: cut along the other's outline, so that the pieces
        // outside it lose the constraint, or bisect.
        attempts.extend(edge_lines_cutting(qq, pp).map(|l| (pslot, p, l, None)));
        attempts.extend(edge_lines_cutting(pp, qq).map(|l| (qslot, q, l, None)));
        attempts.push((pslot, p, bisector(pp), None));
        attempts.push((qslot, q, bisector(qq), None));
        attempts
    }

    /// Replaces piece `id` (at `slot`) by its halves `a` and `b` in the
    /// sorted list; `p` is the candidate. Returns the bytes freed.
    fn replace(
        &mut self,
        (slot, id): At,
        p: u32,
        (a, b): (Piece, Piece),
        scene: &ScreenScene,
        stats: &mut PainterStats,
    ) -> u64 {
        self.remove(slot);
        self.unindex(id);
        if id != p {
            // The moved stack is a chain (each entry must precede the one
            // beneath it, the bottom one the head of the sorted list);
            // splitting any piece but the candidate on top may break a
            // link, and a stale chain would report cycles that do not
            // exist. Start the chain afresh: between two splits every piece
            // still moves at most once, so the loop still ends.
            for k in std::mem::take(&mut self.front) {
                self.pieces[k as usize].moved = false;
                self.insert_sorted(k);
            }
        }
        let base = self.pieces.len() as u32;
        self.extents.push(Extent::of(&a));
        self.extents.push(Extent::of(&b));
        self.pieces.push(a);
        self.pieces.push(b);
        for half in [base, base + 1] {
            let hidden = self.hiz.hides(&self.pieces[half as usize]);
            self.hidden.push(hidden);
            if hidden {
                // Never ordered nor painted: only its slot stays.
                stats.culled += 1;
                self.note(|| TraceEvent::Culled { piece: half });
                if self.centres.len() <= half as usize {
                    self.centres.resize(half as usize + 1, Centres::None);
                }
                self.centres[half as usize] = Centres::None;
                let piece = &mut self.pieces[half as usize];
                piece.polygon = Vec::new();
                piece.cuts = Vec::new();
                piece.tags = Vec::new();
            } else {
                self.index_piece(half, scene);
            }
        }
        // The parent is never painted: free its outline and cuts (its
        // index stays valid, so ids need no remapping).
        let parent = &mut self.pieces[id as usize];
        let freed = parent.bytes() as u64;
        parent.polygon = Vec::new();
        parent.cuts = Vec::new();
        parent.tags = Vec::new();
        let freed = freed - parent.bytes() as u64;
        for half in [base, base + 1] {
            if !self.hidden[half as usize] {
                self.insert_sorted(half);
            }
        }
        freed
    }

    /// The first member of `members` whose polygon the plane of another
    /// member with an overlapping bounding box really cuts, the meeting
    /// line and the other member's triangle.
    fn plane_cut_among(
        &self,
        members: &[At],
        tris: &[ScreenTri],
    ) -> Option<(Slot, u32, PlaneEq, u32)> {
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
                if sides(py, px, tris).cut() {
                    let line = depth_difference(&py.depth, &px.depth);
                    return Some((slot, y, line, px.source));
                }
            }
        }
        None
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
        let (lo, hi) = range_over(&target.polygon, &line);
        let tol = CUT_MARGIN * length;
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
