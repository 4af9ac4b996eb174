//! The 8 x 4 grid mask of the 32-bit path with AVX2 intrinsics, chosen at
//! run time behind [`Avx2`], the instruction-set token the tiled
//! z-buffer's front end uses too.
//!
//! The portable code computes, per cell, the sign of
//! `(-E0 - off0) & (-E1 - off1) & (-E2 - off2)` in 32 `i32` lanes and
//! gathers the signs with a multiply per row of 8; left to the compiler on
//! baseline x86-64 that is four SSE2 registers per row and edge. Here a
//! row of 8 cells is one 256-bit register per edge, and
//! `_mm256_movemask_ps` gathers its 8 sign bits in one instruction: the
//! same adds (wrapping, like the portable lanes, which never overflow:
//! the values are clamped to +-2^30 and the offsets are below 2^30) and
//! the same bits. The per-triangle offsets `-(a*x_c + b*y_r)` are set up
//! the same way, a row of 8 per register: every value is below 2^29 in
//! magnitude on this path (edge coefficients below 2^20, sample
//! coordinates below 256), so `i32` arithmetic gives the portable `i64`
//! values exactly.

use hider_geom::EdgeFunction;
use hider_geom::isa::Avx2;

/// The grid mask (bit `r * 8 + c` = cell `(c, r)`) from the clamped,
/// negated corner values `nb` and the per-cell offsets `noff`: the
/// portable `grid_mask`'s answer, bit for bit.
#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "a target-feature call proven sound by the Avx2 token, and unaligned loads from arrays of 32 i32"
)]
#[inline]
pub(crate) fn grid_mask(_proof: Avx2, noff: &[[i32; 32]; 3], nb: [i32; 3]) -> u32 {
    #[target_feature(enable = "avx2")]
    fn wide(noff: &[[i32; 32]; 3], nb: [i32; 3]) -> u32 {
        use std::arch::x86_64::{
            __m256i, _mm256_add_epi32, _mm256_and_si256, _mm256_castsi256_ps, _mm256_loadu_si256,
            _mm256_movemask_ps, _mm256_set1_epi32,
        };
        let b = [
            _mm256_set1_epi32(nb[0]),
            _mm256_set1_epi32(nb[1]),
            _mm256_set1_epi32(nb[2]),
        ];
        let mut mask = 0u32;
        for r in 0..4 {
            // SAFETY: `noff[e][8 * r..8 * r + 8]` is 8 initialised i32s,
            // 32 bytes; `loadu` accepts any alignment.
            let row = |e: usize| unsafe {
                _mm256_loadu_si256(noff[e][8 * r..8 * r + 8].as_ptr().cast::<__m256i>())
            };
            let w = _mm256_and_si256(
                _mm256_and_si256(
                    _mm256_add_epi32(b[0], row(0)),
                    _mm256_add_epi32(b[1], row(1)),
                ),
                _mm256_add_epi32(b[2], row(2)),
            );
            // Negative in all three edges = inside all three.
            let signs = _mm256_movemask_ps(_mm256_castsi256_ps(w)) as u32;
            mask |= signs << (8 * r);
        }
        mask
    }
    // SAFETY: an `Avx2` value exists only where AVX2 was detected.
    unsafe { wide(noff, nb) }
}

/// The offsets `-(a*x_c + b*y_r)` of each edge and grid cell `r * 8 + c`
/// (`x_c = 32c + 16`, `y_r = 64r + 32`) into `noff`: the portable set-up's
/// values, for edges of the 32-bit path.
#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "a target-feature call proven sound by the Avx2 token, and unaligned stores into arrays of 32 i32"
)]
#[inline]
pub(crate) fn offsets(_proof: Avx2, edges: &[EdgeFunction; 3], noff: &mut [[i32; 32]; 3]) {
    #[target_feature(enable = "avx2")]
    fn wide(edges: &[EdgeFunction; 3], noff: &mut [[i32; 32]; 3]) {
        use std::arch::x86_64::{
            __m256i, _mm256_add_epi32, _mm256_mullo_epi32, _mm256_set1_epi32, _mm256_setr_epi32,
            _mm256_storeu_si256,
        };
        let x = _mm256_setr_epi32(16, 48, 80, 112, 144, 176, 208, 240);
        for (edge, out) in edges.iter().zip(noff.iter_mut()) {
            // |a|, |b| < 2^20: -a and every product fit i32.
            let col = _mm256_mullo_epi32(_mm256_set1_epi32(-(edge.a as i32)), x);
            for r in 0..4 {
                let row = -(edge.b * (r as i64 * 64 + 32)) as i32;
                let cells = _mm256_add_epi32(col, _mm256_set1_epi32(row));
                // SAFETY: `out[8 * r..8 * r + 8]` is 8 i32s, 32 writable
                // bytes; `storeu` accepts any alignment.
                unsafe {
                    _mm256_storeu_si256(out[8 * r..8 * r + 8].as_mut_ptr().cast::<__m256i>(), cells)
                };
            }
        }
    }
    // SAFETY: an `Avx2` value exists only where AVX2 was detected.
    unsafe { wide(edges, noff) }
}

/// [`TriCoverage::classify_run`](crate::coverage::TriCoverage::classify_run) with AVX2: the 8 pixels' edge
/// values `base + k * step` plus the hull offsets in two registers of 4
/// `i64` per edge, compared with zero and gathered by `movemask`. The
/// same integer sums (no lane overflows: edge values stay far below
/// `2^62`) and the same strict comparisons, so the same bits.
#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "a target-feature call proven sound by the Avx2 token"
)]
#[inline]
pub(crate) fn classify_run(
    _proof: Avx2,
    base: [i64; 3],
    step: [i64; 3],
    (hull_min, hull_max): ([i64; 3], [i64; 3]),
) -> (u32, u32) {
    #[target_feature(enable = "avx2")]
    #[inline]
    fn wide(
        base: [i64; 3],
        step: [i64; 3],
        (hull_min, hull_max): ([i64; 3], [i64; 3]),
    ) -> (u32, u32) {
        use std::arch::x86_64::{
            _mm256_add_epi64, _mm256_and_si256, _mm256_castsi256_pd, _mm256_cmpgt_epi64,
            _mm256_movemask_pd, _mm256_set_epi64x, _mm256_set1_epi64x, _mm256_setzero_si256,
        };
        let zero = _mm256_setzero_si256();
        let all = _mm256_set1_epi64x(-1);
        let (mut full_lo, mut full_hi, mut touched_lo, mut touched_hi) = (all, all, all, all);
        for e in 0..3 {
            let s = step[e];
            let lo = _mm256_set_epi64x(3 * s, 2 * s, s, 0);
            let hi = _mm256_add_epi64(lo, _mm256_set1_epi64x(4 * s));
            let low = _mm256_set1_epi64x(base[e] + hull_min[e]);
            let high = _mm256_set1_epi64x(base[e] + hull_max[e]);
            let inside = |b, k| _mm256_cmpgt_epi64(_mm256_add_epi64(b, k), zero);
            full_lo = _mm256_and_si256(full_lo, inside(low, lo));
            full_hi = _mm256_and_si256(full_hi, inside(low, hi));
            touched_lo = _mm256_and_si256(touched_lo, inside(high, lo));
            touched_hi = _mm256_and_si256(touched_hi, inside(high, hi));
        }
        let bits = |lo, hi| {
            (_mm256_movemask_pd(_mm256_castsi256_pd(lo))
                | _mm256_movemask_pd(_mm256_castsi256_pd(hi)) << 4) as u32
        };
        (bits(full_lo, full_hi), bits(touched_lo, touched_hi))
    }
    // SAFETY: an `Avx2` value exists only where AVX2 was detected.
    unsafe { wide(base, step, (hull_min, hull_max)) }
}
