//! The pixel-centre sink: decisions written straight into the frame's id
//! and depth buffers, one sample per pixel at its centre.
//!
//! Every sample that ends up written was decided either by the z-buffer's
//! own test at that sample (`nearest_at`), by the per-sample edge test of
//! the only polygon left, or by a surrounder certified in front of all
//! others at every sample of its region; in all three cases the id is the
//! one a `LESS` z-buffer computing depth in `f64` keeps, and the depth is
//! the same `PlaneEq::eval` at the same point.

use hider_scene::Frame;

use crate::classify::Tri;
use crate::debug::{CutRegion, LeafRegion};
use crate::grid::{Grid, Region};
use crate::stats::{Rule, WarnockStats};
use crate::subdivide::Sink;

/// Writes pixel-centre decisions into a frame.
pub(crate) struct PixelSink<'a> {
    pub frame: &'a mut Frame,
    pub leaves: Option<&'a mut Vec<LeafRegion>>,
    pub cuts: Option<&'a mut Vec<CutRegion>>,
}

impl PixelSink<'_> {
    #[inline]
    fn write(&mut self, u: u32, v: u32, prim: u32, depth: f64, stats: &mut WarnockStats) {
        let i = self.frame.index(u, v);
        self.frame.ids[i] = prim;
        self.frame.depth[i] = depth as f32;
        stats.samples_written += 1;
    }
}

impl Sink for PixelSink<'_> {
    fn fill(&mut self, grid: &Grid, r: &Region, t: Tri<'_>, stats: &mut WarnockStats) {
        for v in r.v0..r.v1 {
            let y = grid.sample_y(v);
            for u in r.u0..r.u1 {
                let d = t.depth_at(grid.sample_x(u), y);
                self.write(u, v, t.prim(), d, stats);
            }
        }
        stats.depth_evaluations += r.cells();
    }

    fn single(&mut self, grid: &Grid, r: &Region, t: Tri<'_>, stats: &mut WarnockStats) {
        let Some(b) = grid.cells_touching(r, t.setup.x_bounds(), t.setup.y_bounds()) else {
            return;
        };
        for v in b.v0..b.v1 {
            let y = grid.sample_y(v);
            for u in b.u0..b.u1 {
                let x = grid.sample_x(u);
                if t.covers(x, y) {
                    stats.depth_evaluations += 1;
                    self.write(u, v, t.prim(), t.depth_at(x, y), stats);
                }
            }
        }
    }

    fn sample(&mut self, u: u32, v: u32, prim: u32, depth: f64, stats: &mut WarnockStats) {
        self.write(u, v, prim, depth, stats);
    }

    fn leaf(&mut self, r: &Region, rule: Rule, level: usize) {
        if let Some(leaves) = self.leaves.as_deref_mut() {
            leaves.push(LeafRegion::new(r, rule, level));
        }
    }

    fn cut(&mut self, r: &Region, level: usize) {
        if let Some(cuts) = self.cuts.as_deref_mut() {
            cuts.push(CutRegion::new(r, level));
        }
    }
}
