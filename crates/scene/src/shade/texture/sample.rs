//! Sampling one mip level: the texel containing a point (nearest) or the
//! weighted mean of the four nearest texels (bilinear), repeating or
//! clamped to the edge.
//!
//! Bilinear is the path every textured pixel takes, so it is written to be
//! short: each coordinate is wrapped once (not each corner, and without a
//! remainder, which is a division), `floor` is two additions of a
//! constant (not a library call, nor a conversion to an integer and back),
//! the four texels are read with one bounds check each, the
//! alpha channel is looked for once per sample, and colour and alpha are
//! lerped in four lanes. The numbers are the plain formula's, bit for bit
//! (tested against it below).

use super::super::mip::Level;
use super::{Filter, linear_table};

impl Level {
    /// The linear colour and the alpha (in [0, 1], 1 without an alpha
    /// channel) at texture coordinates `(u, v)` (OBJ convention), filtered
    /// with `filter`, repeating or clamped (`clamp`, MTL's `-clamp on`).
    /// Non-finite coordinates give the first texel.
    #[inline(always)]
    pub(crate) fn sample(&self, u: f64, v: f64, filter: Filter, clamp: bool) -> ([f32; 3], f32) {
        let rgb = linear_table();
        // The texel closures are forced inline (as is this function):
        // inlined into a caller with the rest of the fetch, they were
        // left as calls otherwise.
        #[inline(always)]
        fn linear(texels: &[[u8; 3]], rgb: &[f32; 256], k: usize) -> [f32; 3] {
            let c = texels[k];
            [
                rgb[usize::from(c[0])],
                rgb[usize::from(c[1])],
                rgb[usize::from(c[2])],
            ]
        }
        let texels = &self.rgb[..];
        // The alpha channel is looked for once, not per texel; without
        // one, the alpha lane is 1 at every corner (its lerp is exactly 1).
        let c = match self.alpha.as_deref() {
            None => self.filtered(
                u,
                v,
                filter,
                clamp,
                #[inline(always)]
                |k| {
                    let [r, g, b] = linear(texels, rgb, k);
                    [r, g, b, 1.0]
                },
            ),
            Some(a) => {
                let alphas = alpha_table();
                self.filtered(
                    u,
                    v,
                    filter,
                    clamp,
                    #[inline(always)]
                    |k| {
                        let [r, g, b] = linear(texels, rgb, k);
                        [r, g, b, alphas[usize::from(a[k])]]
                    },
                )
            }
        };
        ([c[0], c[1], c[2]], c[3])
    }

    /// [`Self::sample`]'s alpha alone (the same number), without reading
    /// the colour: what the alpha test needs.
    #[inline(always)]
    pub(crate) fn sample_alpha(&self, u: f64, v: f64, filter: Filter, clamp: bool) -> f32 {
        match self.alpha.as_deref() {
            None => 1.0,
            Some(a) => {
                let alphas = alpha_table();
                self.filtered(u, v, filter, clamp, |k| [alphas[usize::from(a[k])]])[0]
            }
        }
    }

    /// The lanes `texel` reads (texel `k`'s values) at `(u, v)`, filtered
    /// with `filter`, repeating or clamped; the first texel's where a
    /// coordinate is not finite.
    #[inline(always)]
    fn filtered<const N: usize>(
        &self,
        u: f64,
        v: f64,
        filter: Filter,
        clamp: bool,
        texel: impl Fn(usize) -> [f32; N],
    ) -> [f32; N] {
        // Texel space: x right, y down from the top row; centres at +0.5.
        // Repeating, a coordinate in [0, 1) is its own (the usual case: no
        // floor and no test of finiteness on the way to the texel);
        // `u - floor(u)` is `rem_euclid(u, 1)` bit for bit (both round the
        // exact fraction once), without a call to `fmod`.
        let unit = |t: f64| (0.0..1.0).contains(&t);
        let (u, v) = if !clamp && unit(u) && unit(v) {
            if let Filter::Bilinear = filter {
                // The corners' texel coordinates (less one half) are then
                // in [-0.5, width) and (-0.5, height): their floor is a
                // truncation, one less below zero.
                let x = u * f64::from(self.width);
                let y = (1.0 - v) * f64::from(self.height);
                return self.bilinear(floor_small(x - 0.5), floor_small(y - 0.5), false, texel);
            }
            (u, v)
        } else if !(u.is_finite() && v.is_finite()) {
            return texel(index(self, 0, 0, true));
        } else if clamp {
            (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0))
        } else {
            (u - floor(u).0, v - floor(v).0)
        };
        let x = u * f64::from(self.width);
        let y = (1.0 - v) * f64::from(self.height);
        match filter {
            // Clamped, u = 1 is the last texel's far edge (the texel look-up
            // clamps it); repeating, it is the next repeat's start.
            Filter::Nearest => {
                let (x, y) = (x.floor() as i64, y.floor() as i64);
                texel(index(self, x, y, clamp))
            }
            Filter::Bilinear => {
                let (fx, fy) = (x - 0.5, y - 0.5);
                let ((x0, i), (y0, j)) = (floor(fx), floor(fy));
                self.bilinear((fx - x0, i), (fy - y0, j), clamp, texel)
            }
        }
    }

    /// The bilinear mean of the texels around a point whose texel-space
    /// coordinates (less one half) are `i + tx` and `j + ty` (`i`, `j`
    /// integers, `tx`, `ty` in [0, 1)), the columns and rows wrapped or
    /// clamped.
    #[inline(always)]
    fn bilinear<const N: usize>(
        &self,
        (tx, i): (f64, i64),
        (ty, j): (f64, i64),
        clamp: bool,
        texel: impl Fn(usize) -> [f32; N],
    ) -> [f32; N] {
        let (tx, ty) = (tx as f32, ty as f32);
        // The two columns and rows, wrapped once each.
        let (xa, xb) = neighbours(i, self.width, clamp);
        let (ya, yb) = neighbours(j, self.height, clamp);
        let w = self.width as usize;
        let (top, bottom) = (ya * w, yb * w);
        let q = [
            texel(top + xa),
            texel(top + xb),
            texel(bottom + xa),
            texel(bottom + xb),
        ];
        // A plain loop, not `array::from_fn`: inlined into a caller that
        // inlines the whole fetch, `from_fn` was left as a call.
        let mut out = [0.0; N];
        for (k, out) in out.iter_mut().enumerate() {
            let top = q[0][k] + (q[1][k] - q[0][k]) * tx;
            let bottom = q[2][k] + (q[3][k] - q[2][k]) * tx;
            *out = top + (bottom - top) * ty;
        }
        out
    }
}

/// `a / 255` of every alpha byte (the alpha is data, not sRGB-decoded).
#[inline]
fn alpha_table() -> &'static [f32; 256] {
    static TABLE: std::sync::OnceLock<[f32; 256]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| std::array::from_fn(|a| a as f32 / 255.0))
}

/// `x.floor()` of a finite `x`, and as an integer (saturating as `as`
/// does). Below 2^51 in magnitude, `x + 1.5 * 2^52` rounds `x` to the
/// nearest integer, held in its low mantissa bits; one less where that
/// rounded up (`f64::floor` is a library call without SSE 4.1, and a
/// conversion to an integer and back is longer).
#[inline]
pub(super) fn floor(x: f64) -> (f64, i64) {
    const MAGIC: f64 = 6_755_399_441_055_744.0;
    if x.abs() < 2_251_799_813_685_248.0 {
        let s = x + MAGIC;
        let r = s - MAGIC;
        // All ones where the rounding went up (`x - r` is exact), from
        // the sign bit: a branch would be mispredicted, as
        // rounding goes up at random across a texture.
        // (`+ 0.0` makes a -0 +0, whose floor is 0.)
        let up = ((x + 0.0 - r).to_bits() as i64 >> 63) as u64;
        let n = s.to_bits() as i64 - MAGIC.to_bits() as i64 + up as i64;
        (r - f64::from_bits(up & 1f64.to_bits()), n)
    } else {
        let f = x.floor();
        (f, f as i64)
    }
}

/// The fraction of `x` (`x - floor(x)`) and its floor as an integer, for
/// `x` in (-1, 2^31): truncation is the floor at and above zero, one more
/// than it below (the same numbers as [`floor`], without its magic
/// constant's three extra additions and the sign-bit games).
#[inline(always)]
fn floor_small(x: f64) -> (f64, i64) {
    let i = x as i64 - i64::from(x < 0.0);
    (x - i as f64, i)
}

/// Texel column (or row) `i` and `i + 1` of a side of `n` texels, clamped
/// to its edge or repeated, as [`index`] finds them.
#[inline(always)]
fn neighbours(i: i64, n: u32, clamp: bool) -> (usize, usize) {
    let n = i64::from(n);
    if clamp {
        (i.clamp(0, n - 1) as usize, (i + 1).clamp(0, n - 1) as usize)
    } else {
        // A wrapped coordinate's column is in [-1, n - 1]: no division
        // (a remainder is one) but far outside it.
        let a = if (0..n).contains(&i) {
            i
        } else if (-n..0).contains(&i) {
            i + n
        } else {
            i.rem_euclid(n)
        };
        (a as usize, if a + 1 == n { 0 } else { a as usize + 1 })
    }
}

/// The texel index of `(x, y)` in `l`, clamped to its edge or repeated.
#[inline]
fn index(l: &Level, x: i64, y: i64, clamp: bool) -> usize {
    let (w, h) = (i64::from(l.width), i64::from(l.height));
    let (x, y) = if clamp {
        (x.clamp(0, w - 1) as usize, y.clamp(0, h - 1) as usize)
    } else {
        (x.rem_euclid(w) as usize, y.rem_euclid(h) as usize)
    };
    y * l.width as usize + x
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shade::texture::srgb_to_linear;

    /// The plain formula: each corner wrapped by its own remainder, the
    /// floor from the library, the texels decoded by `powf`, one channel
    /// at a time.
    fn reference(l: &Level, u: f64, v: f64, clamp: bool) -> ([f32; 3], f32) {
        let (u, v) = if clamp {
            (u.clamp(0.0, 1.0), v.clamp(0.0, 1.0))
        } else {
            (u.rem_euclid(1.0), v.rem_euclid(1.0))
        };
        let fx = u * f64::from(l.width) - 0.5;
        let fy = (1.0 - v) * f64::from(l.height) - 0.5;
        let (x0, y0) = (fx.floor(), fy.floor());
        let (tx, ty) = ((fx - x0) as f32, (fy - y0) as f32);
        let at = |dx: i64, dy: i64| index(l, x0 as i64 + dx, y0 as i64 + dy, clamp);
        let k = [at(0, 0), at(1, 0), at(0, 1), at(1, 1)];
        let lerp = |q: [f32; 4]| {
            let top = q[0] + (q[1] - q[0]) * tx;
            let bottom = q[2] + (q[3] - q[2]) * tx;
            top + (bottom - top) * ty
        };
        let rgb = std::array::from_fn(|c| lerp(k.map(|k| srgb_to_linear(l.rgb[k][c]))));
        let alpha = match &l.alpha {
            Some(a) => lerp(k.map(|k| f32::from(a[k]) / 255.0)),
            None => 1.0,
        };
        (rgb, alpha)
    }

    /// The short path is the formula's, bit for bit: odd and even sizes,
    /// with and without alpha, repeating and clamped, coordinates far
    /// outside [0, 1], negative, at texel centres and edges. Fails with a
    /// floor off by one (the magic constant wrong) or a corner wrapped
    /// the wrong way.
    #[test]
    fn bilinear_is_the_formula_bit_for_bit() {
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let mut checked = 0;
        for (w, h) in [(1, 1), (2, 2), (5, 3), (64, 7), (257, 130)] {
            let n = (w * h) as usize;
            let rgb: Vec<u8> = (0..3 * n).map(|_| next() as u8).collect();
            let alpha: Vec<u8> = (0..n).map(|_| next() as u8).collect();
            for alpha in [None, Some(alpha)] {
                let l = Level {
                    width: w,
                    height: h,
                    rgb: rgb.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect(),
                    alpha,
                };
                let mut coords: Vec<(f64, f64)> = (0..4000)
                    .map(|_| {
                        let r = |k: u64| (k >> 11) as f64 / (1u64 << 53) as f64;
                        (r(next()) * 6.0 - 3.0, r(next()) * 6.0 - 3.0)
                    })
                    .collect();
                // Texel centres and edges, exact integers, tiny negatives,
                // large repeats.
                for k in -3..=2 * w as i32 + 3 {
                    let t = f64::from(k) / (2.0 * f64::from(w));
                    coords.extend([(t, 0.5), (t, t), (-1e-20, t), (t, 1.0)]);
                }
                coords.extend([(1e6 + 0.3, -1e7 - 0.7), (1e17, 3.5), (-0.0, -0.0)]);
                for clamp in [false, true] {
                    for &(u, v) in &coords {
                        let got = l.sample(u, v, Filter::Bilinear, clamp);
                        let want = reference(&l, u, v, clamp);
                        let bits = |(c, a): ([f32; 3], f32)| (c.map(f32::to_bits), a.to_bits());
                        assert_eq!(bits(got), bits(want), "{w}x{h} ({u}, {v}) {clamp}");
                        let alpha = l.sample_alpha(u, v, Filter::Bilinear, clamp);
                        assert_eq!(alpha.to_bits(), want.1.to_bits(), "{w}x{h} ({u}, {v})");
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 80_000, "{checked}");
    }

    #[test]
    fn floor_is_the_library_floor() {
        let xs = [
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            2.5,
            -1.5,
            -2.5,
            0.999_999_999_999,
            -1e-300,
            1e-300,
            4_503_599_627_370_495.5,
            2_251_799_813_685_247.5,
            -2_251_799_813_685_247.5,
            3e15,
            -3e15,
            1e300,
            f64::MAX,
        ];
        for x in xs {
            // x and its neighbouring doubles (by their bits).
            let bits = x.to_bits();
            let near = [bits, bits.wrapping_add(1), bits.wrapping_sub(1)].map(f64::from_bits);
            for x in near.into_iter().filter(|x| x.is_finite()) {
                // Equal as numbers: the sign of a zero may differ.
                let (f, i) = floor(x);
                assert_eq!(f, x.floor(), "{x}");
                assert_eq!(i, x.floor() as i64, "{x}");
            }
        }
        assert_eq!(floor(f64::NAN).1, 0);
    }

    /// `floor_small` is the library floor over its range, near zero and
    /// the integers above it included. Fails with truncation alone (the
    /// negatives) or the correction applied at -0.
    #[test]
    fn floor_small_is_the_library_floor() {
        let mut xs = vec![
            -0.999_999,
            -0.5,
            -1e-300,
            -0.0,
            0.0,
            1e-300,
            0.5,
            2_147_483_647.5,
        ];
        xs.extend((0..2000).map(|k| f64::from(k) * 0.37 - 0.99));
        for k in 0..=64 {
            let x = f64::from(k);
            // x, the next double up and (above zero) down, by their bits.
            xs.extend([x, f64::from_bits(x.to_bits() + 1), x + 0.5]);
            if k > 0 {
                xs.push(f64::from_bits(x.to_bits() - 1));
            }
        }
        for x in xs.into_iter().filter(|&x| x > -1.0 && x < 2_147_483_648.0) {
            let (t, i) = floor_small(x);
            assert_eq!(i as f64, x.floor(), "{x}");
            // Equal as numbers: the fraction of -0 is -0 here, +0 by the
            // library (no texel coordinate is -0: it is `x - 0.5`, x >= 0).
            assert_eq!(t, x - x.floor(), "{x}");
        }
    }
}
