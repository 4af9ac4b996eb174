//! The lean front end: the numbers of [`prepare`](crate::prepare()), bit
//! for bit, without what only some hiders read.
//!
//! [`prepare`](crate::prepare()) writes, per triangle, a 160-byte
//! [`ScreenTri`] and a [`PrimInfo`](super::PrimInfo) (camera-space corners,
//! normals, texture coordinates), and transforms each corner of each
//! triangle: a vertex shared by six triangles is transformed six times.
//! For half a million triangles that is most of what a frame costs. The
//! lean front end works per *vertex*: each vertex is transformed,
//! classified by its outcode, divided and snapped once, eight at a time
//! ([`vertices`], cached in [`fill_vertices`]), and triangles are set up
//! from the cached results. A triangle that must be clipped goes through
//! `prepare`'s own per-triangle path ([`FrontEnd::triangle`], by way of
//! [`ClipFallback`], which both users share).
//!
//! Two users share the vertex pass: the tiled z-buffer's depth-only front
//! end, which also drops triangles that cover no pixel centre, and
//! [`prepare_lean_into`], which keeps exactly `prepare`'s triangles as
//! [`LeanTri`]s (snapped corners, their depths, depth plane, primitive id, facing) for
//! hiders that sample inside pixels (the A-buffer), and colours a
//! primitive on demand ([`LeanScene::prim_color`]) from the world-space
//! scene, as `prepare`'s [`PrimInfo`](super::PrimInfo) would have, and,
//! when the frame is shaded per point ([`LeanScene::set_point_shading`]:
//! textures, vertex normals or colours), assembles a primitive's
//! `PrimInfo` from camera-space positions and normals transformed once
//! per vertex ([`LeanScene::prim_info`], [`LeanScene::surface_rgb`]); or,
//! through [`prepare_lean_sinks`], hands each run's triangles to a
//! [`LeanSink`] of the hider's as they are set up (the A-buffer bins them
//! there, instead of storing them and reading them back).

mod attributes;
mod clipped;
mod scene;
mod triangles;
mod vertices;

pub use clipped::ClipFallback;
pub use scene::{LeanScene, LeanSink, LeanTri, prepare_lean_into, prepare_lean_sinks};
pub use vertices::{CachedVertex, NO_WINDOW, NOT_FINITE, vertices};

#[cfg(feature = "parallel")]
use rayon::prelude::*;

use crate::error::Error;
use crate::model::Scene;

use super::{FrontEnd, PrepareOptions, PrepareStats, ScreenTri};
use crate::error::Result;
use crate::view::View;

/// Vertices per parallel work item of the vertex pass.
const VERTEX_CHUNK: usize = 16 * 1024;

/// Triangles below which a lean triangle pass stays on one thread.
const PARALLEL_MIN: usize = 32 * 1024;

/// What a triangle pass did over one run of primitive ids: its counters,
/// and whether an index was out of range.
#[derive(Clone, Copy, Debug, Default)]
pub struct RunOutcome {
    /// The front end's counters for the run's triangles.
    pub stats: PrepareStats,
    /// Whether a triangle indexed a vertex its mesh does not have.
    pub bad_index: bool,
}

/// One mesh's share of a run of primitive ids: the mesh's index, the mesh,
/// its cached vertices, the primitive id of its first triangle, and the
/// indices of its triangles the run holds.
pub struct MeshPart<'a> {
    /// Index in [`Scene::meshes`].
    pub m: usize,
    /// The mesh.
    pub mesh: &'a crate::model::Mesh,
    /// Its vertices from the vertex pass.
    pub cache: &'a [CachedVertex],
    /// The primitive id of its triangle 0.
    pub first_prim: usize,
    /// Its triangles in the run (indices into `mesh.indices`).
    pub triangles: std::ops::Range<usize>,
}

/// The meshes of `scene` with their part of the primitive ids `range`,
/// each with its slice of `cache` (every mesh's vertices one after the
/// other, as [`fill_vertices`] writes them).
pub fn mesh_parts<'a>(
    scene: &'a Scene,
    cache: &'a [CachedVertex],
    range: std::ops::Range<usize>,
) -> impl Iterator<Item = MeshPart<'a>> + 'a {
    let (mut first_prim, mut first_vertex) = (0usize, 0usize);
    scene.meshes.iter().enumerate().map(move |(m, mesh)| {
        let n = mesh.indices.len();
        let lo = range.start.max(first_prim).saturating_sub(first_prim);
        let hi = range.end.min(first_prim + n).saturating_sub(first_prim);
        let part = MeshPart {
            m,
            mesh,
            cache: &cache[first_vertex..first_vertex + mesh.positions.len()],
            first_prim,
            triangles: lo..hi.max(lo),
        };
        first_prim += n;
        first_vertex += mesh.positions.len();
        part
    })
}

/// The two passes of a lean front end: the frame's transforms (checked as
/// [`prepare`](crate::prepare()) checks them), the vertex pass into
/// `vertices`, then `pass` over contiguous runs of primitive ids, one per
/// entry of `runs`, in parallel on the current rayon pool when `options`
/// ask for it and the scene is large. Returns the transforms and the
/// counters summed over the runs (`output` left for the caller, which
/// knows what it kept).
///
/// # Errors
///
/// As [`prepare`](crate::prepare()): an absurd image size, an invalid
/// camera, or an invalid scene (a non-finite position or an index out of
/// range, found by the passes).
pub fn lean_passes<R: Default + Send>(
    scene: &Scene,
    view: &View,
    options: &PrepareOptions,
    vertices: &mut Vec<CachedVertex>,
    runs: &mut Vec<R>,
    pass: impl Fn(&FrontEnd, &[CachedVertex], std::ops::Range<usize>, &mut R) -> RunOutcome + Sync,
) -> Result<(FrontEnd, PrepareStats)> {
    // Positions and indices are checked by the two passes, which read
    // them all anyway (a separate `Scene::validate` pass cost 4 % of the
    // 499k sphere's frame).
    let front = FrontEnd::checked(scene, view, options, false)?;
    let count = scene.triangle_count();
    let split = run_split(options, count);
    if !fill_vertices(scene, &front, split.0, vertices) {
        return Err(invalid_scene(scene));
    }
    // The vertex pass is the front end's larger share on big meshes; its
    // runs poll on their own.
    options.cancel.poll()?;
    let cache = &vertices[..];
    let stats = in_runs(count, split, runs, |range, run| {
        pass(&front, cache, range, run)
    })
    .ok_or_else(|| invalid_scene(scene))?;
    Ok((front, stats))
}

/// How a lean front end splits a scene of `count` triangles: whether it
/// works on the current rayon pool (asked for by `options`, more than one
/// thread, and a scene large enough to pay for it), and into how many
/// contiguous runs of primitive ids (never parallel without the
/// `parallel` feature: see [`crate::pool::current_threads`]).
fn run_split(options: &PrepareOptions, count: usize) -> (bool, usize) {
    let threads = crate::pool::current_threads();
    let parallel = options.parallel && threads > 1 && count >= PARALLEL_MIN;
    (parallel, if parallel { threads } else { 1 })
}

/// Runs a triangle pass over primitive ids `0..count` cut into contiguous
/// runs, one per entry of `runs` (resized to `parts`), in parallel on the
/// current rayon pool when `parallel` (`run_split` gives both). Returns
/// the counters summed over the runs (`input` is `count`), or `None` when
/// a run found an index out of range.
fn in_runs<R: Default + Send>(
    count: usize,
    (parallel, parts): (bool, usize),
    runs: &mut Vec<R>,
    pass: impl Fn(std::ops::Range<usize>, &mut R) -> RunOutcome + Sync,
) -> Option<PrepareStats> {
    runs.resize_with(parts, R::default);
    let per = count.div_ceil(parts).max(1);
    let work = |(k, run): (usize, &mut R)| {
        // The run's output is moved to this thread's stack while it is
        // written: the runs' headers sit side by side in `runs`, and a
        // length updated on every push shared a cache line with the
        // other thread's (the 500 sphere's triangle pass took 6.2 to 6.6
        // ms at 2 threads against 4.3 ms on one).
        let mut local = std::mem::take(run);
        let outcome = pass((k * per).min(count)..((k + 1) * per).min(count), &mut local);
        *run = local;
        outcome
    };
    #[cfg(feature = "parallel")]
    let outcomes: Vec<RunOutcome> = if parallel {
        runs.par_iter_mut().enumerate().map(work).collect()
    } else {
        runs.iter_mut().enumerate().map(work).collect()
    };
    // One thread without the `parallel` feature (`parallel` is false).
    #[cfg(not(feature = "parallel"))]
    let outcomes: Vec<RunOutcome> = {
        let _ = parallel;
        runs.iter_mut().enumerate().map(work).collect()
    };
    if outcomes.iter().any(|o| o.bad_index) {
        return None;
    }
    let mut stats = PrepareStats {
        input: count as u64,
        ..PrepareStats::default()
    };
    for o in &outcomes {
        stats.add(&o.stats);
    }
    Some(stats)
}

/// Runs the vertex pass ([`vertices`]) over every mesh of `scene`, meshes
/// one after the other, into `out` (resized to the scene's vertex count),
/// on the current rayon pool when `parallel` (ignored without the
/// `parallel` feature: on this thread). Returns whether every world
/// position is finite (a non-finite one is an invalid scene: report it
/// with [`invalid_scene`]).
pub fn fill_vertices(
    scene: &Scene,
    front: &FrontEnd,
    parallel: bool,
    out: &mut Vec<CachedVertex>,
) -> bool {
    #[cfg(not(feature = "parallel"))]
    let _ = parallel;
    let total: usize = scene.meshes.iter().map(|m| m.positions.len()).sum();
    out.resize(total, CachedVertex::default());
    let mut rest = &mut out[..];
    let mut finite = true;
    for mesh in &scene.meshes {
        let (mine, tail) = rest.split_at_mut(mesh.positions.len());
        rest = tail;
        let work = |(c, chunk): (usize, &mut [CachedVertex])| {
            let first = c * VERTEX_CHUNK;
            let positions = &mesh.positions[first..first + chunk.len()];
            vertices(front, positions, chunk)
        };
        #[cfg(feature = "parallel")]
        if parallel {
            finite &= mine
                .par_chunks_mut(VERTEX_CHUNK)
                .enumerate()
                .map(work)
                .reduce(|| true, |a, b| a & b);
            continue;
        }
        finite &= mine
            .chunks_mut(VERTEX_CHUNK)
            .enumerate()
            .fold(true, |ok, c| ok & work(c));
    }
    finite
}

/// The error of a scene whose positions or indices a lean pass found
/// invalid, as [`Scene::validate`] words it (naming the mesh, vertex or
/// triangle).
#[cold]
pub fn invalid_scene(scene: &Scene) -> Error {
    match scene.validate() {
        Err(e) => e,
        Ok(()) => Error::InvalidScene("a position or index is invalid".to_owned()),
    }
}

impl From<&ScreenTri> for LeanTri {
    fn from(t: &ScreenTri) -> Self {
        Self {
            v: t.v,
            z: t.z,
            depth: t.depth,
            prim: t.prim,
            front_facing: t.front_facing,
        }
    }
}

#[cfg(test)]
mod tests;
