//! Fixed-point window coordinates: 8 sub-pixel bits, as GL rasterizers use.
//!
//! Snapping every vertex to the 1/256-pixel grid once, in the front end, is
//! what lets every hider decide coverage with exact integer arithmetic: two
//! triangles that share an edge share its snapped end points bit for bit.

/// Number of sub-pixel bits of a fixed-point coordinate.
pub const SUBPIXEL_BITS: u32 = 8;
/// Fixed-point units per pixel (256).
pub const SUBPIXEL_SCALE: i32 = 1 << SUBPIXEL_BITS;
/// Half a pixel in fixed-point units: pixel `i`'s centre is `i * 256 + 128`.
pub const HALF_PIXEL: i32 = SUBPIXEL_SCALE / 2;

/// Largest image side the front end accepts, in pixels.
pub const MAX_IMAGE_SIDE: u32 = 16384;
/// How far outside the image (in pixels, on every side) geometry may reach
/// before it is clipped. With [`MAX_IMAGE_SIDE`] this keeps every snapped
/// coordinate within ±2^15 pixels = ±2^23 fixed-point units, so edge
/// function products stay below 2^48 and never overflow an `i64`.
pub const GUARD_BAND_PIXELS: u32 = 16384;

/// A point in window coordinates, in 1/256 pixel units (x right, y down).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct FixedPt {
    /// x in 1/256 pixels.
    pub x: i32,
    /// y in 1/256 pixels.
    pub y: i32,
}

impl FixedPt {
    /// A point from raw fixed-point units.
    pub const fn new(x: i32, y: i32) -> Self {
        Self { x, y }
    }

    /// The position in pixels.
    pub fn to_pixels(self) -> (f64, f64) {
        (
            f64::from(self.x) / f64::from(SUBPIXEL_SCALE),
            f64::from(self.y) / f64::from(SUBPIXEL_SCALE),
        )
    }
}

/// The largest distance from the origin, in fixed-point units, of a snapped
/// coordinate: 2^15 pixels (see [`GUARD_BAND_PIXELS`]).
pub const FIXED_LIMIT: i32 = 1 << 23;

/// `x` rounded to the nearest integer, ties to even, for `|x| < 2^31`:
/// what SSE's `cvtps2dq` does under the default rounding mode, the
/// conversion llvmpipe snaps vertices with (Mesa's `lp_setup_tri.c`,
/// `calc_fixed_position`). Equal to `x.round_ties_even() as i32`, without
/// the library call that compiles to on baseline x86-64 and with no
/// branch, so that loops over lanes vectorise: the integer part `t` is
/// exact, and so is the remainder `x - t` (both are multiples of `x`'s
/// unit in the last place, and `t` is within a factor of two of `x` or
/// zero: Sterbenz), so comparing it with one half decides exactly.
/// Beyond `2^31` the result is meaningless but computed without panicking.
#[inline(always)]
pub fn round_ties_even_f32(x: f32) -> i32 {
    let t = x as i32;
    let rest = x - t as f32;
    let odd = t & 1 != 0;
    t.wrapping_add(i32::from((rest > 0.5) | ((rest == 0.5) & odd)))
        .wrapping_sub(i32::from((rest < -0.5) | ((rest == -0.5) & odd)))
}

/// [`round_ties_even_f32`] in `f64`.
#[inline(always)]
pub fn round_ties_even_f64(x: f64) -> i32 {
    let t = x as i32;
    let rest = x - f64::from(t);
    let odd = t & 1 != 0;
    t.wrapping_add(i32::from((rest > 0.5) | ((rest == 0.5) & odd)))
        .wrapping_sub(i32::from((rest < -0.5) | ((rest == -0.5) & odd)))
}

/// GL's fixed-point coordinate of a window coordinate `win` (pixels, in
/// GL's own frame): `round((win - 0.5) * 256)`, ties to even, so that pixel
/// centres sit at multiples of 256 (llvmpipe subtracts its half-pixel
/// offset before scaling). Also whether `win` is within 2^15 pixels of the
/// first pixel centre (finite and snappable); the value is meaningless, but
/// computed without panicking, when it is not.
#[inline(always)]
pub fn gl_fixed_f32(win: f32) -> (bool, i32) {
    let v = win - 0.5;
    // `abs` of NaN is NaN and fails the comparison; infinities fail it too.
    (v.abs() <= 32_768.0, round_ties_even_f32(v * 256.0))
}

/// [`gl_fixed_f32`] in `f64`: the same steps, rounded in `f64`.
#[inline(always)]
pub fn gl_fixed_f64(win: f64) -> (bool, i32) {
    let v = win - 0.5;
    (v.abs() <= 32_768.0, round_ties_even_f64(v * 256.0))
}

/// The fixed-point coordinate of the centre of pixel column or row `i`.
#[inline(always)]
pub const fn pixel_center(i: i32) -> i32 {
    i * SUBPIXEL_SCALE + HALF_PIXEL
}

/// [`pixel_center`] of every lane: a plain loop, which the compiler turns
/// into a shift and an addition per vector of lanes.
#[inline(always)]
pub fn pixel_centers<const N: usize>(i: [i32; N]) -> [i32; N] {
    let mut out = [0; N];
    for (o, &i) in out.iter_mut().zip(&i) {
        *o = pixel_center(i);
    }
    out
}

/// The first pixel column (or row) whose centre is at or after the
/// fixed-point coordinate `m`: `ceil((m - 128) / 256)`, as an arithmetic
/// shift (which is Euclidean division by 256).
#[inline(always)]
pub const fn first_center_from(m: i32) -> i32 {
    (m + (HALF_PIXEL - 1)) >> SUBPIXEL_BITS
}

/// The last pixel column (or row) whose centre is at or before the
/// fixed-point coordinate `m`: `floor((m - 128) / 256)`.
#[inline(always)]
pub const fn last_center_upto(m: i32) -> i32 {
    (m - HALF_PIXEL) >> SUBPIXEL_BITS
}

/// [`first_center_from`] of every lane.
#[inline(always)]
pub fn first_centers_from<const N: usize>(m: [i32; N]) -> [i32; N] {
    let mut out = [0; N];
    for (o, &m) in out.iter_mut().zip(&m) {
        *o = first_center_from(m);
    }
    out
}

/// [`last_center_upto`] of every lane.
#[inline(always)]
pub fn last_centers_upto<const N: usize>(m: [i32; N]) -> [i32; N] {
    let mut out = [0; N];
    for (o, &m) in out.iter_mut().zip(&m) {
        *o = last_center_upto(m);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_is_ties_to_even() {
        let probes = [
            0.5,
            -0.5,
            1.5,
            -1.5,
            2.5,
            -2.5,
            0.49999997,
            2.4999998,
            -7.5,
            123_456.5,
            -0.0,
            0.0,
            8_388_607.5,
            -8_388_607.5,
        ];
        for x in probes {
            assert_eq!(round_ties_even_f32(x), x.round_ties_even() as i32, "{x}");
            let x = f64::from(x);
            assert_eq!(round_ties_even_f64(x), x.round_ties_even() as i32, "{x}");
        }
        assert_eq!(round_ties_even_f64(0.49999999999999994), 0);
        let mut s = 0x1234_5678_u64;
        for _ in 0..100_000 {
            s = s
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let x = ((s >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 2.0 * 8_388_608.0;
            assert_eq!(round_ties_even_f64(x), x.round_ties_even() as i32, "{x}");
            let tie = x.floor() + 0.5;
            assert_eq!(
                round_ties_even_f64(tie),
                tie.round_ties_even() as i32,
                "{tie}"
            );
            let y = f32::from_bits((s >> 32) as u32);
            if y.abs() < 2.0e9 {
                assert_eq!(round_ties_even_f32(y), y.round_ties_even() as i32, "{y}");
            }
            let tie = (x as f32 / 4.0).floor() + 0.5;
            assert_eq!(
                round_ties_even_f32(tie),
                tie.round_ties_even() as i32,
                "{tie}"
            );
        }
    }

    #[test]
    fn gl_fixed_puts_pixel_centres_on_multiples_of_256() {
        assert_eq!(gl_fixed_f32(0.5), (true, 0));
        assert_eq!(gl_fixed_f32(3.5), (true, 3 * 256));
        assert_eq!(gl_fixed_f64(3.5), (true, 3 * 256));
        // Half a step above a centre rounds to the even neighbour: down at
        // 0, up at 1.
        assert_eq!(gl_fixed_f32(0.5 + 0.5 / 256.0), (true, 0));
        assert_eq!(gl_fixed_f32(0.5 + 1.5 / 256.0), (true, 2));
        assert_eq!(gl_fixed_f64(0.5 - 0.5 / 256.0), (true, 0));
        assert_eq!(gl_fixed_f64(0.5 - 1.5 / 256.0), (true, -2));
        for bad in [
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            40_000.0,
            -40_000.0,
        ] {
            assert!(!gl_fixed_f32(bad).0, "{bad}");
            assert!(!gl_fixed_f64(f64::from(bad)).0, "{bad}");
        }
        assert!(gl_fixed_f32(32_768.5).0 && !gl_fixed_f32(32_768.6).0);
    }

    #[test]
    fn pixel_centres_are_half_integers() {
        assert_eq!(pixel_center(0), 128);
        assert_eq!(pixel_center(3), 3 * 256 + 128);
        assert_eq!(FixedPt::new(pixel_center(2), 128).to_pixels(), (2.5, 0.5));
        assert_eq!(pixel_centers([0, 3, -1]), [128, 3 * 256 + 128, -128]);
    }

    #[test]
    fn first_and_last_centres_of_a_span() {
        for m in -2000i32..2000 {
            let first = (m - 128 + 255).div_euclid(256);
            let last = (m - 128).div_euclid(256);
            assert_eq!(first_center_from(m), first, "{m}");
            assert_eq!(last_center_upto(m), last, "{m}");
            assert!(pixel_center(first) >= m && pixel_center(first - 1) < m);
            assert!(pixel_center(last) <= m && pixel_center(last + 1) > m);
        }
        assert_eq!(first_centers_from([128, 129]), [0, 1]);
        assert_eq!(last_centers_upto([383, 384]), [0, 1]);
    }
}
