//! The ray-cast oracle: the lecture's "one depth variable" z-buffer.
//!
//! The lecture on image-space hidden-surface algorithms describes a z-buffer
//! variant that keeps a single depth variable instead of a depth array: for
//! each pixel, loop over every polygon, compute the depth where the ray
//! through the pixel meets it, keep the nearest. That is the oracle here,
//! with two changes that make it a referee rather than a renderer:
//!
//! - **coverage** is the shared exact decision (`ScreenTri::edges()`, the
//!   top-left rule on snapped fixed-point vertices), so every hider and the
//!   oracle agree on *which* triangles are candidates at a pixel centre;
//! - **depth** is not interpolated at all: the camera-space ray through the
//!   pixel centre is intersected in `f64` with a camera-space plane (see
//!   [`DepthPlane`] for which one). Nothing about screen-space interpolation
//!   (linear or 1/w, `f32` or fixed-point buffers) can leak in.
//!
//! Beside the winner it records the relative gap to the second-nearest
//! *distinct primitive* (pieces of one clipped primitive share an id), so a
//! test can tell a genuine tie from an error; see [`crate::DEFAULT_TIE_TOLERANCE`].

use glam::DVec3;
use hider_scene::{Error, Frame, Hider, NO_ID, Result, ScreenScene, ScreenTri, check_frame};

use crate::depth::{DepthModel, ray_plane_depth, snapped_plane, source_plane};
use crate::nearest::{EMPTY, Nearest};
use crate::options::{DepthPlane, OracleOptions};
use crate::reference::Reference;
use crate::tolerance::WINDOW_TIE_TOLERANCE;

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
        /// Covered pixels whose two nearest distinct primitives are within
        /// the tie tolerance.
        pub ties: u64 => "ties",
        /// Bytes of the per-pixel working arrays (nearest surfaces and
        /// camera rays).
        pub peak_bytes: u64 => PEAK,
    }
}

/// The exact per-pixel-centre reference. See the module documentation.
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
    /// takes: per pixel the nearest two surfaces, the camera ray, and the
    /// reference's id, depth and two gaps.
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
        Ok(self.evaluate(scene))
    }

    /// Evaluates every pixel centre of `scene`: the visible primitive, its
    /// window depth and the gap to the runner-up. Never fails and never
    /// panics; a primitive id without [`hider_scene::PrimInfo`] (a
    /// hand-built scene) is depth-tested on its window-depth plane.
    pub fn evaluate(&mut self, scene: &ScreenScene) -> Reference {
        self.run(scene).0
    }

    /// Errors when `scene` needs more memory or costs more tests than the
    /// budgets allow; the memory first, as it is known from the image size
    /// alone.
    fn check_budget(&self, scene: &ScreenScene) -> Result<()> {
        let vp = scene.viewport;
        let bytes = Self::bytes_needed(vp.width, vp.height);
        if bytes > self.options.max_bytes {
            return Err(Error::Budget {
                what: "oracle working bytes",
                value: bytes,
                limit: self.options.max_bytes,
            });
        }
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
        self.rays.reserve(w * h);
        for j in 0..vp.height {
            for i in 0..vp.width {
                self.rays
                    .push(scene.camera_ray(f64::from(i) + 0.5, f64::from(j) + 0.5));
            }
        }
        for tri in &scene.tris {
            self.cast(scene, &model, tri, &mut stats);
        }
        let reference = self.resolve(scene, &model, &mut stats);
        stats.peak_bytes = (self.nearest.capacity() * std::mem::size_of::<Nearest>()
            + self.rays.capacity() * std::mem::size_of::<(DVec3, DVec3)>())
            as u64;
        (reference, stats)
    }

    /// Offers `tri`'s depth at every pixel centre it covers.
    fn cast(
        &mut self,
        scene: &ScreenScene,
        model: &DepthModel,
        tri: &ScreenTri,
        stats: &mut OracleStats,
    ) {
        let vp = scene.viewport;
        let w = vp.width as usize;
        let corners = model.corner_depths(tri);
        let plane = match self.options.depth_plane {
            DepthPlane::Snapped => Some(snapped_plane(scene, tri, corners, model.perspective)),
            DepthPlane::Source => scene
                .prims
                .get(tri.prim as usize)
                .map(|p| source_plane(p.camera)),
        };
        let lo = corners.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = corners.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let (rays, nearest) = (&self.rays, &mut self.nearest);
        tri.for_each_centre(vp, |i, j, covered| {
            stats.pixel_tests += 1;
            if !covered {
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
            nearest[k].offer(clamped, tri.prim);
        });
    }

    /// Turns the nearest surfaces per pixel into the reference: ids with
    /// the tie rule, window depths and both gaps.
    fn resolve(
        &self,
        scene: &ScreenScene,
        model: &DepthModel,
        stats: &mut OracleStats,
    ) -> Reference {
        let vp = scene.viewport;
        let n = self.nearest.len();
        let mut ids = vec![NO_ID; n];
        let mut depth = vec![1.0f32; n];
        let mut gap = vec![f64::INFINITY; n];
        let mut window_gap = vec![f64::INFINITY; n];
        for (k, n) in self.nearest.iter().enumerate() {
            if n.first.1 == NO_ID {
                continue;
            }
            let (g, wg) = if n.second.1 == NO_ID {
                (f64::INFINITY, f64::INFINITY)
            } else {
                (
                    (n.second.0 - n.first.0) / model.gap_scale(n.first.0),
                    model.window_of_view_depth(n.second.0) - model.window_of_view_depth(n.first.0),
                )
            };
            if g < self.options.tie_tolerance || wg < WINDOW_TIE_TOLERANCE {
                stats.ties += 1;
            }
            // The id is the nearest surface's unless the relative gap is a
            // tie; a window-depth tie keeps the nearest, so that the strict
            // comparison (ties by relative gap only) can hold hiders with
            // `f64` depth to it.
            ids[k] = if g < self.options.tie_tolerance {
                n.first.1.min(n.second.1)
            } else {
                n.first.1
            };
            gap[k] = g;
            window_gap[k] = wg;
            depth[k] = model.window_of_view_depth(n.first.0).clamp(0.0, 1.0) as f32;
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

    /// Writes the reference ids and window depths into `frame`. Errors,
    /// before allocating anything, when the frame's size differs from the
    /// scene's, the image needs more than [`OracleOptions::max_bytes`] or
    /// the scene costs more than [`OracleOptions::max_pixel_tests`].
    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<OracleStats> {
        check_frame("oracle", scene, frame)?;
        self.check_budget(scene)?;
        let (reference, stats) = self.run(scene);
        frame.clear();
        frame.ids.copy_from_slice(&reference.ids);
        frame.depth.copy_from_slice(&reference.depth);
        Ok(stats)
    }
}
