//! The viewport transform: normalised device coordinates to window pixels.

use glam::DVec3;

use crate::fixed::{FixedPt, first_center_from, last_center_upto, pixel_center};

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

    /// Maps NDC `(x, y, z)` in [-1, 1]^3 to window `(x, y)` in pixels and
    /// window depth in [0, 1].
    pub fn ndc_to_window(&self, ndc: DVec3) -> DVec3 {
        DVec3::new(
            (ndc.x + 1.0) * 0.5 * f64::from(self.width),
            (1.0 - ndc.y) * 0.5 * f64::from(self.height),
            (ndc.z + 1.0) * 0.5,
        )
    }

    /// The same mapping in `f32`, as a GL implementation computes it.
    pub fn ndc_to_window_f32(&self, ndc: [f32; 3]) -> [f32; 3] {
        [
            (ndc[0] * 0.5 + 0.5) * self.width as f32,
            (0.5 - ndc[1] * 0.5) * self.height as f32,
            ndc[2] * 0.5 + 0.5,
        ]
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
    /// functions of [`crate::edge`] (top-left rule) cover none of them.
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
    /// functions of [`crate::edge`] (top-left rule), in row-major order.
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
/// (`E(p) = orient2d(from, to, p)`; top-left edges own `E == 0`).
#[inline(always)]
fn centre_inside(a: FixedPt, b: FixedPt, c: FixedPt, px: i32, py: i32) -> bool {
    let edge = |f: FixedPt, t: FixedPt| {
        let (dx, dy) = (
            i64::from(t.x) - i64::from(f.x),
            i64::from(t.y) - i64::from(f.y),
        );
        let e = dx * (i64::from(py) - i64::from(f.y)) - dy * (i64::from(px) - i64::from(f.x));
        e + i64::from((dy < 0) | ((dy == 0) & (dx > 0))) > 0
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
        assert_eq!(v.ndc_to_window_f32([1.0, -1.0, 1.0]), [640.0, 480.0, 1.0]);
    }
}
