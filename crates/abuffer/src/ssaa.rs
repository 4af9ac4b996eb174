//! The supersampled z-buffer baseline: a depth and an id per sample.
//!
//! What the A-buffer is measured against: the same sample positions
//! ([`SamplePattern`]), the same coverage masks ([`TriCoverage`], fast path
//! included), the same sample depths ([`plane_depth`] rounded to `f32`)
//! and the same depth order ([`in_front`]); the difference is that every
//! covered sample is depth-tested and written individually, and the buffer
//! holds `samples` depths and ids for every pixel of the image whether it
//! needs them or not. Opacity is ignored (every surface is opaque): this is
//! the plain z-buffer; see [`crate::SortedTransparencyZBuffer`] for the
//! usual transparency work-around. Cut-outs are alpha-tested at every
//! sample and at the centre ([`crate::cutout`]); partial alpha is tested
//! at one half.
//!
//! Resolve: each pixel's colour is the mean of its samples' primitive
//! colours (background black), its coverage the fraction of covered
//! samples; ids and depth come from the pixel-centre test of
//! [`crate::centre`].
//!
//! From a world-space scene ([`Hider::render_scene`]) the triangles and
//! colours come from the A-buffer's lean front end ([`FrontEnds`]), as
//! the A-buffer's do, textured and smooth-shaded scenes included: the same
//! frame as through `prepare`, bit for bit.

use hider_scene::{Frame, Hider, NO_ID, PrepareOptions, Result, Scene, ScreenScene, View};

use crate::centre::{CentreBuffer, in_front};
use crate::coverage::{TriCoverage, pixel_range_of};
use crate::cutout::Cutouts;
use crate::depth::plane_depth;
use crate::options::SsaaOptions;
use crate::palette::{sample_point, to_pixel};
use crate::pattern::{CENTRE, SamplePattern};
use crate::source::{FrontEnds, Source};
use crate::stats::SsaaStats;
use hider_scene::shade::SetupCache;

/// An N-sample supersampled z-buffer (N = 1, 4, 8, 16, 32).
#[derive(Clone, Debug, Default)]
pub struct SupersampledZBuffer {
    options: SsaaOptions,
    depth: Vec<f32>,
    ids: Vec<u32>,
    centre: CentreBuffer,
    colors: Vec<[f32; 4]>,
    front: FrontEnds,
}

impl SupersampledZBuffer {
    /// The sample buffers' bytes for `pixels` pixels (an f32 depth and a
    /// u32 id a sample), or the budget's error: what `draw` holds, and
    /// what `check_size` asks before a frame exists.
    fn bytes_for(&self, pixels: usize) -> Result<u64> {
        self.options
            .check_budget("supersampled z-buffer memory (bytes)", pixels, 8)
    }

    /// After a render: the primitive at every sample (`samples` per pixel,
    /// row-major), [`NO_ID`] for background.
    pub fn sample_ids(&self) -> &[u32] {
        &self.ids
    }

    /// Writes ids and depth from the centre buffer, and colour and coverage
    /// as the mean over each pixel's samples.
    fn resolve(&self, scene: &Source<'_>, frame: &mut Frame) {
        let pixels = frame.len();
        let n = self.options.pattern.count();
        let positions = self.options.pattern.positions();
        let mut setups = SetupCache::default();
        let w = frame.width() as usize;
        self.centre.write(frame);
        frame.coverage.clear();
        frame.coverage.resize(pixels, 0.0);
        let inv_n = 1.0 / n as f32;
        for p in 0..pixels {
            let mut sum = [0.0f32; 3];
            let mut covered = 0u32;
            let ij = ((p % w) as u32, (p / w) as u32);
            for (&id, &pos) in self.ids[p * n..(p + 1) * n].iter().zip(positions) {
                if id != NO_ID {
                    covered += 1;
                    let rgba = self.colors[id as usize];
                    let c = scene.at_point(&mut setups, id, rgba, sample_point(ij, pos));
                    for (s, v) in sum.iter_mut().zip(c) {
                        *s += v;
                    }
                }
            }
            frame.coverage[p] = covered as f32 * inv_n;
            frame.color[p] = to_pixel(sum.map(|c| c * inv_n));
        }
    }

    /// Draws `scene`'s triangles into `frame` (of the scene's size).
    fn draw(&mut self, scene: &Source<'_>, frame: &mut Frame) -> Result<SsaaStats> {
        let (w, h) = (scene.viewport.width, scene.viewport.height);
        let pixels = w as usize * h as usize;
        let pattern = self.options.pattern;
        let n = pattern.count();
        let mut stats = SsaaStats {
            bytes: self.bytes_for(pixels)?,
            ..SsaaStats::default()
        };
        frame.clear();
        self.depth.clear();
        self.depth.resize(pixels * n, f32::INFINITY);
        self.ids.clear();
        self.ids.resize(pixels * n, NO_ID);
        self.centre.reset(pixels);
        scene.prim_colors(self.options.shade, &mut self.colors);
        let positions = pattern.positions();
        // Partial alpha is tested at one half too: this z-buffer draws
        // every surface opaque.
        let cutouts = Cutouts::new(scene.screen_scene(), pattern);

        for (k, tri) in scene.tris.iter().enumerate() {
            self.options.cancel.poll_every(k)?;
            let cut = cutouts.as_ref().filter(|c| c.may_cut(tri.prim));
            let Some((x0, y0, x1, y1)) = pixel_range_of(&tri.v, pattern, w, h) else {
                continue;
            };
            let setup = TriCoverage::from_vertices(&tri.v, pattern);
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
                    for (k, &pos) in positions.iter().enumerate() {
                        if c.mask >> k & 1 == 0 {
                            continue;
                        }
                        stats.depth_tests += 1;
                        let s = p * n + k;
                        let z = plane_depth(&tri.depth, i, j, pos) as f32;
                        if in_front(z, tri.prim, self.depth[s], self.ids[s]) {
                            self.depth[s] = z;
                            self.ids[s] = tri.prim;
                            stats.depth_writes += 1;
                        }
                    }
                }
            }
        }

        self.resolve(scene, frame);
        Ok(stats)
    }
}

impl Hider for SupersampledZBuffer {
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
        // The sample count is part of the name so tables tell the
        // baselines apart.
        match self.options.pattern {
            SamplePattern::Centre => "ssaa-1",
            SamplePattern::Grid4 => "ssaa-4",
            SamplePattern::Grid8 => "ssaa-8",
            SamplePattern::Grid16 => "ssaa-16",
            SamplePattern::Grid32 => "ssaa-32",
        }
    }

    fn check_size(&self, width: u32, height: u32) -> Result<()> {
        self.bytes_for(width as usize * height as usize).map(drop)
    }

    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<SsaaStats> {
        hider_scene::check_frame("ssaa", scene, frame)?;
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
            "ssaa",
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
}
