//! The depth planes of a batch's eight triangles
//! ([`PlaneEq::from_points`]) in four-lane `f64` registers.
//!
//! One by one, a kept triangle's plane is a chain of dependent scalar
//! operations ending in two divisions, and on the 79,600-triangle sphere,
//! where most lanes of a batch are kept, the divisions' latency was the
//! hottest spot of the triangle pass. Here the lanes 0-3 and 4-7 are one
//! register each: the same IEEE operations in the same order per lane
//! (separate multiplications and subtractions, never fused), so every lane
//! gets the bits `from_points` gives. The one rewrite is `to_pixels`'
//! division by 256 as a multiplication by 1/256: both are exact for every
//! `i32` (a power of two, no underflow), so they are the same value.

use hider_geom::PlaneEq;
use hider_geom::isa::Avx2;

use crate::depth_scene::classify::LANES;

/// The depth planes of a batch, structure of arrays; a lane not asked
/// for holds whatever its corners gave (possibly not finite).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Planes {
    pub(crate) x0: [f64; LANES],
    pub(crate) y0: [f64; LANES],
    pub(crate) dx: [f64; LANES],
    pub(crate) dy: [f64; LANES],
}

impl Planes {
    /// Lane `i`'s plane, its value at the reference point the lane's first
    /// depth `z0`.
    #[cfg_attr(
        not(target_arch = "x86_64"),
        expect(dead_code, reason = "read only by the x86-64 AVX2 code")
    )]
    #[inline(always)]
    pub(crate) fn get(&self, i: usize, z0: f64) -> PlaneEq {
        PlaneEq {
            x0: self.x0[i],
            y0: self.y0[i],
            value: z0,
            dx: self.dx[i],
            dy: self.dy[i],
        }
    }
}

/// The planes of the lanes in `want` through the corners `x`, `y` (fixed
/// point) with depths `z`, the last two corners swapped in the lanes of
/// `swap` ([`Lanes::swap`](crate::depth_scene::classify::Lanes::swap)):
/// for each such lane whose corners are not collinear, the
/// [`PlaneEq::from_points`] of corners 0, 1, 2 (0, 2, 1 when swapped).
/// The [`Avx2`] argument is the proof the intrinsics need (see
/// [`super::classify::classify`]).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn planes(
    _proof: Avx2,
    x: &[[i32; LANES]; 3],
    y: &[[i32; LANES]; 3],
    z: &[[f64; LANES]; 3],
    (swap, want): (u8, u8),
) -> Planes {
    avx2::planes(x, y, z, (swap, want))
}

/// Without x86-64 there is no [`Avx2`] value, so this is never called.
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
pub(crate) fn planes(
    proof: Avx2,
    _: &[[i32; LANES]; 3],
    _: &[[i32; LANES]; 3],
    _: &[[f64; LANES]; 3],
    _: (u8, u8),
) -> Planes {
    unreachable!("{proof:?} exists only on x86-64")
}

#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "AVX2 intrinsics, reached only with the Avx2 token that proves the CPU has them"
)]
mod avx2 {
    use std::arch::x86_64::*;

    use hider_geom::fixed::SUBPIXEL_SCALE;

    use super::{LANES, Planes};

    // SAFETY (every `unsafe` block of this module): reached only through
    // `super::planes`, whose `Avx2` argument proves the CPU has AVX2.

    /// Four lanes of an `i32` array as `f64` pixels: `to_pixels`.
    #[inline(always)]
    fn pixels(v: &[i32; LANES], half: usize) -> __m256d {
        unsafe {
            let q = _mm_loadu_si128(v[half * 4..].as_ptr().cast());
            // Exactly `f64::from(q) / 256` (see the module's note).
            _mm256_mul_pd(
                _mm256_cvtepi32_pd(q),
                _mm256_set1_pd(1.0 / f64::from(SUBPIXEL_SCALE)),
            )
        }
    }

    #[inline(always)]
    fn load(v: &[f64; LANES], half: usize) -> __m256d {
        unsafe { _mm256_loadu_pd(v[half * 4..].as_ptr()) }
    }

    #[inline(always)]
    fn store(to: &mut [f64; LANES], half: usize, v: __m256d) {
        unsafe { _mm256_storeu_pd(to[half * 4..].as_mut_ptr(), v) }
    }

    /// Lanes `4 * half .. 4 * half + 4`.
    #[inline(always)]
    fn half(
        x: &[[i32; LANES]; 3],
        y: &[[i32; LANES]; 3],
        z: &[[f64; LANES]; 3],
        swap: u8,
        h: usize,
        out: &mut Planes,
    ) {
        unsafe {
            let bits = i64::from(swap >> (4 * h));
            let neg = _mm256_castsi256_pd(_mm256_cmpgt_epi64(
                _mm256_and_si256(_mm256_set1_epi64x(bits), _mm256_setr_epi64x(1, 2, 4, 8)),
                _mm256_setzero_si256(),
            ));
            let pick =
                |a: __m256d, b: __m256d| (_mm256_blendv_pd(a, b, neg), _mm256_blendv_pd(b, a, neg));
            let (x0, y0) = (pixels(&x[0], h), pixels(&y[0], h));
            let (xb, xc) = pick(pixels(&x[1], h), pixels(&x[2], h));
            let (yb, yc) = pick(pixels(&y[1], h), pixels(&y[2], h));
            let (zb, zc) = pick(load(&z[1], h), load(&z[2], h));
            let z0 = load(&z[0], h);
            // `PlaneEq::from_points`, operation for operation.
            let (x1, y1) = (_mm256_sub_pd(xb, x0), _mm256_sub_pd(yb, y0));
            let (x2, y2) = (_mm256_sub_pd(xc, x0), _mm256_sub_pd(yc, y0));
            let det = _mm256_sub_pd(_mm256_mul_pd(x1, y2), _mm256_mul_pd(x2, y1));
            let d1 = _mm256_sub_pd(zb, z0);
            let d2 = _mm256_sub_pd(zc, z0);
            let dx = _mm256_div_pd(
                _mm256_sub_pd(_mm256_mul_pd(d1, y2), _mm256_mul_pd(d2, y1)),
                det,
            );
            let dy = _mm256_div_pd(
                _mm256_sub_pd(_mm256_mul_pd(x1, d2), _mm256_mul_pd(x2, d1)),
                det,
            );
            store(&mut out.x0, h, x0);
            store(&mut out.y0, h, y0);
            store(&mut out.dx, h, dx);
            store(&mut out.dy, h, dy);
        }
    }

    /// See [`super::planes`]: a half of the batch with no lane wanted is
    /// skipped.
    #[inline(always)]
    pub(super) fn planes(
        x: &[[i32; LANES]; 3],
        y: &[[i32; LANES]; 3],
        z: &[[f64; LANES]; 3],
        (swap, want): (u8, u8),
    ) -> Planes {
        let mut out = Planes::default();
        for h in 0..2 {
            if want >> (4 * h) & 0xf != 0 {
                half(x, y, z, swap, h, &mut out);
            }
        }
        out
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use hider_geom::isa::Avx2;
    use hider_geom::{FixedPt, PlaneEq};
    use proptest::prelude::*;

    use super::LANES;

    /// One value per corner (the outer array) and triangle (the lanes).
    pub(crate) type PerCorner<T> = [[T; LANES]; 3];

    /// A batch's corners (a fixed-point position and a depth each, three
    /// per triangle) as the gather leaves them: structure of arrays, one
    /// array per corner, one lane per triangle.
    pub(crate) fn lanes_of(
        c: &[[((i32, i32), f64); 3]; LANES],
    ) -> (PerCorner<i32>, PerCorner<i32>, PerCorner<f64>) {
        let (mut x, mut y, mut z) = ([[0; LANES]; 3], [[0; LANES]; 3], [[0.0; LANES]; 3]);
        for (i, tri) in c.iter().enumerate() {
            for (k, &((cx, cy), cz)) in tri.iter().enumerate() {
                (x[k][i], y[k][i], z[k][i]) = (cx, cy, cz);
            }
        }
        (x, y, z)
    }

    /// Corners of a batch: near one another (small triangles, as most
    /// are), or anywhere in the snappable range.
    fn corner() -> impl Strategy<Value = (i32, i32)> {
        const LIMIT: i32 = 1 << 23;
        prop_oneof![
            (-LIMIT..LIMIT, -LIMIT..LIMIT),
            (256 * 500..256 * 520, 256 * 300..256 * 304),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        /// Every wanted lane's plane has the bits of
        /// `PlaneEq::from_points` on its corners in the lane's order.
        #[test]
        fn planes_are_from_points(
            c in proptest::array::uniform8(proptest::array::uniform3((corner(), 0.0f64..=1.0))),
            swap in any::<u8>(),
            want in any::<u8>(),
        ) {
            let Some(avx2) = Avx2::detect() else { return Ok(()) };
            let (x, y, z) = lanes_of(&c);
            let got = super::planes(avx2, &x, &y, &z, (swap, want));
            for i in (0..LANES).filter(|i| want >> i & 1 != 0) {
                let order = if swap >> i & 1 != 0 { [0, 2, 1] } else { [0, 1, 2] };
                let v = order.map(|k| FixedPt::new(x[k][i], y[k][i]));
                let Some(p) = PlaneEq::from_points(&v, order.map(|k| z[k][i])) else {
                    continue;
                };
                let q = got.get(i, z[0][i]);
                let bits = |p: PlaneEq| [p.x0, p.y0, p.value, p.dx, p.dy].map(f64::to_bits);
                prop_assert_eq!(bits(q), bits(p), "lane {}", i);
            }
        }
    }
}
