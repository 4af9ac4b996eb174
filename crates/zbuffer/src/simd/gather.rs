//! The triangle pass's corner gather for eight triangles: one bounds
//! check for the batch's 24 vertex indices (three registers, an unsigned
//! maximum), then each coordinate of the cached vertices read straight
//! into one register per corner.
//!
//! Written triangle by triangle, the gather checked each index, copied
//! three 24-byte vertices and scattered their fields into the batch's
//! arrays one store each (some 66 instructions a triangle). With this
//! version the front end executes 12 % fewer instructions on the
//! 499k-triangle sphere (131M to 115M a frame) at the same speed or a
//! little faster.
//!
//! The position and depth (a vertex's first 16 bytes) are read as one
//! row per vertex and transposed in registers (`unpack`, `shuffle`,
//! `permute`), the outcode word by word: 12 % fewer instructions again in
//! the front end on the 79,600-triangle sphere than reading each field
//! word by word, and its wall time 8 % (12 % on the 499k-triangle sphere)
//! lower.
//!
//! Tried and not kept (`docs/notes/2026-11-28-zbuffer-front-end.md`): the
//! hardware gathers (`vpgatherdd`, `vgatherdpd`), fifteen a batch, cut
//! the instructions by a further 6 % but made the front end 10 to 15 %
//! slower on this machine's Zen 5 cores.
//!
//! The result is the bytes the one-by-one gather copies. It is used only
//! when every index of the batch is in range; the one-by-one path reads a
//! culling vertex for the others and reports them.

use hider_geom::FixedPt;
use hider_geom::isa::Avx2;
use hider_scene::prepare::lean::CachedVertex;

use crate::depth_scene::classify::LANES;

/// A batch's corners, structure of arrays, as the triangle pass classifies
/// them, with the OR of every vertex's outcode and the OR over the
/// triangles of the AND of their three outcodes.
#[derive(Default)]
pub(crate) struct Corners {
    pub(crate) x: [[i32; LANES]; 3],
    pub(crate) y: [[i32; LANES]; 3],
    pub(crate) z: [[f64; LANES]; 3],
    pub(crate) any: u32,
    pub(crate) beyond: u32,
}

// The reads are aligned: a vertex is a whole number of `f64`s, its
// position's and code's offsets whole `i32`s and its depth's a whole
// `f64`.
const SIZE: usize = std::mem::size_of::<CachedVertex>();
const X: usize = std::mem::offset_of!(CachedVertex, p) + std::mem::offset_of!(FixedPt, x);
const Y: usize = std::mem::offset_of!(CachedVertex, p) + std::mem::offset_of!(FixedPt, y);
const Z: usize = std::mem::offset_of!(CachedVertex, z);
const CODE: usize = std::mem::offset_of!(CachedVertex, code);
// A vertex's first 16 bytes are its position and its depth, read as one
// row.
const _: () = assert!(X == 0 && Y == 4 && Z == 8);
const _: () = assert!(
    SIZE.is_multiple_of(8)
        && X.is_multiple_of(4)
        && Y.is_multiple_of(4)
        && CODE.is_multiple_of(4)
        && Z.is_multiple_of(8)
);

/// Writes the corners of the eight triangles `indices` from `cache` into
/// `out` and returns true, or returns false (`out` untouched) when an
/// index is out of range (the caller gathers those one by one). The
/// [`Avx2`] argument is the proof the intrinsics need (see
/// [`super::classify::classify`]).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn corners(
    _proof: Avx2,
    indices: &[[u32; 3]; LANES],
    cache: &[CachedVertex],
    out: &mut Corners,
) -> bool {
    !cache.is_empty() && avx2::corners(indices, cache, out)
}

/// Without x86-64 there is no [`Avx2`] value, so this is never called.
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
pub(crate) fn corners(
    proof: Avx2,
    _: &[[u32; 3]; LANES],
    _: &[CachedVertex],
    _: &mut Corners,
) -> bool {
    unreachable!("{proof:?} exists only on x86-64")
}

#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "AVX2 intrinsics, reached only with the Avx2 token that proves the CPU has them, and reads at indices checked against the cache's length"
)]
mod avx2 {
    use std::arch::x86_64::*;

    use super::{CODE, CachedVertex, Corners, LANES, SIZE, X};

    // SAFETY (every `unsafe` block of this module): reached only through
    // `super::corners`, whose `Avx2` argument proves the CPU has AVX2.

    /// The `i32` at byte offset `FIELD` of the vertices at byte offsets
    /// `at` from `base`, in eight lanes.
    #[inline(always)]
    unsafe fn words<const FIELD: usize>(base: *const u8, at: &[usize; LANES]) -> __m256i {
        // SAFETY: the caller checked every index, so every address is
        // inside the cache.
        unsafe {
            let w = |i: usize| base.add(at[i] + FIELD).cast::<i32>().read();
            _mm256_setr_epi32(w(0), w(1), w(2), w(3), w(4), w(5), w(6), w(7))
        }
    }

    /// See [`super::corners`].
    #[inline(always)]
    pub(super) fn corners(
        indices: &[[u32; 3]; LANES],
        cache: &[CachedVertex],
        out: &mut Corners,
    ) -> bool {
        unsafe {
            let flat: &[u32; 3 * LANES] = bytemuck::cast_ref(indices);
            // Every index at most the last one (unsigned), or none read.
            let top = _mm256_max_epu32(
                _mm256_loadu_si256(flat[0..].as_ptr().cast()),
                _mm256_max_epu32(
                    _mm256_loadu_si256(flat[8..].as_ptr().cast()),
                    _mm256_loadu_si256(flat[16..].as_ptr().cast()),
                ),
            );
            let last = _mm256_set1_epi32((cache.len() - 1) as i32);
            if _mm256_movemask_epi8(_mm256_cmpeq_epi32(_mm256_max_epu32(top, last), last)) != -1 {
                return false;
            }
            let base = cache.as_ptr().cast::<u8>();
            let mut codes = [_mm256_setzero_si256(); 3];
            for k in 0..3 {
                let at: [usize; LANES] = [
                    indices[0][k] as usize * SIZE,
                    indices[1][k] as usize * SIZE,
                    indices[2][k] as usize * SIZE,
                    indices[3][k] as usize * SIZE,
                    indices[4][k] as usize * SIZE,
                    indices[5][k] as usize * SIZE,
                    indices[6][k] as usize * SIZE,
                    indices[7][k] as usize * SIZE,
                ];
                // Each vertex's position and depth (its first 16 bytes)
                // as one row, lanes i and i + 4 in one register ...
                let row = |i: usize| {
                    let lo = _mm_loadu_si128(base.add(at[i] + X).cast());
                    let hi = _mm_loadu_si128(base.add(at[i + 4] + X).cast());
                    _mm256_inserti128_si256::<1>(_mm256_castsi128_si256(lo), hi)
                };
                let (r0, r1, r2, r3) = (row(0), row(1), row(2), row(3));
                // ... transposed: positions of lanes 0, 1 | 4, 5 and 2, 3
                // | 6, 7, then x and y in lane order; depths of lanes
                // 0, 1 | 4, 5 and 2, 3 | 6, 7, then in lane order.
                let (p, q) = (
                    _mm256_castsi256_ps(_mm256_unpacklo_epi64(r0, r1)),
                    _mm256_castsi256_ps(_mm256_unpacklo_epi64(r2, r3)),
                );
                out.x[k] = bytemuck::cast(_mm256_shuffle_ps::<0b10_00_10_00>(p, q));
                out.y[k] = bytemuck::cast(_mm256_shuffle_ps::<0b11_01_11_01>(p, q));
                let (zp, zq) = (_mm256_unpackhi_epi64(r0, r1), _mm256_unpackhi_epi64(r2, r3));
                out.z[k] = bytemuck::cast([
                    _mm256_permute2x128_si256::<0x20>(zp, zq),
                    _mm256_permute2x128_si256::<0x31>(zp, zq),
                ]);
                codes[k] = words::<CODE>(base, &at);
            }
            let any: [u32; LANES] = bytemuck::cast(_mm256_or_si256(
                _mm256_or_si256(codes[0], codes[1]),
                codes[2],
            ));
            let all: [u32; LANES] = bytemuck::cast(_mm256_and_si256(
                _mm256_and_si256(codes[0], codes[1]),
                codes[2],
            ));
            out.any = any.iter().fold(0, |m, &c| m | c);
            out.beyond = all.iter().fold(0, |m, &c| m | c);
            true
        }
    }
}

#[cfg(test)]
mod tests {
    use hider_geom::FixedPt;
    use hider_geom::isa::Avx2;
    use hider_scene::prepare::lean::CachedVertex;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(500))]
        /// The gathered corners are the cache's vertices at the indices, and
        /// a batch with an index out of range is left to the one-by-one
        /// gather.
        #[test]
        fn gathers_the_indexed_vertices(
            len in 1usize..64,
            raw in proptest::array::uniform8(proptest::array::uniform3(0u32..80)),
            seed in any::<u64>(),
            wrap in proptest::bool::weighted(0.8),
        ) {
            // Mostly batches with every index in range (24 random indices
            // rarely are), else the rest.
            let raw = if wrap { raw.map(|t| t.map(|i| i % len as u32)) } else { raw };
            let Some(avx2) = Avx2::detect() else { return Ok(()) };
            let cache: Vec<CachedVertex> = (0..len as u64)
                .map(|i| {
                    let h = (i + 1).wrapping_mul(seed | 1).rotate_left(17);
                    CachedVertex {
                        p: FixedPt::new(h as i32, (h >> 32) as i32),
                        z: (h % 1000) as f64 / 7.0,
                        code: (h >> 40) as u32,
                    }
                })
                .collect();
            let mut got = super::Corners::default();
            let gathered = super::corners(avx2, &raw, &cache, &mut got);
            let in_range = raw.iter().flatten().all(|&i| (i as usize) < len);
            prop_assert_eq!(gathered, in_range);
            if !gathered {
                return Ok(());
            }
            let (mut any, mut beyond) = (0, 0);
            for (i, tri) in raw.iter().enumerate() {
                let v = tri.map(|j| cache[j as usize]);
                for (k, v) in v.iter().enumerate() {
                    prop_assert_eq!((got.x[k][i], got.y[k][i]), (v.p.x, v.p.y));
                    prop_assert_eq!(got.z[k][i].to_bits(), v.z.to_bits());
                }
                any |= v[0].code | v[1].code | v[2].code;
                beyond |= v[0].code & v[1].code & v[2].code;
            }
            prop_assert_eq!((got.any, got.beyond), (any, beyond));
        }
    }
}
