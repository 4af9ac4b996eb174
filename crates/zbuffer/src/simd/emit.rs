//! The triangles a batch keeps, written into the run as [`DepthTri`]s
//! eight lanes at a time.
//!
//! Assembled lane by lane, a [`DepthTri`] is 22 fields gathered from the
//! batch's structure of arrays (corners in positive order, plane, primitive
//! id, small-box set-up) and stored one by one, and the compiler spilled
//! most of them on the way: about 60 instructions a triangle on the
//! 79,600-triangle sphere, where two thirds of the triangles are kept as
//! triangles. Here the arrays are transposed in registers (`unpack`
//! shuffles, a few per batch) into each lane's 16- and 8-byte pieces of
//! the record, and a kept lane costs seven loads and seven stores, into
//! the vector's spare capacity.
//!
//! The values are the ones the lane-by-lane code stores (the same arrays,
//! moved, never computed again), and the triangle pass's tests compare
//! the output with the one-by-one definition; this module's test compares
//! the records with the fields they are made of.

use hider_geom::isa::Avx2;
use hider_geom::{FixedPt, PlaneEq};

use super::plane::Planes;
use crate::depth_scene::DepthTri;
use crate::depth_scene::SmallSetup;
use crate::depth_scene::classify::{LANES, Setups};

/// What a batch's records are made of: the corners as gathered, the lanes
/// whose last two corners are swapped for positive order, the planes
/// (their values the first corners' depths), the set-ups (none in every
/// lane when absent) and the batch's first primitive id.
#[cfg_attr(
    not(target_arch = "x86_64"),
    expect(dead_code, reason = "read only by the x86-64 AVX2 code")
)]
pub(crate) struct Batch<'a> {
    pub(crate) x: &'a [[i32; LANES]; 3],
    pub(crate) y: &'a [[i32; LANES]; 3],
    pub(crate) z0: &'a [f64; LANES],
    pub(crate) swap: u8,
    pub(crate) planes: &'a Planes,
    pub(crate) setups: Option<&'a Setups>,
    pub(crate) first_prim: u32,
}

// The record's pieces, by their byte offsets: the three corners, the
// plane, then the primitive id and the set-up (`DepthTri` and
// `SmallSetup` are `repr(C)`; these check the fields of hider-geom's
// types too).
const V: usize = std::mem::offset_of!(DepthTri, v);
const DEPTH: usize = std::mem::offset_of!(DepthTri, depth);
const PRIM: usize = std::mem::offset_of!(DepthTri, prim);
const SETUP: usize = std::mem::offset_of!(DepthTri, setup);
const _: () = assert!(
    V == 0
        && std::mem::size_of::<FixedPt>() == 8
        && std::mem::offset_of!(FixedPt, x) == 0
        && std::mem::offset_of!(FixedPt, y) == 4
        && DEPTH == 24
        && std::mem::offset_of!(PlaneEq, x0) == 0
        && std::mem::offset_of!(PlaneEq, y0) == 8
        && std::mem::offset_of!(PlaneEq, value) == 16
        && std::mem::offset_of!(PlaneEq, dx) == 24
        && std::mem::offset_of!(PlaneEq, dy) == 32
        && PRIM == 64
        && SETUP == 68
        && std::mem::offset_of!(SmallSetup, bbox) == 0
        && std::mem::offset_of!(SmallSetup, e) == 8
        && std::mem::size_of::<DepthTri>() == 88
);

/// Appends the triangles of the lanes in `want`, in lane order, to `tris`:
/// lane `i`'s record is `DepthTri { v: corners 0, 1, 2 (0, 2, 1 when
/// swapped), depth: planes.get(i, z0[i]), prim: first_prim + i, setup }`.
/// The [`Avx2`] argument is the proof the intrinsics need (see
/// [`super::classify::classify`]).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn push(_proof: Avx2, batch: &Batch<'_>, want: u8, tris: &mut Vec<DepthTri>) {
    avx2::push(batch, want, tris);
}

/// Without x86-64 there is no [`Avx2`] value, so this is never called.
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
pub(crate) fn push(proof: Avx2, _: &Batch<'_>, _: u8, _: &mut Vec<DepthTri>) {
    unreachable!("{proof:?} exists only on x86-64")
}

#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "AVX2 intrinsics, reached only with the Avx2 token that proves the CPU has them, and records written into reserved capacity"
)]
mod avx2 {
    use std::arch::x86_64::*;

    use super::{Batch, DEPTH, DepthTri, LANES, PRIM, SETUP, Setups, V};

    // SAFETY (every `unsafe` block of this module, but for the writes,
    // which say why they are sound): reached only through `super::push`,
    // whose `Avx2` argument proves the CPU has AVX2.

    #[inline(always)]
    fn load(v: &[i32; LANES]) -> __m256i {
        bytemuck::cast(*v)
    }

    /// Four rows of eight lanes as each lane's four words.
    #[inline(always)]
    fn quads([r0, r1, r2, r3]: [__m256i; 4]) -> [[i32; 4]; LANES] {
        unsafe {
            // Lanes 0, 1 | 4, 5 and 2, 3 | 6, 7 of rows 0, 1 and 2, 3 ...
            let (t0, t1) = (_mm256_unpacklo_epi32(r0, r1), _mm256_unpackhi_epi32(r0, r1));
            let (t2, t3) = (_mm256_unpacklo_epi32(r2, r3), _mm256_unpackhi_epi32(r2, r3));
            // ... then lanes 0 | 4, 1 | 5, 2 | 6, 3 | 7 of all four ...
            let (u0, u1) = (_mm256_unpacklo_epi64(t0, t2), _mm256_unpackhi_epi64(t0, t2));
            let (u2, u3) = (_mm256_unpacklo_epi64(t1, t3), _mm256_unpackhi_epi64(t1, t3));
            // ... then in lane order, so that a lane's index is its place
            // (no index arithmetic per kept lane).
            bytemuck::cast([
                _mm256_permute2x128_si256::<0x20>(u0, u1),
                _mm256_permute2x128_si256::<0x20>(u2, u3),
                _mm256_permute2x128_si256::<0x31>(u0, u1),
                _mm256_permute2x128_si256::<0x31>(u2, u3),
            ])
        }
    }

    /// Two rows of eight lanes as each lane's two words.
    #[inline(always)]
    fn pairs(r0: __m256i, r1: __m256i) -> [[i32; 2]; LANES] {
        unsafe {
            // Lanes 0, 1 | 4, 5 and 2, 3 | 6, 7, then in lane order.
            let (t0, t1) = (_mm256_unpacklo_epi32(r0, r1), _mm256_unpackhi_epi32(r0, r1));
            bytemuck::cast([
                _mm256_permute2x128_si256::<0x20>(t0, t1),
                _mm256_permute2x128_si256::<0x31>(t0, t1),
            ])
        }
    }

    /// Two rows of `f64` lanes as each lane's two values.
    #[inline(always)]
    fn doubles(r0: &[f64; LANES], r1: &[f64; LANES]) -> [[f64; 2]; LANES] {
        unsafe {
            let half = |h: usize| {
                let (a, b) = (
                    _mm256_loadu_pd(r0[4 * h..].as_ptr()),
                    _mm256_loadu_pd(r1[4 * h..].as_ptr()),
                );
                // Lanes 0 | 2 and 1 | 3 of the half, then in lane order.
                let (lo, hi) = (_mm256_unpacklo_pd(a, b), _mm256_unpackhi_pd(a, b));
                [
                    _mm256_permute2f128_pd::<0x20>(lo, hi),
                    _mm256_permute2f128_pd::<0x31>(lo, hi),
                ]
            };
            let ([a, b], [c, d]) = (half(0), half(1));
            bytemuck::cast([a, b, c, d])
        }
    }

    /// See [`super::push`].
    #[inline(always)]
    pub(super) fn push(b: &Batch<'_>, want: u8, tris: &mut Vec<DepthTri>) {
        unsafe {
            let neg = _mm256_cmpgt_epi32(
                _mm256_and_si256(
                    _mm256_set1_epi32(i32::from(b.swap)),
                    _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128),
                ),
                _mm256_setzero_si256(),
            );
            let (x1, x2, y1, y2) = (load(&b.x[1]), load(&b.x[2]), load(&b.y[1]), load(&b.y[2]));
            let (xb, xc) = (
                _mm256_blendv_epi8(x1, x2, neg),
                _mm256_blendv_epi8(x2, x1, neg),
            );
            let (yb, yc) = (
                _mm256_blendv_epi8(y1, y2, neg),
                _mm256_blendv_epi8(y2, y1, neg),
            );
            let corners = quads([load(&b.x[0]), load(&b.y[0]), xb, yb]);
            let last = pairs(xc, yc);
            let prim = _mm256_add_epi32(
                _mm256_set1_epi32(b.first_prim as i32),
                _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7),
            );
            let (lo, hi, e) = match b.setups {
                Some(s) => (load(&s.bbox[0]), load(&s.bbox[1]), s.e.map(|e| load(&e))),
                None => {
                    let [lo, hi] = Setups::NONE_BBOX.map(|w| _mm256_set1_epi32(w));
                    (lo, hi, [_mm256_setzero_si256(); 3])
                }
            };
            let ids = quads([prim, lo, hi, e[0]]);
            let edges = pairs(e[1], e[2]);
            let p = b.planes;
            let origin = doubles(&p.x0, &p.y0);
            let slope = doubles(b.z0, &p.dx);
            let n = want.count_ones() as usize;
            tris.reserve(n);
            let base = tris.spare_capacity_mut().as_mut_ptr().cast::<u8>();
            let mut want = want;
            let mut at = base;
            while want != 0 {
                let i = want.trailing_zeros() as usize;
                want &= want - 1;
                // SAFETY: `at` is the start of one of the `n` records
                // reserved above, and each write stays within it (the
                // offsets are the fields', checked at compile time).
                // Unaligned writes: no alignment is assumed.
                at.add(V).cast::<[i32; 4]>().write_unaligned(corners[i]);
                at.add(V + 16).cast::<[i32; 2]>().write_unaligned(last[i]);
                at.add(DEPTH).cast::<[f64; 2]>().write_unaligned(origin[i]);
                at.add(DEPTH + 16)
                    .cast::<[f64; 2]>()
                    .write_unaligned(slope[i]);
                at.add(DEPTH + 32).cast::<f64>().write_unaligned(p.dy[i]);
                at.add(PRIM).cast::<[i32; 4]>().write_unaligned(ids[i]);
                at.add(SETUP + 12)
                    .cast::<[i32; 2]>()
                    .write_unaligned(edges[i]);
                at = at.add(std::mem::size_of::<DepthTri>());
            }
            // SAFETY: the `n` records after the old length are written.
            tris.set_len(tris.len() + n);
        }
    }
}

#[cfg(test)]
mod tests {
    use hider_geom::isa::Avx2;
    use hider_geom::{FixedPt, PlaneEq};
    use proptest::prelude::*;

    use super::{Batch, LANES};
    use crate::depth_scene::DepthTri;
    use crate::depth_scene::classify::Setups;
    use crate::simd::plane::planes;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(1000))]

        /// Each wanted lane's record holds the lane's fields, bit for
        /// bit, appended after what the vector held.
        #[test]
        fn records_hold_the_lanes_fields(
            c in proptest::array::uniform8(proptest::array::uniform3((
                (-(1i32 << 23)..1 << 23, -(1i32 << 23)..1 << 23),
                0.0f64..=1.0,
            ))),
            swap in any::<u8>(),
            want in any::<u8>(),
            raw in proptest::array::uniform8((any::<u16>(), any::<u16>(), any::<[i32; 3]>())),
            with_setups: bool,
            first_prim in any::<u32>(),
            before in 0usize..3,
        ) {
            let Some(avx2) = Avx2::detect() else { return Ok(()) };
            let (x, y, z) = crate::simd::plane::tests::lanes_of(&c);
            let setups = Setups {
                bbox: [
                    raw.map(|(a, b, _)| i32::from(a) | i32::from(b) << 16),
                    raw.map(|(a, b, _)| i32::from(b) | i32::from(a) << 16),
                ],
                e: std::array::from_fn(|k| raw.map(|(_, _, e)| e[k])),
            };
            let p = planes(avx2, &x, &y, &z, (swap, 0xff));
            let batch = Batch {
                x: &x,
                y: &y,
                z0: &z[0],
                swap,
                planes: &p,
                setups: with_setups.then_some(&setups),
                first_prim,
            };
            let old = DepthTri { prim: 7, ..DepthTri::default() };
            let mut tris = vec![old; before];
            super::push(avx2, &batch, want, &mut tris);
            prop_assert_eq!(tris.len(), before + want.count_ones() as usize);
            let bits = |p: PlaneEq| [p.x0, p.y0, p.value, p.dx, p.dy].map(f64::to_bits);
            for t in &tris[..before] {
                prop_assert_eq!(t.prim, 7);
            }
            let lanes = (0..LANES).filter(|i| want >> i & 1 != 0);
            for (t, i) in tris[before..].iter().zip(lanes) {
                let order = if swap >> i & 1 != 0 { [0, 2, 1] } else { [0, 1, 2] };
                prop_assert_eq!(t.v, order.map(|k| FixedPt::new(x[k][i], y[k][i])));
                prop_assert_eq!(bits(t.depth), bits(p.get(i, z[0][i])));
                prop_assert_eq!(t.prim, first_prim.wrapping_add(i as u32));
                let setup = if with_setups { setups.get(i) } else { crate::depth_scene::SmallSetup::NONE };
                prop_assert_eq!(t.setup, setup, "lane {}", i);
            }
        }
    }
}
