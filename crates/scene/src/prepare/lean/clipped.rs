//! The lean front ends' one way out for a triangle that must be clipped.

use crate::model::Scene;
use crate::prepare::{ClipScratch, FrontEnd, Part, PrepareStats, ScreenTri};

/// `prepare`'s own per-triangle path ([`FrontEnd::triangle`]), for the
/// triangles a lean front end cannot set up from its cached vertices: those
/// that cross a clipping plane. Both lean front ends (the A-buffer's
/// [`prepare_lean_into`](super::prepare_lean_into) and the tiled
/// z-buffer's depth scene) send them here, so a clipped triangle's pieces
/// are `prepare`'s, bit for bit, and are counted as `prepare` counts them.
///
/// Keeps the clipper's buffers and the pieces between triangles (no
/// allocation per clipped triangle once warm), and the counters of every
/// triangle it clipped ([`Self::stats`]), which the caller adds to its
/// own once the run is done.
#[derive(Clone, Debug, Default)]
pub struct ClipFallback {
    part: Part,
    scratch: ClipScratch,
}

impl ClipFallback {
    /// Clips, projects, snaps and sets up triangle `t` of mesh `m`
    /// (primitive `prim`) through `prepare`'s path: its screen pieces
    /// (positively oriented, `prepare`'s order), and the counters, to which
    /// the caller may add what it does with the pieces (a piece it drops,
    /// one it hands over as pixels).
    pub fn clip(
        &mut self,
        front: &FrontEnd,
        scene: &Scene,
        which: (usize, usize, u32),
    ) -> (&[ScreenTri], &mut PrepareStats) {
        let part = &mut self.part;
        part.prims.clear();
        part.tris.clear();
        front.triangle(scene, which, part, &mut self.scratch);
        (&part.tris, &mut part.stats)
    }

    /// The counters of every triangle clipped so far.
    pub fn stats(&self) -> &PrepareStats {
        &self.part.stats
    }
}
