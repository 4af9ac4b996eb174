//! Binning inside the lean front end: each run of the front end's
//! triangle pass bins its triangles as it sets them up
//! ([`LeanSink`]), so no [`LeanTri`] is stored and read back. On the
//! 500 sphere that is 96 bytes a triangle written by the front end and
//! read by binning, 48 MB a frame, and a copy of the second run's
//! triangles at 2 threads.

use hider_scene::Scene;
use hider_scene::prepare::lean::{LeanSink, LeanTri};
use rayon::prelude::*;

use super::{BinItem, Bins, Chunk, Grid};
use crate::source::scene_opacity_runs;

/// One run of the lean front end's triangle pass, binned as it goes: its
/// items in order and its chunk of the bins (counted, filled by
/// [`Bins::adopt`] once every run is done and their places are known).
#[derive(Clone, Debug, Default)]
pub(crate) struct BinRun {
    items: Vec<BinItem>,
    chunk: Chunk,
    grid: Grid,
    /// [`crate::source::Source::opacity_runs`] of the frame.
    opacity: Vec<(u32, f32)>,
}

impl BinRun {
    /// Starts a frame on `grid` whose primitives have the opacity runs
    /// `opacity`.
    pub(crate) fn begin(&mut self, grid: Grid, opacity: &[(u32, f32)]) {
        self.grid = grid;
        self.opacity.clear();
        self.opacity.extend_from_slice(opacity);
        self.chunk.begin(grid.count());
    }
}

impl LeanSink for BinRun {
    fn clear(&mut self) {
        self.items.clear();
    }

    #[inline(always)]
    fn push(&mut self, tri: LeanTri) {
        let item = self.chunk.add(&tri, self.grid, &self.opacity);
        self.items.push(item);
    }

    fn len(&self) -> usize {
        self.items.len()
    }
}

impl Bins {
    /// The opacity runs of `scene`, before the lean front end has run
    /// ([`scene_opacity_runs`]), kept where [`Self::bin`] keeps a
    /// prepared scene's.
    pub(crate) fn scene_opacity(&mut self, scene: &Scene) -> &[(u32, f32)] {
        scene_opacity_runs(scene, &mut self.opacity);
        &self.opacity
    }

    /// Lends the items' memory to the first of `runs` before a frame, so
    /// that the first run writes the frame's items in place (the others
    /// are appended by [`Self::adopt`]).
    pub(crate) fn lend(&mut self, runs: &mut [BinRun]) {
        if let Some(first) = runs.first_mut() {
            std::mem::swap(&mut self.items, &mut first.items);
        }
    }

    /// Forgets the frame `runs` were binning when the front end failed
    /// part way: the items' memory goes back (see [`Self::lend`]) and no
    /// tile has triangles.
    pub(crate) fn abandon(&mut self, runs: &mut [BinRun]) {
        self.lend(runs);
        self.items.clear();
        self.chunks.clear();
        self.tiles = 0;
    }

    /// Takes the bins of `runs`, binned on `grid` by the lean front end
    /// after [`Self::lend`]: their items one run after the other, then
    /// each run's bins filled (in parallel) with its items' places.
    pub(crate) fn adopt(&mut self, runs: &mut [BinRun], grid: Grid) {
        self.tiles = grid.count();
        let Some((first, rest)) = runs.split_first_mut() else {
            self.items.clear();
            self.chunks.clear();
            return;
        };
        std::mem::swap(&mut self.items, &mut first.items);
        // Appended in parallel, as the runs were made.
        for run in rest.iter() {
            self.items.par_extend(run.items.par_iter().copied());
        }
        self.chunks.resize_with(runs.len(), Chunk::default);
        let mut firsts = Vec::with_capacity(runs.len());
        let mut next = 0;
        for (chunk, run) in self.chunks.iter_mut().zip(runs.iter_mut()) {
            // The run keeps the chunk it replaces: both keep their memory
            // from frame to frame.
            std::mem::swap(chunk, &mut run.chunk);
            firsts.push(next);
            next += chunk.key_tiles.len();
        }
        let fill = |(chunk, first): (&mut Chunk, usize)| {
            chunk.on_stack(|local| local.fill(first, grid.tiles.0));
        };
        if self.chunks.len() > 1 {
            self.chunks.par_iter_mut().zip(firsts).for_each(fill);
        } else {
            self.chunks.iter_mut().zip(firsts).for_each(fill);
        }
    }
}
