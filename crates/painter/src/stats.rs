//! Work counters of the painters.

use hider_scene::Stats;

/// What a painter did in one frame: the comparisons of the ordering stage,
/// which of Newell, Newell & Sancha's tests settled each pair, the splits,
/// and the painting.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PainterStats {
    /// Triangles taken from the scene.
    pub triangles: u64,
    /// Pairs (candidate P, other polygon Q) examined by the ordering tests.
    /// The naive painter compares nothing beyond its sort.
    pub comparisons: u64,
    /// Pairs settled by test 1, disjoint depth extents. The sorted list is
    /// scanned only while extents overlap, so the whole remainder of the
    /// list counts as one decision here.
    pub decided_depth: u64,
    /// Pairs settled by test 2, disjoint x extents.
    pub decided_x: u64,
    /// Pairs settled by test 3, disjoint y extents.
    pub decided_y: u64,
    /// Pairs settled by test 4: P lies behind Q's plane.
    pub decided_p_behind: u64,
    /// Pairs settled by test 5: Q lies in front of P's plane.
    pub decided_q_in_front: u64,
    /// Pairs settled by test 6: the projections do not overlap (exact for
    /// uncut triangles), or both are pieces of one triangle.
    pub decided_projection: u64,
    /// Pairs where every test failed (Q may be hidden by P).
    pub blocked: u64,
    /// Times a blocking Q was moved to the head of the list.
    pub moves: u64,
    /// Splits along the plane of another polygon (intersections, cycles).
    pub plane_splits: u64,
    /// Splits along a screen line (an edge of the other polygon, or a
    /// bisector): cycles where no plane cuts.
    pub line_splits: u64,
    /// Pieces in the painted list.
    pub pieces_out: u64,
    /// Pixel writes (painted pixels, overdraw included).
    pub pixels_painted: u64,
    /// Peak bytes of the piece arena and lists.
    pub peak_bytes: u64,
}

impl PainterStats {
    /// All splits.
    pub fn splits(&self) -> u64 {
        self.plane_splits + self.line_splits
    }
}

impl From<PainterStats> for Stats {
    fn from(s: PainterStats) -> Self {
        Stats {
            counters: vec![
                ("triangles", s.triangles),
                ("comparisons", s.comparisons),
                ("decided by depth extent", s.decided_depth),
                ("decided by x extent", s.decided_x),
                ("decided by y extent", s.decided_y),
                ("decided by P behind Q's plane", s.decided_p_behind),
                ("decided by Q in front of P's plane", s.decided_q_in_front),
                ("decided by projection", s.decided_projection),
                ("blocked", s.blocked),
                ("moves", s.moves),
                ("plane splits", s.plane_splits),
                ("line splits", s.line_splits),
                ("splits", s.splits()),
                ("pieces out", s.pieces_out),
                ("pixels painted", s.pixels_painted),
            ],
            peak_bytes: s.peak_bytes,
        }
    }
}
