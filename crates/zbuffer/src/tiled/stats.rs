//! Work counters of the tiled z-buffer.

hider_scene::hider_stats! {
    /// Work counters of one tiled z-buffer frame: what explains its time.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub struct TiledZBufferStats {
        /// Triangles whose bounding box met the viewport and were binned.
        pub triangles_binned: u64 => "triangles binned",
        /// Bin entries written: (triangle, tile) pairs of small triangles.
        pub bin_entries: u64 => "bin entries",
        /// Triangles too large to bin tile by tile (they cover many tiles);
        /// every tile their bounding box meets visits them from one shared list.
        pub large_triangles: u64 => "large triangles",
        /// Tiles with at least one triangle drawn into them.
        pub tiles_drawn: u64 => "tiles drawn",
        /// Tiles no triangle touched: cleared straight into the frame, their
        /// depth never initialised.
        pub tiles_skipped: u64 => "tiles skipped",
        /// (triangle, tile) pairs rasterised or rejected.
        pub triangle_tiles: u64 => "triangle-tiles",
        /// (triangle, tile) pairs rejected whole by the tile's maximum depth.
        pub hiz_triangle_rejects: u64 => "hi-z triangle rejects",
        /// (triangle, tile) pairs that passed the tile's test, rejected
        /// whole by the maxima of the blocks their bounding box meets.
        pub hiz_box_rejects: u64 => "hi-z box rejects",
        /// 8x8 blocks visited by large triangles.
        pub blocks_visited: u64 => "blocks visited",
        /// Blocks outside an edge of the triangle, found from their corners.
        pub blocks_outside: u64 => "blocks outside",
        /// Blocks inside all three edges: no per-pixel edge test.
        pub blocks_inside: u64 => "blocks inside",
        /// Blocks rejected by their maximum depth.
        pub hiz_block_rejects: u64 => "hi-z block rejects",
        /// Pixel centres whose edge functions were evaluated one by one.
        pub pixels_tested: u64 => "pixels tested",
        /// Pixel centres inside a triangle, each one depth test.
        pub depth_tests: u64 => "depth tests",
        /// Pixel fragments of triangles the lean front end found too small
        /// to rasterise, each one depth test (not in [`Self::depth_tests`]).
        pub fragments: u64 => "fragments",
        /// Depth tests that passed (of triangles and fragments).
        pub depth_passes: u64 => "depth passes",
        /// Bytes of the per-band tile buffers, bins and hierarchical depth.
        pub scratch_bytes: u64 => PEAK,
    }
}

impl TiledZBufferStats {
    /// Adds another band's counters (the frame-wide ones are set once).
    pub(crate) fn add(&mut self, o: &TiledZBufferStats) {
        self.tiles_drawn += o.tiles_drawn;
        self.tiles_skipped += o.tiles_skipped;
        self.triangle_tiles += o.triangle_tiles;
        self.hiz_triangle_rejects += o.hiz_triangle_rejects;
        self.hiz_box_rejects += o.hiz_box_rejects;
        self.blocks_visited += o.blocks_visited;
        self.blocks_outside += o.blocks_outside;
        self.blocks_inside += o.blocks_inside;
        self.hiz_block_rejects += o.hiz_block_rejects;
        self.pixels_tested += o.pixels_tested;
        self.depth_tests += o.depth_tests;
        self.fragments += o.fragments;
        self.depth_passes += o.depth_passes;
    }
}
