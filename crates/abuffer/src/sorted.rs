//! The sorted-transparency z-buffer: the usual work-around the A-buffer
//! replaces, kept to show what it gets wrong.
//!
//! As GPUs do (and as scratchapixel's depth-buffer lesson says:
//! "transparent surfaces are usually sorted back to front ... which can
//! give wrong results, for example when triangles intersect"): first every opaque triangle is
//! z-buffered per sample, writing depth and colour; then the translucent
//! triangles are sorted back to front by the mean window depth of their
//! corners and blended over the colour buffer (`c = a*src + (1-a)*dst`)
//! wherever they pass the depth test, without writing depth. One depth per
//! *triangle* cannot order triangles that overlap in depth or pierce each
//! other, so where translucent triangles interpenetrate (or a small one
//! sits in front of part of a large one whose centroid is nearer) the
//! blend order is wrong for some samples; the A-buffer orders every sample
//! (or at least every fragment) instead.
//!
//! Cut-outs are alpha-tested at every sample and at the centre
//! ([`crate::cutout`]); a texture with partial alpha makes its triangles
//! translucent, blended at each sample with opacity `d` times the texture
//! alpha there.
//!
//! Same samples, masks and depths as [`crate::SupersampledZBuffer`]; ids
//! and depth from the pixel-centre test of [`crate::centre`], over all
//! triangles whatever their opacity, as the A-buffer reports them; from a
//! world-space scene, the same front end (the A-buffer's lean one).

use hider_scene::prepare::lean::LeanTri;
use hider_scene::{Frame, Hider, PrepareOptions, Result, Scene, ScreenScene, View};

use crate::centre::{CentreBuffer, in_front};
use crate::coverage::{TriCoverage, pixel_range_of};
use crate::cutout::Cutouts;
use crate::depth::plane_depth;
use crate::options::SsaaOptions;
use crate::palette::{sample_point, to_pixel};
use crate::pattern::CENTRE;
use crate::source::{FrontEnds, Source};
use crate::stats::SsaaStats;
use hider_scene::shade::SetupCache;

/// A supersampled z-buffer with opaque-first, sorted back-to-front
/// transparency.
#[derive(Clone, Debug, Default)]
pub struct SortedTransparencyZBuffer {
    options: SsaaOptions,
    depth: Vec<f32>,
    prims: Vec<u32>,
    color: Vec<[f32; 3]>,
    hit: Vec<bool>,
    centre: CentreBuffer,
    colors: Vec<[f32; 4]>,
    order: Vec<(f64, u32)>,
    front: FrontEnds,
}

impl SortedTransparencyZBuffer {
    /// The sample buffers' bytes for `pixels` pixels (an f32 depth, a u32
    /// id, an RGB f32 colour and a coverage flag a sample), or the
    /// budget's error: what `draw` holds, and what `check_size` asks
    /// before a frame exists.
    fn bytes_for(&self, pixels: usize) -> Result<u64> {
        self.options
            .check_budget("sorted-transparency z-buffer memory (bytes)", pixels, 21)
    }

    /// Draws `tri` into the sample buffers: written when opaque, blended
    /// over what is there (depth tested, not written) when `translucent`.
    fn draw_tri(
        &mut self,
        (scene, setups): (&Source<'_>, &mut SetupCache),
        tri: &LeanTri,
        (translucent, cutouts): (bool, Option<&Cutouts<'_>>),
        stats: &mut SsaaStats,
    ) {
        let (w, h) = (scene.viewport.width, scene.viewport.height);
        let pattern = self.options.pattern;
        let n = pattern.count();
        let Some((x0, y0, x1, y1)) = pixel_range_of(&tri.v, pattern, w, h) else {
            return;
        };
        let flat = self.colors[tri.prim as usize];
        let setup = TriCoverage::from_vertices(&tri.v, pattern);
        // Partial alpha is blended (its opacity comes with the sample's
        // colour), cut-outs are tested.
        let cut = cutouts.filter(|c| c.may_cut(tri.prim) && !c.is_partial(tri.prim));
        for j in y0..=y1 {
            for (i, c) in setup.row(x0, x1, j) {
                let c = cut.map_or(c, |cut| cut.coverage(tri.prim, (i, j), c));
                stats.pixel_hits += 1;
                stats.full_coverage += u64::from(c.full);
                let p = j as usize * w as usize + i as usize;
                if c.centre {
                    self.centre
                        .test(p, plane_depth(&tri.depth, i, j, CENTRE), tri.prim);
                }
                for (k, &pos) in pattern.positions().iter().enumerate() {
                    if c.mask >> k & 1 == 0 {
                        continue;
                    }
                    stats.depth_tests += 1;
                    let s = p * n + k;
                    let z = plane_depth(&tri.depth, i, j, pos) as f32;
                    if !in_front(z, tri.prim, self.depth[s], self.prims[s]) {
                        continue;
                    }
                    stats.depth_writes += 1;
                    self.hit[s] = true;
                    let [r, g, b, alpha] =
                        scene.at_point(setups, tri.prim, flat, sample_point((i, j), pos));
                    if translucent {
                        let dst = self.color[s];
                        self.color[s] =
                            [0, 1, 2].map(|c| alpha * [r, g, b][c] + (1.0 - alpha) * dst[c]);
                    } else {
                        self.depth[s] = z;
                        self.prims[s] = tri.prim;
                        self.color[s] = [r, g, b];
                    }
                }
            }
        }
    }

    /// Writes ids and depth from the centre buffer, and colour and coverage
    /// as the mean over each pixel's samples.
    fn resolve(&self, frame: &mut Frame) {
        let pixels = frame.len();
        let n = self.options.pattern.count();
        self.centre.write(frame);
        frame.coverage.clear();
        frame.coverage.resize(pixels, 0.0);
        let inv_n = 1.0 / n as f32;
        for p in 0..pixels {
            let samples = &self.color[p * n..(p + 1) * n];
            let sum = samples.iter().fold([0.0f32; 3], |acc, c| {
                [acc[0] + c[0], acc[1] + c[1], acc[2] + c[2]]
            });
            frame.color[p] = to_pixel(sum.map(|c| c * inv_n));
            let covered = self.hit[p * n..(p + 1) * n].iter().filter(|&&h| h).count();
            frame.coverage[p] = covered as f32 * inv_n;
        }
    }

    /// Draws `scene`'s triangles into `frame` (of the scene's size):
    /// opaque ones first, then translucent ones back to front.
    fn draw(&mut self, scene: &Source<'_>, frame: &mut Frame) -> Result<SsaaStats> {
        let pixels = frame.len();
        let n = self.options.pattern.count();
        let mut stats = SsaaStats {
            bytes: self.bytes_for(pixels)?,
            ..SsaaStats::default()
        };
        frame.clear();
        self.depth.clear();
        self.depth.resize(pixels * n, f32::INFINITY);
        self.prims.clear();
        self.prims.resize(pixels * n, hider_scene::NO_ID);
        self.color.clear();
        self.color.resize(pixels * n, [0.0; 3]);
        self.hit.clear();
        self.hit.resize(pixels * n, false);
        self.centre.reset(pixels);
        scene.prim_colors(self.options.shade, &mut self.colors);
        let mut setups = SetupCache::default();
        let cutouts = Cutouts::new(scene.screen_scene(), self.options.pattern);
        let cutouts = cutouts.as_ref();
        let partial = |prim: u32| cutouts.is_some_and(|c| c.is_partial(prim));

        self.order.clear();
        for (t, tri) in scene.tris.iter().enumerate() {
            self.options.cancel.poll_every(t)?;
            if self.colors[tri.prim as usize][3] >= 1.0 && !partial(tri.prim) {
                self.draw_tri((scene, &mut setups), tri, (false, cutouts), &mut stats);
            } else {
                let mean = (tri.z[0] + tri.z[1] + tri.z[2]) / 3.0;
                self.order.push((mean, t as u32));
            }
        }
        // Back to front: farthest mean depth first.
        self.order
            .sort_unstable_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        let order = std::mem::take(&mut self.order);
        for (k, &(_, t)) in order.iter().enumerate() {
            self.options.cancel.poll_every(k)?;
            let tri = &scene.tris[t as usize];
            self.draw_tri((scene, &mut setups), tri, (true, cutouts), &mut stats);
        }
        self.order = order;
        self.resolve(frame);
        Ok(stats)
    }
}

impl Hider for SortedTransparencyZBuffer {
    type Options = SsaaOptions;
    type Stats = SsaaStats;

    fn new(options: SsaaOptions) -> Self {
        Self {
            options,
            ..Self::default()
        }
    }

    fn options(&self) -> &SsaaOptions {
        &self.options
    }

    fn name(&self) -> &str {
        "ssaa-sorted"
    }

    fn check_size(&self, width: u32, height: u32) -> Result<()> {
        self.bytes_for(width as usize * height as usize).map(drop)
    }

    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<SsaaStats> {
        hider_scene::check_frame("ssaa-sorted", scene, frame)?;
        let mut front = std::mem::take(&mut self.front);
        let result = front.screen(scene, self.options.shade, |s| self.draw(s, frame));
        self.front = front;
        result
    }

    /// The A-buffer's lean front end instead of `prepare` (the same
    /// frame, bit for bit); `screen` is left as it was unless the scene
    /// has cut-outs (alpha-tested per sample from `prepare`'s primitives).
    fn render_scene(
        &mut self,
        scene: &Scene,
        view: &View,
        options: &PrepareOptions,
        screen: &mut ScreenScene,
        frame: &mut Frame,
    ) -> Result<SsaaStats> {
        let mut front = std::mem::take(&mut self.front);
        let result = front.scene(
            "ssaa-sorted",
            (scene, view, options),
            screen,
            (self.options.shade, frame),
            |s, frame| self.draw(s, frame),
        );
        self.front = front;
        result
    }

    fn resolves_color(&self) -> bool {
        true
    }

    fn composites_transparency(&self) -> bool {
        true
    }
}
