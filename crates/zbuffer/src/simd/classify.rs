//! The triangle pass's classification of eight triangles
//! ([`Lanes::classify`]) written with AVX2 intrinsics.
//!
//! The portable classification is written lane by lane and left to the
//! compiler, which keeps much of it scalar: about 100 instructions a
//! triangle on the 500-sphere, a third of the front end. Here the eight
//! triangles are one register per coordinate, and every quantity the
//! scalar code computes in `i64` (the area, the edge functions at the box's
//! first centre and their steps) is computed exactly in two registers of
//! four `i64` lanes, one for the even triangles and one for the odd ones:
//! `vpmuldq` multiplies the low 32 bits of each 64-bit lane as signed
//! integers, so the 8-lane `i32` differences multiply into exact 64-bit
//! products without any unpacking.
//!
//! It is the same integer arithmetic as the scalar definition, so it gives
//! the same bits; the lean front end's property tests (against
//! the brute-force definition) run it on every machine with AVX2.

use hider_geom::FEW_CENTRES;
use hider_geom::isa::Avx2;

use crate::depth_scene::classify::{LANES, Lanes, Setups};

// The centre tests below are written out for the first four centres.
const _: () = assert!(FEW_CENTRES == 4);

/// Classifies the batch; see [`Lanes::classify`]. The [`Avx2`] argument is
/// the proof the intrinsics need: the function is `#[inline(always)]` into
/// the pass compiled for AVX2, and its intrinsics are called in `unsafe`
/// blocks (one of the project's `unsafe` sites) because without that
/// proof the CPU might lack them.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn classify(
    _proof: Avx2,
    x: &[[i32; LANES]; 3],
    y: &[[i32; LANES]; 3],
    (width, height): (u32, u32),
    cull: bool,
) -> Lanes {
    avx2::classify(x, y, (width, height), cull)
}

/// The small-box set-ups ([`SmallSetup`](crate::depth_scene::SmallSetup))
/// of the lanes in `want` (kept as triangles), the corners put in
/// positive order by `swap` ([`Lanes::swap`]): for each, `SmallSetup::new`
/// or none (zero lanes of [`Setups`]).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn setups(
    _proof: Avx2,
    x: &[[i32; LANES]; 3],
    y: &[[i32; LANES]; 3],
    size: (u32, u32),
    (swap, want): (u8, u8),
) -> Setups {
    avx2::setups(x, y, size, (swap, want))
}

/// Without x86-64 there is no [`Avx2`] value, so this is never called.
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
pub(crate) fn setups(
    proof: Avx2,
    _: &[[i32; LANES]; 3],
    _: &[[i32; LANES]; 3],
    _: (u32, u32),
    _: (u8, u8),
) -> Setups {
    unreachable!("{proof:?} exists only on x86-64")
}

/// Without x86-64 there is no [`Avx2`] value, so this is never called.
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
pub(crate) fn classify(
    proof: Avx2,
    _: &[[i32; LANES]; 3],
    _: &[[i32; LANES]; 3],
    _: (u32, u32),
    _: bool,
) -> Lanes {
    unreachable!("{proof:?} exists only on x86-64")
}

#[cfg(target_arch = "x86_64")]
#[allow(
    unsafe_code,
    reason = "AVX2 intrinsics, reached only with the Avx2 token that proves the CPU has them"
)]
mod avx2 {
    use std::arch::x86_64::*;

    use hider_geom::edge::top_left_biases;
    use hider_geom::fixed::{SUBPIXEL_SCALE, first_centers_from, last_centers_upto, pixel_centers};

    use super::{FEW_CENTRES, LANES, Lanes, Setups};
    use crate::tiled::SMALL_AREA;

    /// An `i64` quantity of the eight lanes: lanes 0, 2, 4, 6 and lanes 1,
    /// 3, 5, 7.
    #[derive(Clone, Copy)]
    struct Wide {
        even: __m256i,
        odd: __m256i,
    }

    // SAFETY (every `unsafe` block of this module): reached only through
    // `super::classify`, whose `Avx2` argument proves the CPU has AVX2.

    /// The exact products of eight pairs of `i32`.
    #[inline(always)]
    fn mul(a: __m256i, b: __m256i) -> Wide {
        unsafe {
            Wide {
                even: _mm256_mul_epi32(a, b),
                odd: _mm256_mul_epi32(_mm256_srli_epi64::<32>(a), _mm256_srli_epi64::<32>(b)),
            }
        }
    }

    #[inline(always)]
    fn add(a: Wide, b: Wide) -> Wide {
        unsafe {
            Wide {
                even: _mm256_add_epi64(a.even, b.even),
                odd: _mm256_add_epi64(a.odd, b.odd),
            }
        }
    }

    #[inline(always)]
    fn sub(a: Wide, b: Wide) -> Wide {
        unsafe {
            Wide {
                even: _mm256_sub_epi64(a.even, b.even),
                odd: _mm256_sub_epi64(a.odd, b.odd),
            }
        }
    }

    /// `a > b` per lane, as an 8-lane `i32` mask.
    #[inline(always)]
    fn greater(a: Wide, b: Wide) -> __m256i {
        unsafe {
            // A 64-bit mask has both halves set: the even lanes' masks
            // fill the even 32-bit positions, the odd lanes' the odd ones.
            _mm256_blend_epi32::<0b1010_1010>(
                _mm256_cmpgt_epi64(a.even, b.even),
                _mm256_cmpgt_epi64(a.odd, b.odd),
            )
        }
    }

    /// `a == b` per lane, as an 8-lane `i32` mask.
    #[inline(always)]
    fn equal(a: Wide, b: Wide) -> __m256i {
        unsafe {
            _mm256_blend_epi32::<0b1010_1010>(
                _mm256_cmpeq_epi64(a.even, b.even),
                _mm256_cmpeq_epi64(a.odd, b.odd),
            )
        }
    }

    /// An 8-lane `i32` mask as the even and odd 64-bit masks.
    #[inline(always)]
    fn widen_mask(m: __m256i) -> Wide {
        unsafe {
            Wide {
                even: _mm256_shuffle_epi32::<0b10_10_00_00>(m),
                odd: _mm256_shuffle_epi32::<0b11_11_01_01>(m),
            }
        }
    }

    /// `if m { a } else { b }` per lane, `m` from [`widen_mask`].
    #[inline(always)]
    fn select(m: Wide, a: Wide, b: Wide) -> Wide {
        unsafe {
            Wide {
                even: _mm256_blendv_epi8(b.even, a.even, m.even),
                odd: _mm256_blendv_epi8(b.odd, a.odd, m.odd),
            }
        }
    }

    /// The 8 lanes of an `i32` mask as bits.
    #[inline(always)]
    fn bits(m: __m256i) -> u8 {
        unsafe { _mm256_movemask_ps(_mm256_castsi256_ps(m)) as u8 }
    }

    /// The eight `i32` lanes of a register as an array, for hider-geom's
    /// lane-wise helpers: a bit cast (a register move), and the helpers'
    /// loops compile to the matching vector instructions.
    #[inline(always)]
    fn array(v: __m256i) -> [i32; LANES] {
        bytemuck::cast(v)
    }

    /// The first pixel column (or row) whose centre is not left of (above)
    /// the least of three coordinates ([`first_centers_from`]).
    #[inline(always)]
    fn lo(a: __m256i, b: __m256i, c: __m256i) -> __m256i {
        let m = unsafe { _mm256_min_epi32(_mm256_min_epi32(a, b), c) };
        bytemuck::cast(first_centers_from(array(m)))
    }

    /// The last pixel column (or row) whose centre is not right of (below)
    /// the greatest of three coordinates ([`last_centers_upto`]).
    #[inline(always)]
    fn hi(a: __m256i, b: __m256i, c: __m256i) -> __m256i {
        let m = unsafe { _mm256_max_epi32(_mm256_max_epi32(a, b), c) };
        bytemuck::cast(last_centers_upto(array(m)))
    }

    #[inline(always)]
    fn load(v: &[i32; LANES]) -> __m256i {
        bytemuck::cast(*v)
    }

    /// The corners of the eight triangles, one register per coordinate.
    #[derive(Clone, Copy)]
    struct Corners {
        ax: __m256i,
        ay: __m256i,
        bx: __m256i,
        by: __m256i,
        cx: __m256i,
        cy: __m256i,
    }

    /// The pixel boxes, as `pixel_bounds` computes them: first column and
    /// row, columns and rows (zero or negative when empty).
    #[inline(always)]
    fn pixel_box(c: &Corners, (width, height): (u32, u32)) -> [__m256i; 4] {
        unsafe {
            let zero32 = _mm256_setzero_si256();
            let x0 = _mm256_max_epi32(lo(c.ax, c.bx, c.cx), zero32);
            let y0 = _mm256_max_epi32(lo(c.ay, c.by, c.cy), zero32);
            let x1 = _mm256_min_epi32(hi(c.ax, c.bx, c.cx), _mm256_set1_epi32(width as i32 - 1));
            let y1 = _mm256_min_epi32(hi(c.ay, c.by, c.cy), _mm256_set1_epi32(height as i32 - 1));
            let one32 = _mm256_set1_epi32(1);
            let cols = _mm256_add_epi32(_mm256_sub_epi32(x1, x0), one32);
            let rows = _mm256_add_epi32(_mm256_sub_epi32(y1, y0), one32);
            [x0, y0, cols, rows]
        }
    }

    /// Per lane, bit `j` set where the box's `j`-th centre (row-major, of
    /// the first [`FEW_CENTRES`]) exists and is inside all three edges of
    /// the positively ordered corners `c`; `px`, `py` the box's first
    /// centre (fixed point), `cols` its width, `count` its number of
    /// centres.
    #[inline(always)]
    fn covered(c: &Corners, [px, py, cols, count]: [__m256i; 4]) -> __m256i {
        unsafe {
            let zero32 = _mm256_setzero_si256();
            let zero = Wide {
                even: zero32,
                odd: zero32,
            };
            let one32 = _mm256_set1_epi32(1);
            // The box's first centres, row-major, as sums of steps picked
            // by the box's width (see the portable `centre_hits`).
            let one = widen_mask(_mm256_cmpeq_epi32(cols, one32));
            let two = widen_mask(_mm256_cmpeq_epi32(cols, _mm256_set1_epi32(2)));
            let mut hit = [_mm256_set1_epi32(-1); FEW_CENTRES];
            let edges = [
                (c.ax, c.ay, c.bx, c.by),
                (c.bx, c.by, c.cx, c.cy),
                (c.cx, c.cy, c.ax, c.ay),
            ];
            for (fx, fy, tx, ty) in edges {
                let (dx, dy) = (_mm256_sub_epi32(tx, fx), _mm256_sub_epi32(ty, fy));
                // The fill rule's bias, widened to 64 bits.
                let bias = mul(bytemuck::cast(top_left_biases(array(dx), array(dy))), one32);
                let at = add(
                    sub(
                        mul(dx, _mm256_sub_epi32(py, fy)),
                        mul(dy, _mm256_sub_epi32(px, fx)),
                    ),
                    bias,
                );
                let sx = mul(dy, _mm256_set1_epi32(-SUBPIXEL_SCALE));
                let sy = mul(dx, _mm256_set1_epi32(SUBPIXEL_SCALE));
                let (sx2, sy2) = (add(sx, sx), add(sy, sy));
                let offsets = [
                    select(one, sy, sx),
                    select(one, sy2, select(two, sy, sx2)),
                    select(one, add(sy2, sy), select(two, add(sx, sy), add(sx2, sx))),
                ];
                hit[0] = _mm256_and_si256(hit[0], greater(at, zero));
                for (h, o) in hit[1..].iter_mut().zip(offsets) {
                    *h = _mm256_and_si256(*h, greater(add(at, o), zero));
                }
            }
            centre_bits(&hit, count)
        }
    }

    /// [`covered`] in `i32` lanes, or `None` when a lane of `tested` has a
    /// corner 2^14 or more fixed-point units (64 pixels) from its box's
    /// first centre in x or y. Otherwise every quantity of those lanes fits
    /// `i32` exactly: each edge's extent is below 2^15, each distance from
    /// a corner to the first centre below 2^14, so each product is below
    /// 2^29 and an edge value below 2^30 + 1; the steps to the next three
    /// centres add less than 3 * 2^23. A box of at most [`FEW_CENTRES`]
    /// centres lies within 5 pixels of its corners unless it is clamped to
    /// the image, so only triangles across the image's border take the
    /// `i64` path. The other lanes' bits are meaningless.
    #[inline(always)]
    fn covered_narrow(
        c: &Corners,
        [px, py, cols, count]: [__m256i; 4],
        tested: __m256i,
    ) -> Option<__m256i> {
        unsafe {
            let limit = _mm256_set1_epi32((1 << 14) - 1);
            let mut far = _mm256_setzero_si256();
            for (v, p) in [
                (c.ax, px),
                (c.bx, px),
                (c.cx, px),
                (c.ay, py),
                (c.by, py),
                (c.cy, py),
            ] {
                let d = _mm256_abs_epi32(_mm256_sub_epi32(v, p));
                far = _mm256_or_si256(far, _mm256_cmpgt_epi32(d, limit));
            }
            if _mm256_testz_si256(far, tested) == 0 {
                return None;
            }
            let zero = _mm256_setzero_si256();
            let one32 = _mm256_set1_epi32(1);
            let one = _mm256_cmpeq_epi32(cols, one32);
            let two = _mm256_cmpeq_epi32(cols, _mm256_set1_epi32(2));
            let select = |m: __m256i, a: __m256i, b: __m256i| _mm256_blendv_epi8(b, a, m);
            let mut hit = [_mm256_set1_epi32(-1); FEW_CENTRES];
            let edges = [
                (c.ax, c.ay, c.bx, c.by),
                (c.bx, c.by, c.cx, c.cy),
                (c.cx, c.cy, c.ax, c.ay),
            ];
            for (fx, fy, tx, ty) in edges {
                let (dx, dy) = (_mm256_sub_epi32(tx, fx), _mm256_sub_epi32(ty, fy));
                let bias: __m256i = bytemuck::cast(top_left_biases(array(dx), array(dy)));
                let at = _mm256_add_epi32(
                    _mm256_sub_epi32(
                        _mm256_mullo_epi32(dx, _mm256_sub_epi32(py, fy)),
                        _mm256_mullo_epi32(dy, _mm256_sub_epi32(px, fx)),
                    ),
                    bias,
                );
                // The steps, as in `covered`: -dy and dx times 256.
                let sx = _mm256_sub_epi32(zero, _mm256_slli_epi32::<8>(dy));
                let sy = _mm256_slli_epi32::<8>(dx);
                let (sx2, sy2) = (_mm256_add_epi32(sx, sx), _mm256_add_epi32(sy, sy));
                let offsets = [
                    select(one, sy, sx),
                    select(one, sy2, select(two, sy, sx2)),
                    select(
                        one,
                        _mm256_add_epi32(sy2, sy),
                        select(two, _mm256_add_epi32(sx, sy), _mm256_add_epi32(sx2, sx)),
                    ),
                ];
                hit[0] = _mm256_and_si256(hit[0], _mm256_cmpgt_epi32(at, zero));
                for (h, o) in hit[1..].iter_mut().zip(offsets) {
                    let v = _mm256_add_epi32(at, o);
                    *h = _mm256_and_si256(*h, _mm256_cmpgt_epi32(v, zero));
                }
            }
            Some(centre_bits(&hit, count))
        }
    }

    /// The covered bits from the hits of the first centres: bit `j` where
    /// centre `j` exists (`count > j`) and is hit.
    #[inline(always)]
    fn centre_bits(hit: &[__m256i; FEW_CENTRES], count: __m256i) -> __m256i {
        unsafe {
            let mut covered = _mm256_setzero_si256();
            for (j, h) in hit.iter().enumerate() {
                let within = _mm256_cmpgt_epi32(count, _mm256_set1_epi32(j as i32));
                let bit = _mm256_and_si256(_mm256_and_si256(*h, within), _mm256_set1_epi32(1 << j));
                covered = _mm256_or_si256(covered, bit);
            }
            covered
        }
    }

    /// A lane mask from the bits of `m`.
    #[inline(always)]
    fn lanes_of(m: u8) -> __m256i {
        unsafe {
            _mm256_cmpgt_epi32(
                _mm256_and_si256(
                    _mm256_set1_epi32(i32::from(m)),
                    _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128),
                ),
                _mm256_setzero_si256(),
            )
        }
    }

    /// See [`super::setups`]. A set-up needs the corners inside the image,
    /// and then every product fits `i32` (see
    /// [`SmallSetup`](crate::depth_scene::SmallSetup)): eight lanes of
    /// `i32`, no widening.
    #[inline(always)]
    pub(super) fn setups(
        x: &[[i32; LANES]; 3],
        y: &[[i32; LANES]; 3],
        (width, height): (u32, u32),
        (swap, want): (u8, u8),
    ) -> Setups {
        unsafe {
            let mut c = Corners {
                ax: load(&x[0]),
                ay: load(&y[0]),
                bx: load(&x[1]),
                by: load(&y[1]),
                cx: load(&x[2]),
                cy: load(&y[2]),
            };
            let neg = lanes_of(swap);
            (c.bx, c.by, c.cx, c.cy) = (
                _mm256_blendv_epi8(c.bx, c.cx, neg),
                _mm256_blendv_epi8(c.by, c.cy, neg),
                _mm256_blendv_epi8(c.cx, c.bx, neg),
                _mm256_blendv_epi8(c.cy, c.by, neg),
            );
            let [x0, y0, cols, rows] = pixel_box(&c, (width, height));
            let count = _mm256_mullo_epi32(cols, rows);
            let one32 = _mm256_set1_epi32(1);
            let x1 = _mm256_sub_epi32(_mm256_add_epi32(x0, cols), one32);
            let y1 = _mm256_sub_epi32(_mm256_add_epi32(y0, rows), one32);
            // The first block column.
            let xs = _mm256_andnot_si256(_mm256_set1_epi32(7), x0);
            let px: __m256i = bytemuck::cast(pixel_centers(array(xs)));
            let py: __m256i = bytemuck::cast(pixel_centers(array(y0)));
            let want_lanes = lanes_of(want);
            let small = _mm256_cmpgt_epi32(_mm256_set1_epi32(SMALL_AREA as i32 + 1), count);
            // Corners in [0, width) x [0, height), fixed point.
            let zero = _mm256_setzero_si256();
            let (xmax, ymax) = (
                _mm256_set1_epi32(width as i32 * SUBPIXEL_SCALE - 1),
                _mm256_set1_epi32(height as i32 * SUBPIXEL_SCALE - 1),
            );
            let mut out = _mm256_setzero_si256();
            for (x, y) in [(c.ax, c.ay), (c.bx, c.by), (c.cx, c.cy)] {
                out = _mm256_or_si256(out, _mm256_cmpgt_epi32(zero, x));
                out = _mm256_or_si256(out, _mm256_cmpgt_epi32(zero, y));
                out = _mm256_or_si256(out, _mm256_cmpgt_epi32(x, xmax));
                out = _mm256_or_si256(out, _mm256_cmpgt_epi32(y, ymax));
            }
            let ok = _mm256_andnot_si256(out, _mm256_and_si256(small, want_lanes));
            let edges = [
                (c.ax, c.ay, c.bx, c.by),
                (c.bx, c.by, c.cx, c.cy),
                (c.cx, c.cy, c.ax, c.ay),
            ];
            let mut e = [[0i32; LANES]; 3];
            for (k, (fx, fy, tx, ty)) in edges.into_iter().enumerate() {
                let (dx, dy) = (_mm256_sub_epi32(tx, fx), _mm256_sub_epi32(ty, fy));
                // The fill rule's bias less one.
                let bias: __m256i = bytemuck::cast(top_left_biases(array(dx), array(dy)));
                let at = _mm256_sub_epi32(
                    _mm256_mullo_epi32(dx, _mm256_sub_epi32(py, fy)),
                    _mm256_mullo_epi32(dy, _mm256_sub_epi32(px, fx)),
                );
                let at = _mm256_add_epi32(at, _mm256_sub_epi32(bias, one32));
                e[k] = bytemuck::cast(_mm256_and_si256(at, ok));
            }
            // The box's words (see `Setups`), those of no set-up where
            // there is none.
            let word = |x: __m256i, y: __m256i| _mm256_or_si256(x, _mm256_slli_epi32::<16>(y));
            let [none_lo, none_hi] = Setups::NONE_BBOX.map(|w| _mm256_set1_epi32(w));
            Setups {
                bbox: [
                    bytemuck::cast(_mm256_blendv_epi8(none_lo, word(x0, y0), ok)),
                    bytemuck::cast(_mm256_blendv_epi8(none_hi, word(x1, y1), ok)),
                ],
                e,
            }
        }
    }

    #[inline(always)]
    pub(super) fn classify(
        x: &[[i32; LANES]; 3],
        y: &[[i32; LANES]; 3],
        size: (u32, u32),
        cull: bool,
    ) -> Lanes {
        unsafe {
            let zero32 = _mm256_setzero_si256();
            let zero = Wide {
                even: zero32,
                odd: zero32,
            };
            let mut c = Corners {
                ax: load(&x[0]),
                ay: load(&y[0]),
                bx: load(&x[1]),
                by: load(&y[1]),
                cx: load(&x[2]),
                cy: load(&y[2]),
            };
            let area = sub(
                mul(_mm256_sub_epi32(c.bx, c.ax), _mm256_sub_epi32(c.cy, c.ay)),
                mul(_mm256_sub_epi32(c.by, c.ay), _mm256_sub_epi32(c.cx, c.ax)),
            );
            let [x0, y0, cols, rows] = pixel_box(&c, size);
            let count = _mm256_mullo_epi32(cols, rows);
            // Positive order.
            let neg = greater(zero, area);
            (c.bx, c.by, c.cx, c.cy) = (
                _mm256_blendv_epi8(c.bx, c.cx, neg),
                _mm256_blendv_epi8(c.by, c.cy, neg),
                _mm256_blendv_epi8(c.cx, c.bx, neg),
                _mm256_blendv_epi8(c.cy, c.by, neg),
            );
            let one32 = _mm256_set1_epi32(1);
            let few = _mm256_cmpgt_epi32(_mm256_set1_epi32(FEW_CENTRES as i32 + 1), count);
            // The centres matter in the lanes of few of them and a box that
            // is not empty: in `i32` when every such lane allows it.
            let tested = _mm256_andnot_si256(
                _mm256_or_si256(
                    _mm256_cmpgt_epi32(one32, cols),
                    _mm256_cmpgt_epi32(one32, rows),
                ),
                few,
            );
            let px: __m256i = bytemuck::cast(pixel_centers(array(x0)));
            let py: __m256i = bytemuck::cast(pixel_centers(array(y0)));
            let centres = [px, py, cols, count];
            let covered = match covered_narrow(&c, centres, tested) {
                Some(covered) => covered,
                None => covered(&c, centres),
            };
            let covered = _mm256_and_si256(covered, tested);
            let empty = _mm256_or_si256(
                _mm256_or_si256(
                    _mm256_cmpgt_epi32(one32, cols),
                    _mm256_cmpgt_epi32(one32, rows),
                ),
                _mm256_and_si256(few, _mm256_cmpeq_epi32(covered, zero32)),
            );
            let covered: [i32; LANES] = bytemuck::cast(covered);
            let (x0, y0, cols): ([i32; LANES], [i32; LANES], [i32; LANES]) =
                (bytemuck::cast(x0), bytemuck::cast(y0), bytemuck::cast(cols));
            let back = if cull { bits(greater(area, zero)) } else { 0 };
            let mut lanes = Lanes {
                degenerate: 0,
                back_faces: 0,
                empty: 0,
                keep: 0,
                swap: bits(neg),
                few: bits(few),
                covered: covered.map(|c| c as u8),
                corner: std::array::from_fn(|i| (x0[i] as u32, y0[i] as u32, cols[i] as u32)),
            };
            lanes.drop_reasons(bits(equal(area, zero)), back, bits(empty));
            lanes
        }
    }
}

#[cfg(test)]
mod tests;
