//! The per-pixel oracle: the lecture's "one depth variable" z-buffer,
//! with an exact comparison.
//!
//! The lecture on image-space hidden-surface algorithms describes a z-buffer
//! variant that keeps a single depth variable instead of a depth array: for
//! each pixel, loop over every polygon, compute its depth at the pixel, keep
//! the nearest. That is the oracle here, with these changes that make it a
//! referee rather than a renderer:
//!
//! - **coverage** is the shared exact decision (`ScreenTri::edges()`, the
//!   top-left rule on snapped fixed-point vertices), so every hider and the
//!   oracle agree on *which* triangles are candidates at a pixel centre;
//! - **depth** is what every exact hider compares, the window-depth plane of
//!   the snapped triangle ([`DepthPlane::Snapped`]), and it is **compared
//!   exactly** (`crate::exact`: an `f64` filter with a proved bound, then
//!   exact integer arithmetic). A tie is an exactly equal depth, and the
//!   lower primitive id wins it. [`DepthPlane::Source`] instead intersects
//!   the camera ray through the centre with the source triangle's plane in
//!   `f64`, to measure what snapping does;
//! - beside the winner it records the gaps to the second-nearest *distinct
//!   primitive* (pieces of one clipped primitive share an id): both 0 at an
//!   exact tie, the relative one 0 at a rounding tie (closer than `f64`
//!   evaluation of the two planes resolves, [`crate::plane_rounding_bound`]);
//! - **alpha cut-outs** are tested natively: a pixel centre where a
//!   primitive's texture alpha (sampled as the colour pass samples it) is
//!   below one half is not covered by it, the rule of the colour pass's
//!   cut-out stage (`hider_scene::shade::cutout`), so the cross-validation
//!   holds on scenes with cut-outs.

use glam::DVec3;
use hider_scene::shade::cutout::AlphaTest;
use hider_scene::{Error, Frame, Hider, NO_ID, Result, ScreenScene, TextureOptions, check_frame};

use std::cmp::Ordering;

use hider_geom::fixed::pixel_center;

use crate::depth::{DepthModel, ray_plane_depth, source_plane};
use crate::exact::{DepthAt, compare, compare_exactly, filter, plane_rounding_bound};
use crate::nearest::{Candidate, EMPTY, Nearest};
use crate::options::{DepthPlane, OracleOptions};
use crate::reference::Reference;

hider_scene::hider_stats! {
    /// The work one frame of the oracle did.
    #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
    pub struct OracleStats {
        /// (triangle, pixel centre) pairs tested with the edge functions:
        /// the sum of the triangles' pixel-bounds areas.
        pub pixel_tests: u64 => "pixel tests",
        /// Pairs where the triangle covered the centre (ray-plane
        /// intersections computed).
        pub hits: u64 => "hits",
        /// Hits whose plane intersection was unusable (ray parallel to the
        /// plane, degenerate source triangle) and fell back to the
        /// window-depth plane.
        pub fallbacks: u64 => "fallbacks",
        /// Hits whose plane depth lay outside the piece's corner depths (the
        /// centre is inside the snapped triangle but outside the true one)
        /// and was clamped into that range.
        pub clamped: u64 => "clamped",
        /// Depth comparisons the `f64` filter could not decide, settled by
        /// exact arithmetic ([`DepthPlane::Snapped`] only).
        pub exact: u64 => "exact comparisons",
        /// Covered pixels whose two nearest distinct primitives are at
        /// exactly the same depth (the lower id is reported).
        pub ties: u64 => "ties",
        /// Covered pixels whose two nearest distinct primitives differ in
        /// exact window depth by less than evaluating their planes in
        /// `f64` can resolve (`plane_rounding_bound`; the nearer is
        /// reported).
        pub rounding_ties: u64 => "rounding ties",
        /// Bytes of the per-pixel working arrays (nearest surfaces and
        /// camera rays).
        pub peak_bytes: u64 => PEAK,
    }
}

/// The exact per-pixel-centre reference. See the module documentation
/// (the name is historical: the default mode compares window-depth planes
/// exactly, only [`DepthPlane::Source`] casts rays).
///
/// As a [`Hider`] it writes the reference ids and depths into a frame;
/// [`RayCastOracle::evaluate`] returns the whole [`Reference`], with the
/// tie gaps that scoring needs.
///
/// ```
/// use hider_oracle::{OracleOptions, RayCastOracle};
/// use hider_scene::{Frame, Hider, PrepareOptions, View, prepare, procedural};
///
/// let scene = procedural::cube();
/// let view = View::for_scene(&scene, 16, 16)?;
/// let screen = prepare(&scene, &view, &PrepareOptions::default())?;
/// let mut frame = Frame::new(16, 16)?;
/// let mut oracle = RayCastOracle::new(OracleOptions::default());
/// let stats = oracle.render(&screen, &mut frame)?;
/// assert!(stats.hits > 0);
/// assert_eq!(frame.ids, oracle.evaluate(&screen).ids);
/// # Ok::<(), hider_scene::Error>(())
/// ```
#[derive(Clone, Debug, Default)]
pub struct RayCastOracle {
    options: OracleOptions,
    nearest: Vec<Nearest>,
    rays: Vec<(DVec3, DVec3)>,
}

impl RayCastOracle {
    /// The (triangle, pixel) tests evaluating `scene` costs.
    pub fn pixel_tests(scene: &ScreenScene) -> u64 {
        scene
            .tris
            .iter()
            .filter_map(|t| t.pixel_bounds(scene.viewport))
            .map(|(x0, y0, x1, y1)| u64::from(x1 - x0 + 1) * u64::from(y1 - y0 + 1))
            .sum()
    }

    /// Bytes of the working arrays evaluating a `width x height` image
    /// takes at most: per pixel the nearest two surfaces, the camera ray
    /// (source-plane mode only), and the reference's id, depth and two
    /// gaps.
    pub fn bytes_needed(width: u32, height: u32) -> u64 {
        let per_pixel = std::mem::size_of::<Nearest>()
            + std::mem::size_of::<(DVec3, DVec3)>()
            + std::mem::size_of::<u32>()
            + std::mem::size_of::<f32>()
            + 2 * std::mem::size_of::<f64>();
        u64::from(width) * u64::from(height) * per_pixel as u64
    }

    /// Like [`Self::evaluate`], but refuses with [`Error::Limit`] a scene
    /// costing more than [`OracleOptions::max_pixel_tests`] or needing more
    /// memory than [`OracleOptions::max_bytes`].
    pub fn try_evaluate(&mut self, scene: &ScreenScene) -> Result<Reference> {
        self.check_budget(scene)?;
        let reference = self.evaluate(scene);
        self.options.cancel.poll()?;
        Ok(reference)
    }

    /// Evaluates every pixel centre of `scene`: the visible primitive, its
    /// window depth and the gaps to the runner-up. Never fails and never
    /// panics (a stopped [`OracleOptions::cancel`] leaves the triangles
    /// after it untested: [`Self::try_evaluate`] says so); a primitive id without [`hider_scene::PrimInfo`] (a
    /// hand-built scene) is depth-tested on its window-depth plane.
    pub fn evaluate(&mut self, scene: &ScreenScene) -> Reference {
        self.run(scene).0
    }

    /// Errors when a `width x height` image needs more working memory than
    /// [`OracleOptions::max_bytes`].
    fn check_bytes(&self, width: u32, height: u32) -> Result<()> {
        let bytes = Self::bytes_needed(width, height);
        if bytes > self.options.max_bytes {
            return Err(Error::Budget {
                what: "oracle working bytes",
                value: bytes,
                limit: self.options.max_bytes,
            });
        }
        Ok(())
    }

    /// Errors when `scene` needs more memory or costs more tests than the
    /// budgets allow; the memory first, as it is known from the image size
    /// alone.
    fn check_budget(&self, scene: &ScreenScene) -> Result<()> {
        self.check_bytes(scene.viewport.width, scene.viewport.height)?;
        let tests = Self::pixel_tests(scene);
        if tests > self.options.max_pixel_tests {
            return Err(Error::Limit {
                what: "oracle (triangle, pixel) tests",
                value: tests,
                limit: self.options.max_pixel_tests,
            });
        }
        Ok(())
    }

    /// The reference and the work it took.
    fn run(&mut self, scene: &ScreenScene) -> (Reference, OracleStats) {
        let vp = scene.viewport;
        let (w, h) = (vp.width as usize, vp.height as usize);
        let model = DepthModel::new(scene);
        let mut stats = OracleStats::default();
        self.nearest.clear();
        self.nearest.resize(w * h, EMPTY);
        self.rays.clear();
        if self.options.depth_plane == DepthPlane::Source {
            self.rays.reserve(w * h);
            for j in 0..vp.height {
                for i in 0..vp.width {
                    self.rays
                        .push(scene.camera_ray(f64::from(i) + 0.5, f64::from(j) + 0.5));
                }
            }
        }
        // Cut-outs are tested natively: a centre where the texture's alpha
        // is below one half is not covered (the rule of the colour pass's
        // cut-out stage, `hider_scene::shade::cutout`).
        let alpha = AlphaTest::new(scene, TextureOptions::default());
        for index in 0..scene.tris.len() {
            // A stopped token leaves the rest untested; `render` and
            // `try_evaluate` return its error.
            if self.options.cancel.check().is_err() {
                break;
            }
            let test = alpha.as_ref().filter(|a| a.may_cut(scene.tris[index].prim));
            match self.options.depth_plane {
                DepthPlane::Snapped => self.offer_exact(scene, index, test, &mut stats),
                DepthPlane::Source => self.cast(scene, &model, index, test, &mut stats),
            }
        }
        let reference = self.resolve(scene, &model, &mut stats);
        stats.peak_bytes = (self.nearest.capacity() * std::mem::size_of::<Nearest>()
            + self.rays.capacity() * std::mem::size_of::<(DVec3, DVec3)>())
            as u64;
        (reference, stats)
    }

    /// Offers triangle `index` at every pixel centre it covers, ordered by
    /// the exact window depth of the snapped triangles.
    fn offer_exact(
        &mut self,
        scene: &ScreenScene,
        index: usize,
        alpha: Option<&AlphaTest>,
        stats: &mut OracleStats,
    ) {
        let vp = scene.viewport;
        let w = vp.width as usize;
        let tri = &scene.tris[index];
        let nearest = &mut self.nearest;
        let mut exact = 0;
        tri.for_each_centre(vp, |i, j, covered| {
            stats.pixel_tests += 1;
            if !covered {
                return;
            }
            if alpha.is_some_and(|a| !a.passes(tri.prim, i, j)) {
                return;
            }
            stats.hits += 1;
            let (x, y) = centre(i, j);
            let mine = DepthAt::new(tri, x, y);
            let c = Candidate {
                tri: index as u32,
                prim: tri.prim,
                key: mine.key(),
            };
            // The filter on the stored keys first; the exact sum (from the
            // triangles, recomputed) only where it cannot decide.
            nearest[j as usize * w + i as usize].offer(c, |a, b| {
                filter(a.key, b.key).unwrap_or_else(|| {
                    exact += 1;
                    let at = |c: &Candidate| {
                        if c.tri == index as u32 {
                            mine
                        } else {
                            depth_at(scene, c, x, y)
                        }
                    };
                    compare_exactly(&at(a), &at(b))
                })
            });
        });
        stats.exact += exact;
    }

    /// Offers triangle `index`'s source-plane view depth at every pixel
    /// centre it covers ([`DepthPlane::Source`]).
    fn cast(
        &mut self,
        scene: &ScreenScene,
        model: &DepthModel,
        index: usize,
        alpha: Option<&AlphaTest>,
        stats: &mut OracleStats,
    ) {
        let vp = scene.viewport;
        let w = vp.width as usize;
        let tri = &scene.tris[index];
        let corners = model.corner_depths(tri);
        let plane = scene
            .prims
            .get(tri.prim as usize)
            .map(|p| source_plane(p.camera));
        let lo = corners.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = corners.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let (rays, nearest) = (&self.rays, &mut self.nearest);
        tri.for_each_centre(vp, |i, j, covered| {
            stats.pixel_tests += 1;
            if !covered {
                return;
            }
            if alpha.is_some_and(|a| !a.passes(tri.prim, i, j)) {
                return;
            }
            stats.hits += 1;
            let k = j as usize * w + i as usize;
            let (origin, dir) = rays[k];
            let d = match plane.and_then(|p| ray_plane_depth(p, origin, dir)) {
                Some(d) => d,
                None => {
                    stats.fallbacks += 1;
                    let zw = tri.depth.eval(f64::from(i) + 0.5, f64::from(j) + 0.5);
                    model.view_depth_of_window(zw)
                }
            };
            // Depth along a triangle never leaves its corners' range; a
            // centre inside the snapped triangle but just outside the
            // true one (or a grazing plane) would extrapolate, so clamp.
            let d = if d.is_nan() { lo } else { d };
            let clamped = d.clamp(lo, hi);
            if clamped != d {
                stats.clamped += 1;
            }
            let c = Candidate {
                tri: index as u32,
                prim: tri.prim,
                key: clamped,
            };
            nearest[k].offer(c, |a, b| a.key.total_cmp(&b.key));
        });
    }

    /// Turns the nearest surfaces per pixel into the reference: the nearest
    /// id (the lower id at an exact tie), its window depth and both gaps
    /// (both zero at an exact tie, `gap` alone zero at a rounding tie).
    fn resolve(
        &self,
        scene: &ScreenScene,
        model: &DepthModel,
        stats: &mut OracleStats,
    ) -> Reference {
        let vp = scene.viewport;
        let w = vp.width.max(1) as usize;
        let n = self.nearest.len();
        let snapped = self.options.depth_plane == DepthPlane::Snapped;
        let mut ids = vec![NO_ID; n];
        let mut depth = vec![1.0f32; n];
        let mut gap = vec![f64::INFINITY; n];
        let mut window_gap = vec![f64::INFINITY; n];
        for (k, n) in self.nearest.iter().enumerate() {
            if n.first.prim == NO_ID {
                continue;
            }
            let (i, j) = ((k % w) as u32, (k / w) as u32);
            let (x, y) = centre(i, j);
            // Window depth and view depth of a candidate.
            let depths = |c: &Candidate| {
                if snapped {
                    let zw = depth_at(scene, c, x, y).estimate;
                    (zw, model.view_depth(&scene.tris[c.tri as usize], i, j, zw))
                } else {
                    (model.window_of_view_depth(c.key), c.key)
                }
            };
            let (z1, d1) = depths(&n.first);
            ids[k] = n.first.prim;
            depth[k] = z1.clamp(0.0, 1.0) as f32;
            if n.second.prim == NO_ID {
                continue;
            }
            let tie = if snapped {
                compare(
                    &depth_at(scene, &n.first, x, y),
                    &depth_at(scene, &n.second, x, y),
                ) == Ordering::Equal
            } else {
                n.first.key == n.second.key
            };
            if tie {
                stats.ties += 1;
                gap[k] = 0.0;
                window_gap[k] = 0.0;
                continue;
            }
            // The runner-up is strictly farther; rounding in the estimates
            // must not make its window gap zero (an exact tie) or negative.
            let (z2, d2) = depths(&n.second);
            window_gap[k] = (z2 - z1).max(f64::MIN_POSITIVE);
            // A rounding tie: closer than evaluating the two planes in
            // `f64` (as the hiders do) can tell apart.
            let rounding = snapped && {
                let bound = |c: &Candidate| plane_rounding_bound(&scene.tris[c.tri as usize], i, j);
                let slack = 16.0 * f64::EPSILON * z2.abs().max(z1.abs());
                z2 - z1 <= bound(&n.first) + bound(&n.second) + slack
            };
            if rounding {
                stats.rounding_ties += 1;
                gap[k] = 0.0;
            } else {
                gap[k] = ((d2 - d1) / model.gap_scale(d1)).max(f64::MIN_POSITIVE);
            }
        }
        Reference {
            width: vp.width,
            height: vp.height,
            ids,
            depth,
            gap,
            window_gap,
        }
    }
}

/// The fixed-point position of the centre of pixel `(i, j)`.
fn centre(i: u32, j: u32) -> (i64, i64) {
    (
        i64::from(pixel_center(i as i32)),
        i64::from(pixel_center(j as i32)),
    )
}

/// The window depth of candidate `c`'s screen triangle at the fixed-point
/// centre `(x, y)`.
fn depth_at(scene: &ScreenScene, c: &Candidate, x: i64, y: i64) -> DepthAt {
    DepthAt::new(&scene.tris[c.tri as usize], x, y)
}

impl Hider for RayCastOracle {
    type Options = OracleOptions;
    type Stats = OracleStats;

    fn new(options: OracleOptions) -> Self {
        Self {
            options,
            nearest: Vec::new(),
            rays: Vec::new(),
        }
    }

    fn options(&self) -> &OracleOptions {
        &self.options
    }

    fn name(&self) -> &str {
        "oracle"
    }

    /// Errors when the image needs more than [`OracleOptions::max_bytes`].
    fn check_size(&self, width: u32, height: u32) -> Result<()> {
        self.check_bytes(width, height)
    }

    /// Writes the reference ids and window depths into `frame`. Errors,
    /// before allocating anything, when the frame's size differs from the
    /// scene's, the image needs more than [`OracleOptions::max_bytes`] or
    /// the scene costs more than [`OracleOptions::max_pixel_tests`].
    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<OracleStats> {
        check_frame("oracle", scene, frame)?;
        self.check_budget(scene)?;
        let (reference, stats) = self.run(scene);
        self.options.cancel.poll()?;
        frame.clear();
        frame.ids.copy_from_slice(&reference.ids);
        frame.depth.copy_from_slice(&reference.depth);
        Ok(stats)
    }
}
