//! The read-back of f32 tiles with AVX2: eight pixels of a tile row at a
//! time into the frame's ids and depths (the portable resolve, in
//! `crate::tiled::tile`, is scalar per pixel: about ten instructions a
//! pixel against one here).

use hider_geom::isa::Avx2;

/// Writes the ids (if `IDS`) and window depths (if `DEPTH`) of eight
/// pixels with f32 keys: [`NO_ID`](hider_scene::NO_ID) and depth 1 where
/// the key equals `clear` (nothing was written), the id and the key
/// itself (an f32 key is its window depth) elsewhere. The comparison is
/// IEEE equality, as the portable resolve's `==`.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn resolve8<const IDS: bool, const DEPTH: bool>(
    _proof: Avx2,
    keys: &[f32; 8],
    ids: &[u32; 8],
    clear: f32,
    out_ids: &mut [u32; 8],
    out_depth: &mut [f32; 8],
) {
    avx2::resolve8::<IDS, DEPTH>(keys, ids, clear, out_ids, out_depth);
}

/// Without x86-64 there is no [`Avx2`] value, so this is never called.
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
pub(crate) fn resolve8<const IDS: bool, const DEPTH: bool>(
    proof: Avx2,
    _: &[f32; 8],
    _: &[u32; 8],
    _: f32,
    _: &mut [u32; 8],
    _: &mut [f32; 8],
) {
    unreachable!("{proof:?} exists only on x86-64")
}

#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "AVX2 intrinsics, reached only with the Avx2 token that proves the CPU has them"
)]
mod avx2 {
    use std::arch::x86_64::*;

    #[inline(always)]
    pub(super) fn resolve8<const IDS: bool, const DEPTH: bool>(
        keys: &[f32; 8],
        ids: &[u32; 8],
        clear: f32,
        out_ids: &mut [u32; 8],
        out_depth: &mut [f32; 8],
    ) {
        // SAFETY: see `super::resolve8`: reached only with an `Avx2`
        // proof; the loads and stores are of whole `[_; 8]` arrays.
        unsafe {
            let k = _mm256_loadu_ps(keys.as_ptr());
            let blank = _mm256_cmp_ps::<_CMP_EQ_OQ>(k, _mm256_set1_ps(clear));
            if IDS {
                let i = _mm256_loadu_si256(ids.as_ptr().cast());
                // NO_ID is all ones: OR the blank mask in.
                let i = _mm256_or_si256(i, _mm256_castps_si256(blank));
                _mm256_storeu_si256(out_ids.as_mut_ptr().cast(), i);
            }
            if DEPTH {
                let d = _mm256_blendv_ps(k, _mm256_set1_ps(1.0), blank);
                _mm256_storeu_ps(out_depth.as_mut_ptr(), d);
            }
        }
    }
}

#[cfg(all(test, target_arch = "x86_64"))]
mod tests {
    use hider_scene::NO_ID;

    use super::Avx2;

    /// Every pattern of blank and written lanes, with keys next to the
    /// clear key (its neighbours, the other zero, infinities), against
    /// the scalar rule.
    #[test]
    fn wide_resolve_is_the_scalar_one() {
        let Some(avx2) = Avx2::detect() else { return };
        for clear in [1.0f32, f32::INFINITY, -0.0] {
            let near = [
                clear,
                f32::from_bits(clear.to_bits().wrapping_add(1)),
                f32::from_bits(clear.to_bits().wrapping_sub(1)),
                -clear,
                0.0,
                0.5,
                f32::NEG_INFINITY,
                1e-40,
            ];
            for pattern in 0u32..256 {
                let keys: [f32; 8] = std::array::from_fn(|c| {
                    if pattern >> c & 1 == 1 {
                        clear
                    } else {
                        near[c]
                    }
                });
                let ids: [u32; 8] = std::array::from_fn(|c| 10 + c as u32);
                let (mut out_ids, mut out_depth) = ([0u32; 8], [0f32; 8]);
                super::resolve8::<true, true>(
                    avx2,
                    &keys,
                    &ids,
                    clear,
                    &mut out_ids,
                    &mut out_depth,
                );
                for c in 0..8 {
                    let blank = keys[c] == clear;
                    assert_eq!(out_ids[c], if blank { NO_ID } else { ids[c] });
                    let want = if blank { 1.0 } else { keys[c] };
                    assert_eq!(
                        out_depth[c].to_bits(),
                        want.to_bits(),
                        "{clear} {:?}",
                        keys[c]
                    );
                }
            }
        }
    }
}
