//! The `euc` 0.5.3 peer: a pure-Rust, single-threaded software rasteriser.
//!
//! The pipeline's vertex shader multiplies the `f32` position by the
//! benchmark's `f32` matrix (clip space); depth is tested and written with
//! euc's `IfLessWrite`; the fragment shader returns one constant colour
//! (euc 0.5.3 has no primitive id and interpolates everything it passes from
//! vertex to fragment, so a constant is the flat per-triangle value). Back
//! faces are kept (`BackfaceCullingDisabled`; euc's default culls them).
//!
//! What euc does differently from GL, read from its source: its
//! `IfLessWrite` test is `<=`, not `<`; a pixel centre exactly on an edge is
//! inside both triangles (no fill rule); and it does not clip (the fit
//! camera keeps every scene between the near and far planes, so nothing
//! needs it here). The depth buffer is cleared to 1.0, GL's far plane.
//!
//! The span timed is the one of the GL peer: clear the colour and depth
//! buffers, then draw every triangle.

use std::time::Instant;

use euc::buffer::Buffer2d;
use euc::rasterizer::{BackfaceCullingDisabled, Triangles};
use euc::{DepthStrategy, Pipeline, Target};
use glam::{Mat4, Vec4};

use crate::scenes::Workload;

/// The colour every covered pixel gets.
const COVERED: u32 = 0xffff_ffff;
/// The colour of background pixels.
const BACKGROUND: u32 = 0;

/// The benchmark's pipeline: transform by the matrix, flat constant colour.
struct Flat {
    mvp: Mat4,
}

impl Pipeline for Flat {
    type Vertex = [f32; 3];
    type VsOut = ();
    type Pixel = u32;

    #[inline(always)]
    fn vert(&self, p: &[f32; 3]) -> ([f32; 4], ()) {
        let clip = self.mvp * Vec4::new(p[0], p[1], p[2], 1.0);
        (clip.to_array(), ())
    }

    #[inline(always)]
    fn frag(&self, _: &()) -> u32 {
        COVERED
    }

    fn get_depth_strategy(&self) -> DepthStrategy {
        DepthStrategy::IfLessWrite
    }
}

/// euc's triangle rasteriser with an `f32` depth buffer, culling nothing.
type Raster<'a> = Triangles<'a, Buffer2d<f32>, BackfaceCullingDisabled>;

/// One workload's result: per-run milliseconds and the covered pixels.
pub struct EucRun {
    /// Milliseconds of each timed run (warm-ups excluded).
    pub ms: Vec<f64>,
    /// Pixels covered in the last frame.
    pub covered: u64,
}

/// Draws `work` at least `warmups` times (see [`crate::timed_runs`]), then
/// `runs` times, into buffers of its size, and times
/// the last `runs` (clear both buffers + draw).
pub fn time(work: &Workload, warmups: usize, runs: usize) -> EucRun {
    let side = work.size as usize;
    let mut color = Buffer2d::new([side, side], BACKGROUND);
    let mut depth = Buffer2d::new([side, side], 1.0f32);
    let pipeline = Flat { mvp: work.mvp };
    let ms = crate::timed_runs(warmups, runs, || {
        let t = Instant::now();
        color.clear(BACKGROUND);
        depth.clear(1.0);
        pipeline.draw::<Raster<'_>, _>(&work.positions, &mut color, Some(&mut depth));
        t.elapsed().as_secs_f64() * 1e3
    });
    let covered = color.as_ref().iter().filter(|&&c| c != BACKGROUND).count() as u64;
    EucRun { ms, covered }
}
