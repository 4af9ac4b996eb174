//! The full 8x8 block of the tiled z-buffer's kernel with AVX2
//! intrinsics, for the depth formats whose key is 32 bits (the interface,
//! [`Block8`] and [`WideKey`], and why: `tiled/wide.rs`).

use hider_geom::isa::Avx2;

use crate::tiled::wide::{Block8, WideKey};

/// Draws the block with AVX2; returns (pixels inside, passes, the block's
/// greatest key after the merge).
///
/// `#[inline(always)]` and no `target_feature` of its own: it is inlined
/// into the tile kernel compiled for AVX2 (a `target_feature` function
/// here is a call per block, and the call spills the kernel's registers).
/// The intrinsics are therefore called in `unsafe` blocks, one of the
/// project's `unsafe` sites: they are unsafe only because the CPU might
/// lack AVX2, and the [`Avx2`] argument proves it has it.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn block8<K: WideKey, const EDGES: bool>(
    _proof: Avx2,
    keys: &mut [K; 64],
    ids: &mut [u32; 64],
    b: &Block8<'_>,
) -> (u32, u32, K) {
    avx2::block8::<K, EDGES>(keys, ids, b)
}

/// Without x86-64 there is no [`Avx2`] value, so this is never called.
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
pub(crate) fn block8<K: WideKey, const EDGES: bool>(
    proof: Avx2,
    _: &mut [K; 64],
    _: &mut [u32; 64],
    _: &Block8<'_>,
) -> (u32, u32, K) {
    unreachable!("{proof:?} exists only on x86-64")
}

#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "AVX2 intrinsics, reached only with the Avx2 token that proves the CPU has them"
)]
pub(super) mod avx2 {
    use std::arch::x86_64::*;

    use super::{Block8, WideKey};
    use crate::tiled::wide::Encoding;

    /// The eight depths `col + ty` (exact f64 additions), encoded.
    #[inline(always)]
    pub(in crate::simd) fn encode<K: WideKey>(col: (__m256d, __m256d), ty: __m256d) -> __m256i {
        // SAFETY: see `super::block8`: reached only with an `Avx2` proof.
        unsafe {
            let (lo, hi) = (_mm256_add_pd(col.0, ty), _mm256_add_pd(col.1, ty));
            match K::ENCODING {
                Encoding::F32 => {
                    _mm256_castps_si256(_mm256_set_m128(_mm256_cvtpd_ps(hi), _mm256_cvtpd_ps(lo)))
                }
                Encoding::Reversed => {
                    let one = _mm256_set1_pd(1.0);
                    let (lo, hi) = (_mm256_sub_pd(one, lo), _mm256_sub_pd(one, hi));
                    let f = _mm256_set_m128(_mm256_cvtpd_ps(hi), _mm256_cvtpd_ps(lo));
                    // Negation flips the sign bit, NaN and zero included.
                    _mm256_castps_si256(_mm256_xor_ps(f, _mm256_set1_ps(-0.0)))
                }
                Encoding::Fixed24 => _mm256_set_m128i(quantize24(hi), quantize24(lo)),
            }
        }
    }

    /// `(depth.clamp(0.0, 1.0) * MAX24).round() as u32` on four lanes.
    #[inline(always)]
    fn quantize24(d: __m256d) -> __m128i {
        // SAFETY: see `super::block8`.
        unsafe {
            // MAXPD returns its second operand when either is NaN: a NaN
            // depth becomes 0, as `NaN.clamp(..).round() as u32` does.
            let c = _mm256_min_pd(_mm256_max_pd(d, _mm256_setzero_pd()), _mm256_set1_pd(1.0));
            let x = _mm256_mul_pd(c, _mm256_set1_pd(f64::from((1u32 << 24) - 1)));
            // `round` is half away from zero; for x >= 0 that is floor(x)
            // plus one where the fraction (exact: Sterbenz) is at least 1/2.
            let t = _mm256_round_pd::<{ _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC }>(x);
            let up = _mm256_cmp_pd::<_CMP_GE_OQ>(_mm256_sub_pd(x, t), _mm256_set1_pd(0.5));
            let r = _mm256_add_pd(t, _mm256_and_pd(up, _mm256_set1_pd(1.0)));
            _mm256_cvttpd_epi32(r)
        }
    }

    /// `new < old` per lane, as the key's LESS: all ones where true.
    #[inline(always)]
    pub(in crate::simd) fn less<K: WideKey>(new: __m256i, old: __m256i) -> __m256i {
        // SAFETY: see `super::block8`.
        unsafe {
            match K::ENCODING {
                Encoding::F32 | Encoding::Reversed => {
                    _mm256_castps_si256(_mm256_cmp_ps::<_CMP_LT_OQ>(
                        _mm256_castsi256_ps(new),
                        _mm256_castsi256_ps(old),
                    ))
                }
                // Keys below 2^24: the signed comparison is the unsigned one.
                Encoding::Fixed24 => _mm256_cmpgt_epi32(old, new),
            }
        }
    }

    /// The greater key per lane (stored keys are never NaN: a NaN depth
    /// fails LESS).
    #[inline(always)]
    fn max<K: WideKey>(a: __m256i, b: __m256i) -> __m256i {
        // SAFETY: see `super::block8`.
        unsafe {
            match K::ENCODING {
                Encoding::F32 | Encoding::Reversed => _mm256_castps_si256(_mm256_max_ps(
                    _mm256_castsi256_ps(a),
                    _mm256_castsi256_ps(b),
                )),
                Encoding::Fixed24 => _mm256_max_epi32(a, b),
            }
        }
    }

    #[inline(always)]
    pub(super) fn block8<K: WideKey, const EDGES: bool>(
        keys: &mut [K; 64],
        ids: &mut [u32; 64],
        b: &Block8<'_>,
    ) -> (u32, u32, K) {
        // SAFETY: see `super::block8`.
        unsafe {
            let col: [[f64; 4]; 2] = bytemuck::cast(*b.col);
            let col = (bytemuck::cast(col[0]), bytemuck::cast(col[1]));
            // No closures: a closure is a function of its own, without the
            // kernel's target features, and its intrinsics would be calls.
            let lanes: [__m256i; 3] = bytemuck::cast(*b.lanes);
            let mut e = lanes;
            let mut down = [_mm256_setzero_si256(); 3];
            for k in 0..3 {
                let kept = _mm256_and_si256(lanes[k], _mm256_set1_epi32(b.keep[k]));
                e[k] = _mm256_add_epi32(_mm256_set1_epi32(b.e[k]), kept);
                down[k] = _mm256_set1_epi32(b.down[k]);
            }
            let prim = _mm256_set1_epi32(b.prim as i32);
            let minus_one = _mm256_set1_epi32(-1);
            let (mut inside, mut passes) = (_mm256_setzero_si256(), _mm256_setzero_si256());
            let mut greatest = _mm256_setzero_si256();
            // The row's centre `y + 0.5` is exact in f64, so stepping it by
            // one gives `PlaneEq::eval`'s bits.
            let mut yc = f64::from(b.by) + 0.5;
            // A block is 8 rows of 8: same layout, alignment of `K`.
            let keys = &mut *(keys as *mut [K; 64]).cast::<[[K; 8]; 8]>();
            let ids = &mut *(ids as *mut [u32; 64]).cast::<[[u32; 8]; 8]>();
            for r in 0..8 {
                let ty = b.dy * (yc - b.y0);
                yc += 1.0;
                let new = encode::<K>(col, _mm256_set1_pd(ty));
                // Each row is merged and written back before the next is
                // read: a whole block held in registers until the end
                // spilled about half of them to the stack. The ids are
                // written before the keys, as in `small`: a store right
                // after its own row's load and blend is what LLVM folds
                // into a masked store (see `block8` in `crate::tiled::tile`).
                let (row_keys, row_ids) = (&mut keys[r], &mut ids[r]);
                let old_keys: [u32; 8] = std::array::from_fn(|c| row_keys[c].to_lane());
                let old_keys: __m256i = bytemuck::cast(old_keys);
                let old_ids: __m256i = bytemuck::cast(*row_ids);
                let mut pass = less::<K>(new, old_keys);
                if EDGES {
                    // All ones where the OR of the biased edges is >= 0.
                    let out = _mm256_or_si256(_mm256_or_si256(e[0], e[1]), e[2]);
                    let ok = _mm256_cmpgt_epi32(out, minus_one);
                    pass = _mm256_and_si256(pass, ok);
                    inside = _mm256_sub_epi32(inside, ok);
                    for (e, d) in e.iter_mut().zip(down) {
                        *e = _mm256_add_epi32(*e, d);
                    }
                }
                passes = _mm256_sub_epi32(passes, pass);
                let merged = _mm256_blendv_epi8(old_keys, new, pass);
                greatest = if r == 0 {
                    merged
                } else {
                    max::<K>(greatest, merged)
                };
                *row_ids = bytemuck::cast(_mm256_blendv_epi8(old_ids, prim, pass));
                let k: [u32; 8] = bytemuck::cast(merged);
                for c in 0..8 {
                    row_keys[c] = K::from_lane(k[c]);
                }
            }
            let (inside, passes) = sums(inside, passes);
            let inside = if EDGES { inside } else { 64 };
            let greatest: [u32; 8] = bytemuck::cast(greatest);
            let greatest = greatest.iter().fold(K::from_lane(greatest[0]), |m, &k| {
                m.max_key(K::from_lane(k))
            });
            (inside, passes, greatest)
        }
    }

    /// The lane sums of `a` and of `b` (wrapping, as `i32` sums), with
    /// two horizontal adds for both (a scalar sum of each was about 30
    /// instructions per triangle-tile); `small` shares it.
    #[inline(always)]
    pub(in crate::simd) fn sums(a: __m256i, b: __m256i) -> (u32, u32) {
        // SAFETY: see `super::block8`.
        unsafe {
            let h = _mm256_hadd_epi32(a, b);
            let q = _mm_add_epi32(_mm256_castsi256_si128(h), _mm256_extracti128_si256::<1>(h));
            let s = _mm_hadd_epi32(q, q);
            (
                _mm_cvtsi128_si32(s) as u32,
                _mm_extract_epi32::<1>(s) as u32,
            )
        }
    }
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use super::{Avx2, WideKey};
    use crate::tiled::key::{Fixed24, Reversed};

    /// Depths where an encoding could go wrong: NaN, signed zeros, out of
    /// range, f32 rounding ties and 24-bit rounding ties (half-way between
    /// two steps, where `round` goes away from zero and not to even).
    fn awkward() -> Vec<f64> {
        let max24 = f64::from((1u32 << 24) - 1);
        let mut v = vec![f64::NAN, -0.0, 0.0, 1.0, -1e-300, 1.0 + 1e-16, 2.0, -3.0];
        for k in [0u32, 1, 2, 3, 1000, 4_000_001, (1 << 24) - 2] {
            v.push((f64::from(k) + 0.5) / max24);
            v.push(f64::from(k) / max24);
        }
        for f in [0.1f32, 0.5, 0.7, 0.999_999_9] {
            let d = f64::from(f);
            let up = f64::from(f32::from_bits(f.to_bits() + 1));
            v.extend([
                d,
                (d + up) / 2.0,
                d + (up - d) * 0.499_999,
                d + (up - d) * 0.500_001,
            ]);
        }
        v.extend((0..200).map(|i| f64::from(i) * 0.005_123_456_789));
        v
    }

    /// Every awkward depth drawn over a block cleared to `clear` (the far
    /// key of GL's test, or the blank key of the default one).
    fn check<K: WideKey + std::fmt::Debug>() {
        check_from::<K>(K::FAR);
        check_from::<K>(K::BLANK);
    }

    fn check_from<K: WideKey + std::fmt::Debug>(clear: K) {
        let Some(avx2) = Avx2::detect() else { return };
        let depths = awkward();
        for chunk in depths.chunks(8) {
            // The block's depth is col + ty: the depth in col, and dy = 0
            // so that ty is +0 (which turns a -0 depth into +0, in both).
            let mut col = [0.5; 8];
            col[..chunk.len()].copy_from_slice(chunk);
            let mut keys = [clear; 64];
            let mut ids = [u32::MAX; 64];
            let b = super::Block8 {
                col: &col,
                dy: 0.0,
                y0: 0.0,
                by: 0,
                e: [0; 3],
                lanes: &[[0; 8]; 3],
                keep: [0; 3],
                down: [0; 3],
                prim: 7,
            };
            super::block8::<K, false>(avx2, &mut keys, &mut ids, &b);
            for (c, &d) in col.iter().enumerate() {
                let want = K::encode(d + 0.0);
                let (got, id) = (keys[c], ids[c]);
                if want < clear {
                    assert_eq!(got.to_lane(), want.to_lane(), "{d:e}: {got:?} != {want:?}");
                    assert_eq!(id, 7);
                } else {
                    assert_eq!(got.to_lane(), clear.to_lane(), "{d:e}");
                    assert_eq!(id, u32::MAX);
                }
            }
        }
    }

    #[test]
    fn wide_encodings_are_the_scalar_ones() {
        check::<f32>();
        check::<Reversed>();
        check::<Fixed24>();
    }
}
