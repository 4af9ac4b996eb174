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

    /// Snaps a window-space position (in pixels) to the nearest 1/256 pixel,
    /// ties away from zero (`f64::round`). Returns `None` for non-finite
    /// input or a position outside the guard band.
    pub fn snap(x: f64, y: f64) -> Option<Self> {
        Some(Self {
            x: snap_coordinate(x)?,
            y: snap_coordinate(y)?,
        })
    }

    /// The position in pixels.
    pub fn to_pixels(self) -> (f64, f64) {
        (
            f64::from(self.x) / f64::from(SUBPIXEL_SCALE),
            f64::from(self.y) / f64::from(SUBPIXEL_SCALE),
        )
    }
}

/// Snaps one window coordinate (pixels) to fixed point, or `None` when it is
/// not finite or beyond ±2^15 pixels.
pub fn snap_coordinate(v: f64) -> Option<i32> {
    let (ok, snapped) = snap_coordinate_lanewise(v);
    ok.then_some(snapped)
}

/// [`snap_coordinate`] without branches, for loops the compiler should
/// vectorise: whether `v` can be snapped, and the snapped value (equal to
/// `snap_coordinate(v)` when it can; meaningless, but computed without
/// panicking, when it cannot).
#[inline(always)]
pub fn snap_coordinate_lanewise(v: f64) -> (bool, i32) {
    let limit = f64::from(1u32 << 15);
    // `abs` of NaN is NaN and fails the comparison; infinities fail it too.
    let ok = v.abs() <= limit;
    // Out of range, the product saturates in `round_half_away`'s cast.
    (ok, round_half_away(v * f64::from(SUBPIXEL_SCALE)))
}

/// [`snap_coordinate_lanewise`] of `f64::from(v)`, computed in `f32` (eight
/// lanes to an AVX2 instruction instead of four), with the same result:
/// `v * 256` is exact in both types for `|v| <= 2^15` (a power-of-two
/// scaling), its integer part is the same, and the remainder `x - t` is
/// exact in `f32` too (`t` is `x` truncated, within a factor of two of `x`
/// or zero: Sterbenz), so the comparisons with one half agree.
#[inline(always)]
pub fn snap_coordinate_lanewise_f32(v: f32) -> (bool, i32) {
    let ok = v.abs() <= 32_768.0;
    let x = v * 256.0;
    let t = x as i32;
    let rest = x - t as f32;
    (
        ok,
        t.wrapping_add(i32::from(rest >= 0.5))
            .wrapping_sub(i32::from(rest <= -0.5)),
    )
}

/// `x.round() as i32` (ties away from zero) for `|x| < 2^31`, without the
/// libm call `f64::round` compiles to on baseline x86-64: the integer part
/// `t` is exact, and so is `x - t` (both are multiples of the same power of
/// two as x), so comparing the remainder with one half rounds exactly as
/// `f64::round` does.
#[inline(always)]
fn round_half_away(x: f64) -> i32 {
    let t = x as i32;
    let rest = x - f64::from(t);
    // Branch-free: the remainder's sign and size are data, and on vertex
    // streams the branches mispredicted about half the time.
    // Wrapping: beyond 2^31 the cast saturates and the remainder of an
    // infinity is infinite; the result is unused there, but must not
    // overflow.
    t.wrapping_add(i32::from(rest >= 0.5))
        .wrapping_sub(i32::from(rest <= -0.5))
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
    fn snapping_rounds_to_nearest_256th() {
        assert_eq!(FixedPt::snap(1.0, 2.5), Some(FixedPt::new(256, 640)));
        assert_eq!(snap_coordinate(0.001), Some(0));
        assert_eq!(snap_coordinate(0.5 / 256.0 + 1e-9), Some(1));
        assert_eq!(snap_coordinate(-1.0 / 256.0), Some(-1));
    }

    #[test]
    fn fast_rounding_equals_f64_round() {
        let probes = [
            0.5,
            -0.5,
            1.5,
            -1.5,
            2.4999999999999996,
            0.49999999999999994,
            -7.5,
            123456.5,
            -0.0,
        ];
        for x in probes {
            assert_eq!(round_half_away(x), x.round() as i32, "{x}");
        }
        let mut s = 0x1234_5678_u64;
        for _ in 0..100_000 {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let x = ((s >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 2.0 * 8_388_608.0;
            assert_eq!(round_half_away(x), x.round() as i32, "{x}");
            let tie = (x.floor()) + 0.5;
            assert_eq!(round_half_away(tie), tie.round() as i32, "{tie}");
        }
    }

    #[test]
    fn lanewise_snapping_agrees_and_never_panics() {
        for v in [
            0.0,
            -0.0,
            1.5 / 256.0,
            -2.5 / 256.0,
            32_768.0,
            -32_768.0,
            32_768.001,
            1e300,
            -1e300,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MAX,
        ] {
            let (ok, snapped) = snap_coordinate_lanewise(v);
            assert_eq!(ok.then_some(snapped), snap_coordinate(v), "{v}");
            assert_eq!(ok, v.is_finite() && v.abs() <= 32_768.0, "{v}");
        }
    }

    #[test]
    fn f32_snapping_is_the_f64_snapping() {
        let mut s = 0x9e37_79b9_u64;
        let check = |v: f32| {
            let (ok, snapped) = snap_coordinate_lanewise_f32(v);
            let (ok64, snapped64) = snap_coordinate_lanewise(f64::from(v));
            assert_eq!(ok, ok64, "{v}");
            if ok {
                assert_eq!(snapped, snapped64, "{v}");
            }
        };
        for v in [
            0.0,
            -0.0,
            0.5 / 256.0,
            -0.5 / 256.0,
            1.5 / 256.0,
            32_768.0,
            -32_768.0,
            32_767.998,
            f32::MIN_POSITIVE,
            1e-40,
            f32::NAN,
            f32::INFINITY,
            f32::MAX,
        ] {
            check(v);
        }
        for _ in 0..200_000 {
            s = s
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let bits = (s >> 32) as u32;
            // Every bit pattern's neighbourhood: raw bits (all exponents),
            // and values near the snapping grid's half steps.
            check(f32::from_bits(bits));
            let grid = ((s >> 8) % 16_777_216) as f32 - 8_388_608.0;
            check((grid + 0.5) / 256.0);
            check(grid / 256.0 / 3.0);
        }
    }

    #[test]
    fn snapping_refuses_non_finite_and_far_values() {
        assert_eq!(snap_coordinate(f64::NAN), None);
        assert_eq!(snap_coordinate(f64::INFINITY), None);
        assert_eq!(snap_coordinate(40_000.0), None);
        assert!(snap_coordinate(32_768.0).is_some());
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
