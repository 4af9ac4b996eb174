//! The A-buffer's work counters.

use hider_scene::Stats;

/// What one A-buffer frame did: the counts that explain its time and memory.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ABufferStats {
    /// Fragments generated: one per (triangle, pixel) pair with at least one
    /// covered sample or a covered centre, outside the blocks skipped by
    /// the hierarchical test ([`Self::culled_blocks`]). A partial pixel
    /// culled by the lower bound at its hull corner, before its mask is
    /// computed, counts here (and in [`Self::culled`]) even if its mask
    /// would have been empty.
    pub fragments: u64,
    /// Of those, fragments whose mask came from the full-coverage fast path
    /// (no per-sample edge tests).
    pub full_coverage: u64,
    /// Fragments merged into a neighbour of the same surface instead of
    /// taking a list entry.
    pub merged: u64,
    /// (triangle, 8 x 8 pixel block) pairs skipped by the hierarchical
    /// occlusion test: the triangle's plane over the block is behind the
    /// opaque bound of every pixel of it, so no fragment is generated there.
    pub culled_blocks: u64,
    /// Fragments discarded on arrival because they lie entirely behind the
    /// pixel's opaque bound (every sample and the centre covered by opaque
    /// fragments nearer than their `zmin`).
    pub culled: u64,
    /// Fragments removed from a list when the pixel's opaque bound dropped
    /// in front of them, or when an overflowing list was pruned of
    /// fragments hidden in every sample (both exact).
    pub pruned: u64,
    /// Fragments dropped by [`crate::OverflowPolicy::DropFarthest`] from a
    /// list still full after pruning: the only lossy step.
    pub dropped: u64,
    /// Longest list of any pixel at resolve time.
    pub max_list_len: u64,
    /// Mean list length over the pixels with at least one fragment.
    pub mean_list_len: f64,
    /// Pixels resolved sample by sample (per-sample depth with fragments
    /// overlapping in depth and in mask); the others take the mask path.
    pub per_sample_pixels: u64,
    /// Fragments held by the pool at its fullest (live fragments plus free
    /// slots).
    pub pool_fragments: u64,
    /// Working memory at its peak: pixel table plus fragment pool, bytes.
    pub bytes: u64,
}

impl From<ABufferStats> for Stats {
    fn from(s: ABufferStats) -> Self {
        Stats {
            counters: vec![
                ("fragments", s.fragments),
                ("full coverage", s.full_coverage),
                ("merged", s.merged),
                ("culled", s.culled),
                ("culled blocks", s.culled_blocks),
                ("pruned", s.pruned),
                ("dropped", s.dropped),
                ("max list", s.max_list_len),
                ("mean list x1000", (s.mean_list_len * 1000.0).round() as u64),
                ("per-sample pixels", s.per_sample_pixels),
                ("pool fragments", s.pool_fragments),
            ],
            peak_bytes: s.bytes,
        }
    }
}
