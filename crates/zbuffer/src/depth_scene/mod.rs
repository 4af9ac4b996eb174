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
//! once, eight at a time (`vertices`), and triangles are classified eight
//! at a time from the cached results (`triangles`). A triangle that must
//! be clipped goes through `prepare`'s own per-triangle path.
//!
//! Two kinds of triangles never reach the hider as triangles. Those that
//! certainly cover no pixel centre (their box holds none, or up to four
//! that the exact edge functions do not cover) are dropped: they cover no
//! sample of any pixel-centre hider. Those whose box holds up to four
//! centres and covers some become [`DepthFragment`]s, one per covered
//! centre with the depth there: the front end has tested those centres
//! anyway, and a hider writes a fragment for a fraction of what setting
//! up and scanning a triangle costs.
//!
//! Every number is the same function of the same inputs as in `prepare`
//! (the outcode is [`ClipVolume::outcode`](hider_geom::clip::ClipVolume::outcode), the divide and snap are
//! `prepare`'s `to_window`, the set-up is its `setup_depth`), so the output
//! is bit for bit what [`lean_reference`] works out from `prepare`'s
//! triangles; `tests::lean_equals_prepare` checks it on random scenes in
//! both precisions, with clipping and culling, and the `front_end` fuzz
//! target on hostile ones.

mod classify_avx2;
mod triangles;
mod vertices;

use hider_geom::{EdgeFunction, FixedPt, PlaneEq, Viewport};
use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::model::Scene;
use crate::prepare::{FrontEnd, PrepareOptions, PrepareStats, ScreenScene, ScreenTri};
use crate::view::View;
use triangles::{Outcome, Run};
use vertices::CachedVertex;

/// A triangle as a depth-only hider needs it: [`ScreenTri`] without the
/// per-vertex depths, `w` and the `1/w` plane.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
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

/// One pixel of a triangle too small to rasterise: the lean front end
/// hands a triangle whose box holds at most four pixel centres over as the
/// centres it covers (see [`Viewport::covered_centres`]), with the depth a
/// hider would compute there.
///
/// A fragment stands for a write of its triangle in primitive order. A
/// hider that applies fragments after the triangles gets the same answer
/// if it compares `(depth, prim)` lexicographically: the LESS depth test
/// in primitive order keeps the smallest depth and, among equal depths,
/// the first primitive.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DepthFragment {
    /// Window depth at the pixel centre: the triangle's
    /// [`PlaneEq::at_pixel`], the expression every pixel-centre hider
    /// evaluates.
    pub depth: f64,
    /// Pixel column.
    pub x: u16,
    /// Pixel row.
    pub y: u16,
    /// Primitive id of the triangle.
    pub prim: u32,
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
    /// What the front end did. [`PrepareStats::output`] counts the
    /// triangles kept, [`PrepareStats::empty`] those dropped for covering
    /// no pixel centre.
    pub stats: PrepareStats,
    /// The output in contiguous runs of primitive ids, one per worker.
    runs: Vec<Run>,
    /// Per vertex of every mesh (meshes one after the other): the cached
    /// snapped position, window depth and classification.
    vertices: Vec<CachedVertex>,
}

impl DepthScene {
    /// An empty scene (the buffers grow on first use).
    pub fn new() -> Self {
        Self::default()
    }

    /// The triangles in primitive-id order, cut into contiguous runs (one
    /// per worker that set them up); hiders may work on the runs in
    /// parallel and must visit them in order. Triangles handed over as
    /// [`Self::fragments`] are not among them.
    pub fn parts(&self) -> impl ExactSizeIterator<Item = &[DepthTri]> + '_ {
        self.runs.iter().map(|r| &r.tris[..])
    }

    /// The pixel fragments of the triangles too small to rasterise, one
    /// list per run of [`Self::parts`], each in primitive order.
    pub fn fragments(&self) -> impl ExactSizeIterator<Item = &[DepthFragment]> + '_ {
        self.runs.iter().map(|r| &r.fragments[..])
    }

    /// Number of triangles kept as triangles.
    pub fn len(&self) -> usize {
        self.runs.iter().map(|r| r.tris.len()).sum()
    }

    /// Whether nothing was kept: no triangle and no fragment.
    pub fn is_empty(&self) -> bool {
        self.runs
            .iter()
            .all(|r| r.tris.is_empty() && r.fragments.is_empty())
    }

    /// Every triangle kept as a triangle, in primitive-id order.
    pub fn tris(&self) -> impl Iterator<Item = &DepthTri> + '_ {
        self.parts().flatten()
    }

    /// Bytes of memory held.
    pub fn bytes(&self) -> usize {
        self.runs
            .iter()
            .map(|r| {
                r.tris.capacity() * std::mem::size_of::<DepthTri>()
                    + r.fragments.capacity() * std::mem::size_of::<DepthFragment>()
            })
            .sum::<usize>()
            + self.vertices.capacity() * std::mem::size_of::<CachedVertex>()
    }
}

/// Vertices per parallel work item of the vertex pass.
const VERTEX_CHUNK: usize = 16 * 1024;
/// Below this many triangles the scene is set up on one thread.
const PARALLEL_MIN: usize = 32 * 1024;

/// Runs the lean front end into `out`, reusing its memory. With
/// [`PrepareOptions::parallel`] and a large scene the work is split over
/// the current rayon pool and [`DepthScene::parts`] has one run per
/// thread; otherwise one run.
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
    // Positions and indices are checked by the two passes, which read
    // them all anyway (a separate `Scene::validate` pass cost 4 % of the
    // 499k sphere's frame).
    let front = FrontEnd::checked(scene, view, options, false)?;
    let count = scene.triangle_count();
    let parallel = options.parallel && rayon::current_num_threads() > 1 && count >= PARALLEL_MIN;

    // 1. Vertices, once each.
    let total: usize = scene.meshes.iter().map(|m| m.positions.len()).sum();
    out.vertices.resize(total, CachedVertex::default());
    let mut rest = &mut out.vertices[..];
    let mut finite = true;
    for mesh in &scene.meshes {
        let (mine, tail) = rest.split_at_mut(mesh.positions.len());
        rest = tail;
        let work = |(c, chunk): (usize, &mut [CachedVertex])| {
            let first = c * VERTEX_CHUNK;
            let positions = &mesh.positions[first..first + chunk.len()];
            vertices::vertices(&front, positions, chunk)
        };
        finite &= if parallel {
            mine.par_chunks_mut(VERTEX_CHUNK)
                .enumerate()
                .map(work)
                .reduce(|| true, |a, b| a & b)
        } else {
            mine.chunks_mut(VERTEX_CHUNK)
                .enumerate()
                .fold(true, |ok, c| ok & work(c))
        };
    }
    if !finite {
        return Err(invalid(scene));
    }

    // 2. Triangles, in contiguous runs of primitive ids.
    let parts = if parallel {
        rayon::current_num_threads()
    } else {
        1
    };
    out.runs.resize_with(parts, Run::default);
    out.runs.truncate(parts);
    let per = count.div_ceil(parts).max(1);
    let vertices = &out.vertices;
    let run = |(k, run): (usize, &mut Run)| {
        let range = (k * per).min(count)..((k + 1) * per).min(count);
        let input = triangles::Input {
            scene,
            front: &front,
            vertices,
            range,
        };
        triangles::triangles(&input, run)
    };
    let outcomes: Vec<Outcome> = if parallel {
        out.runs.par_iter_mut().enumerate().map(run).collect()
    } else {
        out.runs.iter_mut().enumerate().map(run).collect()
    };
    if outcomes.iter().any(|o| o.bad_index) {
        for r in &mut out.runs {
            r.tris.clear();
            r.fragments.clear();
        }
        return Err(invalid(scene));
    }
    let mut total_stats = PrepareStats {
        input: count as u64,
        ..PrepareStats::default()
    };
    for o in &outcomes {
        total_stats.add(&o.stats);
    }
    total_stats.output = out.len() as u64;
    out.stats = total_stats;
    out.viewport = front.viewport;
    Ok(())
}

/// What [`prepare_depth_into`] must produce for the scene, view and
/// options that [`prepare`](fn@crate::prepare) turned into `screen`,
/// worked out by brute force over each triangle's pixel box: the
/// triangles whose box holds more than [`hider_geom::FEW_CENTRES`] (four)
/// pixel centres, as
/// [`DepthTri`]s, and one [`DepthFragment`] per covered centre of the
/// others (those covering none are dropped), both in primitive order. The
/// lean front end's tests and fuzz target compare it with this.
pub fn lean_reference(screen: &ScreenScene) -> (Vec<DepthTri>, Vec<DepthFragment>) {
    let (mut tris, mut fragments) = (Vec::new(), Vec::new());
    for t in &screen.tris {
        let Some((x0, y0, x1, y1)) = t.pixel_bounds(screen.viewport) else {
            continue;
        };
        if ((x1 - x0 + 1) * (y1 - y0 + 1)) as usize > hider_geom::FEW_CENTRES {
            tris.push(DepthTri::from(t));
            continue;
        }
        for y in y0..=y1 {
            for x in x0..=x1 {
                let (cx, cy) = (i64::from(x) * 256 + 128, i64::from(y) * 256 + 128);
                if hider_geom::triangle_covers(&t.v, cx, cy) {
                    fragments.push(DepthFragment {
                        depth: t.depth.at_pixel(x, y),
                        x: x as u16,
                        y: y as u16,
                        prim: t.prim,
                    });
                }
            }
        }
    }
    (tris, fragments)
}

/// The error of a scene whose positions or indices the passes found
/// invalid, as [`Scene::validate`] words it (naming the mesh, vertex or
/// triangle).
#[cold]
fn invalid(scene: &Scene) -> Error {
    match scene.validate() {
        Err(e) => e,
        Ok(()) => Error::InvalidScene("a position or index is invalid".to_owned()),
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use proptest::prelude::*;

    use super::*;
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
        Scene::from_mesh(positions, indices)
    }

    fn view(size: u32, near: f64) -> View {
        View {
            viewport: Viewport::new(size, size),
            camera: crate::hard_cases::look_at(DVec3::new(0.0, 0.0, 3.0), DVec3::ZERO, near, 6.0),
        }
    }

    fn check(scene: &Scene, view: &View, options: &PrepareOptions) {
        let full = prepare(scene, view, options).unwrap();
        let (want, want_fragments) = lean_reference(&full);
        let mut lean = DepthScene::new();
        prepare_depth_into(scene, view, options, &mut lean).unwrap();
        let got: Vec<DepthTri> = lean.tris().copied().collect();
        assert_eq!(got, want);
        let got_fragments: Vec<DepthFragment> = lean.fragments().flatten().copied().collect();
        assert_eq!(got_fragments, want_fragments);
        let s = lean.stats;
        assert_eq!(s.input, full.stats.input);
        assert_eq!(s.culled, full.stats.culled);
        assert_eq!(s.clipped, full.stats.clipped);
        assert_eq!(s.degenerate, full.stats.degenerate);
        assert_eq!(s.back_faces, full.stats.back_faces);
        assert_eq!(s.output + s.empty + s.fragmented, full.stats.output);
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
        assert_eq!(parallel.parts().len(), 3);
        assert_eq!(serial.parts().len(), 1);
        assert!(parallel.tris().eq(serial.tris()));
        assert!(
            parallel
                .fragments()
                .flatten()
                .eq(serial.fragments().flatten())
        );
        assert_eq!(parallel.stats, serial.stats);
        // The dense sphere has triangles of every kind.
        let s = serial.stats;
        assert!(s.output > 0 && s.empty > 0 && s.fragmented > 0, "{s:?}");
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
        let s = lean.stats;
        assert_eq!(
            lean.len() as u64,
            want.tris.len() as u64 - s.empty - s.fragmented
        );
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
