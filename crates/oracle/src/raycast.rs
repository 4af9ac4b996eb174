//! The ray-cast oracle: the lecture's "one depth variable" z-buffer.
//!
//! Seed 004 (the lecture on image-space hidden-surface algorithms) describes
//! a z-buffer variant that keeps a single depth variable instead of a depth
//! array: for each pixel, loop over every polygon, compute the depth where
//! the ray through the pixel meets it, keep the nearest. That is the oracle
//! here, with two changes that make it a referee rather than a renderer:
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

use glam::{DMat4, DVec3, DVec4};
use hider_geom::Projection;
use hider_geom::fixed::pixel_center;
use hider_scene::{Error, Frame, Hider, NO_ID, Result, ScreenScene, ScreenTri, Stats, check_frame};

use crate::{DEFAULT_TIE_TOLERANCE, WINDOW_TIE_TOLERANCE};

/// Which camera-space plane the oracle intersects the pixel rays with.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DepthPlane {
    /// The plane through the screen triangle's *snapped* corners lifted back
    /// to camera space (each corner on the ray through its snapped window
    /// position, at its clip `w`). Projection maps planes to planes, so this
    /// is exactly the surface every hider is asked to render; the oracle
    /// differs from a hider only by arithmetic, and a tie tolerance of
    /// [`crate::DEFAULT_TIE_TOLERANCE`] separates rounding from errors. The
    /// referee for cross-validating hiders (the default).
    #[default]
    Snapped,
    /// The plane of the *source* triangle (`PrimInfo::camera`, before
    /// clipping and snapping). Measures what the front end's 1/256-pixel
    /// snapping does to visibility: where two surfaces cross or nearly
    /// touch, moving corners by up to 1/512 pixel can flip the order.
    /// Near the near plane, where screen-space depth gradients are steep,
    /// such flips appear at relative gaps above `1e-5`, so hiders are not
    /// scored against this plane.
    Source,
}

/// Options of the [`RayCastOracle`]. `Default` is the accurate choice.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OracleOptions {
    /// The plane each triangle's depth is taken from.
    pub depth_plane: DepthPlane,
    /// Relative gap under which the two nearest surfaces at a pixel count as
    /// a tie; at a tie the reference id is the lower primitive id (what a
    /// LESS z-buffer drawing in id order keeps).
    pub tie_tolerance: f64,
    /// Most (triangle, pixel) candidate tests one frame may cost, checked
    /// before any work in [`RayCastOracle::try_evaluate`] and `render`: the
    /// oracle is slow on purpose and should refuse rather than run for
    /// hours.
    pub max_pixel_tests: u64,
}

impl Default for OracleOptions {
    fn default() -> Self {
        Self {
            depth_plane: DepthPlane::Snapped,
            tie_tolerance: DEFAULT_TIE_TOLERANCE,
            max_pixel_tests: 1 << 34,
        }
    }
}

impl OracleOptions {
    /// Sets [`Self::depth_plane`].
    pub fn with_depth_plane(mut self, plane: DepthPlane) -> Self {
        self.depth_plane = plane;
        self
    }

    /// Sets [`Self::tie_tolerance`].
    pub fn with_tie_tolerance(mut self, tolerance: f64) -> Self {
        self.tie_tolerance = tolerance;
        self
    }

    /// Sets [`Self::max_pixel_tests`].
    pub fn with_max_pixel_tests(mut self, tests: u64) -> Self {
        self.max_pixel_tests = tests;
        self
    }
}

/// The work one evaluation did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OracleStats {
    /// (triangle, pixel centre) pairs tested with the edge functions: the
    /// sum of the triangles' pixel-bounds areas.
    pub pixel_tests: u64,
    /// Pairs where the triangle covered the centre (ray-plane
    /// intersections computed).
    pub hits: u64,
    /// Hits whose plane intersection was unusable (ray parallel to the
    /// plane, degenerate source triangle) and fell back to the window-depth
    /// plane.
    pub fallbacks: u64,
    /// Hits whose plane depth lay outside the piece's corner depths (the
    /// centre is inside the snapped triangle but outside the true one) and
    /// was clamped into that range.
    pub clamped: u64,
    /// Covered pixels whose two nearest distinct primitives are within the
    /// tie tolerance.
    pub ties: u64,
}

impl From<OracleStats> for Stats {
    fn from(s: OracleStats) -> Self {
        Stats {
            counters: vec![
                ("pixel tests", s.pixel_tests),
                ("hits", s.hits),
                ("fallbacks", s.fallbacks),
                ("clamped", s.clamped),
                ("ties", s.ties),
            ],
            peak_bytes: 0,
        }
    }
}

/// The oracle's answer for one frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Reference {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Visible primitive per pixel ([`NO_ID`] for background), row-major.
    pub ids: Vec<u32>,
    /// Window depth of the visible surface (1.0 for background).
    pub depth: Vec<f32>,
    /// Relative depth gap between the nearest and the second-nearest
    /// distinct primitive at each pixel centre (`f64::INFINITY` when fewer
    /// than two primitives cover it). See [`crate::DEFAULT_TIE_TOLERANCE`]
    /// for the measure.
    pub gap: Vec<f64>,
    /// Window-depth difference between the same two surfaces
    /// (`f64::INFINITY` when fewer than two cover the centre); below
    /// [`WINDOW_TIE_TOLERANCE`] an `f32` depth buffer cannot order them, so
    /// the pixel is a tie too.
    pub window_gap: Vec<f64>,
}

/// The nearest and second-nearest distinct primitives at one pixel.
#[derive(Clone, Copy, Debug)]
struct Nearest {
    first: (f64, u32),
    second: (f64, u32),
}

const EMPTY: Nearest = Nearest {
    first: (f64::INFINITY, NO_ID),
    second: (f64::INFINITY, NO_ID),
};

/// `a` is nearer than `b`: smaller depth, equal depth broken by lower id.
fn nearer(a: (f64, u32), b: (f64, u32)) -> bool {
    a.0 < b.0 || (a.0 == b.0 && a.1 < b.1)
}

impl Nearest {
    /// Offers a surface at view depth `d` of primitive `prim`.
    fn offer(&mut self, d: f64, prim: u32) {
        let c = (d, prim);
        if prim == self.first.1 {
            // Another piece of the winning primitive: same plane.
            self.first.0 = self.first.0.min(d);
        } else if nearer(c, self.first) {
            // The old winner is nearer than anything else that is not
            // `prim`, so it becomes the runner-up.
            self.second = self.first;
            self.first = c;
        } else if prim == self.second.1 {
            self.second.0 = self.second.0.min(d);
        } else if nearer(c, self.second) {
            self.second = c;
        }
    }
}

/// The camera quantities the per-pixel depth needs, computed once a frame.
struct DepthModel {
    projection: DMat4,
    inverse: DMat4,
    near: f64,
    far: f64,
    perspective: bool,
}

impl DepthModel {
    fn new(scene: &ScreenScene) -> Self {
        let (near, far, perspective) = match scene.camera.projection {
            Projection::Perspective { near, far, .. } => (near, far, true),
            Projection::Orthographic { near, far, .. } => (near, far, false),
        };
        Self {
            projection: scene.projection_matrix,
            inverse: scene.projection_matrix.inverse(),
            near,
            far,
            perspective,
        }
    }

    /// The denominator of the relative gap: the view depth itself for a
    /// perspective camera (at least `near`), the depth range for an
    /// orthographic one (whose window depth is linear in view depth).
    fn gap_scale(&self, d: f64) -> f64 {
        if self.perspective {
            d.max(self.near)
        } else {
            self.far - self.near
        }
    }

    /// View depth (distance in front of the eye along -Z) of window depth
    /// `zw`.
    fn view_depth_of_window(&self, zw: f64) -> f64 {
        let p = self.inverse * DVec4::new(0.0, 0.0, 2.0 * zw - 1.0, 1.0);
        -p.z / p.w
    }

    /// Window depth of view depth `d`.
    fn window_of_view_depth(&self, d: f64) -> f64 {
        let c = self.projection * DVec4::new(0.0, 0.0, -d, 1.0);
        (c.z / c.w + 1.0) * 0.5
    }

    /// View depths of a piece's corners: clip w for a perspective camera,
    /// linear in window depth for an orthographic one.
    fn corner_depths(&self, tri: &ScreenTri) -> [f64; 3] {
        if self.perspective {
            tri.w
        } else {
            tri.z.map(|z| self.near + z * (self.far - self.near))
        }
    }
}

/// The exact per-pixel-centre reference. See the module documentation.
#[derive(Clone, Debug, Default)]
pub struct RayCastOracle {
    options: OracleOptions,
    nearest: Vec<Nearest>,
    rays: Vec<(DVec3, DVec3)>,
    stats: OracleStats,
}

impl RayCastOracle {
    /// An oracle with the default options.
    pub fn new() -> Self {
        Self::default()
    }

    /// An oracle with the given options.
    pub fn with_options(options: OracleOptions) -> Self {
        Self {
            options,
            ..Self::default()
        }
    }

    /// The options in use.
    pub fn options(&self) -> &OracleOptions {
        &self.options
    }

    /// The work done by the last evaluation.
    pub fn stats(&self) -> OracleStats {
        self.stats
    }

    /// The (triangle, pixel) tests evaluating `scene` costs.
    pub fn pixel_tests(scene: &ScreenScene) -> u64 {
        scene
            .tris
            .iter()
            .filter_map(|t| t.pixel_bounds(scene.viewport))
            .map(|(x0, y0, x1, y1)| u64::from(x1 - x0 + 1) * u64::from(y1 - y0 + 1))
            .sum()
    }

    /// Like [`Self::evaluate`], but refuses with [`Error::Limit`] a scene
    /// costing more than [`OracleOptions::max_pixel_tests`].
    pub fn try_evaluate(&mut self, scene: &ScreenScene) -> Result<Reference> {
        let tests = Self::pixel_tests(scene);
        if tests > self.options.max_pixel_tests {
            return Err(Error::Limit {
                what: "oracle (triangle, pixel) tests",
                value: tests,
                limit: self.options.max_pixel_tests,
            });
        }
        Ok(self.evaluate(scene))
    }

    /// Evaluates every pixel centre of `scene`: the visible primitive, its
    /// window depth and the gap to the runner-up. Never fails and never
    /// panics; a primitive id without [`hider_scene::PrimInfo`] (a
    /// hand-built scene) is depth-tested on its window-depth plane.
    pub fn evaluate(&mut self, scene: &ScreenScene) -> Reference {
        let vp = scene.viewport;
        let (w, h) = (vp.width as usize, vp.height as usize);
        let model = DepthModel::new(scene);
        self.stats = OracleStats::default();
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
            let Some((x0, y0, x1, y1)) = tri.pixel_bounds(vp) else {
                continue;
            };
            let edges = tri.edges();
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
            for j in y0..=y1 {
                let py = i64::from(pixel_center(j as i32));
                for i in x0..=x1 {
                    self.stats.pixel_tests += 1;
                    let px = i64::from(pixel_center(i as i32));
                    if !edges.iter().all(|e| e.contains(px, py)) {
                        continue;
                    }
                    self.stats.hits += 1;
                    let k = j as usize * w + i as usize;
                    let (origin, dir) = self.rays[k];
                    let d = match plane.and_then(|p| ray_plane_depth(p, origin, dir)) {
                        Some(d) => d,
                        None => {
                            self.stats.fallbacks += 1;
                            let zw = tri.depth.eval(f64::from(i) + 0.5, f64::from(j) + 0.5);
                            model.view_depth_of_window(zw)
                        }
                    };
                    // Depth along a triangle never leaves its corners'
                    // range; a centre inside the snapped triangle but just
                    // outside the true one (or a grazing plane) would
                    // extrapolate, so clamp.
                    let d = if d.is_nan() { lo } else { d };
                    let clamped = d.clamp(lo, hi);
                    if clamped != d {
                        self.stats.clamped += 1;
                    }
                    self.nearest[k].offer(clamped, tri.prim);
                }
            }
        }

        let mut ids = vec![NO_ID; w * h];
        let mut depth = vec![1.0f32; w * h];
        let mut gap = vec![f64::INFINITY; w * h];
        let mut window_gap = vec![f64::INFINITY; w * h];
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
                self.stats.ties += 1;
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

/// The plane of a camera-space triangle: a point on it and its (unnormalised)
/// normal.
fn source_plane(c: [DVec3; 3]) -> (DVec3, DVec3) {
    (c[0], (c[1] - c[0]).cross(c[2] - c[0]))
}

/// The plane through a screen triangle's snapped corners lifted to camera
/// space: each corner on the camera ray through its snapped window position,
/// at its view depth (clip `w` for a perspective camera, which keeps full
/// precision where window depth is all but 1; linear in window depth for an
/// orthographic one).
fn snapped_plane(
    scene: &ScreenScene,
    tri: &ScreenTri,
    depths: [f64; 3],
    perspective: bool,
) -> (DVec3, DVec3) {
    let lift = |k: usize| {
        let (x, y) = tri.v[k].to_pixels();
        let (origin, dir) = scene.camera_ray(x, y);
        // Perspective: dir ends on the near plane (dir.z = -near), so the
        // point at view depth d is dir * (d / near). Orthographic: dir spans
        // near to far, window depth is the fraction along it.
        let t = if perspective {
            depths[k] / -dir.z
        } else {
            tri.z[k]
        };
        origin + dir * t
    };
    source_plane([lift(0), lift(1), lift(2)])
}

/// View depth where the ray `origin + t dir` meets the plane, or `None`
/// when the ray is (nearly) parallel to it or the triangle is degenerate.
fn ray_plane_depth((a, n): (DVec3, DVec3), origin: DVec3, dir: DVec3) -> Option<f64> {
    let denom = n.dot(dir);
    // Relative test: a plane seen exactly edge-on, or a zero normal from a
    // degenerate source triangle, has no usable intersection.
    let usable = denom.abs() > 1e-12 * n.length() * dir.length();
    if !usable {
        return None;
    }
    let t = n.dot(a - origin) / denom;
    let d = -(origin.z + t * dir.z);
    d.is_finite().then_some(d)
}

impl Hider for RayCastOracle {
    fn name(&self) -> &str {
        "oracle"
    }

    fn render(&mut self, scene: &ScreenScene, frame: &mut Frame) -> Result<Stats> {
        check_frame("oracle", scene, frame)?;
        let reference = self.try_evaluate(scene)?;
        frame.clear();
        frame.ids.copy_from_slice(&reference.ids);
        frame.depth.copy_from_slice(&reference.depth);
        let mut stats = Stats::from(self.stats);
        stats.peak_bytes = (self.nearest.capacity() * std::mem::size_of::<Nearest>()
            + self.rays.capacity() * std::mem::size_of::<(DVec3, DVec3)>())
            as u64;
        Ok(stats)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_keeps_distinct_primitives() {
        let mut n = EMPTY;
        n.offer(2.0, 5);
        n.offer(1.0, 7);
        n.offer(1.5, 7); // second piece of the winner
        assert_eq!(n.first, (1.0, 7));
        assert_eq!(n.second, (2.0, 5));
        n.offer(1.8, 5); // nearer piece of the runner-up
        assert_eq!(n.second, (1.8, 5));
        n.offer(0.5, 5); // runner-up overtakes
        assert_eq!(n.first, (0.5, 5));
        assert_eq!(n.second, (1.0, 7));
        n.offer(0.5, 3); // exact tie: lower id wins
        assert_eq!(n.first, (0.5, 3));
        assert_eq!(n.second, (0.5, 5));
    }

    #[test]
    fn ray_plane_depth_of_a_facing_plane() {
        let plane = source_plane([
            DVec3::new(-1.0, -1.0, -4.0),
            DVec3::new(1.0, -1.0, -4.0),
            DVec3::new(0.0, 1.0, -4.0),
        ]);
        let d = ray_plane_depth(plane, DVec3::ZERO, DVec3::new(0.1, 0.2, -0.5)).unwrap();
        assert!((d - 4.0).abs() < 1e-12);
        // Edge-on: no intersection.
        let edge_on = source_plane([
            DVec3::ZERO,
            DVec3::new(0.0, 0.0, -1.0),
            DVec3::new(0.0, 1.0, -1.0),
        ]);
        assert_eq!(
            ray_plane_depth(edge_on, DVec3::ZERO, DVec3::new(0.0, 0.3, -1.0)),
            None
        );
        // Degenerate source triangle.
        let line = source_plane([DVec3::ZERO, DVec3::X, DVec3::X * 2.0]);
        assert_eq!(ray_plane_depth(line, DVec3::ZERO, DVec3::NEG_Z), None);
    }
}
