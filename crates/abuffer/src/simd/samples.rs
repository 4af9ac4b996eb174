//! The depth test of one pixel's 8 x 4 grid samples with AVX2 intrinsics,
//! chosen at run time behind [`Avx2`], the token the masks use.
//!
//! The portable code evaluates the triangle's plane at each covered
//! sample (`value + dx * (x - x0) + dy * (y - y0)` in `f64`, rounded to
//! `f32`, [`crate::depth::plane_depth`]) and keeps it where it is nearer
//! than the sample's depth, or as near with a lower primitive id. Here a
//! row of 8 samples is two registers of 4 `f64` and one of 8 keys: the
//! same operations in the same order (IEEE adds, subtractions and
//! multiplies give the same result in any lane; there is no fused
//! multiply-add), the same rounding to `f32` (to nearest, as `as f32`),
//! so the same depths and the same winners, bit for bit (property-tested
//! against the portable path).

use hider_geom::PlaneEq;
use hider_geom::isa::Avx2;

use crate::bins::BinItem;
use crate::pattern::SamplePattern;
use crate::resolve::{Band, Input, Resolver, Samples};
use crate::samples::{Held, SampleBuffer};
use crate::stats::ABufferStats;

/// [`SampleBuffer::triangle`] for the 8 x 4 grid, the whole loop compiled
/// with AVX2 enabled so that the depth test and the mask inline into it.
#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "a target-feature call proven sound by the Avx2 token"
)]
pub(crate) fn triangle(
    isa: Avx2,
    buffer: &mut SampleBuffer,
    item: &BinItem,
    stats: &mut ABufferStats,
) {
    #[target_feature(enable = "avx2")]
    #[inline]
    fn wide(isa: Avx2, buffer: &mut SampleBuffer, item: &BinItem, stats: &mut ABufferStats) {
        buffer.triangle_with(item, SamplePattern::Grid32, stats, Some(isa));
    }
    // SAFETY: an `Avx2` value exists only where AVX2 was detected.
    unsafe { wide(isa, buffer, item, stats) }
}

/// [`SampleBuffer::whole_block`] compiled with AVX2 enabled, so that the
/// rows' plane evaluations inline into it.
#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "a target-feature call proven sound by the Avx2 token"
)]
pub(crate) fn whole_block(
    _proof: Avx2,
    buffer: &mut SampleBuffer,
    held: Held,
    ij: (u32, u32),
    stats: &mut ABufferStats,
) {
    #[target_feature(enable = "avx2")]
    #[inline]
    fn wide(buffer: &mut SampleBuffer, held: Held, ij: (u32, u32), stats: &mut ABufferStats) {
        buffer.whole_block_with(held, ij, stats);
    }
    // SAFETY: an `Avx2` value exists only where AVX2 was detected.
    unsafe { wide(buffer, held, ij, stats) }
}

/// [`SampleBuffer::resolve`] compiled with AVX2 enabled, so that the
/// per-primitive sample counts ([`equal_mask`]) inline into it.
#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "a target-feature call proven sound by the Avx2 token"
)]
pub(crate) fn resolve(
    _proof: Avx2,
    buffer: &mut SampleBuffer,
    (input, resolver): (&mut Input<'_>, &mut Resolver),
    k: &Samples,
    frame: &mut Band<'_>,
) {
    #[target_feature(enable = "avx2")]
    #[inline]
    fn wide(
        buffer: &mut SampleBuffer,
        (input, resolver): (&mut Input<'_>, &mut Resolver),
        k: &Samples,
        frame: &mut Band<'_>,
    ) {
        buffer.resolve_with(input, resolver, k, frame);
    }
    // SAFETY: an `Avx2` value exists only where AVX2 was detected.
    unsafe { wide(buffer, (input, resolver), k, frame) }
}

/// Depth-tests the samples of `mask` (bit `r * 8 + c` = cell `(c, r)`)
/// of pixel `(i, j)` on plane `plane` for primitive `prim` against
/// `keys` and `prims`, keeping the winners; returns the largest key of
/// the pixel's samples afterwards.
#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "a target-feature call proven sound by the Avx2 token, and unaligned loads and stores of arrays of 32 i32"
)]
#[inline(always)]
pub(crate) fn write_grid(
    _proof: Avx2,
    keys: &mut [i32; 32],
    prims: &mut [u32; 32],
    plane: &PlaneEq,
    (i, j): (u32, u32),
    prim: u32,
    mask: u32,
) -> i32 {
    #[target_feature(enable = "avx2")]
    #[inline]
    fn wide(
        keys: &mut [i32; 32],
        prims: &mut [u32; 32],
        plane: &PlaneEq,
        (i, j): (u32, u32),
        prim: u32,
        mask: u32,
    ) -> i32 {
        use std::arch::x86_64::{
            __m256i, _mm_cvtsi128_si32, _mm_max_epi32, _mm_shuffle_epi32, _mm256_add_pd,
            _mm256_and_si256, _mm256_blendv_epi8, _mm256_castsi256_si128, _mm256_cmpeq_epi32,
            _mm256_cmpgt_epi32, _mm256_extracti128_si256, _mm256_loadu_si256, _mm256_max_epi32,
            _mm256_mul_pd, _mm256_or_si256, _mm256_set1_epi32, _mm256_set1_pd, _mm256_setr_epi32,
            _mm256_setr_pd, _mm256_storeu_si256, _mm256_sub_pd, _mm256_xor_si256,
        };
        let fi = f64::from(i);
        // x of columns 0-3 and 4-7: i + (32c + 16) / 256, exact.
        let x_lo = _mm256_setr_pd(fi + 0.0625, fi + 0.1875, fi + 0.3125, fi + 0.4375);
        let x_hi = _mm256_setr_pd(fi + 0.5625, fi + 0.6875, fi + 0.8125, fi + 0.9375);
        let (x0, dx, value) = (
            _mm256_set1_pd(plane.x0),
            _mm256_set1_pd(plane.dx),
            _mm256_set1_pd(plane.value),
        );
        // value + dx * (x - x0), per column.
        let a_lo = _mm256_add_pd(value, _mm256_mul_pd(dx, _mm256_sub_pd(x_lo, x0)));
        let a_hi = _mm256_add_pd(value, _mm256_mul_pd(dx, _mm256_sub_pd(x_hi, x0)));
        let bias = _mm256_set1_epi32(i32::MIN);
        let prim_v = _mm256_set1_epi32(prim as i32);
        let prim_b = _mm256_xor_si256(prim_v, bias);
        let lane = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
        let mut far = _mm256_set1_epi32(i32::MIN);
        for r in 0..4 {
            // SAFETY: `keys[8 * r..8 * r + 8]` and `prims[...]` are 8
            // initialised 4-byte values, 32 bytes; `loadu` and `storeu`
            // accept any alignment.
            let (kp, pp) = unsafe {
                (
                    keys.as_mut_ptr().add(8 * r).cast::<__m256i>(),
                    prims.as_mut_ptr().add(8 * r).cast::<__m256i>(),
                )
            };
            let old = unsafe { _mm256_loadu_si256(kp) };
            // An empty row is computed too (its lanes keep their keys):
            // whether a partial mask misses a row is a coin toss, and as
            // a branch it mispredicted.
            let bits = (mask >> (8 * r)) & 0xff;
            // + dy * (y - y0), y = j + (64r + 32) / 256, exact.
            let ty = plane.dy * ((f64::from(j) + (r as f64 * 64.0 + 32.0) / 256.0) - plane.y0);
            let ty = _mm256_set1_pd(ty);
            let key = keys8(_mm256_add_pd(a_lo, ty), _mm256_add_pd(a_hi, ty));
            let old_p = unsafe { _mm256_loadu_si256(pp) };
            let nearer = _mm256_cmpgt_epi32(old, key);
            let tie = _mm256_and_si256(
                _mm256_cmpeq_epi32(old, key),
                _mm256_cmpgt_epi32(_mm256_xor_si256(old_p, bias), prim_b),
            );
            let bv = _mm256_set1_epi32(bits as i32);
            let covered = _mm256_cmpeq_epi32(_mm256_and_si256(bv, lane), lane);
            let win = _mm256_and_si256(_mm256_or_si256(nearer, tie), covered);
            let new = _mm256_blendv_epi8(old, key, win);
            unsafe {
                _mm256_storeu_si256(kp, new);
                _mm256_storeu_si256(pp, _mm256_blendv_epi8(old_p, prim_v, win));
            }
            far = _mm256_max_epi32(far, new);
        }
        let half = _mm_max_epi32(
            _mm256_castsi256_si128(far),
            _mm256_extracti128_si256(far, 1),
        );
        let half = _mm_max_epi32(half, _mm_shuffle_epi32(half, 0b01_00_11_10));
        let half = _mm_max_epi32(half, _mm_shuffle_epi32(half, 0b10_11_00_01));
        _mm_cvtsi128_si32(half)
    }
    // SAFETY: an `Avx2` value exists only where AVX2 was detected.
    unsafe { wide(keys, prims, plane, (i, j), prim, mask) }
}

/// The mask of the samples of `prims` equal to `value` (bit `k` =
/// sample `k`).
#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "a target-feature call proven sound by the Avx2 token, and unaligned loads of an array of 32 u32"
)]
#[inline(always)]
pub(crate) fn equal_mask(_proof: Avx2, prims: &[u32; 32], value: u32) -> u32 {
    #[target_feature(enable = "avx2")]
    #[inline]
    fn wide(prims: &[u32; 32], value: u32) -> u32 {
        use std::arch::x86_64::{
            __m256i, _mm256_castsi256_ps, _mm256_cmpeq_epi32, _mm256_loadu_si256,
            _mm256_movemask_ps, _mm256_set1_epi32,
        };
        let v = _mm256_set1_epi32(value as i32);
        let mut mask = 0u32;
        for r in 0..4 {
            // SAFETY: `prims[8 * r..8 * r + 8]` is 8 initialised u32s,
            // 32 bytes; `loadu` accepts any alignment.
            let row = unsafe { _mm256_loadu_si256(prims.as_ptr().add(8 * r).cast::<__m256i>()) };
            let eq = _mm256_cmpeq_epi32(row, v);
            mask |= (_mm256_movemask_ps(_mm256_castsi256_ps(eq)) as u32) << (8 * r);
        }
        mask
    }
    // SAFETY: an `Avx2` value exists only where AVX2 was detected.
    unsafe { wide(prims, value) }
}

/// [`SampleBuffer::row_near_keys`]: the key of `plane` at the sample-hull
/// corner `corner` of the 8 pixels from `(i0, j)` on, in the portable
/// order of [`crate::depth::plane_depth`] (`value + dx * (x - x0)` first,
/// then `dy * (y - y0)` added; no fused multiply-add; rounded to `f32` to
/// nearest), so the same keys.
#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "a target-feature call proven sound by the Avx2 token, and an unaligned store of 8 i32"
)]
#[inline(always)]
pub(crate) fn row_keys(
    _proof: Avx2,
    plane: &PlaneEq,
    (i0, j): (u32, u32),
    (sx, sy): (i32, i32),
) -> [i32; 8] {
    #[target_feature(enable = "avx2")]
    #[inline]
    fn wide(plane: &PlaneEq, (i0, j): (u32, u32), (sx, sy): (i32, i32)) -> [i32; 8] {
        use std::arch::x86_64::{
            __m256i, _mm256_add_pd, _mm256_mul_pd, _mm256_set1_pd, _mm256_setr_pd,
            _mm256_storeu_si256, _mm256_sub_pd,
        };
        // Pixel columns and corner offsets (1/256 pixel) are exact in f64:
        // x + k + sx / 256 is the portable f64::from(i0 + k) + sx / 256.
        let (x, frac) = (f64::from(i0), _mm256_set1_pd(f64::from(sx) / 256.0));
        let lo = _mm256_add_pd(_mm256_setr_pd(x, x + 1.0, x + 2.0, x + 3.0), frac);
        let hi = _mm256_add_pd(_mm256_setr_pd(x + 4.0, x + 5.0, x + 6.0, x + 7.0), frac);
        let y = f64::from(j) + f64::from(sy) / 256.0;
        let (x0, dx, value, dy) = (
            _mm256_set1_pd(plane.x0),
            _mm256_set1_pd(plane.dx),
            _mm256_set1_pd(plane.value),
            _mm256_set1_pd(plane.dy * (y - plane.y0)),
        );
        let z = |x| {
            _mm256_add_pd(
                _mm256_add_pd(value, _mm256_mul_pd(dx, _mm256_sub_pd(x, x0))),
                dy,
            )
        };
        let key = keys8(z(lo), z(hi));
        let mut out = [0i32; 8];
        // SAFETY: `out` is 8 i32s, 32 writable bytes; `storeu` accepts any
        // alignment.
        unsafe { _mm256_storeu_si256(out.as_mut_ptr().cast::<__m256i>(), key) };
        out
    }
    // SAFETY: an `Avx2` value exists only where AVX2 was detected.
    unsafe { wide(plane, (i0, j), (sx, sy)) }
}

/// The depth keys ([`crate::depth::depth_key`]) of 8 depths given in two
/// registers of 4 `f64` (lanes 0-3 and 4-7), each rounded to `f32` to
/// nearest as `as f32` does.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn keys8(
    lo: std::arch::x86_64::__m256d,
    hi: std::arch::x86_64::__m256d,
) -> std::arch::x86_64::__m256i {
    use std::arch::x86_64::{
        _mm256_castps_si256, _mm256_cvtpd_ps, _mm256_set_m128, _mm256_srai_epi32,
        _mm256_srli_epi32, _mm256_xor_si256,
    };
    let z = _mm256_castps_si256(_mm256_set_m128(_mm256_cvtpd_ps(hi), _mm256_cvtpd_ps(lo)));
    // Keys ordered like `total_cmp`: negative values flip their magnitude
    // bits.
    _mm256_xor_si256(z, _mm256_srli_epi32(_mm256_srai_epi32(z, 31), 1))
}

/// The lanes `k` where `a[k] > b[k]`, as bits.
#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "a target-feature call proven sound by the Avx2 token, and unaligned loads of 8 i32"
)]
#[inline(always)]
pub(crate) fn greater(_proof: Avx2, a: &[i32; 8], b: &[i32; 8]) -> u32 {
    #[target_feature(enable = "avx2")]
    #[inline]
    fn wide(a: &[i32; 8], b: &[i32; 8]) -> u32 {
        use std::arch::x86_64::{
            __m256i, _mm256_castsi256_ps, _mm256_cmpgt_epi32, _mm256_loadu_si256,
            _mm256_movemask_ps,
        };
        // SAFETY: `a` and `b` are 8 i32s, 32 bytes each; `loadu` accepts
        // any alignment.
        let (a, b) = unsafe {
            (
                _mm256_loadu_si256(a.as_ptr().cast::<__m256i>()),
                _mm256_loadu_si256(b.as_ptr().cast::<__m256i>()),
            )
        };
        _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(a, b))) as u32
    }
    // SAFETY: an `Avx2` value exists only where AVX2 was detected.
    unsafe { wide(a, b) }
}
