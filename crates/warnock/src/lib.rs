//! Warnock's area-subdivision hidden-surface algorithm on the hider front
//! end.
//!
//! Warnock (1969, "A hidden surface algorithm for computer generated
//! halftone pictures") divides and conquers the *image*: look at a window;
//! if what it holds is simple enough to draw, draw it; otherwise cut it into
//! four quadrants and look again. The lecture seed lists it with the
//! z-buffer and the scanline algorithm among the image-space methods.
//!
//! This crate runs that loop ([`subdivide`], iterative with an explicit
//! stack) over the shared [`ScreenScene`]:
//! - each polygon is classified against a region as surrounding,
//!   intersecting, contained or disjoint ([`classify`]) with the shared
//!   exact integer edge functions, evaluated at the region's extreme
//!   *samples* (a region is a rectangle of pixels, and what matters is which
//!   of their centres a triangle covers);
//! - a region is decided when it is empty, holds one polygon, or holds a
//!   surrounding polygon in front of all others at every sample (certified
//!   at the four corners on the affine depth planes; if planes cross inside
//!   the region it is subdivided further);
//! - at pixel size the pixel is resolved at its centre exactly as the
//!   z-buffer does (`LESS`, ties to the earlier primitive), so the picture
//!   equals the oracle's on every non-tie pixel, with identical coverage;
//! - candidate lists pass down the recursion in one reusable arena: a
//!   region's children see only its survivors;
//! - optionally ([`WarnockOptions::samples_per_side`]) the subdivision goes
//!   on inside pixels to an `n x n` sample grid for anti-aliased coverage
//!   ([`coverage`]);
//! - a debug record of the final regions draws the picture in the docs
//!   ([`debug`]).
//!
//! # Example
//!
//! ```
//! use hider_scene::{prepare, procedural, Frame, Hider, PrepareOptions, View};
//! use hider_warnock::{Rule, Warnock, WarnockOptions};
//!
//! let scene = procedural::intersecting_pair();
//! let view = View::for_scene(&scene, 64, 64)?;
//! let screen = prepare(&scene, &view, &PrepareOptions::default())?;
//! let mut frame = Frame::new(64, 64)?;
//! let mut warnock = Warnock::new(WarnockOptions::default());
//! let stats = warnock.render_frame(&screen, &mut frame)?;
//! // The two triangles pierce each other: both are visible somewhere.
//! assert!(frame.ids.contains(&0) && frame.ids.contains(&1));
//! // Big regions were settled whole (empty, or one triangle in front of the
//! // other); only the silhouettes and the piercing line were subdivided
//! // down to single pixels.
//! assert!(stats.decided_by(Rule::Empty) > 0);
//! assert!(stats.decided_by(Rule::SurrounderInFront) > 0);
//! assert_eq!(stats.max_level(), 6); // 64 = 2^6: level 6 is one pixel
//! assert!(stats.regions < 64 * 64 / 8);
//! # Ok::<(), hider_scene::Error>(())
//! ```

pub mod classify;
pub mod coverage;
pub mod debug;
pub mod grid;
pub mod options;
pub mod pixel;
pub mod stats;
pub mod subdivide;

pub use debug::{LeafRegion, draw_region_outlines};
pub use options::{MAX_SAMPLES_PER_SIDE, WarnockOptions};
pub use stats::{Rule, WarnockStats};

use hider_scene::{Error, Frame, Hider, Result, ScreenScene, Stats, check_frame};

use crate::classify::TriSetup;
use crate::coverage::{ColorCache, CoverageSink, SampleBuffer};
use crate::grid::{Grid, Region};
use crate::pixel::PixelSink;
use crate::subdivide::Subdivider;

/// The Warnock hider. Keeps its set-up records, candidate arena, stacks and
/// sample buffer between frames.
#[derive(Clone, Debug)]
pub struct Warnock {
    options: WarnockOptions,
    name: String,
    setups: Vec<TriSetup>,
    outer: Subdivider,
    inner: Subdivider,
    samples: SampleBuffer,
    colors: ColorCache,
    leaves: Vec<LeafRegion>,
}

impl Warnock {
    /// A Warnock hider with the given options. Its [`Hider::name`] is
    /// `warnock`, or `warnock-NxN` in the anti-aliased mode.
    pub fn new(options: WarnockOptions) -> Self {
        let n = options.samples_per_side;
        let name = if n > 1 {
            format!("warnock-{n}x{n}")
        } else {
            "warnock".to_owned()
        };
        Self {
            options,
            name,
            setups: Vec::new(),
            outer: Subdivider::default(),
            inner: Subdivider::default(),
            samples: SampleBuffer::default(),
            colors: ColorCache::default(),
            leaves: Vec::new(),
        }
    }

    /// The options in use.
    pub fn options(&self) -> &WarnockOptions {
        &self.options
    }

    /// The final regions of the pixel pass of the last frame, when
    /// [`WarnockOptions::record_regions`] is on (empty otherwise). They tile
    /// the window: every pixel lies in exactly one.
    pub fn leaf_regions(&self) -> &[LeafRegion] {
        &self.leaves
    }

    /// Worst-case working memory for `scene`, in bytes: the set-up records,
    /// one candidate list per subdivision level plus the root list (what the
    /// arena can hold at most), the colour cache and the region record.
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
        let mut bytes = lists * tris * 4 + tris * std::mem::size_of::<TriSetup>() as u64;
        if self.options.is_antialiased() {
            bytes += scene.prims.len() as u64 * 16;
        }
        if self.options.record_regions {
            let pixels = u64::from(vp.width) * u64::from(vp.height);
            bytes += pixels * std::mem::size_of::<LeafRegion>() as u64;
        }
        bytes
    }

    /// Renders `scene` into `frame` and returns the typed statistics.
    ///
    /// Errors (before touching the frame) when the options are invalid,
    /// the frame's size differs from the scene's viewport, or the worst-case
    /// working memory is over [`WarnockOptions::max_working_bytes`].
    pub fn render_frame(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<WarnockStats> {
        self.options.validate()?;
        check_frame(&self.name, scene, frame)?;
        let bytes = self.working_bytes(scene);
        if bytes > self.options.max_working_bytes {
            return Err(Error::Limit {
                what: "warnock worst-case working memory (bytes)",
                value: bytes,
                limit: self.options.max_working_bytes,
            });
        }
        let count = u32::try_from(scene.tris.len()).map_err(|_| Error::Limit {
            what: "warnock triangle count",
            value: scene.tris.len() as u64,
            limit: u64::from(u32::MAX),
        })?;

        self.setups.clear();
        for t in &scene.tris {
            let setup = TriSetup::new(t).ok_or_else(|| Error::Render {
                hider: self.name.clone(),
                message: format!("primitive {} lies outside the guard band", t.prim),
            })?;
            self.setups.push(setup);
        }
        frame.clear();
        self.leaves.clear();
        self.outer.reset_peak();
        self.inner.reset_peak();
        let mut stats = WarnockStats::default();
        let vp = scene.viewport;
        let root = [Region::new(0, 0, vp.width, vp.height)];
        let leaves = self.options.record_regions.then_some(&mut self.leaves);
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
            };
            let grid = Grid::pixels_with_samples(n);
            self.outer.run(
                &grid,
                &root,
                0..count,
                0,
                &self.setups,
                &mut sink,
                &mut stats,
            );
        } else {
            let mut sink = PixelSink { frame, leaves };
            let grid = Grid::pixel_centres();
            self.outer.run(
                &grid,
                &root,
                0..count,
                0,
                &self.setups,
                &mut sink,
                &mut stats,
            );
        }
        stats.peak_candidates = (self.outer.peak() + self.inner.peak()) as u64;
        stats.peak_bytes = (self.setups.capacity() * std::mem::size_of::<TriSetup>()
            + self.outer.bytes()
            + self.inner.bytes()
            + self.samples.bytes()
            + self.colors.bytes()
            + self.leaves.capacity() * std::mem::size_of::<LeafRegion>())
            as u64;
        Ok(stats)
    }
}

impl Default for Warnock {
    fn default() -> Self {
        Self::new(WarnockOptions::default())
    }
}

impl Hider for Warnock {
    fn name(&self) -> &str {
        &self.name
    }

    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<Stats> {
        self.render_frame(scene, frame).map(Stats::from)
    }

    fn resolves_color(&self) -> bool {
        self.options.is_antialiased()
    }
}
