//! The supersampled z-buffer baseline: a depth and an id per sample.
//!
//! What the A-buffer is measured against: the same sample positions
//! ([`SamplePattern`]), the same coverage masks ([`TriCoverage`], fast path
//! included), the same sample depths ([`sample_depth`] rounded to `f32`)
//! and the same depth order ([`in_front`]); the difference is that every
//! covered sample is depth-tested and written individually, and the buffer
//! holds `samples` depths and ids for every pixel of the image whether it
//! needs them or not. Opacity is ignored (every surface is opaque): this is
//! the plain z-buffer; see [`crate::SortedTransparencyZBuffer`] for the
//! usual transparency work-around.
//!
//! Resolve: each pixel's colour is the mean of its samples' primitive
//! colours (background black), its coverage the fraction of covered
//! samples; ids and depth come from the pixel-centre test of
//! [`crate::centre`].

use hider_scene::{Error, Frame, Hider, NO_ID, Result, ScreenScene, ShadeMode, Stats, check_frame};

use crate::centre::{CentreBuffer, in_front};
use crate::coverage::{TriCoverage, pixel_range, sample_depth};
use crate::options::DEFAULT_MAX_BYTES;
use crate::palette::{prim_colors, to_pixel};
use crate::pattern::{CENTRE, SamplePattern};

/// Options of the supersampling baselines ([`SupersampledZBuffer`] and
/// [`crate::SortedTransparencyZBuffer`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SsaaOptions {
    /// Sample positions (default: all 32 cells of the 8 x 4 grid).
    pub pattern: SamplePattern,
    /// How primitives are coloured.
    pub shade: ShadeMode,
    /// Bound on the sample buffers, in bytes, checked before allocating.
    pub max_bytes: u64,
}

impl Default for SsaaOptions {
    fn default() -> Self {
        Self {
            pattern: SamplePattern::Grid32,
            shade: ShadeMode::Lambert,
            max_bytes: DEFAULT_MAX_BYTES,
        }
    }
}

impl SsaaOptions {
    /// Sets [`Self::pattern`].
    pub fn with_pattern(mut self, pattern: SamplePattern) -> Self {
        self.pattern = pattern;
        self
    }

    /// Sets [`Self::shade`].
    pub fn with_shade(mut self, shade: ShadeMode) -> Self {
        self.shade = shade;
        self
    }

    /// Sets [`Self::max_bytes`].
    pub fn with_max_bytes(mut self, bytes: u64) -> Self {
        self.max_bytes = bytes;
        self
    }

    /// Checks that `pixels` pixels of `per_sample` bytes per sample (plus
    /// the centre buffer) fit in [`Self::max_bytes`]; returns the bytes.
    pub(crate) fn check_budget(
        &self,
        hider: &'static str,
        pixels: usize,
        per_sample: u64,
    ) -> Result<u64> {
        let bytes = pixels as u64 * (self.pattern.count() as u64 * per_sample + 12);
        if bytes > self.max_bytes {
            return Err(Error::Limit {
                what: hider,
                value: bytes,
                limit: self.max_bytes,
            });
        }
        Ok(bytes)
    }
}

/// Work counters of a supersampled z-buffer frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SsaaStats {
    /// (triangle, pixel) pairs with at least one covered sample or centre.
    pub pixel_hits: u64,
    /// Of those, decided by the full-coverage fast path.
    pub full_coverage: u64,
    /// Covered samples depth-tested.
    pub depth_tests: u64,
    /// Depth tests passed (sample written).
    pub depth_writes: u64,
    /// Bytes of the sample and centre buffers.
    pub bytes: u64,
}

impl From<SsaaStats> for Stats {
    fn from(s: SsaaStats) -> Self {
        Stats {
            counters: vec![
                ("pixel hits", s.pixel_hits),
                ("full coverage", s.full_coverage),
                ("depth tests", s.depth_tests),
                ("depth writes", s.depth_writes),
            ],
            peak_bytes: s.bytes,
        }
    }
}

/// An N-sample supersampled z-buffer (N = 1, 4, 8, 16, 32).
#[derive(Clone, Debug, Default)]
pub struct SupersampledZBuffer {
    options: SsaaOptions,
    depth: Vec<f32>,
    ids: Vec<u32>,
    centre: CentreBuffer,
    colors: Vec<[f32; 4]>,
    last: SsaaStats,
}

impl SupersampledZBuffer {
    /// A supersampled z-buffer with the given options.
    pub fn new(options: SsaaOptions) -> Self {
        Self {
            options,
            ..Self::default()
        }
    }

    /// The options.
    pub fn options(&self) -> &SsaaOptions {
        &self.options
    }

    /// The counters of the last frame.
    pub fn stats(&self) -> SsaaStats {
        self.last
    }

    /// After a render: the primitive at every sample (`samples` per pixel,
    /// row-major), [`NO_ID`] for background.
    pub fn sample_ids(&self) -> &[u32] {
        &self.ids
    }
}

impl Hider for SupersampledZBuffer {
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

    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<Stats> {
        check_frame("ssaa", scene, frame)?;
        let (w, h) = (scene.viewport.width, scene.viewport.height);
        let pixels = w as usize * h as usize;
        let pattern = self.options.pattern;
        let n = pattern.count();
        let mut stats = SsaaStats {
            bytes: self
                .options
                .check_budget("supersampled z-buffer memory (bytes)", pixels, 8)?,
            ..SsaaStats::default()
        };
        frame.clear();
        self.depth.clear();
        self.depth.resize(pixels * n, f32::INFINITY);
        self.ids.clear();
        self.ids.resize(pixels * n, NO_ID);
        self.centre.reset(pixels);
        prim_colors(scene, self.options.shade, &mut self.colors);
        let positions = pattern.positions();

        for tri in &scene.tris {
            let Some((x0, y0, x1, y1)) = pixel_range(tri, pattern, w, h) else {
                continue;
            };
            let setup = TriCoverage::new(tri, pattern);
            for j in y0..=y1 {
                for (i, c) in setup.row(x0, x1, j) {
                    stats.pixel_hits += 1;
                    stats.full_coverage += u64::from(c.full);
                    let p = j as usize * w as usize + i as usize;
                    if c.centre {
                        self.centre
                            .test(p, sample_depth(tri, i, j, CENTRE), tri.prim);
                    }
                    for (k, &pos) in positions.iter().enumerate() {
                        if c.mask >> k & 1 == 0 {
                            continue;
                        }
                        stats.depth_tests += 1;
                        let s = p * n + k;
                        let z = sample_depth(tri, i, j, pos) as f32;
                        if in_front(z, tri.prim, self.depth[s], self.ids[s]) {
                            self.depth[s] = z;
                            self.ids[s] = tri.prim;
                            stats.depth_writes += 1;
                        }
                    }
                }
            }
        }

        self.centre.write(frame);
        frame.coverage.clear();
        frame.coverage.resize(pixels, 0.0);
        let inv_n = 1.0 / n as f32;
        for p in 0..pixels {
            let mut sum = [0.0f32; 3];
            let mut covered = 0u32;
            for &id in &self.ids[p * n..(p + 1) * n] {
                if id != NO_ID {
                    covered += 1;
                    let c = self.colors[id as usize];
                    for (s, v) in sum.iter_mut().zip(c) {
                        *s += v;
                    }
                }
            }
            frame.coverage[p] = covered as f32 * inv_n;
            frame.color[p] = to_pixel(sum.map(|c| c * inv_n));
        }
        self.last = stats;
        Ok(stats.into())
    }

    fn resolves_color(&self) -> bool {
        true
    }
}
