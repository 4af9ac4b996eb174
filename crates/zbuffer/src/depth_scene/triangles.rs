//! The triangle pass of the lean front end: each triangle set up from its
//! cached vertices, or cut by `prepare`'s own clipping path when it must
//! be.
//!
//! Triangles are classified eight at a time: orientation, pixel box and
//! the exact test of the (at most four) pixel centres of a small box are
//! integer work done in lanes (the compiler vectorises it; on a CPU with
//! AVX2 the pass runs in a copy compiled for it, where a 32 x 32 -> 64-bit
//! product is one instruction for four lanes). Only then are the depth
//! planes of the kept triangles computed (two divisions each; with AVX2
//! four lanes to a register, `simd::plane`, else one by one). A batch
//! with a vertex that needs clipping, or is outside the window, goes
//! through the same steps one triangle at a time ([`Pass::one`]), which is
//! the definition the batch must match.
//!
//! A triangle whose box holds at most four pixel centres is tested against
//! them anyway (to drop it when it covers none), so when it covers some it
//! is handed over as those pixels ([`DepthFragment`]s, the depth evaluated
//! at the centre) rather than as a triangle: the hider then writes a depth
//! instead of setting up and scanning a triangle. On the 499k-triangle
//! sphere at 1024 x 1024 that is 201k of the 218k triangles kept.

use hider_geom::clip::{OUTSIDE_PLANES, OUTSIDE_VIEWPORT};
#[cfg(target_arch = "x86_64")]
use hider_geom::isa::Avx2;
use hider_geom::isa::{Isa, Portable};
use hider_geom::{Centres, FEW_CENTRES, FixedPt, PlaneEq, orient2d};
use hider_scene::prepare::{FrontEnd, WindowVertex, setup_depth};
use hider_scene::{Mesh, PrepareStats, Scene};

use super::classify::{CENTRE_AT, LANES, Lanes};
use super::depth_tri::{DepthFragment, DepthTri, SmallSetup};
use crate::simd;
#[cfg(target_arch = "x86_64")]
use crate::simd::Kernel;
use crate::simd::emit::Batch;
use crate::simd::fragments::Small;
use crate::simd::gather::Corners;
use hider_scene::prepare::lean::{
    CachedVertex, ClipFallback, NO_WINDOW, NOT_FINITE, RunOutcome, mesh_parts,
};

/// One contiguous run of primitive ids of the output.
#[derive(Clone, Debug, Default)]
pub(super) struct Run {
    pub(super) tris: Vec<DepthTri>,
    pub(super) fragments: Vec<DepthFragment>,
}

/// A vertex with a code that culls the triangle: what an index out of
/// range reads (the caller turns that into an error).
const OUT_OF_RANGE: CachedVertex = CachedVertex {
    p: FixedPt { x: 0, y: 0 },
    z: 0.0,
    code: NOT_FINITE,
};

/// Lanes kept as triangles from which a batch's small-box set-ups are
/// computed in lanes: eight lanes cost about as much as the tile kernel
/// saves on two or three triangles (on the 499k-triangle sphere, where
/// most kept lanes become fragments, computing them for every batch made
/// the frame 3 % slower).
const DENSE_BATCH: u32 = 3;

/// Codes that send a triangle off the common path.
const SPECIAL: u32 = NOT_FINITE | OUTSIDE_PLANES | NO_WINDOW;

/// What the pass reads: the scene, the frame's transforms, the vertex
/// cache (every mesh's vertices one after the other) and the primitive
/// ids to set up.
pub(super) struct Input<'a> {
    pub(super) scene: &'a Scene,
    pub(super) front: &'a FrontEnd,
    pub(super) vertices: &'a [CachedVertex],
    pub(super) range: std::ops::Range<usize>,
}

/// Sets up the triangles of `input` into `run`: in the [`pass`] compiled
/// for AVX2 when the CPU has it ([`simd::with_avx2`]; integer arithmetic
/// is exact and the few floating-point operations are IEEE operations Rust
/// never fuses, so both copies give the same bits).
pub(super) fn triangles(input: &Input<'_>, run: &mut Run) -> RunOutcome {
    #[cfg(target_arch = "x86_64")]
    if let Some(avx2) = Avx2::detect() {
        return simd::with_avx2(Triangles { input, run }, avx2);
    }
    pass(input, run, Portable)
}

/// [`pass`] as a [`Kernel`], for [`simd::with_avx2`].
#[cfg(target_arch = "x86_64")]
struct Triangles<'a, 'b> {
    input: &'a Input<'b>,
    run: &'a mut Run,
}

#[cfg(target_arch = "x86_64")]
impl Kernel for Triangles<'_, '_> {
    type Output = RunOutcome;

    #[inline(always)]
    fn run<I: Isa>(self, isa: I) -> RunOutcome {
        pass(self.input, self.run, isa)
    }
}

#[inline(always)]
fn pass<I: Isa>(input: &Input<'_>, run: &mut Run, isa: I) -> RunOutcome {
    let Input {
        scene,
        front,
        vertices,
        ref range,
    } = *input;
    run.tris.clear();
    run.fragments.clear();
    let mut pass = Pass {
        isa,
        scene,
        front,
        run,
        stats: PrepareStats::default(),
        bad_index: false,
        fallback: ClipFallback::default(),
    };
    for part in mesh_parts(scene, vertices, range.clone()) {
        let (lo, hi) = (part.triangles.start, part.triangles.end);
        let mesh = MeshRef {
            m: part.m,
            mesh: part.mesh,
            cache: part.cache,
            first_prim: part.first_prim,
        };
        let mut t = lo;
        while t + LANES <= hi {
            pass.batch(&mesh, t);
            t += LANES;
        }
        for t in t..hi {
            pass.one(&mesh, t);
        }
    }
    let Pass {
        mut stats,
        fallback,
        bad_index,
        ..
    } = pass;
    stats.add(fallback.stats());
    RunOutcome { stats, bad_index }
}

/// A mesh, its cached vertices and its first primitive id.
struct MeshRef<'a> {
    m: usize,
    mesh: &'a Mesh,
    cache: &'a [CachedVertex],
    first_prim: usize,
}

impl MeshRef<'_> {
    /// The indices of triangles `t..t + LANES`, when the mesh has them.
    #[inline(always)]
    fn indices8(&self, t: usize) -> Option<&[[u32; 3]; LANES]> {
        self.mesh.indices.get(t..t + LANES)?.try_into().ok()
    }

    /// The cached corners of triangle `t`, and whether an index is out of
    /// range.
    #[inline(always)]
    fn corners(&self, t: usize) -> ([CachedVertex; 3], bool) {
        let idx = self.mesh.indices[t];
        let bad = idx.iter().any(|&i| i as usize >= self.cache.len());
        let c = idx.map(|i| self.cache.get(i as usize).copied().unwrap_or(OUT_OF_RANGE));
        (c, bad)
    }
}

/// The state of the pass over one run.
struct Pass<'a, I> {
    isa: I,
    scene: &'a Scene,
    front: &'a FrontEnd,
    run: &'a mut Run,
    stats: PrepareStats,
    bad_index: bool,
    /// `prepare`'s per-triangle path, for triangles that must be clipped.
    fallback: ClipFallback,
}

impl<I: Isa> Pass<'_, I> {
    /// Triangle `t` of the mesh, by itself: the definition of the pass.
    #[inline(always)]
    fn one(&mut self, mesh: &MeshRef<'_>, t: usize) {
        let prim = (mesh.first_prim + t) as u32;
        let (c, bad) = mesh.corners(t);
        self.bad_index |= bad;
        let (all, any) = (
            c[0].code & c[1].code & c[2].code,
            c[0].code | c[1].code | c[2].code,
        );
        // The order of these tests is clip_triangle's, then the window
        // step's, so every triangle is dropped or kept for the same reason
        // as in `prepare`.
        if any & NOT_FINITE != 0 || all & (OUTSIDE_VIEWPORT | OUTSIDE_PLANES) != 0 {
            self.stats.culled += 1;
            return;
        }
        if any & OUTSIDE_PLANES != 0 {
            self.clipped((mesh.m, t, prim));
            return;
        }
        if any & NO_WINDOW != 0 {
            self.stats.culled += 1;
            return;
        }
        // Orientation, facing and the pixel box are integer work on the
        // snapped corners; only triangles that survive them pay for the
        // depth plane (two divisions). A zero area is exactly a zero plane
        // determinant (both are exact), so every triangle is still dropped
        // for `prepare`'s reason.
        let v = c.map(|k| k.p);
        let area = orient2d(v[0], v[1], v[2]);
        if area == 0 {
            self.stats.degenerate += 1;
            return;
        }
        if self.front.options.cull_back_faces && area > 0 {
            self.stats.back_faces += 1;
            return;
        }
        let centres = match self.front.viewport.covered_centres(&v, area) {
            Centres::Few { count: 0, .. } => {
                self.stats.empty += 1;
                return;
            }
            centres => centres,
        };
        let window = c.map(|k| WindowVertex {
            p: k.p,
            z: k.z,
            w: 0.0,
        });
        let Some((c, _, depth)) = setup_depth(window, area) else {
            self.stats.degenerate += 1;
            return;
        };
        // One by one, a set-up costs the front end what it saves the
        // tile kernel: none.
        let tri = DepthTri {
            v: c.map(|k| k.p),
            depth,
            prim,
            setup: SmallSetup::NONE,
        };
        emit(self.run, &mut self.stats, tri, centres);
    }

    /// Triangles `t..t + LANES` of the mesh: the integer work in lanes,
    /// then the kept ones one by one; the same output as [`Self::one`] on
    /// each.
    #[inline(always)]
    fn batch(&mut self, mesh: &MeshRef<'_>, t: usize) {
        // Gather the corners, structure of arrays: eight at a time with
        // AVX2 when every index is in range, else one by one.
        let mut corners = Corners::default();
        let gathered = match (self.isa.avx2(), mesh.indices8(t)) {
            (Some(avx2), Some(i)) => simd::gather::corners(avx2, i, mesh.cache, &mut corners),
            _ => false,
        };
        if !gathered {
            self.gather(mesh, t, &mut corners);
        }
        let Corners {
            ref x,
            ref y,
            ref z,
            any,
            beyond,
        } = corners;
        if any & SPECIAL != 0 || beyond & OUTSIDE_VIEWPORT != 0 {
            // Some triangle needs clipping or is culled: rare, or true of
            // a whole region of the mesh at once.
            for i in 0..LANES {
                self.one(mesh, t + i);
            }
            return;
        }
        let size = (self.front.viewport.width, self.front.viewport.height);
        let cull = self.front.options.cull_back_faces;
        let lanes = match self.isa.avx2() {
            Some(avx2) => simd::classify::classify(avx2, x, y, size, cull),
            None => Lanes::classify(x, y, size, cull),
        };
        self.stats.degenerate += lanes.degenerate;
        self.stats.back_faces += lanes.back_faces;
        self.stats.empty += lanes.empty;
        let triangles = lanes.keep & !lanes.few;
        if let Some(avx2) = self.isa.avx2() {
            // The kept lanes' depth planes four lanes to a register (first:
            // the divisions' latency overlaps the set-ups' integer work),
            // the small-box set-ups of the lanes kept as triangles where
            // the batch has enough of them to pay for it (the others go
            // without: the tile kernel then sets them up itself, to the
            // same values), then the records eight lanes at a time.
            let planes = simd::plane::planes(avx2, x, y, z, (lanes.swap, lanes.keep));
            let setups = (triangles.count_ones() >= DENSE_BATCH)
                .then(|| simd::classify::setups(avx2, x, y, size, (lanes.swap, triangles)));
            let batch = Batch {
                x,
                y,
                z0: &z[0],
                swap: lanes.swap,
                planes: &planes,
                setups: setups.as_ref(),
                first_prim: (mesh.first_prim + t) as u32,
            };
            if triangles != 0 {
                simd::emit::push(avx2, &batch, triangles, &mut self.run.tris);
            }
            let few = lanes.keep & lanes.few;
            if few != 0 {
                self.stats.fragmented += u64::from(few.count_ones());
                let small = Small {
                    lanes: few,
                    corner: &lanes.corner,
                    covered: &lanes.covered,
                };
                simd::fragments::push(avx2, &batch, &small, &mut self.run.fragments);
            }
            return;
        }
        // Only the kept lanes, by their bits: no branch per dropped lane.
        let mut keep = lanes.keep;
        while keep != 0 {
            let i = keep.trailing_zeros() as usize;
            keep &= keep - 1;
            let prim = (mesh.first_prim + t + i) as u32;
            // `setup_depth`: the last two corners swapped to positive
            // order, then the plane (it exists: the area is not zero).
            let (b, c) = if lanes.swap >> i & 1 != 0 {
                (2, 1)
            } else {
                (1, 2)
            };
            let v = [
                FixedPt::new(x[0][i], y[0][i]),
                FixedPt::new(x[b][i], y[b][i]),
                FixedPt::new(x[c][i], y[c][i]),
            ];
            let depth = PlaneEq::from_points(&v, [z[0][i], z[b][i], z[c][i]]).unwrap_or_default();
            if lanes.few >> i & 1 == 0 {
                // Set-ups exist only with AVX2.
                self.run.tris.push(DepthTri {
                    v,
                    depth,
                    prim,
                    setup: SmallSetup::NONE,
                });
                continue;
            }
            self.fragments(&lanes, i, &depth, prim);
        }
    }

    /// Lane `i`'s covered centres as fragments, the lane's plane `depth`
    /// and primitive id `prim`.
    #[inline(always)]
    fn fragments(&mut self, lanes: &Lanes, i: usize, depth: &PlaneEq, prim: u32) {
        let (x0, y0, w) = lanes.corner[i];
        self.stats.fragmented += 1;
        // A box of a few centres is at most FEW_CENTRES wide.
        let [cols, rows] = &CENTRE_AT[(w as usize).min(FEW_CENTRES)];
        let mut covered = lanes.covered[i];
        while covered != 0 {
            let j = covered.trailing_zeros() as usize;
            covered &= covered - 1;
            let (x, y) = (x0 + cols[j] as u32, y0 + rows[j] as u32);
            push_fragment(self.run, depth, prim, (x, y));
        }
    }

    /// The corners of triangles `t..t + LANES`, one by one; an index out
    /// of range reads a culling vertex and sets [`Self::bad_index`].
    #[inline(always)]
    fn gather(&mut self, mesh: &MeshRef<'_>, t: usize, c: &mut Corners) {
        for i in 0..LANES {
            let (v, bad) = mesh.corners(t + i);
            self.bad_index |= bad;
            for (k, v) in v.iter().enumerate() {
                (c.x[k][i], c.y[k][i], c.z[k][i]) = (v.p.x, v.p.y, v.z);
            }
            // Any vertex's special code, and any triangle whose three
            // vertices are beyond one side of the viewport (culled, not
            // classified).
            c.any |= v[0].code | v[1].code | v[2].code;
            c.beyond |= v[0].code & v[1].code & v[2].code;
        }
    }

    /// A triangle that must be clipped: `prepare`'s own path, keeping the
    /// depth part of each piece that covers a pixel centre or may.
    fn clipped(&mut self, which: (usize, usize, u32)) {
        let (pieces, stats) = self.fallback.clip(self.front, self.scene, which);
        for t in pieces {
            // Pieces are positively oriented already.
            match self.front.viewport.covered_centres(&t.v, 1) {
                Centres::Few { count: 0, .. } => stats.empty += 1,
                centres => emit(self.run, stats, DepthTri::from(t), centres),
            }
        }
    }
}

/// Appends a kept triangle to the run: as a triangle, or as the pixels it
/// covers when its box holds at most [`FEW_CENTRES`](hider_geom::FEW_CENTRES) centres.
#[inline(always)]
fn emit(run: &mut Run, stats: &mut PrepareStats, tri: DepthTri, centres: Centres) {
    if centres == Centres::Many {
        run.tris.push(tri);
        return;
    }
    stats.fragmented += 1;
    for &pixel in centres.pixels() {
        push_fragment(run, &tri.depth, tri.prim, pixel);
    }
}

/// Appends the fragment at pixel `(x, y)` of the triangle of plane
/// `depth` and primitive id `prim`.
#[inline(always)]
fn push_fragment(run: &mut Run, depth: &PlaneEq, prim: u32, (x, y): (u32, u32)) {
    run.fragments.push(DepthFragment {
        // The hiders' own expression for a pixel's depth.
        depth: depth.at_pixel(x, y),
        // Images are at most 16384 pixels wide and high.
        x: x as u16,
        y: y as u16,
        prim,
    });
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use hider_geom::Camera;
    use hider_geom::isa::Avx2;
    use hider_scene::prepare::lean::lean_passes;
    use hider_scene::{PrepareOptions, Scene, TransformPrecision, View, procedural};

    use super::{Input, Portable, Run, pass, triangles};

    /// The pass with AVX2 (intrinsics, records written in lanes) gives
    /// the portable pass's triangles, fragments and counters, on meshes of
    /// small triangles, a soup, and a sphere the far plane cuts, in both
    /// precisions, with and without back-face culling.
    #[test]
    fn the_avx2_pass_is_the_portable_pass() {
        if Avx2::detect().is_none() {
            return;
        }
        // The far plane through the sphere's centre.
        let cut = View {
            viewport: hider_geom::Viewport::new(300, 200),
            camera: Camera::perspective(DVec3::new(0.0, 0.0, 3.0), DVec3::ZERO, 0.5, 3.0),
        };
        let scenes: Vec<(Scene, Option<View>)> = vec![
            (procedural::uv_sphere(60), None),
            (procedural::random_soup(4000, 3), None),
            (procedural::uv_sphere(40), Some(cut)),
        ];
        let (mut tris, mut fragments) = (0, 0);
        let mut clipped = 0;
        for (scene, view) in &scenes {
            for size in [97, 512] {
                let view = (*view).unwrap_or_else(|| View::for_scene(scene, size, size).unwrap());
                for (precision, cull) in [
                    (TransformPrecision::F32, false),
                    (TransformPrecision::F64, true),
                ] {
                    let options = PrepareOptions {
                        precision,
                        cull_back_faces: cull,
                        ..PrepareOptions::default()
                    };
                    let (mut vertices, mut runs) = (Vec::new(), Vec::<Run>::new());
                    lean_passes(
                        scene,
                        &view,
                        &options,
                        &mut vertices,
                        &mut runs,
                        |front, cache, range, run| {
                            let input = Input {
                                scene,
                                front,
                                vertices: cache,
                                range,
                            };
                            let mut portable = Run::default();
                            let want = pass(&input, &mut portable, Portable);
                            let got = triangles(&input, run);
                            assert_eq!(run.tris, portable.tris, "{size} {precision:?}");
                            assert_eq!(run.fragments, portable.fragments, "{size} {precision:?}");
                            assert_eq!(got.stats, want.stats);
                            got
                        },
                    )
                    .map(|(_, stats)| clipped += stats.clipped)
                    .unwrap();
                    for r in &runs {
                        (tris, fragments) = (tris + r.tris.len(), fragments + r.fragments.len());
                    }
                }
            }
        }
        // Both kinds of output were compared, and clipped triangles.
        assert!(
            tris > 1000 && fragments > 1000 && clipped > 0,
            "{tris} triangles, {fragments} fragments, {clipped} clipped"
        );
    }
}
