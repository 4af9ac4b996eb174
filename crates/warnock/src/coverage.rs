//! The anti-aliased mode: Warnock's subdivision carried on inside pixels
//! down to an `n x n` grid of samples, for coverage instead of a single
//! centre sample.
//!
//! Warnock's own papers subdivide below the pixel to anti-alias edges; here
//! the pixel pass (regions of whole pixels, each holding `n x n` samples)
//! decides everything it can for whole pixels at once: a surrounder in
//! front covers all `n^2` samples of every pixel of its region, a single
//! polygon covers the samples its edge functions accept. A one-pixel region
//! still in doubt is handed to a second subdivision on that pixel's own
//! sample grid ([`Grid::samples_of_pixel`]), which writes a small sample
//! buffer that is then resolved into the pixel:
//!
//! - coverage: covered samples / `n^2` (scored against the oracle's
//!   analytic per-pixel coverage);
//! - colour: the box-filtered average of the samples' colours, background
//!   black;
//! - id: the primitive holding the most samples (ties to the earlier one),
//!   depth: its nearest sample depth.
//!
//! Alpha cut-outs: the subdivision decides visibility without textures,
//! so a pixel where it finds a primitive that may cut out visible (filled,
//! the single polygon, or at a sample of the inner subdivision) is
//! resolved again sample by sample: at each of its `n x n` samples, the
//! nearest primitive that covers it and passes the alpha test there
//! ([`CutoutSearch::nearest_at`], the texture alpha at the sample's own
//! position). Scenes without cut-outs never build the search.

use hider_scene::shade::cutout::{AlphaTest, CutoutSearch};
use hider_scene::shade::{SetupCache, prim_color, to_srgb8};
use hider_scene::{Frame, NO_ID, ScreenScene, ShadeMode, TextureOptions, TextureSampler};

use crate::classify::{Setups, Tri};
use crate::debug::{CutRegion, LeafRegion};
use crate::grid::{Grid, Region};
use crate::stats::{Rule, WarnockStats};
use crate::subdivide::{Roots, Sink, Subdivider};

/// Linear colours of primitives, computed on first use, kept between
/// frames for their memory.
#[derive(Clone, Debug, Default)]
pub(crate) struct ColorCache {
    colors: Vec<Option<[f32; 3]>>,
    /// The frame's sampler, when some primitive's colour varies across it
    /// (a texture, vertex normals, highlights).
    sampler: Option<TextureSampler>,
    /// The shading setups of the primitives shaded per point this frame.
    setups: SetupCache,
}

impl ColorCache {
    /// Forgets the colours and sizes the cache for `scene`.
    pub(crate) fn reset(&mut self, scene: &ScreenScene) {
        self.colors.clear();
        self.colors.resize(scene.prims.len(), None);
        let sampler = TextureSampler::new(scene, TextureOptions::default());
        self.sampler = scene.varies(&sampler).then_some(sampler);
        self.setups.clear();
    }

    fn get(&mut self, scene: &ScreenScene, shade: ShadeMode, prim: u32) -> [f32; 3] {
        match self.colors.get_mut(prim as usize) {
            Some(slot) => *slot.get_or_insert_with(|| prim_color(scene, prim, shade).0),
            None => [0.0; 3],
        }
    }

    /// The colour of `prim` in pixel `(u, v)`: its flat colour, or under
    /// Lambert shading its colour at the pixel centre when it varies (a
    /// primitive is shaded once per pixel, as multisample rasterisers and
    /// the A-buffer shade).
    fn at(&mut self, scene: &ScreenScene, shade: ShadeMode, prim: u32, u: u32, v: u32) -> [f32; 3] {
        let flat = self.get(scene, shade, prim);
        match &self.sampler {
            Some(sampler) if shade == ShadeMode::Lambert => {
                let (x, y) = (f64::from(u) + 0.5, f64::from(v) + 0.5);
                scene.surface_rgb_cached(sampler, &mut self.setups, prim, flat, x, y)
            }
            _ => flat,
        }
    }

    pub(crate) fn bytes(&self) -> usize {
        self.colors.capacity() * std::mem::size_of::<Option<[f32; 3]>>()
    }
}

/// One pixel's samples: the primitive seen at each (or [`NO_ID`]) and its
/// depth. Kept between pixels and frames.
#[derive(Clone, Debug, Default)]
pub(crate) struct SampleBuffer {
    side: u32,
    prims: Vec<u32>,
    depth: Vec<f64>,
    /// Scratch for the resolve: (primitive, samples, nearest depth).
    tally: Vec<(u32, u32, f64)>,
}

impl SampleBuffer {
    fn reset(&mut self, side: u32) {
        let n = (side * side) as usize;
        self.side = side;
        self.prims.clear();
        self.prims.resize(n, NO_ID);
        self.depth.clear();
        self.depth.resize(n, 1.0);
    }

    #[inline]
    fn set(&mut self, u: u32, v: u32, prim: u32, depth: f64, stats: &mut WarnockStats) {
        let i = (v * self.side + u) as usize;
        self.prims[i] = prim;
        self.depth[i] = depth;
        stats.samples_written += 1;
    }

    pub(crate) fn bytes(&self) -> usize {
        self.prims.capacity() * 4 + self.depth.capacity() * 8 + self.tally.capacity() * 16
    }
}

/// Writes one sub-pixel sample buffer: the sink of the inner subdivision.
struct SampleSink<'a> {
    buffer: &'a mut SampleBuffer,
}

impl Sink for SampleSink<'_> {
    fn fill(&mut self, grid: &Grid, r: &Region, t: Tri<'_>, stats: &mut WarnockStats) {
        for v in r.v0..r.v1 {
            for u in r.u0..r.u1 {
                let d = t.depth_at(grid.sample_x(u), grid.sample_y(v));
                self.buffer.set(u, v, t.prim(), d, stats);
            }
        }
        stats.depth_evaluations += r.cells();
    }

    fn single(&mut self, grid: &Grid, r: &Region, t: Tri<'_>, stats: &mut WarnockStats) {
        for v in r.v0..r.v1 {
            for u in r.u0..r.u1 {
                let (x, y) = (grid.sample_x(u), grid.sample_y(v));
                if t.covers(x, y) {
                    stats.depth_evaluations += 1;
                    self.buffer.set(u, v, t.prim(), t.depth_at(x, y), stats);
                }
            }
        }
    }

    fn sample(&mut self, u: u32, v: u32, prim: u32, depth: f64, stats: &mut WarnockStats) {
        self.buffer.set(u, v, prim, depth, stats);
    }
}

/// Writes anti-aliased pixels: the sink of the pixel pass in the
/// anti-aliased mode.
pub(crate) struct CoverageSink<'a> {
    pub side: u32,
    pub scene: &'a ScreenScene,
    pub shade: ShadeMode,
    pub frame: &'a mut Frame,
    pub colors: &'a mut ColorCache,
    pub inner: &'a mut Subdivider,
    pub samples: &'a mut SampleBuffer,
    pub leaves: Option<&'a mut Vec<LeafRegion>>,
    pub cuts: Option<&'a mut Vec<CutRegion>>,
    /// The alpha test of cut-outs, when some material may cut out
    /// ([`SampleCutouts::new`]).
    pub cutouts: Option<SampleCutouts<'a>>,
}

/// The alpha test of a frame's cut-outs at the sub-samples, and the search
/// that resolves a pixel where one is visible (binned on first use).
pub(crate) struct SampleCutouts<'a> {
    test: AlphaTest<'a>,
    search: Option<CutoutSearch<'a>>,
    scene: &'a ScreenScene,
}

impl<'a> SampleCutouts<'a> {
    /// `None` when no material of `scene` may cut out.
    pub(crate) fn new(scene: &'a ScreenScene) -> Option<Self> {
        let test = AlphaTest::new(scene, TextureOptions::default())?;
        Some(Self {
            test,
            search: None,
            scene,
        })
    }
}

impl CoverageSink<'_> {
    /// Whether `prim` may cut out (its samples then need the alpha test).
    fn may_cut(&self, prim: u32) -> bool {
        self.cutouts.as_ref().is_some_and(|c| c.test.may_cut(prim))
    }

    /// Resolves pixel `(u, v)` sample by sample: at each sample the nearest
    /// primitive covering it that passes the alpha test there.
    fn cut_pixel(&mut self, u: u32, v: u32, stats: &mut WarnockStats) {
        let Some(cut) = self.cutouts.as_mut() else {
            return;
        };
        let search = cut
            .search
            .get_or_insert_with(|| CutoutSearch::new(cut.scene));
        self.samples.reset(self.side);
        let grid = Grid::samples_of_pixel(u, v, self.side);
        let mut looked = 0;
        for sv in 0..self.side {
            for su in 0..self.side {
                let (x, y) = (grid.sample_x(su), grid.sample_y(sv));
                if let Some((prim, depth)) = search.nearest_at(&cut.test, x, y, &mut looked) {
                    stats.depth_evaluations += 1;
                    self.samples.set(su, sv, prim, depth, stats);
                }
            }
        }
        stats.cutout_candidates += looked;
        stats.cutout_pixels += 1;
        self.resolve_samples(u, v);
    }

    /// Writes pixel `(u, v)`: `covered` of its samples show something, the
    /// most of them `prim`, nearest at `depth`; `rgb_sum` is the sum of the
    /// covered samples' linear colours.
    fn write_pixel(
        &mut self,
        u: u32,
        v: u32,
        prim: u32,
        depth: f64,
        covered: u32,
        rgb_sum: [f32; 3],
    ) {
        let i = self.frame.index(u, v);
        let total = (self.side * self.side) as f32;
        self.frame.ids[i] = prim;
        self.frame.depth[i] = depth as f32;
        self.frame.coverage[i] = covered as f32 / total;
        let c = rgb_sum.map(|c| to_srgb8(c / total));
        self.frame.color[i] = [c[0], c[1], c[2], 255];
    }

    /// Resolves the sample buffer into pixel `(u, v)`.
    fn resolve_samples(&mut self, u: u32, v: u32) {
        let b = &mut *self.samples;
        b.tally.clear();
        for (&prim, &d) in b.prims.iter().zip(&b.depth) {
            if prim == NO_ID {
                continue;
            }
            match b.tally.iter_mut().find(|e| e.0 == prim) {
                Some(e) => {
                    e.1 += 1;
                    e.2 = e.2.min(d);
                }
                None => b.tally.push((prim, 1, d)),
            }
        }
        // Most samples wins; on equal counts the earlier primitive.
        let Some(&(prim, _, depth)) = b.tally.iter().min_by_key(|e| (std::cmp::Reverse(e.1), e.0))
        else {
            return;
        };
        let tally = std::mem::take(&mut self.samples.tally);
        let mut rgb = [0.0f32; 3];
        let mut covered = 0;
        for &(p, n, _) in &tally {
            let c = self.colors.at(self.scene, self.shade, p, u, v);
            for k in 0..3 {
                rgb[k] += c[k] * n as f32;
            }
            covered += n;
        }
        self.samples.tally = tally;
        self.write_pixel(u, v, prim, depth, covered, rgb);
    }
}

impl Sink for CoverageSink<'_> {
    fn fill(&mut self, grid: &Grid, r: &Region, t: Tri<'_>, stats: &mut WarnockStats) {
        if self.may_cut(t.prim()) {
            for v in r.v0..r.v1 {
                for u in r.u0..r.u1 {
                    self.cut_pixel(u, v, stats);
                }
            }
            return;
        }
        let n = self.side * self.side;
        for v in r.v0..r.v1 {
            for u in r.u0..r.u1 {
                let color = self
                    .colors
                    .at(self.scene, self.shade, t.prim(), u, v)
                    .map(|c| c * n as f32);
                // Depth is affine: its minimum over the pixel's samples is
                // at one of the corner samples.
                let one = Region::new(u, v, u + 1, v + 1);
                let s = grid.sample_rect(&one);
                let depth = [(s.x0, s.y0), (s.x1, s.y0), (s.x0, s.y1), (s.x1, s.y1)]
                    .map(|(x, y)| t.depth_at(x, y))
                    .into_iter()
                    .fold(f64::INFINITY, f64::min);
                self.write_pixel(u, v, t.prim(), depth, n, color);
            }
        }
        stats.depth_evaluations += 4 * r.cells();
        stats.samples_written += u64::from(n) * r.cells();
    }

    fn single(&mut self, grid: &Grid, r: &Region, t: Tri<'_>, stats: &mut WarnockStats) {
        let Some(b) = grid.cells_touching(r, t.setup.x_bounds(), t.setup.y_bounds()) else {
            return;
        };
        let cuts = self.may_cut(t.prim());
        for v in b.v0..b.v1 {
            for u in b.u0..b.u1 {
                if cuts {
                    self.cut_pixel(u, v, stats);
                    continue;
                }
                let color = self.colors.at(self.scene, self.shade, t.prim(), u, v);
                let g = Grid::samples_of_pixel(u, v, self.side);
                let mut covered = 0;
                let mut depth = f64::INFINITY;
                for sv in 0..self.side {
                    let y = g.sample_y(sv);
                    for su in 0..self.side {
                        let x = g.sample_x(su);
                        if t.covers(x, y) {
                            covered += 1;
                            depth = depth.min(t.depth_at(x, y));
                        }
                    }
                }
                if covered > 0 {
                    stats.depth_evaluations += u64::from(covered);
                    stats.samples_written += u64::from(covered);
                    self.write_pixel(
                        u,
                        v,
                        t.prim(),
                        depth,
                        covered,
                        color.map(|c| c * covered as f32),
                    );
                }
            }
        }
    }

    fn sample(&mut self, _u: u32, _v: u32, _prim: u32, _depth: f64, _stats: &mut WarnockStats) {
        // Cells of the pixel pass hold several samples: single-cell regions
        // go to `resolve_cell`, never here.
    }

    fn resolve_cell(
        &mut self,
        _grid: &Grid,
        r: &Region,
        candidates: &[u32],
        setups: &Setups,
        level: usize,
        stats: &mut WarnockStats,
    ) -> Rule {
        let (u, v) = (r.u0, r.v0);
        self.samples.reset(self.side);
        let grid = Grid::samples_of_pixel(u, v, self.side);
        let (roots, n) = Region::new(0, 0, self.side, self.side).quadrants();
        let mut sink = SampleSink {
            buffer: self.samples,
        };
        let roots = Roots {
            grid: &grid,
            regions: &roots[..n],
            level: level + 1,
        };
        self.inner
            .run(roots, candidates.iter().copied(), setups, &mut sink, stats);
        if self
            .samples
            .prims
            .iter()
            .any(|&p| p != NO_ID && self.may_cut(p))
        {
            self.cut_pixel(u, v, stats);
        } else {
            self.resolve_samples(u, v);
        }
        Rule::PixelSubdivided
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
