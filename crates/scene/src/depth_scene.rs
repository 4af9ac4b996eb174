//! The lean front end for depth-only hiders: the same snapped corners and
//! depth planes as [`prepare`](fn@crate::prepare), without what shading and
//! the oracle need.
//!
//! [`prepare`](fn@crate::prepare) writes, per triangle, a 160-byte
//! [`ScreenTri`] and a [`PrimInfo`](crate::PrimInfo) (camera-space corners,
//! normals, texture coordinates): for half a million triangles that is
//! 150 MB of writes, most of what a z-buffer frame costs. A z-buffer reads
//! only the snapped corners, the depth plane and the primitive id.
//! [`prepare_depth_into`] produces just those ([`DepthTri`], 72 bytes), and
//! works per *vertex* where `prepare` works per triangle corner: each
//! vertex is transformed, classified by its outcode, divided and snapped
//! once, and a triangle whose vertices need no clipping is set up from the
//! cached results. A triangle that must be clipped goes through
//! `prepare`'s own per-triangle path.
//!
//! Every number is the same function of the same inputs as in `prepare`
//! (the outcode is [`ClipVolume::outcode`](hider_geom::clip::ClipVolume::outcode), the divide and snap are
//! `prepare`'s `to_window`, the set-up is its `setup_depth`), so the
//! triangles are bit for bit the depth part of `prepare`'s, in the same
//! order, except that triangles that certainly cover no pixel centre are
//! dropped (their box holds none, or one or two that the exact edge
//! functions do not cover): they cover no sample of any pixel-centre hider. `tests::lean_equals_prepare` checks it on
//! random scenes in both precisions, with clipping and culling.

use glam::DVec4;
use hider_geom::clip::{ClipVertex, OUTSIDE_PLANES, OUTSIDE_VIEWPORT};
use hider_geom::{EdgeFunction, FixedPt, PlaneEq, Viewport, orient2d};
use rayon::prelude::*;

use crate::error::Result;
use crate::model::Scene;
use crate::prepare::{
    ClipScratch, FrontEnd, Part, PrepareOptions, PrepareStats, ScreenTri, setup_depth, to_window,
};
use crate::view::View;

/// A triangle as a depth-only hider needs it: [`ScreenTri`] without the
/// per-vertex depths, `w` and the `1/w` plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthTri {
    /// Snapped vertices, ordered so that the edge functions are positive
    /// inside (as [`ScreenTri::v`]).
    pub v: [FixedPt; 3],
    /// Window depth as an affine function of window position.
    pub depth: PlaneEq,
    /// Primitive id: index of the source triangle in the scene.
    pub prim: u32,
}

impl DepthTri {
    /// The edge functions of this triangle (top-left rule applied).
    #[inline]
    pub fn edges(&self) -> [EdgeFunction; 3] {
        hider_geom::edge::triangle_edges(&self.v)
    }

    /// The inclusive pixel rectangle whose centres may be covered (see
    /// [`Viewport::pixel_bounds`]).
    #[inline]
    pub fn pixel_bounds(&self, viewport: Viewport) -> Option<(u32, u32, u32, u32)> {
        viewport.pixel_bounds(&self.v)
    }
}

impl From<&ScreenTri> for DepthTri {
    fn from(t: &ScreenTri) -> Self {
        Self {
            v: t.v,
            depth: t.depth,
            prim: t.prim,
        }
    }
}

/// A scene as depth-only hiders consume it: what [`prepare_depth_into`]
/// makes. Keeps its memory between frames.
#[derive(Clone, Debug, Default)]
pub struct DepthScene {
    /// The image size.
    pub viewport: Viewport,
    /// The triangles in primitive-id order, cut into contiguous runs (one
    /// per worker that set them up); hiders may work on the runs in
    /// parallel and must visit them in order.
    pub parts: Vec<Vec<DepthTri>>,
    /// What the front end did. [`PrepareStats::output`] counts the
    /// triangles kept, [`PrepareStats::empty`] those dropped for covering
    /// no pixel centre.
    pub stats: PrepareStats,
    /// Per vertex of every mesh (meshes one after the other): the cached
    /// snapped position, window depth and classification.
    vertices: Vec<CachedVertex>,
}

impl DepthScene {
    /// An empty scene (the buffers grow on first use).
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of triangles kept.
    pub fn len(&self) -> usize {
        self.parts.iter().map(Vec::len).sum()
    }

    /// Whether no triangle was kept.
    pub fn is_empty(&self) -> bool {
        self.parts.iter().all(Vec::is_empty)
    }

    /// Every triangle kept, in primitive-id order.
    pub fn tris(&self) -> impl Iterator<Item = &DepthTri> + '_ {
        self.parts.iter().flatten()
    }

    /// Bytes of memory held.
    pub fn bytes(&self) -> usize {
        self.parts
            .iter()
            .map(|p| p.capacity() * std::mem::size_of::<DepthTri>())
            .sum::<usize>()
            + self.vertices.capacity() * std::mem::size_of::<CachedVertex>()
    }
}

/// Outcode bit: the clip-space position is not finite.
const NOT_FINITE: u32 = 1 << 30;
/// Outcode bit: the vertex has no window position (it fails a clip plane,
/// so only the clipping path uses it, or its divide left the snappable
/// range).
const NO_WINDOW: u32 = 1 << 31;

/// One vertex after transform, classification, divide and snap.
#[derive(Clone, Copy, Debug, Default)]
struct CachedVertex {
    p: FixedPt,
    z: f64,
    code: u32,
}

/// Vertices per parallel work item of the vertex pass.
const VERTEX_CHUNK: usize = 16 * 1024;
/// Below this many triangles the scene is set up on one thread.
const PARALLEL_MIN: usize = 32 * 1024;

/// Runs the lean front end into `out`, reusing its memory. With
/// [`PrepareOptions::parallel`] and a large scene the work is split over
/// the current rayon pool and `out.parts` has one run per thread;
/// otherwise one run.
///
/// # Errors
///
/// As [`prepare`](fn@crate::prepare): an absurd image size, an invalid camera
/// or an invalid scene.
pub fn prepare_depth_into(
    scene: &Scene,
    view: &View,
    options: &PrepareOptions,
    out: &mut DepthScene,
) -> Result<()> {
    let front = FrontEnd::new(scene, view, options)?;
    let count = scene.triangle_count();
    let parallel = options.parallel && rayon::current_num_threads() > 1 && count >= PARALLEL_MIN;

    // 1. Vertices, once each.
    let total: usize = scene.meshes.iter().map(|m| m.positions.len()).sum();
    out.vertices.resize(total, CachedVertex::default());
    let mut rest = &mut out.vertices[..];
    for mesh in &scene.meshes {
        let (mine, tail) = rest.split_at_mut(mesh.positions.len());
        rest = tail;
        let work = |(c, chunk): (usize, &mut [CachedVertex])| {
            let first = c * VERTEX_CHUNK;
            for (v, p) in chunk.iter_mut().zip(&mesh.positions[first..]) {
                *v = vertex(&front, front.clip(*p));
            }
        };
        if parallel {
            mine.par_chunks_mut(VERTEX_CHUNK).enumerate().for_each(work);
        } else {
            mine.chunks_mut(VERTEX_CHUNK).enumerate().for_each(work);
        }
    }

    // 2. Triangles, in contiguous runs of primitive ids.
    let parts = if parallel {
        rayon::current_num_threads()
    } else {
        1
    };
    out.parts.resize_with(parts, Vec::new);
    out.parts.truncate(parts);
    let per = count.div_ceil(parts).max(1);
    let vertices = &out.vertices;
    let run = |(k, tris): (usize, &mut Vec<DepthTri>)| {
        let range = (k * per).min(count)..((k + 1) * per).min(count);
        triangles(scene, &front, vertices, range, tris)
    };
    let stats: Vec<PrepareStats> = if parallel {
        out.parts.par_iter_mut().enumerate().map(run).collect()
    } else {
        out.parts.iter_mut().enumerate().map(run).collect()
    };
    let mut total_stats = PrepareStats {
        input: count as u64,
        ..PrepareStats::default()
    };
    for s in &stats {
        total_stats.add(s);
    }
    total_stats.output = out.parts.iter().map(|p| p.len() as u64).sum();
    out.stats = total_stats;
    out.viewport = front.viewport;
    Ok(())
}

/// Classifies, divides and snaps one vertex exactly as `prepare` does for
/// each corner that uses it.
#[inline]
fn vertex(front: &FrontEnd, clip: DVec4) -> CachedVertex {
    if !clip.is_finite() {
        return CachedVertex {
            code: NOT_FINITE,
            ..CachedVertex::default()
        };
    }
    let code = front.volume.outcode(clip);
    if code & OUTSIDE_PLANES != 0 {
        return CachedVertex {
            code: code | NO_WINDOW,
            ..CachedVertex::default()
        };
    }
    let v = ClipVertex {
        pos: clip,
        bary: glam::DVec3::ZERO,
    };
    match to_window(&v, front.viewport, front.options.precision) {
        Some(w) => CachedVertex {
            p: w.p,
            z: w.z,
            code,
        },
        None => CachedVertex {
            code: code | NO_WINDOW,
            ..CachedVertex::default()
        },
    }
}

/// Sets up the triangles with primitive ids in `range`, appending to `out`.
fn triangles(
    scene: &Scene,
    front: &FrontEnd,
    vertices: &[CachedVertex],
    range: std::ops::Range<usize>,
    out: &mut Vec<DepthTri>,
) -> PrepareStats {
    out.clear();
    let mut stats = PrepareStats::default();
    let mut fallback = Part::default();
    let mut scratch = ClipScratch::default();
    let vp = front.viewport;
    let cull = front.options.cull_back_faces;
    let (mut first_prim, mut first_vertex) = (0usize, 0usize);
    for (m, mesh) in scene.meshes.iter().enumerate() {
        let n = mesh.indices.len();
        let lo = range.start.max(first_prim);
        let hi = range.end.min(first_prim + n);
        let cache = &vertices[first_vertex..first_vertex + mesh.positions.len()];
        for t in lo.saturating_sub(first_prim)..hi.saturating_sub(first_prim) {
            let prim = (first_prim + t) as u32;
            let c = mesh.indices[t].map(|i| cache[i as usize]);
            let (all, any) = (
                c[0].code & c[1].code & c[2].code,
                c[0].code | c[1].code | c[2].code,
            );
            // The order of these tests is clip_triangle's, then the
            // window step's, so every triangle is dropped or kept for the
            // same reason as in `prepare`.
            if any & NOT_FINITE != 0 || all & (OUTSIDE_VIEWPORT | OUTSIDE_PLANES) != 0 {
                stats.culled += 1;
                continue;
            }
            if any & OUTSIDE_PLANES != 0 {
                clipped(scene, front, (m, t, prim), &mut fallback, &mut scratch, out);
                continue;
            }
            if any & NO_WINDOW != 0 {
                stats.culled += 1;
                continue;
            }
            // Orientation, facing and the pixel box are integer work on
            // the snapped corners; only triangles that survive them pay
            // for the depth plane (two divisions). A zero area is exactly
            // a zero plane determinant (both are exact), so every
            // triangle is still dropped for `prepare`'s reason.
            let area = orient2d(c[0].p, c[1].p, c[2].p);
            if area == 0 {
                stats.degenerate += 1;
                continue;
            }
            if cull && area > 0 {
                stats.back_faces += 1;
                continue;
            }
            if vp.misses_every_centre(&c.map(|k| k.p), area) {
                stats.empty += 1;
                continue;
            }
            let window = c.map(|k| crate::prepare::WindowVertex {
                p: k.p,
                z: k.z,
                w: 0.0,
            });
            let Some((c, _, depth)) = setup_depth(window, area) else {
                stats.degenerate += 1;
                continue;
            };
            let v = c.map(|k| k.p);
            out.push(DepthTri { v, depth, prim });
        }
        first_prim += n;
        first_vertex += mesh.positions.len();
    }
    stats.add(&fallback.stats);
    stats
}

/// A triangle that must be clipped: `prepare`'s own path, keeping the
/// depth part of each piece.
fn clipped(
    scene: &Scene,
    front: &FrontEnd,
    which: (usize, usize, u32),
    part: &mut Part,
    scratch: &mut ClipScratch,
    out: &mut Vec<DepthTri>,
) {
    part.prims.clear();
    part.tris.clear();
    front.triangle(scene, which, part, scratch);
    for t in &part.tris {
        // Pieces are positively oriented already.
        if !front.viewport.misses_every_centre(&t.v, 1) {
            out.push(DepthTri::from(t));
        } else {
            part.stats.empty += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use proptest::prelude::*;

    use super::*;
    use crate::model::Mesh;
    use crate::prepare::{TransformPrecision, prepare};

    fn scene_of(points: &[(f64, f64, f64)], shared: bool) -> Scene {
        let positions: Vec<DVec3> = points
            .iter()
            .map(|&(x, y, z)| DVec3::new(x, y, z))
            .collect();
        let n = positions.len() as u32;
        let indices = if shared {
            // A strip: neighbouring triangles share vertices, as meshes do.
            (0..n.saturating_sub(2))
                .map(|i| [i, i + 1, i + 2])
                .collect()
        } else {
            (0..n / 3).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect()
        };
        let mut s = Scene::default();
        s.push_mesh(
            Mesh {
                positions,
                indices,
                ..Mesh::default()
            },
            None,
        );
        s
    }

    fn view(size: u32, near: f64) -> View {
        View {
            viewport: Viewport::new(size, size),
            camera: crate::hard_cases::look_at(DVec3::new(0.0, 0.0, 3.0), DVec3::ZERO, near, 6.0),
        }
    }

    fn check(scene: &Scene, view: &View, options: &PrepareOptions) {
        let full = prepare(scene, view, options).unwrap();
        // Every triangle that covers a pixel centre is kept; of the others
        // (brute force over the box), only those with a box of more than
        // two centres.
        let keep = |t: &&ScreenTri| {
            let Some((x0, y0, x1, y1)) = t.pixel_bounds(view.viewport) else {
                return false;
            };
            let covers = (y0..=y1).any(|y| {
                (x0..=x1).any(|x| {
                    hider_geom::triangle_covers(
                        &t.v,
                        i64::from(x) * 256 + 128,
                        i64::from(y) * 256 + 128,
                    )
                })
            });
            covers || (x1 - x0 + 1) * (y1 - y0 + 1) > 2
        };
        let want: Vec<DepthTri> = full.tris.iter().filter(keep).map(DepthTri::from).collect();
        let mut lean = DepthScene::new();
        prepare_depth_into(scene, view, options, &mut lean).unwrap();
        let got: Vec<DepthTri> = lean.tris().copied().collect();
        assert_eq!(got, want);
        let s = lean.stats;
        assert_eq!(s.input, full.stats.input);
        assert_eq!(s.culled, full.stats.culled);
        assert_eq!(s.clipped, full.stats.clipped);
        assert_eq!(s.degenerate, full.stats.degenerate);
        assert_eq!(s.back_faces, full.stats.back_faces);
        assert_eq!(s.output + s.empty, full.stats.output);
    }

    proptest! {
        /// Random triangles around and through the view volume (behind the
        /// eye, across the near plane, beyond the far plane, far outside the
        /// image), both precisions, with and without back-face culling.
        #[test]
        fn lean_equals_prepare(
            points in prop::collection::vec(
                (-4.0f64..4.0, -4.0f64..4.0, -6.0f64..5.0), 3..60),
            shared in any::<bool>(),
            f32_precision in any::<bool>(),
            cull in any::<bool>(),
            size in 1u32..96,
            near in prop::sample::select(vec![0.05, 0.5, 2.0]),
        ) {
            let scene = scene_of(&points, shared);
            let precision = if f32_precision { TransformPrecision::F32 } else { TransformPrecision::F64 };
            let options = PrepareOptions::default()
                .with_precision(precision)
                .with_cull_back_faces(cull);
            check(&scene, &view(size, near), &options);
        }
    }

    #[test]
    fn parallel_runs_concatenate_to_the_serial_result() {
        let scene = crate::procedural::uv_sphere(140);
        assert!(scene.triangle_count() >= PARALLEL_MIN);
        let v = View::for_scene(&scene, 300, 300).unwrap();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .unwrap();
        let mut serial = DepthScene::new();
        prepare_depth_into(&scene, &v, &PrepareOptions::default(), &mut serial).unwrap();
        let mut parallel = DepthScene::new();
        pool.install(|| {
            prepare_depth_into(
                &scene,
                &v,
                &PrepareOptions::default().with_parallel(true),
                &mut parallel,
            )
        })
        .unwrap();
        assert_eq!(parallel.parts.len(), 3);
        assert_eq!(serial.parts.len(), 1);
        assert!(parallel.tris().eq(serial.tris()));
        assert_eq!(parallel.stats, serial.stats);
        check(&scene, &v, &PrepareOptions::default());
    }

    #[test]
    fn several_meshes_and_reuse() {
        let mut scene = crate::procedural::uv_sphere(12);
        let cube = crate::procedural::cube();
        for mut m in cube.meshes {
            m.material = None;
            scene.push_mesh(m, None);
        }
        let v = View::for_scene(&scene, 64, 64).unwrap();
        check(&scene, &v, &PrepareOptions::default());
        // Reusing the buffers for a smaller scene leaves nothing stale.
        let mut lean = DepthScene::new();
        prepare_depth_into(&scene, &v, &PrepareOptions::default(), &mut lean).unwrap();
        let small = crate::procedural::cube();
        prepare_depth_into(&small, &v, &PrepareOptions::default(), &mut lean).unwrap();
        let want = prepare(&small, &v, &PrepareOptions::default()).unwrap();
        assert_eq!(lean.len(), want.tris.len() - lean.stats.empty as usize);
    }

    #[test]
    fn clipped_culled_and_empty_triangles_are_counted() {
        let scene = scene_of(
            &[
                // Across the near plane (eye at z = 3, near 0.5): clipped.
                (-1.0, -1.0, 0.0),
                (1.0, -1.0, 0.0),
                (0.0, 1.0, 5.0),
                // Behind the eye: culled.
                (-1.0, 0.0, 4.0),
                (1.0, 0.0, 4.0),
                (0.0, 1.0, 4.0),
                // Tiny, between pixel centres: empty.
                (0.01, 0.01, 0.0),
                (0.06, 0.01, 0.0),
                (0.01, 0.06, 0.0),
            ],
            false,
        );
        let v = view(8, 0.5);
        let mut lean = DepthScene::new();
        prepare_depth_into(&scene, &v, &PrepareOptions::default(), &mut lean).unwrap();
        assert_eq!(lean.stats.clipped, 1);
        assert_eq!(lean.stats.culled, 1);
        assert_eq!(lean.stats.empty, 1);
        assert!(!lean.is_empty());
        check(&scene, &v, &PrepareOptions::default());
    }

    #[test]
    fn bad_input_is_an_error() {
        let mut scene = scene_of(
            &[(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (f64::NAN, 1.0, 0.0)],
            false,
        );
        let v = view(16, 0.5);
        let mut lean = DepthScene::new();
        assert!(prepare_depth_into(&scene, &v, &PrepareOptions::default(), &mut lean).is_err());
        scene.meshes[0].positions[2] = DVec3::Y;
        let mut bad = v;
        bad.viewport = Viewport::new(0, 16);
        assert!(prepare_depth_into(&scene, &bad, &PrepareOptions::default(), &mut lean).is_err());
    }
}
