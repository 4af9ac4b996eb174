//! The lean front end for depth-only hiders: the same snapped corners and
//! depth planes as [`prepare`](fn@hider_scene::prepare), without what
//! shading and the oracle need.
//!
//! [`prepare`](fn@hider_scene::prepare) writes, per triangle, a 160-byte
//! [`ScreenTri`] and a [`PrimInfo`](hider_scene::PrimInfo) (camera-space
//! corners, normals, texture coordinates): for half a million triangles
//! that is 150 MB of writes, most of what a z-buffer frame costs. A
//! z-buffer reads only the snapped corners, the depth plane and the
//! primitive id. [`prepare_depth_into`] produces just those ([`DepthTri`],
//! 88 bytes with the tile kernel's small-box set-up), and works per
//! *vertex* where `prepare` works per triangle corner: each vertex is transformed, classified by its outcode, divided
//! and snapped once, eight at a time (the vertex pass shared with the
//! A-buffer, [`hider_scene::prepare::lean`]), and triangles are
//! classified eight at a time from the cached results (`classify`,
//! `triangles`; with AVX2 the corners are gathered, the planes computed
//! and the records written in registers too, `simd::gather`,
//! `simd::plane`, `simd::emit`, `simd::fragments`). A triangle that must
//! be clipped goes through `prepare`'s own per-triangle path
//! ([`FrontEnd::triangle`]).
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
//! (the outcode is [`ClipVolume::outcode`](hider_geom::clip::ClipVolume::outcode),
//! the divide and snap are `prepare`'s, the set-up is
//! [`setup_depth`](hider_scene::prepare::setup_depth)), so the output is
//! bit for bit what a brute-force pass over `prepare`'s triangles gives:
//! the triangles whose pixel box holds more than four centres, and one
//! fragment per covered centre of the others. The crate's
//! `lean_front_end` tests check that on random scenes in both precisions,
//! with clipping and culling, and the `front_end` fuzz target on hostile
//! ones.

pub(crate) mod classify;
mod depth_tri;
mod triangles;

pub(crate) use depth_tri::SmallSetup;
pub use depth_tri::{DepthFragment, DepthTri};

use hider_geom::Viewport;
use hider_scene::prepare::lean::{CachedVertex, lean_passes};
use hider_scene::{PrepareOptions, PrepareStats, Result, Scene, View};

use triangles::Run;

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
    /// The viewport the triangles' small-box set-ups were made for (see
    /// [`Self::setups_valid`]).
    setups_for: Viewport,
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

    /// Whether the triangles' [`SmallSetup`]s hold for [`Self::viewport`]:
    /// false only if a caller changed the viewport by hand after
    /// [`prepare_depth_into`] (a larger one would make the stored boxes
    /// too small).
    pub(crate) fn setups_valid(&self) -> bool {
        self.setups_for == self.viewport
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

/// Runs the lean front end into `out`, reusing its memory. With
/// [`PrepareOptions::parallel`] and a large scene the work is split over
/// the current rayon pool and [`DepthScene::parts`] has one run per
/// thread; otherwise one run.
///
/// # Errors
///
/// As [`prepare`](fn@hider_scene::prepare): an absurd image size, an invalid camera
/// or an invalid scene.
pub fn prepare_depth_into(
    scene: &Scene,
    view: &View,
    options: &PrepareOptions,
    out: &mut DepthScene,
) -> Result<()> {
    // The shared vertex pass, then this crate's triangle pass over runs
    // of primitive ids.
    let passes = lean_passes(
        scene,
        view,
        options,
        &mut out.vertices,
        &mut out.runs,
        |front, vertices, range, run| {
            let input = triangles::Input {
                scene,
                front,
                vertices,
                range,
            };
            triangles::triangles(&input, run)
        },
    );
    let (front, mut stats) = match passes {
        Ok(passes) => passes,
        Err(error) => {
            for r in &mut out.runs {
                r.tris.clear();
                r.fragments.clear();
            }
            return Err(error);
        }
    };
    stats.output = out.len() as u64;
    out.stats = stats;
    out.viewport = front.viewport;
    out.setups_for = front.viewport;
    Ok(())
}

#[cfg(test)]
mod tests {
    use hider_scene::{PrepareOptions, View, procedural};

    use super::{DepthScene, prepare_depth_into};

    /// An index out of range is an error wherever it sits: in a batch of
    /// eight triangles gathered together (at the cache's length, or so
    /// large that a signed comparison would take it for a small one) or
    /// in the last few, set up one by one.
    #[test]
    fn an_index_out_of_range_is_an_error_in_every_batch() {
        let scene = procedural::uv_sphere(11);
        let view = View::for_scene(&scene, 64, 64).unwrap();
        let options = PrepareOptions::default();
        let mut lean = DepthScene::new();
        prepare_depth_into(&scene, &view, &options, &mut lean).unwrap();
        let kept = lean.clone();
        let (n, len) = (
            scene.meshes[0].indices.len(),
            scene.meshes[0].positions.len(),
        );
        assert!(
            n > 16 && n % 8 != 0,
            "{n} triangles: full batches and a rest"
        );
        for (t, index) in [(3, len as u32), (11, u32::MAX), (n - 1, len as u32)] {
            let mut bad = scene.clone();
            bad.meshes[0].indices[t][1] = index;
            assert!(
                prepare_depth_into(&bad, &view, &options, &mut lean).is_err(),
                "triangle {t}, index {index}"
            );
        }
        prepare_depth_into(&scene, &view, &options, &mut lean).unwrap();
        assert_eq!(
            lean.tris().collect::<Vec<_>>(),
            kept.tris().collect::<Vec<_>>()
        );
    }
}
