//! The shared front end: world-space [`Scene`] to screen-space
//! [`ScreenScene`].
//!
//! `prepare` transforms, clips (near, far, guard band), divides, maps to the
//! viewport, snaps to 1/256 pixel and sets up each triangle once. Every hider
//! consumes the result and none re-projects, which is what makes
//! cross-validation between hiders exact rather than approximate.

#[cfg(feature = "parallel")]
use rayon::prelude::*;

use crate::error::Result;
use crate::model::{Material, Scene};
use crate::view::View;

mod front_end;
pub mod lean;
mod options;
mod screen;
#[cfg(test)]
mod tests;

pub use front_end::{ClipScratch, FrontEnd, Part, WindowVertex, setup_depth};
pub use screen::{PrepareStats, PrimInfo, ScreenScene, ScreenTri};

pub use options::{PrepareOptions, TransformPrecision};

/// Runs the front end. See the module documentation.
pub fn prepare(scene: &Scene, view: &View, options: &PrepareOptions) -> Result<ScreenScene> {
    let mut out = ScreenScene::empty(view);
    prepare_into(scene, view, options, &mut out)?;
    Ok(out)
}

/// [`prepare`] into an existing [`ScreenScene`], reusing its memory: for
/// repeated frames this avoids allocating (and the kernel zeroing) hundreds
/// of megabytes for large scenes. Every field of `out` is overwritten.
pub fn prepare_into(
    scene: &Scene,
    view: &View,
    options: &PrepareOptions,
    out: &mut ScreenScene,
) -> Result<()> {
    let vp = view.viewport;
    let front = FrontEnd::new(scene, view, options)?;
    let (view_matrix, projection_matrix) = (front.view_matrix, front.projection_matrix);

    let mut materials = std::mem::take(&mut out.materials);
    materials.clear();
    materials.extend_from_slice(&scene.materials);
    materials.push(Material::default());

    let mut prims = std::mem::take(&mut out.prims);
    prims.clear();
    prims.reserve(scene.triangle_count());
    let mut tris = std::mem::take(&mut out.tris);
    tris.clear();
    tris.reserve(scene.triangle_count());
    let mut stats = PrepareStats {
        input: scene.triangle_count() as u64,
        ..PrepareStats::default()
    };
    if let Some(parts) = parallel_parts(scene, &front, options) {
        for part in parts? {
            prims.extend_from_slice(&part.prims);
            tris.extend_from_slice(&part.tris);
            stats.add(&part.stats);
        }
    } else {
        let mut scratch = ClipScratch::default();
        let mut part = Part { prims, tris, stats };
        for (k, (prim, m, t)) in scene.triangles().enumerate() {
            options.cancel.poll_every(k)?;
            front.triangle(scene, (m, t, prim), &mut part, &mut scratch);
        }
        (prims, tris, stats) = (part.prims, part.tris, part.stats);
    }
    stats.output = tris.len() as u64;
    let lights = scene
        .lights
        .iter()
        .map(|l| front.light_to_camera(l))
        .collect();
    *out = ScreenScene {
        viewport: vp,
        camera: view.camera,
        view_matrix,
        projection_matrix,
        tris,
        prims,
        materials,
        lights,
        stats,
    };
    Ok(())
}

/// The parallel front end's parts, in primitive order: `None` when the
/// scene is prepared on this thread (not asked for by `options`, one
/// thread, or too small a scene to pay for the fork-join).
#[cfg(feature = "parallel")]
fn parallel_parts(
    scene: &Scene,
    front: &FrontEnd,
    options: &PrepareOptions,
) -> Option<Result<Vec<Part>>> {
    // Below this many triangles the fork-join overhead is not worth it.
    const PARALLEL_CHUNK: usize = 16 * 1024;
    if !(options.parallel
        && rayon::current_num_threads() > 1
        && scene.triangle_count() > 2 * PARALLEL_CHUNK)
    {
        return None;
    }
    let mut segments = Vec::new();
    let mut first_prim = 0u32;
    for (m, mesh) in scene.meshes.iter().enumerate() {
        for start in (0..mesh.indices.len()).step_by(PARALLEL_CHUNK) {
            let end = (start + PARALLEL_CHUNK).min(mesh.indices.len());
            segments.push((m, start..end, first_prim));
            first_prim += (end - start) as u32;
        }
    }
    let parts: Result<Vec<Part>> = segments
        .into_par_iter()
        .map(|(m, range, first)| {
            let mut part = Part::default();
            let mut scratch = ClipScratch::default();
            for (k, t) in range.enumerate() {
                options.cancel.poll_every(k)?;
                front.triangle(scene, (m, t, first + k as u32), &mut part, &mut scratch);
            }
            Ok(part)
        })
        .collect();
    Some(parts)
}

/// Without the `parallel` feature the front end runs on this thread.
#[cfg(not(feature = "parallel"))]
fn parallel_parts(_: &Scene, _: &FrontEnd, _: &PrepareOptions) -> Option<Result<Vec<Part>>> {
    None
}
