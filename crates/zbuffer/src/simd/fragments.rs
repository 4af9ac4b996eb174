//! The fragments of a batch's lanes whose box holds a few centres, the
//! depths of a lane's four centres in one `f64` register.
//!
//! One by one, each covered centre paid for converting its pixel, the
//! plane's evaluation and a checked push (about 30 instructions a
//! fragment, more on the 499k-triangle sphere than its triangles). Here a
//! lane's first [`FEW_CENTRES`] centres are evaluated together, with the
//! same IEEE operations in the same order as [`PlaneEq::at_pixel`]
//! (separate multiplications and additions, never fused), so each depth
//! has its bits; the records are built in registers and a covered centre
//! costs one 16-byte store into the vector's spare capacity.

use hider_geom::FEW_CENTRES;
use hider_geom::isa::Avx2;

use super::emit::Batch;
use crate::depth_scene::DepthFragment;
use crate::depth_scene::classify::LANES;

// A fragment's record: the depth, then the pixel's column and row, then
// the primitive id (`DepthFragment` is `repr(C)`).
const _: () = assert!(
    std::mem::offset_of!(DepthFragment, depth) == 0
        && std::mem::offset_of!(DepthFragment, x) == 8
        && std::mem::offset_of!(DepthFragment, y) == 10
        && std::mem::offset_of!(DepthFragment, prim) == 12
        && std::mem::size_of::<DepthFragment>() == 16
        && FEW_CENTRES == 4
);

/// The lanes of a batch whose box holds a few centres (bits of `lanes`):
/// each box's first pixel and width, and its covered centres
/// ([`Lanes::corner`](crate::depth_scene::classify::Lanes::corner),
/// [`Lanes::covered`](crate::depth_scene::classify::Lanes::covered)).
#[cfg_attr(
    not(target_arch = "x86_64"),
    expect(dead_code, reason = "read only by the x86-64 AVX2 code")
)]
pub(crate) struct Small<'a> {
    pub(crate) lanes: u8,
    pub(crate) corner: &'a [(u32, u32, u32); LANES],
    pub(crate) covered: &'a [u8; LANES],
}

/// Appends, for each lane of `small.lanes` in order, the fragments of its
/// covered centres in order: lane `i`'s box starts at pixel
/// `(corner[i].0, corner[i].1)` and is `corner[i].2` centres wide (at most
/// [`FEW_CENTRES`]), bit `j` of `covered[i]` says centre `j` (row-major)
/// is covered, and its fragment is `DepthFragment { depth:
/// planes.get(i, z0[i]).at_pixel(x, y), x, y, prim: first_prim + i }`.
/// The [`Avx2`] argument is the proof the intrinsics need (see
/// [`super::classify::classify`]).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn push(
    _proof: Avx2,
    batch: &Batch<'_>,
    small: &Small<'_>,
    out: &mut Vec<DepthFragment>,
) {
    avx2::push(batch, small, out);
}

/// Without x86-64 there is no [`Avx2`] value, so this is never called.
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
pub(crate) fn push(proof: Avx2, _: &Batch<'_>, _: &Small<'_>, _: &mut Vec<DepthFragment>) {
    unreachable!("{proof:?} exists only on x86-64")
}

#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "AVX2 intrinsics, reached only with the Avx2 token that proves the CPU has them, and records written into reserved capacity"
)]
mod avx2 {
    use std::arch::x86_64::*;

    use super::{Batch, DepthFragment, FEW_CENTRES, Small};
    use crate::depth_scene::classify::CENTRE_AT;

    // SAFETY (every `unsafe` block of this module, but for the writes,
    // which say why they are sound): reached only through `super::push`,
    // whose `Avx2` argument proves the CPU has AVX2.

    /// See [`super::push`].
    #[inline(always)]
    pub(super) fn push(b: &Batch<'_>, small: &Small<'_>, out: &mut Vec<DepthFragment>) {
        let Small {
            lanes,
            corner,
            covered,
        } = *small;
        unsafe {
            let n = FEW_CENTRES * lanes.count_ones() as usize;
            out.reserve(n);
            let base = out.spare_capacity_mut().as_mut_ptr();
            let mut written = 0;
            let half = _mm256_set1_pd(0.5);
            let mut lanes = lanes;
            while lanes != 0 {
                let i = lanes.trailing_zeros() as usize;
                lanes &= lanes - 1;
                let (x0, y0, w) = corner[i];
                let [cols, rows] = &CENTRE_AT[(w as usize).min(FEW_CENTRES)];
                // The centres' pixels (below 2^14), then `at_pixel`:
                // `f64::from(x) + 0.5`, and `value + dx * (x - x0) + dy *
                // (y - y0)` from left to right.
                let xs = _mm_add_epi32(
                    _mm_set1_epi32(x0 as i32),
                    _mm_loadu_si128(cols.as_ptr().cast()),
                );
                let ys = _mm_add_epi32(
                    _mm_set1_epi32(y0 as i32),
                    _mm_loadu_si128(rows.as_ptr().cast()),
                );
                let px = _mm256_add_pd(_mm256_cvtepi32_pd(xs), half);
                let py = _mm256_add_pd(_mm256_cvtepi32_pd(ys), half);
                let p = b.planes.get(i, b.z0[i]);
                let depth = _mm256_add_pd(
                    _mm256_add_pd(
                        _mm256_set1_pd(p.value),
                        _mm256_mul_pd(
                            _mm256_set1_pd(p.dx),
                            _mm256_sub_pd(px, _mm256_set1_pd(p.x0)),
                        ),
                    ),
                    _mm256_mul_pd(
                        _mm256_set1_pd(p.dy),
                        _mm256_sub_pd(py, _mm256_set1_pd(p.y0)),
                    ),
                );
                // Each centre's second half: column and row as `u16`s,
                // then the primitive id.
                let pixel = _mm_or_si128(xs, _mm_slli_epi32::<16>(ys));
                let prim = _mm_set1_epi32(b.first_prim.wrapping_add(i as u32) as i32);
                let ids = _mm256_castsi256_pd(_mm256_set_m128i(
                    _mm_unpackhi_epi32(pixel, prim),
                    _mm_unpacklo_epi32(pixel, prim),
                ));
                // Centres 0 | 2 and 1 | 3, then in order.
                let (even, odd) = (
                    _mm256_unpacklo_pd(depth, ids),
                    _mm256_unpackhi_pd(depth, ids),
                );
                let records: [[f64; 2]; FEW_CENTRES] = bytemuck::cast([
                    _mm256_permute2f128_pd::<0x20>(even, odd),
                    _mm256_permute2f128_pd::<0x31>(even, odd),
                ]);
                let mut bits = covered[i];
                while bits != 0 {
                    let j = bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    // SAFETY: at most FEW_CENTRES bits a lane, so fewer
                    // than the `n` records reserved above; an unaligned
                    // write of the record's 16 bytes (its fields' offsets
                    // checked at compile time).
                    base.add(written)
                        .cast::<[f64; 2]>()
                        .write_unaligned(records[j]);
                    written += 1;
                }
            }
            // SAFETY: the `written` records after the old length are
            // written.
            out.set_len(out.len() + written);
        }
    }
}

#[cfg(test)]
mod tests {
    use hider_geom::FEW_CENTRES;
    use hider_geom::isa::Avx2;
    use proptest::prelude::*;

    use super::LANES;
    use crate::depth_scene::DepthFragment;
    use crate::depth_scene::classify::CENTRE_AT;
    use crate::simd::emit::Batch;
    use crate::simd::plane::planes;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1000))]

        /// The fragments are those of `PlaneEq::at_pixel` at the covered
        /// centres, in lane and centre order, bit for bit.
        #[test]
        fn fragments_are_at_pixel(
            c in proptest::array::uniform8(proptest::array::uniform3((
                (0i32..16384 * 256, 0i32..16384 * 256),
                0.0f64..=1.0,
            ))),
            boxes in proptest::array::uniform8((0u32..16380, 0u32..16380, 1u32..=4, any::<u8>())),
            swap in any::<u8>(),
            lanes in any::<u8>(),
            first_prim in any::<u32>(),
        ) {
            let Some(avx2) = Avx2::detect() else { return Ok(()) };
            let (x, y, z) = crate::simd::plane::tests::lanes_of(&c);
            let corner = boxes.map(|(x0, y0, w, _)| (x0, y0, w));
            // Only the centres of a box of at most four.
            let covered = boxes.map(|(_, _, w, bits)| bits & ((1 << (FEW_CENTRES as u32 / w * w)) - 1));
            let p = planes(avx2, &x, &y, &z, (swap, 0xff));
            let batch = Batch {
                x: &x,
                y: &y,
                z0: &z[0],
                swap,
                planes: &p,
                setups: None,
                first_prim,
            };
            let old = DepthFragment { prim: 7, ..DepthFragment::default() };
            let mut got = vec![old];
            let small = super::Small { lanes, corner: &corner, covered: &covered };
            super::push(avx2, &batch, &small, &mut got);
            let mut want = vec![old];
            for i in (0..LANES).filter(|i| lanes >> i & 1 != 0) {
                let (x0, y0, w) = corner[i];
                let [cols, rows] = CENTRE_AT[w as usize];
                let plane = p.get(i, z[0][i]);
                for j in (0..FEW_CENTRES).filter(|j| covered[i] >> j & 1 != 0) {
                    let (px, py) = (x0 + cols[j] as u32, y0 + rows[j] as u32);
                    want.push(DepthFragment {
                        depth: plane.at_pixel(px, py),
                        x: px as u16,
                        y: py as u16,
                        prim: first_prim.wrapping_add(i as u32),
                    });
                }
            }
            prop_assert_eq!(got.len(), want.len());
            for (g, w) in got.iter().zip(&want) {
                // Near-collinear corners may make a plane that is not
                // finite: any NaN then (the payload is the hardware's).
                let same = g.depth.to_bits() == w.depth.to_bits()
                    || (g.depth.is_nan() && w.depth.is_nan());
                prop_assert!(same, "{:?} against {:?}", g, w);
                prop_assert_eq!((g.x, g.y, g.prim), (w.x, w.y, w.prim));
            }
        }
    }
}
