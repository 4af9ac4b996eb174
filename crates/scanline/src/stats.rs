//! The work counters of one scanline frame.

hider_scene::hider_stats! {
    /// What one [`crate::Scanline`] frame did: the counts that explain its
    /// cost next to a z-buffer's (which pays per covered pixel per polygon,
    /// where the scanline pays per edge per row and per span).
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub struct ScanlineStats {
        /// Polygons (screen triangles) entered in the polygon table: those
        /// with at least one pixel-centre row inside the image.
        pub polygons: u64 => "polygons",
        /// Edges entered in the edge table (non-horizontal edges crossing at
        /// least one pixel-centre row inside the image).
        pub edges: u64 => "edges",
        /// Image rows scanned.
        pub rows: u64 => "rows",
        /// Edge crossings: the ends of polygon runs (two per non-empty run
        /// of a polygon on a row), i.e. the entries sorted per row.
        pub crossings: u64 => "crossings",
        /// Spans: runs of pixels between two consecutive crossings with at
        /// least one polygon in them, each resolved as a whole.
        pub spans: u64 => "spans",
        /// Spans that had to be split because two polygons' depths cross
        /// inside them (interpenetration).
        pub split_spans: u64 => "split spans",
        /// Split points found (a span split twice counts two).
        pub splits: u64 => "splits",
        /// Spans (or their remainders) handed to the one-row depth buffer
        /// fallback after [`crate::ScanlineOptions::max_splits_per_span`]
        /// splits.
        pub fallback_spans: u64 => "fallback spans",
        /// Pixels resolved by the fallback.
        pub fallback_pixels: u64 => "fallback pixels",
        /// Largest number of polygons active on one row (their row range
        /// covers it, whether or not they cover a pixel centre on it).
        pub active_polygons_max: u64 => "active polygons max",
        /// Sum over rows of the polygons active on the row; divided by
        /// [`Self::rows`] it is the mean ([`Self::active_polygons_mean`]).
        pub active_polygon_rows: u64 => "active polygon rows",
        /// [`Self::active_polygons_mean`] in thousandths, rounded (the
        /// table holds integers), filled when the frame ends.
        pub active_polygons_mean_x1000: u64 => "active polygons mean x1000",
        /// Largest number of polygons overlapping in one span (the depth
        /// complexity the visible-surface step faced).
        pub span_polygons_max: u64 => "span polygons max",
        /// Depth-plane evaluations spent deciding visibility (not counting
        /// the one per written pixel for the depth output).
        pub depth_evaluations: u64 => "depth evaluations",
        /// Pixels written (each covered pixel exactly once: no overdraw).
        pub pixels_written: u64 => "pixels written",
        /// Passes over the active polygon list removing the polygons whose
        /// runs ended (at most one per crossing column of a row).
        pub apl_removal_passes: u64 => "apl removal passes",
        /// Active polygon list entries those passes examined: linear in
        /// the crossings of a row when polygons leave together, where a
        /// removal per polygon examined the list once per polygon.
        pub apl_removal_scanned: u64 => "apl removal scanned",
        /// Comparisons made sorting active polygon lists by depth: close to
        /// linear in the list length when the order is coherent from one
        /// span to the next, `N log N` at worst.
        pub sort_comparisons: u64 => "sort comparisons",
        /// Peak bytes of the working tables and lists (capacity, not
        /// length).
        pub peak_bytes: u64 => PEAK,
    }
}

impl ScanlineStats {
    /// Mean number of polygons active per image row.
    pub fn active_polygons_mean(&self) -> f64 {
        if self.rows == 0 {
            0.0
        } else {
            self.active_polygon_rows as f64 / self.rows as f64
        }
    }

    /// Fills the derived counters from the others, at the end of a frame.
    pub(crate) fn finish(&mut self) {
        self.active_polygons_mean_x1000 = (self.active_polygons_mean() * 1000.0).round() as u64;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_scene::HiderStats;

    #[test]
    fn mean_and_conversion() {
        let mut s = ScanlineStats {
            rows: 4,
            active_polygon_rows: 6,
            spans: 9,
            peak_bytes: 100,
            ..ScanlineStats::default()
        };
        s.finish();
        assert_eq!(s.active_polygons_mean(), 1.5);
        let g = s.table();
        assert_eq!(g.counters[4], ("spans", 9));
        assert_eq!(g.counters[11], ("active polygons mean x1000", 1500));
        assert_eq!(g.peak_bytes, 100);
        assert_eq!(ScanlineStats::default().active_polygons_mean(), 0.0);
    }

    /// The benchmark prints the counters under these names, in this order.
    #[test]
    fn the_table_keeps_the_printed_names_and_order() {
        let table = ScanlineStats::default().table();
        let names: Vec<&str> = table.counters.iter().map(|&(name, _)| name).collect();
        assert_eq!(
            names,
            [
                "polygons",
                "edges",
                "rows",
                "crossings",
                "spans",
                "split spans",
                "splits",
                "fallback spans",
                "fallback pixels",
                "active polygons max",
                "active polygon rows",
                "active polygons mean x1000",
                "span polygons max",
                "depth evaluations",
                "pixels written",
                "apl removal passes",
                "apl removal scanned",
                "sort comparisons",
            ]
        );
    }
}
