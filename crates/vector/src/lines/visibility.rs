//! Visibility of a line segment: the interval each occluder hides,
//! decided in camera space against the unsnapped triangle (its shadow
//! volume from the eye), or against its screen pieces when clipped.

use glam::{DVec3, DVec4};
use hider_scene::{ScreenScene, ScreenTri};

use super::index::OccluderIndex;
use super::{Feature, LineStats, Visibility};
use crate::VectorOptions;
use crate::cull::{Culled, cull};
use crate::grid::{Grid, clip_all};

/// What hides line points: the occluders of every primitive, binned by
/// their screen triangles, the culled ones left out.
pub(super) struct Occlusion {
    index: OccluderIndex,
    occluders: Vec<Occluder>,
    /// Per primitive: all its screen triangles culled (see
    /// [`crate::cull`]), so every line on it alone is hidden.
    pub prim_culled: Vec<bool>,
    /// The cull, for lines hidden all along by its tiles' bounds.
    culled: Culled,
}

impl Occlusion {
    /// The occlusion of `scene` on `grid`; nothing culled when hidden
    /// lines are drawn.
    pub fn new(scene: &ScreenScene, grid: &Grid, options: &VectorOptions) -> Self {
        let (polys, boxes) = clip_all(scene, grid);
        let n = scene.tris.len();
        let culled = if options.dashed_hidden {
            Culled::none(n)
        } else {
            cull(
                scene,
                grid,
                &boxes,
                &vec![false; n],
                options.depth_tolerance,
            )
        };
        let mut prim_culled = vec![false; scene.prims.len()];
        let mut prim_live = vec![false; scene.prims.len()];
        let live: Vec<_> = boxes
            .iter()
            .enumerate()
            .map(|(k, b)| {
                let prim = scene.tris[k].prim as usize;
                if culled.hidden[k] {
                    prim_culled[prim] = true;
                    None
                } else {
                    prim_live[prim] = true;
                    *b
                }
            })
            .collect();
        for (c, &l) in prim_culled.iter_mut().zip(&prim_live) {
            *c &= !l;
        }
        let occluders: Vec<Occluder> = scene
            .prims
            .iter()
            .map(|p| Occluder::new(scene, p.camera))
            .collect();
        let unsnapped: Vec<bool> = occluders
            .iter()
            .map(|o| matches!(o, Occluder::Camera(_)))
            .collect();
        Self {
            index: OccluderIndex::new(scene, grid, &live, &polys, &unsnapped),
            occluders,
            prim_culled,
            culled,
        }
    }

    /// Whether nothing of `f` can be drawn: it lies on culled primitives
    /// only, or the cull's tiles hide its whole window segment.
    pub fn buries(&self, grid: &Grid, f: &Feature) -> bool {
        f.own.iter().all(|&p| self.prim_culled[p as usize])
            || self.culled.buries_segment(grid, f.ends[0], f.ends[1])
    }
}

/// Every feature's visible and hidden parts (see
/// [`super::feature_visibility`]).
pub(super) fn split_all(
    scene: &ScreenScene,
    occlusion: &Occlusion,
    features: &[Feature],
    options: &VectorOptions,
    stats: &mut LineStats,
) -> hider_scene::Result<Vec<Visibility>> {
    let context = Context {
        scene,
        index: &occlusion.index,
        occluders: &occlusion.occluders,
        tolerance: options.depth_tolerance,
    };
    // Per triangle and per primitive, the last feature (plus one) that
    // looked at it: a long occluder comes from many bins.
    let mut seen = Seen {
        tris: vec![0; scene.tris.len()],
        prims: vec![0; scene.prims.len()],
        stamp: 0,
        stars: Vec::new(),
    };
    features
        .iter()
        .map(|f| {
            options.cancel.poll()?;
            seen.stamp += 1;
            Ok(split_visibility(&context, f, &mut seen, stats))
        })
        .collect()
}

/// Which triangles and primitives the current feature has looked at.
struct Seen {
    tris: Vec<u32>,
    prims: Vec<u32>,
    stamp: u32,
    /// Scratch for the stars a query meets.
    stars: Vec<u32>,
}

/// Visible or hidden pieces shorter than this (pixels) are dropped.
const MIN_LENGTH: f64 = 1e-3;

/// Pieces shorter than this (in parameter) are dropped: they come from
/// occluders that only touch the segment at a shared vertex.
const MIN_PIECE: f64 = 1e-9;

/// How far (in barycentric terms) outside its edges an occluder still
/// holds a point: rounding of the camera-space products, so that a
/// segment lying exactly under the common edge of two occluders (a cube's
/// side edge under its front face's diagonal, seen head-on) is inside
/// both, not between them.
const ON_EDGE: f64 = 1e-12;

/// A triangle this close to edge-on (|det| against the product of its
/// corners' lengths) covers no solid angle worth testing.
const EDGE_ON: f64 = 1e-14;

/// How a primitive hides line points.
///
/// Lines are decided against the unsnapped camera-space triangle, not its
/// snapped screen triangle: near a smooth mesh's silhouette the front
/// faces are almost edge-on, their snapped projections (moved by up to
/// 1/512 pixel) cross the silhouette edges, and their ill-conditioned
/// depth planes put them in front there (on the 200-segment sphere at
/// 512 pixels that cut its outline into 12 pieces). In camera space a
/// point is hidden by a triangle exactly when it lies in the triangle's
/// shadow volume from the eye: three planes through the eye and an edge,
/// and the triangle's plane. Each is an affine function of the point, so
/// along a segment the hidden part is again one interval.
#[derive(Clone, Copy, Debug)]
enum Occluder {
    /// Affine forms `a . X + d` (as `(a, d)`) of a camera-space point:
    /// three edge sides, >= 0 inside (scaled so the opposite corner is
    /// 1), and the distance behind the plane, relative to the distance of
    /// the plane along the ray (perspective) or in camera units along the
    /// view direction (orthographic).
    Camera([DVec4; 4]),
    /// The front end clipped the triangle (it crosses the near or far
    /// plane): its screen pieces are what is drawn, so they are tested.
    Screen,
    /// Edge-on: hides nothing.
    Nothing,
}

impl Occluder {
    fn new(scene: &ScreenScene, c: [DVec3; 3]) -> Self {
        let m = scene.projection_matrix;
        let inside = c.iter().all(|p| {
            let k = m * p.extend(1.0);
            k.w > 0.0 && k.z >= -k.w && k.z <= k.w
        });
        if !inside {
            return Self::Screen;
        }
        let n = (c[1] - c[0]).cross(c[2] - c[0]);
        let form = |a: DVec3, d: f64| a.extend(d);
        if scene.is_perspective() {
            // det = c0 . (c1 x c2) = n . c0; (ci x cj) . ck = det.
            let det = n.dot(c[0]);
            let scale = c[0].length() * c[1].length() * c[2].length();
            // NaN corners fail the test too.
            if det.abs() <= EDGE_ON * scale || det.is_nan() {
                return Self::Nothing;
            }
            let side = |i: usize, j: usize| form(c[i].cross(c[j]) / det, 0.0);
            // n . X / det is 1 on the plane and 0 at the eye: minus 1 it
            // is how much farther X is than the plane along its ray.
            Self::Camera([side(1, 2), side(2, 0), side(0, 1), form(n / det, -1.0)])
        } else {
            let d = DVec3::NEG_Z;
            let nd = n.dot(d);
            if nd.abs() <= EDGE_ON * n.length() || nd.is_nan() {
                return Self::Nothing;
            }
            let side = |i: usize, j: usize, k: usize| {
                let a = (c[j] - c[i]).cross(d);
                let s = a.dot(c[k] - c[i]);
                form(a / s, -a.dot(c[i]) / s)
            };
            // X = hit + t d: t = n . (X - c0) / (n . d).
            Self::Camera([
                side(1, 2, 0),
                side(2, 0, 1),
                side(0, 1, 2),
                form(n / nd, -n.dot(c[0]) / nd),
            ])
        }
    }
}

/// What [`split_visibility`] reads.
struct Context<'a> {
    scene: &'a ScreenScene,
    index: &'a OccluderIndex,
    occluders: &'a [Occluder],
    tolerance: f64,
}

/// Shrinks `(a, b)` to where the affine `g(s) = g0 + s (g1 - g0)` is
/// `> 0`, or `>= 0` when `closed`; `b < a` when nothing is left.
fn keep(span: &mut (f64, f64), g0: f64, g1: f64, closed: bool) {
    let out = |g: f64| if closed { g < 0.0 } else { g <= 0.0 };
    if out(g0) && out(g1) {
        span.1 = -1.0;
    } else if out(g0) {
        span.0 = span.0.max(g0 / (g0 - g1));
    } else if out(g1) {
        span.1 = span.1.min(g0 / (g0 - g1));
    }
}

/// The window-segment parameter of camera-segment parameter `u`: under
/// perspective, `w` is not constant along the segment.
fn window_parameter(scene: &ScreenScene, f: &Feature, u: f64) -> f64 {
    if !scene.is_perspective() || u <= 0.0 || u >= 1.0 {
        return u;
    }
    let m = scene.projection_matrix;
    let w0 = (m * f.camera[0].extend(1.0)).w;
    let w1 = (m * f.camera[1].extend(1.0)).w;
    u * w1 / ((1.0 - u) * w0 + u * w1)
}

/// The camera-segment parameter interval of `f` that occluder `o` hides.
fn camera_hidden(
    forms: &[DVec4; 4],
    f: &Feature,
    tolerance: f64,
    perspective: bool,
) -> Option<(f64, f64)> {
    let [x0, x1] = f.camera;
    let eval = |g: DVec4, x: DVec3| g.truncate().dot(x) + g.w;
    let mut span = (0.0f64, 1.0f64);
    for g in &forms[..3] {
        keep(
            &mut span,
            eval(*g, x0) + ON_EDGE,
            eval(*g, x1) + ON_EDGE,
            true,
        );
    }
    // Behind the plane by more than the tolerance (relative to the
    // distance along the ray, or to the point's depth orthographically).
    let behind = |x: DVec3| {
        let scale = if perspective { 1.0 } else { x.z.abs().max(1.0) };
        eval(forms[3], x) - tolerance * scale
    };
    keep(&mut span, behind(x0), behind(x1), false);
    (span.1 - span.0 > MIN_PIECE).then_some(span)
}

/// The visible and hidden parameter intervals of one feature segment.
fn split_visibility(
    c: &Context,
    f: &Feature,
    seen: &mut Seen,
    stats: &mut LineStats,
) -> Visibility {
    let [p, q] = f.ends;
    let mut out = Visibility::default();
    // Only the part inside the image is drawn: outside it the occluders
    // are not binned (the regions clip them), and a plotter's page ends
    // there.
    let Some((from, to)) = inside_image(c.scene, p, q) else {
        return out;
    };
    let mut cover: Vec<(f64, f64)> = Vec::new();
    let mut stars = std::mem::take(&mut seen.stars);
    c.index
        .query(p.lerp(q, from), p.lerp(q, to), &mut stars, |k| {
            stats.occluder_candidates += 1;
            if std::mem::replace(&mut seen.tris[k as usize], seen.stamp) == seen.stamp {
                return;
            }
            let t = &c.scene.tris[k as usize];
            if f.own.contains(&t.prim) {
                return;
            }
            match &c.occluders[t.prim as usize] {
                Occluder::Nothing => {}
                Occluder::Camera(forms) => {
                    if std::mem::replace(&mut seen.prims[t.prim as usize], seen.stamp) == seen.stamp
                    {
                        return;
                    }
                    stats.occluder_tests += 1;
                    if let Some((a, b)) =
                        camera_hidden(forms, f, c.tolerance, c.scene.is_perspective())
                    {
                        cover.push((
                            window_parameter(c.scene, f, a),
                            window_parameter(c.scene, f, b),
                        ));
                    }
                }
                Occluder::Screen => {
                    stats.occluder_tests += 1;
                    if let Some(iv) = hidden_interval(t, p, q, c.tolerance) {
                        cover.push(iv);
                    }
                }
            }
        });
    seen.stars = stars;
    // Longest first among equal starts, so that the hidden pieces do not
    // depend on the order the index finds the occluders in.
    cover.sort_by(|a, b| a.0.total_cmp(&b.0).then(b.1.total_cmp(&a.1)));
    // Pieces under a thousandth of a pixel are where faces merely touch
    // the segment at a shared corner.
    let length = (q.x - p.x).hypot(q.y - p.y);
    let min_piece = (MIN_LENGTH / length).max(MIN_PIECE);
    let mut at = from;
    for (a, b) in cover {
        let (a, b) = (a.max(from), b.min(to));
        if b <= a {
            continue;
        }
        if a > at + min_piece {
            out.visible.push((at, a));
        }
        if b > at {
            if b - a.max(at) > min_piece {
                out.hidden.push((a.max(at), b));
            }
            at = b;
        }
    }
    if to > at + min_piece {
        out.visible.push((at, to));
    }
    out
}

/// The parameter interval of the window segment `p -> q` inside the image
/// (Liang-Barsky), `None` when it misses the image.
fn inside_image(scene: &ScreenScene, p: DVec3, q: DVec3) -> Option<(f64, f64)> {
    let (w, h) = (
        f64::from(scene.viewport.width),
        f64::from(scene.viewport.height),
    );
    let mut span = (0.0f64, 1.0f64);
    for (g0, g1) in [
        (p.x, q.x),
        (w - p.x, w - q.x),
        (p.y, q.y),
        (h - p.y, h - q.y),
    ] {
        keep(&mut span, g0, g1, true);
    }
    (span.1 > span.0).then_some(span)
}

/// The parameter interval of the segment `p -> q` (window space) that
/// the screen triangle `t` hides: inside the triangle and behind its depth
/// plane by more than `tolerance`.
fn hidden_interval(t: &ScreenTri, p: DVec3, q: DVec3, tolerance: f64) -> Option<(f64, f64)> {
    let mut span = (0.0f64, 1.0f64);
    let v = t.v.map(|v| v.to_pixels());
    // The triangle is closed: a segment lying exactly along its edge is
    // inside it (edge ends and corners are both on the 1/256-pixel grid,
    // so `side` is exact there and collinear means exactly 0).
    for k in 0..3 {
        let (e0, e1) = (v[k], v[(k + 1) % 3]);
        let side = |x: f64, y: f64| (e1.0 - e0.0) * (y - e0.1) - (e1.1 - e0.1) * (x - e0.0);
        keep(&mut span, side(p.x, p.y), side(q.x, q.y), true);
    }
    // Behind: the segment's depth minus the triangle's, beyond tolerance.
    let behind = |s: DVec3| s.z - t.depth.eval(s.x, s.y) - tolerance;
    keep(&mut span, behind(p), behind(q), false);
    (span.1 - span.0 > MIN_PIECE).then_some(span)
}
