//! The viewport transform: normalised device coordinates to window pixels.

use glam::DVec3;

use crate::fixed::{
    FIXED_LIMIT, FixedPt, HALF_PIXEL, SUBPIXEL_SCALE, first_center_from, gl_fixed_f32,
    gl_fixed_f64, last_center_upto, pixel_center,
};

/// A window of `width x height` pixels with GL's default depth range [0, 1].
///
/// Window coordinates have their origin at the top-left corner, x right and
/// y *down* (NDC y is flipped), so buffers are row-major, top row first.
/// Pixel `(i, j)` covers `[i, i+1) x [j, j+1)` and is sampled at its centre.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Viewport {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl Viewport {
    /// A viewport of the given size.
    pub const fn new(width: u32, height: u32) -> Self {
        Self { width, height }
    }

    /// Width / height.
    pub fn aspect(&self) -> f64 {
        f64::from(self.width) / f64::from(self.height.max(1))
    }

    /// Maps NDC `(x, y, z)` in [-1, 1]^3 to window `(x, y)` in pixels (y
    /// down) and window depth in [0, 1]: the continuous mapping, for rays
    /// and measurements. Vertices are snapped with [`Self::snap_ndc`]
    /// instead, which rounds in GL's frame.
    pub fn ndc_to_window(&self, ndc: DVec3) -> DVec3 {
        DVec3::new(
            (ndc.x + 1.0) * 0.5 * f64::from(self.width),
            (1.0 - ndc.y) * 0.5 * f64::from(self.height),
            (ndc.z + 1.0) * 0.5,
        )
    }

    /// Snaps NDC `(x, y)` to hider's fixed-point window coordinates the way
    /// a GL rasterizer does, in `f64` (the steps of [`Self::snap_ndc_f32`],
    /// rounded in `f64` instead of `f32`). `None` when the position is not
    /// finite or beyond 2^15 pixels.
    pub fn snap_ndc(&self, ndc_x: f64, ndc_y: f64) -> Option<FixedPt> {
        let (ok, p) = self.snap_ndc_lanewise(ndc_x, ndc_y);
        ok.then_some(p)
    }

    /// Snaps NDC `(x, y)` as Mesa's llvmpipe does, in `f32`:
    ///
    /// 1. GL's viewport transform in GL's own frame (y up, row 0 at the
    ///    bottom): `win = ndc * (N/2) + N/2`, a multiply and an add;
    /// 2. the half-pixel offset and 8 sub-pixel bits:
    ///    `round((win - 0.5) * 256)`, ties to even
    ///    ([`gl_fixed_f32`]);
    /// 3. the flip to hider's y-down frame, in integers
    ///    ([`Self::from_gl_fixed`]).
    ///
    /// Rounding after the flip instead would round values on a snapping
    /// boundary the other way and move whole rows along horizontal edges.
    /// `None` when the position is not finite or beyond 2^15 pixels.
    ///
    /// ```
    /// use hider_geom::{FixedPt, Viewport};
    ///
    /// let vp = Viewport::new(4, 4);
    /// // NDC (-1, 1) is the top-left corner: half a pixel before the first
    /// // centre in x and y.
    /// assert_eq!(vp.snap_ndc_f32(-1.0, 1.0), Some(FixedPt::new(0, 0)));
    /// assert_eq!(vp.snap_ndc_f32(0.0, 0.0), Some(FixedPt::new(512, 512)));
    /// ```
    pub fn snap_ndc_f32(&self, ndc_x: f32, ndc_y: f32) -> Option<FixedPt> {
        let (ok, p) = self.snap_ndc_lanewise_f32(ndc_x, ndc_y);
        ok.then_some(p)
    }

    /// [`Self::snap_ndc`] without branches, for loops the compiler should
    /// vectorise: whether the position can be snapped, and the snapped
    /// point (meaningless, but computed without panicking, when it cannot).
    #[inline(always)]
    pub fn snap_ndc_lanewise(&self, ndc_x: f64, ndc_y: f64) -> (bool, FixedPt) {
        let (sx, sy) = (f64::from(self.width) * 0.5, f64::from(self.height) * 0.5);
        let (ok_x, fx) = gl_fixed_f64(ndc_x * sx + sx);
        let (ok_y, fy) = gl_fixed_f64(ndc_y * sy + sy);
        self.flipped(ok_x & ok_y, fx, fy)
    }

    /// [`Self::snap_ndc_f32`] without branches (see
    /// [`Self::snap_ndc_lanewise`]).
    #[inline(always)]
    pub fn snap_ndc_lanewise_f32(&self, ndc_x: f32, ndc_y: f32) -> (bool, FixedPt) {
        // Exact: image sides are at most 2^14.
        let (sx, sy) = (self.width as f32 * 0.5, self.height as f32 * 0.5);
        let (ok_x, fx) = gl_fixed_f32(ndc_x * sx + sx);
        let (ok_y, fy) = gl_fixed_f32(ndc_y * sy + sy);
        self.flipped(ok_x & ok_y, fx, fy)
    }

    /// [`Self::from_gl_fixed`], and whether the result is snappable: `ok`
    /// and both coordinates within [`FIXED_LIMIT`].
    #[inline(always)]
    fn flipped(&self, ok: bool, fx: i32, fy: i32) -> (bool, FixedPt) {
        let p = self.from_gl_fixed(fx, fy);
        let inside = |v: i32| (-FIXED_LIMIT..=FIXED_LIMIT).contains(&v);
        (ok & inside(p.x) & inside(p.y), p)
    }

    /// Hider's y-down fixed-point point of a point in GL's fixed-point
    /// frame (y up, pixel centres at multiples of 256): GL row `r` is image
    /// row `height - 1 - r`, so `y = height * 256 - 128 - fy` and
    /// `x = fx + 128`. Exact (integers), so coverage decided in the y-down
    /// frame with the mirrored rule of [`crate::edge`] is coverage decided
    /// with the top-left rule in GL's row order. Wrapping, so that
    /// out-of-range lanes never panic.
    #[inline(always)]
    pub fn from_gl_fixed(&self, fx: i32, fy: i32) -> FixedPt {
        let top = (self.height as i32).wrapping_mul(SUBPIXEL_SCALE) - HALF_PIXEL;
        FixedPt::new(fx.wrapping_add(HALF_PIXEL), top.wrapping_sub(fy))
    }

    /// The inclusive rectangle `(x0, y0, x1, y1)` of pixels whose centres
    /// the snapped triangle `v` may cover, clamped to the viewport, or
    /// `None` when no centre of the viewport lies in its bounding box (then
    /// it covers no sample of any pixel-centre hider).
    #[inline]
    pub fn pixel_bounds(&self, v: &[FixedPt; 3]) -> Option<(u32, u32, u32, u32)> {
        let [a, b, c] = *v;
        let (min_x, max_x) = (a.x.min(b.x).min(c.x), a.x.max(b.x).max(c.x));
        let (min_y, max_y) = (a.y.min(b.y).min(c.y), a.y.max(b.y).max(c.y));
        let x0 = first_center_from(min_x).max(0);
        let y0 = first_center_from(min_y).max(0);
        let x1 = last_center_upto(max_x).min(self.width as i32 - 1);
        let y1 = last_center_upto(max_y).min(self.height as i32 - 1);
        (x0 <= x1 && y0 <= y1).then_some((x0 as u32, y0 as u32, x1 as u32, y1 as u32))
    }

    /// Whether the snapped triangle `v` (signed doubled area `area`, not
    /// zero; either orientation) certainly covers no pixel centre: its box
    /// holds none, or holds at most [`FEW_CENTRES`] and the exact edge
    /// functions of [`crate::edge`] (fill rule) cover none of them.
    /// Larger boxes answer `false` without a test. Far from the camera
    /// most triangles of a dense mesh are a pixel or less and miss every
    /// centre (281k of a 499k-triangle sphere's at 1024 x 1024): a hider
    /// that drops them early saves all their later work.
    #[inline(always)]
    pub fn misses_every_centre(&self, v: &[FixedPt; 3], area: i64) -> bool {
        matches!(self.covered_centres(v, area), Centres::Few { count: 0, .. })
    }

    /// Which pixel centres the snapped triangle `v` (signed doubled area
    /// `area`, not zero; either orientation) covers, when its box holds at
    /// most [`FEW_CENTRES`]: [`Centres::Few`], tested with the exact edge
    /// functions of [`crate::edge`] (fill rule), in row-major order.
    /// Larger boxes answer [`Centres::Many`] without a test.
    ///
    /// On the 499k-triangle sphere at 1024 x 1024, 281k triangles cover
    /// no centre and 201k of the other 218k have a box of at most four: a
    /// depth-only front end can hand those over as pixels.
    #[inline(always)]
    pub fn covered_centres(&self, v: &[FixedPt; 3], area: i64) -> Centres {
        let Some((x0, y0, x1, y1)) = self.pixel_bounds(v) else {
            return Centres::Few {
                pixels: [(0, 0); FEW_CENTRES],
                count: 0,
            };
        };
        if ((x1 - x0 + 1) * (y1 - y0 + 1)) as usize > FEW_CENTRES {
            return Centres::Many;
        }
        let a = v[0];
        let (b, c) = if area < 0 { (v[2], v[1]) } else { (v[1], v[2]) };
        let (mut pixels, mut count) = ([(0, 0); FEW_CENTRES], 0u8);
        for y in y0..y1 + 1 {
            for x in x0..x1 + 1 {
                // Centres are below 2^23 in fixed point (images are at
                // most 16384).
                if centre_inside(a, b, c, pixel_center(x as i32), pixel_center(y as i32)) {
                    pixels[usize::from(count)] = (x, y);
                    count += 1;
                }
            }
        }
        Centres::Few { pixels, count }
    }

    /// Number of pixels.
    pub fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }
}

/// The most pixel centres a box may hold for [`Viewport::covered_centres`]
/// to test them one by one.
pub const FEW_CENTRES: usize = 4;

/// The pixel centres a small triangle covers: what
/// [`Viewport::covered_centres`] answers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Centres {
    /// The triangle's box holds more than [`FEW_CENTRES`] pixel centres
    /// (not tested).
    Many,
    /// The box holds at most [`FEW_CENTRES`] centres; `pixels[..count]`
    /// are the ones covered, as `(column, row)`, in row-major order.
    Few {
        /// The covered centres (the first `count` entries).
        pixels: [(u32, u32); FEW_CENTRES],
        /// How many are covered.
        count: u8,
    },
}

impl Centres {
    /// The covered centres of a [`Centres::Few`] answer (empty for
    /// [`Centres::Many`]).
    pub fn pixels(&self) -> &[(u32, u32)] {
        match self {
            Self::Many => &[],
            Self::Few { pixels, count } => &pixels[..usize::from(*count)],
        }
    }
}

/// Whether centre `(px, py)` (fixed point) is inside the positively
/// oriented triangle `a b c`: [`crate::edge`]'s edge functions written out
/// (`E(p) = orient2d(from, to, p)`; the fill rule's edges own `E == 0`).
#[inline(always)]
fn centre_inside(a: FixedPt, b: FixedPt, c: FixedPt, px: i32, py: i32) -> bool {
    let edge = |f: FixedPt, t: FixedPt| {
        let (dx, dy) = (
            i64::from(t.x) - i64::from(f.x),
            i64::from(t.y) - i64::from(f.y),
        );
        let e = dx * (i64::from(py) - i64::from(f.y)) - dy * (i64::from(px) - i64::from(f.x));
        e + i64::from((dy < 0) | ((dy == 0) & (dx < 0))) > 0
    };
    edge(a, b) & edge(b, c) & edge(c, a)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The shift-based box equals the definition (first centre at or
        /// after the minimum, last at or before the maximum, by Euclidean
        /// division), also in the guard band.
        #[test]
        fn pixel_bounds_are_the_centres_in_the_box(
            pts in proptest::array::uniform3((-40_000i32..40_000, -40_000i32..40_000)),
            w in 1u32..100,
            h in 1u32..100,
        ) {
            let v = pts.map(|(x, y)| FixedPt::new(x, y));
            let first = |m: i32| (m - 128 + 255).div_euclid(256);
            let last = |m: i32| (m - 128).div_euclid(256);
            let xs = v.map(|p| p.x);
            let ys = v.map(|p| p.y);
            let x0 = first(*xs.iter().min().unwrap()).max(0);
            let y0 = first(*ys.iter().min().unwrap()).max(0);
            let x1 = last(*xs.iter().max().unwrap()).min(w as i32 - 1);
            let y1 = last(*ys.iter().max().unwrap()).min(h as i32 - 1);
            let want = (x0 <= x1 && y0 <= y1).then_some((x0 as u32, y0 as u32, x1 as u32, y1 as u32));
            prop_assert_eq!(Viewport::new(w, h).pixel_bounds(&v), want);
        }

        /// `covered_centres` lists exactly the covered centres of a box of
        /// at most `FEW_CENTRES`, row-major, and answers `Many` for larger
        /// boxes; `misses_every_centre` is true exactly for a small box
        /// covering none. Brute force with the shared coverage test, both
        /// orientations.
        #[test]
        fn covered_centres_are_the_brute_force_ones(
            pts in proptest::array::uniform3((-300i32..1300, -300i32..1300)),
            w in 1u32..6,
            h in 1u32..6,
        ) {
            let v = pts.map(|(x, y)| FixedPt::new(x, y));
            let area = crate::orient2d(v[0], v[1], v[2]);
            prop_assume!(area != 0);
            let vp = Viewport::new(w, h);
            let positive = if area > 0 { v } else { [v[0], v[2], v[1]] };
            let got = vp.covered_centres(&v, area);
            let Some((x0, y0, x1, y1)) = vp.pixel_bounds(&v) else {
                prop_assert!(got.pixels().is_empty() && got != Centres::Many);
                prop_assert!(vp.misses_every_centre(&v, area));
                return Ok(());
            };
            let want: Vec<(u32, u32)> = (y0..=y1)
                .flat_map(|y| (x0..=x1).map(move |x| (x, y)))
                .filter(|&(x, y)| crate::triangle_covers(
                    &positive, i64::from(pixel_center(x as i32)), i64::from(pixel_center(y as i32))))
                .collect();
            let few = ((x1 - x0 + 1) * (y1 - y0 + 1)) as usize <= FEW_CENTRES;
            if few {
                prop_assert_eq!(got.pixels(), &want[..]);
            } else {
                prop_assert_eq!(got, Centres::Many);
            }
            prop_assert_eq!(vp.misses_every_centre(&v, area), few && want.is_empty());
        }
    }

    #[test]
    fn corners_map_to_window_corners_with_y_down() {
        let v = Viewport::new(640, 480);
        assert_eq!(
            v.ndc_to_window(DVec3::new(-1.0, 1.0, -1.0)),
            DVec3::new(0.0, 0.0, 0.0)
        );
        assert_eq!(
            v.ndc_to_window(DVec3::new(1.0, -1.0, 1.0)),
            DVec3::new(640.0, 480.0, 1.0)
        );
    }

    #[test]
    fn snapping_rounds_in_gls_frame_and_flips_in_integers() {
        let v = Viewport::new(640, 480);
        assert_eq!(v.snap_ndc(-1.0, 1.0), Some(FixedPt::new(0, 0)));
        assert_eq!(
            v.snap_ndc(1.0, -1.0),
            Some(FixedPt::new(640 * 256, 480 * 256))
        );
        assert_eq!(
            v.snap_ndc_f32(1.0, -1.0),
            Some(FixedPt::new(640 * 256, 480 * 256))
        );
        // A window y of GL row 1's centre plus 1.5 steps (1.5 + 1.5/256) is
        // a tie, 257.5 steps above GL's first centre: ties to even give 258,
        // image y = 512 * 256 - 128 - 258. Rounding the same position in
        // the y-down frame (130 685.5 steps) ties away would give 130 686.
        let square = Viewport::new(512, 512);
        let ndc_y = (1.5 + 1.5 / 256.0) / 256.0 - 1.0;
        assert_eq!(ndc_y * 256.0 + 256.0, 1.5 + 1.5 / 256.0, "exact");
        let want = 512 * 256 - 128 - 258;
        assert_eq!(square.snap_ndc_f32(0.0, ndc_y as f32).unwrap().y, want);
        assert_eq!(square.snap_ndc(0.0, ndc_y).unwrap().y, want);
        assert_eq!(v.snap_ndc(f64::NAN, 0.0), None);
        assert_eq!(v.snap_ndc_f32(0.0, f32::INFINITY), None);
        assert_eq!(v.snap_ndc(-300.0, 0.0), None);
    }
}
