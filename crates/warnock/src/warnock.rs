//! [`Warnock`]: the subdivision as a [`Hider`]: checks, set-up, the pixel
//! pass (and, in the anti-aliased mode, the passes inside pixels).

use hider_scene::{Error, Frame, Hider, Result, ScreenScene, check_frame};

use crate::classify::{Setups, TriSetup};
use crate::coverage::{ColorCache, CoverageSink, SampleBuffer};
use crate::debug::{CutRegion, LeafRegion};
use crate::grid::{Grid, Region};
use crate::options::WarnockOptions;
use crate::pixel::PixelSink;
use crate::stats::WarnockStats;
use crate::subdivide::{Roots, Subdivider};
use crate::trace::{MAX_CLASS_RECORDS, PolygonClass, WindowClasses, WindowRecord};

/// The Warnock hider. Keeps its set-up records, candidate arena, stacks and
/// sample buffer between frames.
///
/// Its [`Hider::name`] is `warnock`, or `warnock-NxN` in the anti-aliased
/// mode ([`WarnockOptions::samples_per_side`] `N > 1`), where it also
/// resolves colour and coverage itself.
#[derive(Clone, Debug)]
pub struct Warnock {
    options: WarnockOptions,
    name: String,
    setups: Setups,
    outer: Subdivider,
    inner: Subdivider,
    samples: SampleBuffer,
    colors: ColorCache,
    leaves: Vec<LeafRegion>,
    cuts: Vec<CutRegion>,
}

impl Warnock {
    /// The final regions of the pixel pass of the last frame, when
    /// [`WarnockOptions::record_regions`] is on (empty otherwise). They tile
    /// the window: every pixel lies in exactly one.
    pub fn leaf_regions(&self) -> &[LeafRegion] {
        &self.leaves
    }

    /// The regions of the pixel pass of the last frame that were cut (no
    /// rule settled them whole), in the order they were cut, when
    /// [`WarnockOptions::record_regions`] is on (empty otherwise). With
    /// [`Self::leaf_regions`] they are every region the subdivision
    /// reached: each pixel lies in one cut region per level above its
    /// leaf.
    pub fn cut_regions(&self) -> &[CutRegion] {
        &self.cuts
    }

    /// Every window the pixel pass of the last frame looked at or settled,
    /// with each polygon's class against it and what decided it, when
    /// [`WarnockOptions::record_classes`] is on (empty otherwise).
    pub fn window_classes(&self) -> &WindowClasses {
        &self.outer.record
    }

    /// Worst-case working memory for `scene`, in bytes: the set-up records,
    /// one candidate list per subdivision level plus the root list (what the
    /// arena can hold at most), the colour cache and the region record.
    /// This is what [`WarnockOptions::max_bytes`] is checked against.
    pub fn working_bytes(&self, scene: &ScreenScene) -> u64 {
        let vp = scene.viewport;
        let side = vp.width.max(vp.height).max(1);
        let pixel_levels = u64::from(side.next_power_of_two().trailing_zeros()) + 1;
        let sample_levels = u64::from(self.options.samples_per_side.max(1).trailing_zeros());
        let tris = scene.tris.len() as u64;
        let lists = pixel_levels
            + 1
            + if sample_levels > 0 {
                sample_levels + 1
            } else {
                0
            };
        let mut bytes = lists * tris * 4 + tris * Setups::BYTES_PER_TRIANGLE as u64;
        if self.options.is_antialiased() {
            bytes += scene.prims.len() as u64 * 16;
        }
        if self.options.record_regions {
            let pixels = u64::from(vp.width) * u64::from(vp.height);
            // The cut regions are internal nodes of a tree whose leaves
            // are at most one a pixel: fewer than the leaves.
            bytes += pixels
                * (std::mem::size_of::<LeafRegion>() + std::mem::size_of::<CutRegion>()) as u64;
        }
        if self.options.record_classes {
            // Windows: the leaves and the cut ones, fewer than two a pixel.
            let pixels = u64::from(vp.width) * u64::from(vp.height);
            bytes += 2 * pixels * std::mem::size_of::<WindowRecord>() as u64
                + (MAX_CLASS_RECORDS * std::mem::size_of::<PolygonClass>()) as u64;
        }
        bytes
    }

    /// The checks made before anything is touched: options, frame size,
    /// memory budget, triangle count (returned).
    fn check(&self, scene: &ScreenScene, frame: &Frame) -> Result<u32> {
        self.options.validate()?;
        check_frame(&self.name, scene, frame)?;
        let bytes = self.working_bytes(scene);
        if bytes > self.options.max_bytes {
            return Err(Error::Budget {
                what: "warnock worst-case working memory (bytes)",
                value: bytes,
                limit: self.options.max_bytes,
            });
        }
        u32::try_from(scene.tris.len()).map_err(|_| Error::Limit {
            what: "warnock triangle count",
            value: scene.tris.len() as u64,
            limit: u64::from(u32::MAX),
        })
    }

    /// The set-up record of every triangle.
    fn set_up(&mut self, scene: &ScreenScene) -> Result<()> {
        self.setups.tris.clear();
        self.setups.depth.clear();
        for t in &scene.tris {
            let setup = TriSetup::new(t).ok_or_else(|| Error::Render {
                hider: self.name.clone(),
                message: format!("primitive {} lies outside the guard band", t.prim),
            })?;
            self.setups.tris.push(setup);
            self.setups.depth.push(t.depth);
        }
        Ok(())
    }

    /// Subdivides the whole window, starting from all `count` triangles,
    /// into `frame` (cleared).
    fn subdivide(
        &mut self,
        scene: &ScreenScene,
        frame: &mut Frame,
        count: u32,
        stats: &mut WarnockStats,
    ) {
        let vp = scene.viewport;
        let root = [Region::new(0, 0, vp.width, vp.height)];
        let record = self.options.record_regions;
        let leaves = record.then_some(&mut self.leaves);
        let cuts = record.then_some(&mut self.cuts);
        let n = self.options.samples_per_side;
        if n > 1 {
            frame.coverage.clear();
            frame.coverage.resize(frame.len(), 0.0);
            self.colors.reset(scene);
            let mut sink = CoverageSink {
                side: n,
                scene,
                shade: self.options.shade,
                frame,
                colors: &mut self.colors,
                inner: &mut self.inner,
                samples: &mut self.samples,
                leaves,
                cuts,
                cutouts: crate::coverage::SampleCutouts::new(scene),
            };
            let grid = Grid::pixels_with_samples(n);
            let roots = Roots {
                grid: &grid,
                regions: &root,
                level: 0,
            };
            self.outer
                .run(roots, 0..count, &self.setups, &mut sink, stats);
        } else {
            let mut sink = PixelSink {
                frame,
                leaves,
                cuts,
            };
            let grid = Grid::pixel_centres();
            let roots = Roots {
                grid: &grid,
                regions: &root,
                level: 0,
            };
            self.outer
                .run(roots, 0..count, &self.setups, &mut sink, stats);
        }
    }

    /// Bytes held by the working memory (capacity).
    fn bytes(&self) -> u64 {
        (self.setups.bytes()
            + self.outer.bytes()
            + self.inner.bytes()
            + self.samples.bytes()
            + self.colors.bytes()
            + self.leaves.capacity() * std::mem::size_of::<LeafRegion>()
            + self.cuts.capacity() * std::mem::size_of::<CutRegion>()) as u64
    }
}

impl Default for Warnock {
    fn default() -> Self {
        Self::new(WarnockOptions::default())
    }
}

impl Hider for Warnock {
    type Options = WarnockOptions;
    type Stats = WarnockStats;

    fn new(options: WarnockOptions) -> Self {
        let n = options.samples_per_side;
        let name = if n > 1 {
            format!("warnock-{n}x{n}")
        } else {
            "warnock".to_owned()
        };
        Self {
            options,
            name,
            setups: Setups::default(),
            outer: Subdivider::default(),
            inner: Subdivider::default(),
            samples: SampleBuffer::default(),
            colors: ColorCache::default(),
            leaves: Vec::new(),
            cuts: Vec::new(),
        }
    }

    fn options(&self) -> &WarnockOptions {
        &self.options
    }

    fn name(&self) -> &str {
        &self.name
    }

    /// Renders `scene` into `frame`: ids and depths, and in the
    /// anti-aliased mode coverage and colour too.
    ///
    /// Errors (before touching the frame) when the options are invalid,
    /// the frame's size differs from the scene's viewport, or the worst-case
    /// working memory ([`Warnock::working_bytes`]) is over
    /// [`WarnockOptions::max_bytes`].
    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<WarnockStats> {
        let count = self.check(scene, frame)?;
        self.set_up(scene)?;
        frame.clear();
        self.leaves.clear();
        self.cuts.clear();
        self.outer.record.reset(self.options.record_classes);
        self.outer.reset_peak();
        self.inner.reset_peak();
        let mut stats = WarnockStats::default();
        self.outer.cancel = self.options.cancel;
        self.subdivide(scene, frame, count, &mut stats);
        self.options.cancel.poll()?;
        stats.peak_candidates = (self.outer.peak() + self.inner.peak()) as u64;
        stats.peak_bytes = self.bytes();
        Ok(stats)
    }

    fn resolves_color(&self) -> bool {
        self.options.is_antialiased()
    }
}
