//! Work counters of the painters.

hider_scene::hider_stats! {
    /// What a painter did in one frame: the comparisons of the ordering
    /// stage, which of Newell, Newell & Sancha's tests settled each pair, the
    /// splits, and the painting. The naive painter fills only the triangle,
    /// piece, pixel and memory counters.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub struct PainterStats {
        /// Triangles taken from the scene.
        pub triangles: u64 => "triangles",
        /// Pairs (candidate P, other polygon Q) examined by the ordering
        /// tests. The naive painter compares nothing beyond its sort.
        pub comparisons: u64 => "comparisons",
        /// Pairs settled by test 1, disjoint depth extents. The sorted list
        /// is scanned only while extents overlap, so the whole remainder of
        /// the list counts as one decision here.
        pub decided_depth: u64 => "decided by depth extent",
        /// Pairs settled by test 2, disjoint x extents.
        pub decided_x: u64 => "decided by x extent",
        /// Pairs settled by test 3, disjoint y extents.
        pub decided_y: u64 => "decided by y extent",
        /// Pairs settled by test 4: P lies behind Q's plane.
        pub decided_p_behind: u64 => "decided by P behind Q's plane",
        /// Pairs settled by test 5: Q lies in front of P's plane.
        pub decided_q_in_front: u64 => "decided by Q in front of P's plane",
        /// Pairs settled by test 6: the projections do not overlap (exact
        /// for uncut triangles), or both are pieces of one triangle.
        pub decided_projection: u64 => "decided by projection",
        /// Pairs settled on the one pixel centre that matters: one of the
        /// two covers at most one centre, and P is not nearer there (or
        /// they share none).
        pub decided_centre: u64 => "decided by pixel centre",
        /// Pairs where every test failed (Q may be hidden by P).
        pub blocked: u64 => "blocked",
        /// Times a blocking Q was moved to the head of the list.
        pub moves: u64 => "moves",
        /// Splits along the plane of another polygon (intersections,
        /// cycles).
        pub plane_splits: u64 => "plane splits",
        /// Splits along a screen line (an edge of the other polygon, or a
        /// bisector): cycles where no plane cuts.
        pub line_splits: u64 => "line splits",
        /// All splits: [`Self::plane_splits`] plus [`Self::line_splits`],
        /// filled when the ordering ends.
        pub splits: u64 => "splits",
        /// Pieces dropped before ordering because no point of them can
        /// show: every pixel square they meet is covered entirely by a
        /// triangle nearer everywhere on it (`cull.rs`).
        pub culled: u64 => "culled",
        /// Pieces in the painted list.
        pub pieces_out: u64 => "pieces out",
        /// Pixel writes (painted pixels, overdraw included).
        pub pixels_painted: u64 => "pixels painted",
        /// Peak bytes of the piece arena and lists.
        pub peak_bytes: u64 => PEAK,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_scene::HiderStats;

    /// The benchmark prints the counters under these names, in this order.
    #[test]
    fn the_table_keeps_the_printed_names_and_order() {
        let stats = PainterStats {
            plane_splits: 2,
            line_splits: 1,
            splits: 3,
            peak_bytes: 64,
            ..PainterStats::default()
        };
        let table = stats.table();
        let names: Vec<&str> = table.counters.iter().map(|&(name, _)| name).collect();
        assert_eq!(
            names,
            [
                "triangles",
                "comparisons",
                "decided by depth extent",
                "decided by x extent",
                "decided by y extent",
                "decided by P behind Q's plane",
                "decided by Q in front of P's plane",
                "decided by projection",
                "decided by pixel centre",
                "blocked",
                "moves",
                "plane splits",
                "line splits",
                "splits",
                "culled",
                "pieces out",
                "pixels painted",
            ]
        );
        assert_eq!(table.counters[13], ("splits", 3));
        assert_eq!(table.peak_bytes, 64);
    }
}
