//! A small triangle's box in a tile with AVX2, for the depth formats whose
//! key is 32 bits: one 8-lane register per row of each 8x8 block the box
//! meets (the interface, [`SmallBox`], and why: `tiled/wide.rs`).

use hider_geom::isa::Avx2;

use crate::tiled::wide::{SmallBox, WideKey};

/// Draws the box with AVX2 into the tile's block-linear `keys` and `ids`;
/// returns (pixels inside, passes). `#[inline(always)]` for the same
/// reason as [`super::block::block8`], whose proof it shares.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn small_box<K: WideKey>(
    _proof: Avx2,
    keys: &mut [K],
    ids: &mut [u32],
    s: &SmallBox<'_>,
) -> (u32, u32) {
    // Two copies: the column mask costs a few instructions a row, and
    // only tiles cut by the viewport's right edge need it.
    if s.mask_x {
        avx2::small_box::<K, true>(keys, ids, s)
    } else {
        avx2::small_box::<K, false>(keys, ids, s)
    }
}

/// Without x86-64 there is no [`Avx2`] value, so this is never called.
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
pub(crate) fn small_box<K: WideKey>(
    proof: Avx2,
    _: &mut [K],
    _: &mut [u32],
    _: &SmallBox<'_>,
) -> (u32, u32) {
    unreachable!("{proof:?} exists only on x86-64")
}

#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "AVX2 intrinsics, reached only with the Avx2 token that proves the CPU has them"
)]
mod avx2 {
    use std::arch::x86_64::*;

    use hider_geom::PlaneEq;

    use super::super::block::avx2::{encode, less, sums};
    use super::{SmallBox, WideKey};

    /// The depth plane's column terms at four columns `x`,
    /// `value + dx * ((x + 0.5) - x0)` as `PlaneEq::eval` computes them
    /// (`x` is exact in f64). A function, not a closure: a closure would
    /// lack the kernel's target features and call its intrinsics.
    #[inline(always)]
    fn column_terms(p: &PlaneEq, x: __m128i) -> __m256d {
        // SAFETY: see `super::small_box`.
        unsafe {
            let x = _mm256_add_pd(_mm256_cvtepi32_pd(x), _mm256_set1_pd(0.5));
            let x = _mm256_sub_pd(x, _mm256_set1_pd(p.x0));
            _mm256_add_pd(
                _mm256_set1_pd(p.value),
                _mm256_mul_pd(_mm256_set1_pd(p.dx), x),
            )
        }
    }

    #[inline(always)]
    pub(super) fn small_box<K: WideKey, const MASK_X: bool>(
        keys: &mut [K],
        ids: &mut [u32],
        s: &SmallBox<'_>,
    ) -> (u32, u32) {
        // SAFETY: see `super::small_box`: reached only with an `Avx2` proof.
        unsafe {
            let p = s.plane;
            let iota = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
            // Offsets of each edge along a row; wrapping i32 arithmetic is
            // exact here because every value the box takes fits i32 (the
            // caller checked its corners), so sums are right modulo 2^32.
            let mut lanes = [_mm256_setzero_si256(); 3];
            let mut down = [_mm256_setzero_si256(); 3];
            for k in 0..3 {
                lanes[k] = _mm256_mullo_epi32(_mm256_set1_epi32(s.sx[k]), iota);
                down[k] = _mm256_set1_epi32(s.sy[k]);
            }
            let (first, last) = (s.lx0 as i32, s.lx1 as i32);
            let prim = _mm256_set1_epi32(s.prim as i32);
            let minus_one = _mm256_set1_epi32(-1);
            let (mut inside, mut passes) = (_mm256_setzero_si256(), _mm256_setzero_si256());
            let (bc0, bc1) = (s.lx0 / 8, s.lx1 / 8);
            // The box's last row of its last block column ends every
            // access: one bounds check per box instead of two per row
            // (out of range only if a caller broke the tile's geometry).
            let end = ((s.ly1 / 8) as usize * s.per_row + bc1 as usize) * 64
                + (s.ly1 % 8) as usize * 8
                + 8;
            if end > keys.len() || end > ids.len() {
                return (0, 0);
            }
            for bc in bc0..bc1 + 1 {
                let xs = (bc * 8) as i32;
                let xl = _mm256_add_epi32(_mm256_set1_epi32(xs), iota);
                // All ones in the lanes outside the box's columns (x <
                // first or x > last): OR-ed into the edges' sign below, one
                // instruction a row instead of a mask to AND in.
                let off_x = if MASK_X {
                    _mm256_or_si256(
                        _mm256_cmpgt_epi32(_mm256_set1_epi32(first), xl),
                        _mm256_cmpgt_epi32(xl, _mm256_set1_epi32(last)),
                    )
                } else {
                    _mm256_setzero_si256()
                };
                // The column terms `value + dx * ((x + 0.5) - x0)`, as
                // `PlaneEq::eval` computes them (x exact in f64).
                let xa = _mm256_add_epi32(xl, _mm256_set1_epi32(s.tile_x0 as i32));
                let col = (
                    column_terms(p, _mm256_castsi256_si128(xa)),
                    column_terms(p, _mm256_extracti128_si256::<1>(xa)),
                );
                let step = (bc - bc0) as i32 * 8;
                let mut e = [_mm256_setzero_si256(); 3];
                for k in 0..3 {
                    let base = s.e[k].wrapping_add(s.sx[k].wrapping_mul(step));
                    e[k] = _mm256_add_epi32(_mm256_set1_epi32(base), lanes[k]);
                }
                // The row's storage index, stepped: eight on, and to the
                // next block row (less the block's 64) when that lands on
                // a block's start (after its last row), with a select.
                let mut at = ((s.ly0 / 8) as usize * s.per_row + bc as usize) * 64
                    + (s.ly0 % 8) as usize * 8;
                let wrap = s.per_row * 64 - 64;
                // The row's centre `y + 0.5` is exact in f64, so stepping it
                // by one gives `PlaneEq::eval`'s bits.
                let mut yc = f64::from(s.tile_y0 + s.ly0) + 0.5;
                for y in s.ly0..s.ly1 + 1 {
                    let ty = p.dy * (yc - p.y0);
                    let new = encode::<K>(col, _mm256_set1_pd(ty));
                    debug_assert!(
                        at == ((y / 8) as usize * s.per_row + bc as usize) * 64
                            + (y % 8) as usize * 8
                            && at + 8 <= end
                    );
                    // SAFETY: `at + 8 <= end`, checked against both slices
                    // above; `[K; 8]` has the alignment of `K`.
                    let row_keys = &mut *keys.as_mut_ptr().add(at).cast::<[K; 8]>();
                    let row_ids = &mut *ids.as_mut_ptr().add(at).cast::<[u32; 8]>();
                    let old_keys: [u32; 8] = std::array::from_fn(|c| row_keys[c].to_lane());
                    let old_keys: __m256i = bytemuck::cast(old_keys);
                    let old_ids: __m256i = bytemuck::cast(*row_ids);
                    // All ones where the OR of the biased edges is >= 0, in
                    // the box's columns.
                    let mut out = _mm256_or_si256(_mm256_or_si256(e[0], e[1]), e[2]);
                    if MASK_X {
                        out = _mm256_or_si256(out, off_x);
                    }
                    let ok = _mm256_cmpgt_epi32(out, minus_one);
                    let pass = _mm256_and_si256(less::<K>(new, old_keys), ok);
                    inside = _mm256_sub_epi32(inside, ok);
                    passes = _mm256_sub_epi32(passes, pass);
                    let k: [u32; 8] = bytemuck::cast(_mm256_blendv_epi8(old_keys, new, pass));
                    *row_ids = bytemuck::cast(_mm256_blendv_epi8(old_ids, prim, pass));
                    for c in 0..8 {
                        row_keys[c] = K::from_lane(k[c]);
                    }
                    for k in 0..3 {
                        e[k] = _mm256_add_epi32(e[k], down[k]);
                    }
                    let next = at + 8;
                    at = if next.is_multiple_of(64) {
                        next + wrap
                    } else {
                        next
                    };
                    yc += 1.0;
                }
            }
            sums(inside, passes)
        }
    }
}
