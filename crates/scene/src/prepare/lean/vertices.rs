//! The vertex pass of the lean front end: every vertex transformed,
//! classified by its outcode, divided and snapped once, eight at a time.
//!
//! Each lane computes exactly what `prepare` computes for a corner that
//! uses the vertex, in the same order of operations (the transform is
//! glam's `Mat4 * Vec4` written out, `((x·X + y·Y) + z·Z) + W`, in `f64`
//! on the position minus the eye; the reciprocal of `w`, the divide and
//! the depth map are `to_window`'s; the viewport map and snap are
//! [`Viewport::snap_ndc_lanewise`](hider_geom::Viewport::snap_ndc_lanewise)'s), with
//! selects instead of early returns so that the compiler can keep the
//! eight lanes in vector registers. On a CPU with AVX2 the pass runs in a
//! copy compiled for it (eight `f32` or four `f64` lanes per instruction
//! instead of four or two).

use glam::{DVec3, DVec4};
use hider_geom::FixedPt;
use hider_geom::clip::OUTSIDE_PLANES;
#[cfg(target_arch = "x86_64")]
use hider_geom::isa::Avx2;

use crate::prepare::{FrontEnd, TransformPrecision};

/// Outcode bit: the clip-space position is not finite.
pub const NOT_FINITE: u32 = 1 << 30;
/// Outcode bit: the vertex has no window position (it fails a clip plane,
/// so only the clipping path uses it, or its divide left the snappable
/// range).
pub const NO_WINDOW: u32 = 1 << 31;

/// One vertex after transform, classification, divide and snap.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CachedVertex {
    /// The snapped window position (0 when [`NO_WINDOW`] is set).
    pub p: FixedPt,
    /// The window depth, clamped to [0, 1] (0 when [`NO_WINDOW`] is set).
    pub z: f64,
    /// The clip volume's outcode, or [`NOT_FINITE`], with [`NO_WINDOW`]
    /// when the vertex has no window position.
    pub code: u32,
}

/// Vertices per batch.
const LANES: usize = 8;

/// Runs the pass over one mesh's `positions` into `out` (the same
/// length). Returns whether every world position is finite (a non-finite
/// one is an invalid scene; the caller reports it).
pub fn vertices(front: &FrontEnd, positions: &[DVec3], out: &mut [CachedVertex]) -> bool {
    #[cfg(target_arch = "x86_64")]
    if let Some(avx2) = Avx2::detect() {
        return vertices_avx2(front, positions, out, avx2);
    }
    batches(front, positions, out)
}

/// [`batches`] compiled for AVX2.
///
/// `unsafe` only because calling a `target_feature` function on a CPU
/// without the feature would be undefined; the [`Avx2`] value proves it
/// has it. The results are the same bits: IEEE operations are exact per
/// operation and Rust never contracts `a * b + c` into a fused one.
#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "a target-feature call, proven sound by the Avx2 token"
)]
fn vertices_avx2(
    front: &FrontEnd,
    positions: &[DVec3],
    out: &mut [CachedVertex],
    _proof: Avx2,
) -> bool {
    #[target_feature(enable = "avx2")]
    fn wide(front: &FrontEnd, positions: &[DVec3], out: &mut [CachedVertex]) -> bool {
        batches(front, positions, out)
    }
    // SAFETY: an `Avx2` value exists only where AVX2 was detected.
    unsafe { wide(front, positions, out) }
}

#[inline(always)]
fn batches(front: &FrontEnd, positions: &[DVec3], out: &mut [CachedVertex]) -> bool {
    let mut finite = true;
    let mut from = positions.chunks_exact(LANES);
    let mut to = out.chunks_exact_mut(LANES);
    for (p, o) in (&mut from).zip(&mut to) {
        if let (Ok(p), Ok(o)) = (
            <&[DVec3; LANES]>::try_from(p),
            <&mut [_; LANES]>::try_from(o),
        ) {
            finite &= lanes(front, p, o);
        }
    }
    // The last few vertices, padded with the origin (finite, unused).
    let (rest, rest_out) = (from.remainder(), to.into_remainder());
    if !rest.is_empty() {
        let mut p = [DVec3::ZERO; LANES];
        p[..rest.len()].copy_from_slice(rest);
        let mut o = [CachedVertex::default(); LANES];
        finite &= lanes(front, &p, &mut o);
        rest_out.copy_from_slice(&o[..rest.len()]);
    }
    finite
}

/// Eight vertices. Returns whether their world positions are finite.
#[inline(always)]
fn lanes(front: &FrontEnd, p: &[DVec3; LANES], out: &mut [CachedVertex; LANES]) -> bool {
    let finite_world = p.iter().fold(true, |ok, p| {
        ok & p.x.is_finite() & p.y.is_finite() & p.z.is_finite()
    });
    let vp = front.viewport;
    // Clip-space x, y, z, w and window x, y, z of each lane. Plain
    // indexed loops: `array::from_fn` with closures was not inlined into
    // the AVX2 copy, and every call went through memory.
    let mut clip = [[0.0f64; LANES]; 4];
    // Window depth, and the snapped window position with whether it is
    // in the snappable range.
    let mut depth = [0.0f64; LANES];
    let (mut x, mut y) = ([0i32; LANES], [0i32; LANES]);
    let mut snaps = [false; LANES];
    match front.options.precision {
        TransformPrecision::F32 => {
            let m = front.mvp32;
            let mut c = [[0.0f32; LANES]; 4];
            for i in 0..LANES {
                let (x, y, z) = (p[i].x as f32, p[i].y as f32, p[i].z as f32);
                // glam's `Mat4 * Vec4` (w = 1, and `W * 1` is `W` exactly).
                for (k, c) in c.iter_mut().enumerate() {
                    c[i] = ((m.x_axis[k] * x + m.y_axis[k] * y) + m.z_axis[k] * z) + m.w_axis[k];
                }
            }
            // `to_window` in f32: the reciprocal, the divide, then
            // `snap_ndc_f32` (GL's frame, ties to even, the flip), the
            // snap in a loop of its own (4 % fewer instructions in this
            // pass than with the divide in the same loop; the snap's
            // saturating `as i32` stays a compare and a branch per lane
            // either way, the larger part of the snap's cost).
            let mut ndc = [[0.0f32; LANES]; 2];
            for i in 0..LANES {
                let r = 1.0 / c[3][i];
                (ndc[0][i], ndc[1][i]) = (c[0][i] * r, c[1][i] * r);
                depth[i] = f64::from(c[2][i] * r * 0.5 + 0.5);
                for (clip, c) in clip.iter_mut().zip(&c) {
                    clip[i] = f64::from(c[i]);
                }
            }
            for i in 0..LANES {
                let (ok, q) = vp.snap_ndc_lanewise_f32(ndc[0][i], ndc[1][i]);
                (snaps[i], x[i], y[i]) = (ok, q.x, q.y);
            }
        }
        TransformPrecision::F64 => {
            let (m, eye) = (front.eye_to_clip, front.eye);
            for i in 0..LANES {
                // Relative to the eye first, as `prepare`.
                let (x, y, z) = (p[i].x - eye.x, p[i].y - eye.y, p[i].z - eye.z);
                // glam's `DMat4 * DVec4` (w = 1).
                for (k, clip) in clip.iter_mut().enumerate() {
                    clip[i] = ((m.x_axis[k] * x + m.y_axis[k] * y) + m.z_axis[k] * z) + m.w_axis[k];
                }
            }
            // `to_window` in f64: the reciprocal, the divide, `snap_ndc`.
            for i in 0..LANES {
                let r = 1.0 / clip[3][i];
                let (ok, q) = vp.snap_ndc_lanewise(clip[0][i] * r, clip[1][i] * r);
                (snaps[i], x[i], y[i]) = (ok, q.x, q.y);
                depth[i] = clip[2][i] * r * 0.5 + 0.5;
            }
        }
    }
    // Lane-wise classification and snap, each in its own loop over the
    // lanes so that it vectorises; the scatter into the cache is last.
    let mut code = [0u32; LANES];
    let mut inside = [false; LANES];
    let mut z = [0.0f64; LANES];
    for i in 0..LANES {
        let pos = DVec4::new(clip[0][i], clip[1][i], clip[2][i], clip[3][i]);
        let finite = pos.is_finite();
        let c = front.volume.outcode(pos);
        code[i] = if finite { c } else { NOT_FINITE };
        inside[i] = finite & (c & OUTSIDE_PLANES == 0) & snaps[i];
        // `to_window`'s clamp: rounding of the divide can leave window
        // depth outside [0, 1].
        z[i] = depth[i].clamp(0.0, 1.0);
    }
    for i in 0..LANES {
        let ok = inside[i];
        out[i] = CachedVertex {
            p: FixedPt::new(if ok { x[i] } else { 0 }, if ok { y[i] } else { 0 }),
            z: if ok { z[i] } else { 0.0 },
            code: if ok || code[i] == NOT_FINITE {
                code[i]
            } else {
                code[i] | NO_WINDOW
            },
        };
    }
    finite_world
}
