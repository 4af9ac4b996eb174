//! The work counters of one scanline frame.

use hider_scene::Stats;

/// What one [`crate::Scanline`] frame did: the counts that explain its cost
/// next to a z-buffer's (which pays per covered pixel per polygon, where the
/// scanline pays per edge per row and per span).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ScanlineStats {
    /// Polygons (screen triangles) entered in the polygon table: those with
    /// at least one pixel-centre row inside the image.
    pub polygons: u64,
    /// Edges entered in the edge table (non-horizontal edges crossing at
    /// least one pixel-centre row inside the image).
    pub edges: u64,
    /// Image rows scanned.
    pub rows: u64,
    /// Edge crossings: the ends of polygon runs (two per non-empty run of a
    /// polygon on a row), i.e. the entries sorted per row.
    pub crossings: u64,
    /// Spans: runs of pixels between two consecutive crossings with at least
    /// one polygon in them, each resolved as a whole.
    pub spans: u64,
    /// Spans that had to be split because two polygons' depths cross inside
    /// them (interpenetration).
    pub split_spans: u64,
    /// Split points found (a span split twice counts two).
    pub splits: u64,
    /// Spans (or their remainders) handed to the one-row depth buffer
    /// fallback after [`crate::ScanlineOptions::max_splits_per_span`]
    /// splits.
    pub fallback_spans: u64,
    /// Pixels resolved by the fallback.
    pub fallback_pixels: u64,
    /// Largest number of polygons active on one row (their row range covers
    /// it, whether or not they cover a pixel centre on it).
    pub active_polygons_max: u64,
    /// Sum over rows of the polygons active on the row; divided by
    /// [`Self::rows`] it is the mean ([`Self::active_polygons_mean`]).
    pub active_polygon_rows: u64,
    /// Largest number of polygons overlapping in one span (the depth
    /// complexity the visible-surface step faced).
    pub span_polygons_max: u64,
    /// Depth-plane evaluations spent deciding visibility (not counting the
    /// one per written pixel for the depth output).
    pub depth_evaluations: u64,
    /// Pixels written (each covered pixel exactly once: no overdraw).
    pub pixels_written: u64,
    /// Peak bytes of the working tables and lists (capacity, not length).
    pub peak_bytes: u64,
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
}

impl From<ScanlineStats> for Stats {
    fn from(s: ScanlineStats) -> Self {
        let mut out = Stats {
            counters: Vec::with_capacity(15),
            peak_bytes: s.peak_bytes,
        };
        out.push("polygons", s.polygons);
        out.push("edges", s.edges);
        out.push("rows", s.rows);
        out.push("crossings", s.crossings);
        out.push("spans", s.spans);
        out.push("split spans", s.split_spans);
        out.push("splits", s.splits);
        out.push("fallback spans", s.fallback_spans);
        out.push("fallback pixels", s.fallback_pixels);
        out.push("active polygons max", s.active_polygons_max);
        out.push("active polygon rows", s.active_polygon_rows);
        // Stats holds integers: the mean in thousandths keeps three digits.
        out.push(
            "active polygons mean x1000",
            (s.active_polygons_mean() * 1000.0).round() as u64,
        );
        out.push("span polygons max", s.span_polygons_max);
        out.push("depth evaluations", s.depth_evaluations);
        out.push("pixels written", s.pixels_written);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mean_and_conversion() {
        let s = ScanlineStats {
            rows: 4,
            active_polygon_rows: 6,
            spans: 9,
            peak_bytes: 100,
            ..ScanlineStats::default()
        };
        assert_eq!(s.active_polygons_mean(), 1.5);
        let g: Stats = s.into();
        assert_eq!(g.get("spans"), Some(9));
        assert_eq!(g.get("active polygons mean x1000"), Some(1500));
        assert_eq!(g.peak_bytes, 100);
        assert_eq!(ScanlineStats::default().active_polygons_mean(), 0.0);
    }
}
