//! The work counters of the hiders of this crate, typed, with the names
//! the benchmark prints them under.

hider_scene::hider_stats! {
    /// What one A-buffer frame did: the counts that explain its time and
    /// memory.
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    pub struct ABufferStats {
        /// Fragments generated: one per (triangle, pixel) pair with at least
        /// one covered sample or a covered centre, outside the blocks skipped
        /// by the hierarchical test ([`Self::culled_blocks`]). A partial
        /// pixel culled by the lower bound at its hull corner, before its
        /// mask is computed, counts here (and in [`Self::culled`]) even if
        /// its mask would have been empty.
        pub fragments: u64 => "fragments",
        /// Of those, fragments whose mask came from the full-coverage fast
        /// path (no per-sample edge tests).
        pub full_coverage: u64 => "full coverage",
        /// Fragments merged into a neighbour of the same surface instead of
        /// taking a list entry.
        pub merged: u64 => "merged",
        /// Fragments discarded on arrival because they lie entirely behind
        /// the pixel's opaque bound (every sample and the centre covered by
        /// opaque fragments nearer than their `zmin`).
        pub culled: u64 => "culled",
        /// (triangle, 8 x 8 pixel block) pairs skipped by the hierarchical
        /// occlusion test: the triangle's plane over the block is behind the
        /// opaque bound of every pixel of it, so no fragment is generated
        /// there.
        pub culled_blocks: u64 => "culled blocks",
        /// (Triangle, tile) pairs over more than one 8 x 8 block rejected
        /// whole by the tile's opaque bound, before any block test (their
        /// blocks count in [`Self::culled_blocks`] too); in a tile resolved
        /// from the sample buffer, (triangle, pass of 32 rows) pairs.
        pub culled_tiles: u64 => "culled tiles",
        /// Fragments removed from a list when the pixel's opaque bound
        /// dropped in front of them, or when an overflowing list was pruned
        /// of fragments hidden in every sample (both exact).
        pub pruned: u64 => "pruned",
        /// Fragments dropped by [`crate::OverflowPolicy::DropFarthest`] from
        /// a list still full after pruning: the only lossy step.
        pub dropped: u64 => "dropped",
        /// (triangle, tile) pairs skipped because an opaque triangle with
        /// the same snapped vertices, in the same order, and a lower
        /// primitive id was taken before it in the tile: it would tie in
        /// depth at every sample and lose every tie (a face whose vertex
        /// list repeats itself is fan-split into such copies).
        pub coincident: u64 => "coincident",
        /// Longest list of any pixel at resolve time, in the tiles resolved
        /// from lists (0 when every tile took the sample buffer, whose
        /// pixels keep no lists: [`Self::sample_tiles`]).
        pub max_list_len: u64 => "max list",
        /// Mean list length over the pixels with at least one fragment, in
        /// the tiles resolved from lists (0 when every tile took the sample
        /// buffer).
        pub mean_list_len: f64 => _,
        /// [`Self::mean_list_len`] times 1000, rounded: the mean as the
        /// table prints it (its counters are integers).
        pub mean_list_len_x1000: u64 => "mean list x1000",
        /// Pixels resolved sample by sample (per-sample depth with fragments
        /// overlapping in depth and in mask); the others take the mask path.
        pub per_sample_pixels: u64 => "per-sample pixels",
        /// Tiles resolved from the sample buffer instead of fragment lists
        /// ([`crate::ABufferOptions::sample_tiles`]); their fragments count
        /// in [`Self::fragments`] and [`Self::culled`] like the lists'.
        pub sample_tiles: u64 => "sample tiles",
        /// Of the sample buffer's fragments, those that covered their whole
        /// pixel in front of everything there and were kept as one
        /// primitive for the pixel, with no per-sample depth (a later
        /// fragment that shares the pixel expands it to samples).
        pub whole_pixels: u64 => "whole pixels",
        /// Fragments held by the pool at its fullest (live fragments plus
        /// free slots).
        pub pool_fragments: u64 => "pool fragments",
        /// Working memory at its peak: pixel table plus fragment pool, bytes.
        pub bytes: u64 => PEAK,
    }
    warnings: ABufferStats::warnings
}

impl ABufferStats {
    /// What a user should be told about this frame, one line each: today
    /// only fragments lost to [`crate::OverflowPolicy::DropFarthest`]
    /// (empty when nothing was lost).
    pub fn warnings(&self) -> Vec<String> {
        let mut out = Vec::new();
        if self.dropped > 0 {
            out.push(format!(
                "abuffer dropped {} fragments from pixel lists full at max_list_len \
                 (longest list {}): surfaces may be missing there; raise max_list_len, \
                 or use OverflowPolicy::Error to fail instead",
                self.dropped, self.max_list_len
            ));
        }
        out
    }
}

hider_scene::hider_stats! {
    /// Work counters of a supersampled z-buffer frame (plain or with sorted
    /// transparency).
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub struct SsaaStats {
        /// (triangle, pixel) pairs with at least one covered sample or
        /// centre.
        pub pixel_hits: u64 => "pixel hits",
        /// Of those, decided by the full-coverage fast path.
        pub full_coverage: u64 => "full coverage",
        /// Covered samples depth-tested.
        pub depth_tests: u64 => "depth tests",
        /// Depth tests passed (sample written).
        pub depth_writes: u64 => "depth writes",
        /// Bytes of the sample and centre buffers.
        pub bytes: u64 => PEAK,
    }
}
