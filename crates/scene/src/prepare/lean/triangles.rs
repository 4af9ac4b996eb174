//! The triangle pass of [`prepare_lean_into`](super::prepare_lean_into):
//! each triangle set up from its cached vertices, or cut by `prepare`'s own
//! clipping path when it must be, dropped or kept for `prepare`'s reasons.

use hider_geom::clip::{OUTSIDE_PLANES, OUTSIDE_VIEWPORT};
use hider_geom::{FixedPt, orient2d};

use crate::model::{Mesh, Scene};
use crate::prepare::{FrontEnd, WindowVertex, setup_depth};

use super::scene::{LeanSink, LeanTri};
use super::vertices::{CachedVertex, NO_WINDOW, NOT_FINITE};
use super::{ClipFallback, RunOutcome, mesh_parts};

/// A vertex with a code that culls the triangle: what an index out of
/// range reads (the caller turns that into an error).
const OUT_OF_RANGE: CachedVertex = CachedVertex {
    p: FixedPt { x: 0, y: 0 },
    z: 0.0,
    code: NOT_FINITE,
};

/// Sets up the triangles of primitive ids `range` of `scene` into `out`
/// (cleared first), from `cache` (every mesh's vertices one after the
/// other).
pub(super) fn triangles<S: LeanSink>(
    scene: &Scene,
    front: &FrontEnd,
    cache: &[CachedVertex],
    range: std::ops::Range<usize>,
    out: &mut S,
) -> RunOutcome {
    out.clear();
    let mut pass = Pass {
        scene,
        front,
        out,
        outcome: RunOutcome::default(),
        fallback: ClipFallback::default(),
    };
    for part in mesh_parts(scene, cache, range) {
        for t in part.triangles {
            pass.one(
                part.mesh,
                part.cache,
                (part.m, t, (part.first_prim + t) as u32),
            );
        }
    }
    let Pass {
        mut outcome,
        fallback,
        ..
    } = pass;
    outcome.stats.add(fallback.stats());
    outcome
}

/// The state of the pass over one run.
struct Pass<'a, S> {
    scene: &'a Scene,
    front: &'a FrontEnd,
    out: &'a mut S,
    outcome: RunOutcome,
    /// `prepare`'s per-triangle path, for triangles that must be clipped.
    fallback: ClipFallback,
}

impl<S: LeanSink> Pass<'_, S> {
    /// Triangle `t` of mesh `m` (primitive `prim`), with the mesh's cached
    /// vertices.
    #[inline(always)]
    fn one(&mut self, mesh: &Mesh, cache: &[CachedVertex], (m, t, prim): (usize, usize, u32)) {
        let idx = mesh.indices[t];
        self.outcome.bad_index |= idx.iter().any(|&i| i as usize >= cache.len());
        let c = idx.map(|i| cache.get(i as usize).copied().unwrap_or(OUT_OF_RANGE));
        let (all, any) = (
            c[0].code & c[1].code & c[2].code,
            c[0].code | c[1].code | c[2].code,
        );
        let stats = &mut self.outcome.stats;
        // The order of these tests is clip_triangle's, then the window
        // step's, so every triangle is dropped or kept for the same reason
        // as in `prepare`.
        if any & NOT_FINITE != 0 || all & (OUTSIDE_VIEWPORT | OUTSIDE_PLANES) != 0 {
            stats.culled += 1;
            return;
        }
        if any & OUTSIDE_PLANES != 0 {
            self.clipped((m, t, prim));
            return;
        }
        if any & NO_WINDOW != 0 {
            stats.culled += 1;
            return;
        }
        // Orientation and facing are exact integer work on the snapped
        // corners; only triangles that survive them pay for the depth
        // plane (two divisions). A zero area is exactly a zero plane
        // determinant (both are exact), so `setup_depth` cannot fail here.
        let v = c.map(|k| k.p);
        let area = orient2d(v[0], v[1], v[2]);
        if area == 0 {
            stats.degenerate += 1;
            return;
        }
        if self.front.options.cull_back_faces && area > 0 {
            stats.back_faces += 1;
            return;
        }
        let window = c.map(|k| WindowVertex {
            p: k.p,
            z: k.z,
            w: 0.0,
        });
        let Some((c, front_facing, depth)) = setup_depth(window, area) else {
            stats.degenerate += 1;
            return;
        };
        self.out.push(LeanTri {
            v: c.map(|k| k.p),
            z: c.map(|k| k.z),
            depth,
            prim,
            front_facing,
        });
    }

    /// A triangle that must be clipped: `prepare`'s own path, keeping its
    /// pieces.
    fn clipped(&mut self, which: (usize, usize, u32)) {
        let (pieces, _) = self.fallback.clip(self.front, self.scene, which);
        for tri in pieces {
            self.out.push(LeanTri::from(tri));
        }
    }
}
