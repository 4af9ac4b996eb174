//! The viewport transform: normalised device coordinates to window pixels.

use glam::DVec3;

use crate::fixed::{FixedPt, SUBPIXEL_SCALE};

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
        const _: () = assert!(SUBPIXEL_SCALE == 256);
        let [a, b, c] = *v;
        let (min_x, max_x) = (a.x.min(b.x).min(c.x), a.x.max(b.x).max(c.x));
        let (min_y, max_y) = (a.y.min(b.y).min(c.y), a.y.max(b.y).max(c.y));
        // Centre of pixel i is i * 256 + 128: the first centre >= m is
        // ceil((m - 128) / 256), the last <= m is floor((m - 128) / 256);
        // an arithmetic shift is div_euclid by 256.
        let x0 = ((min_x + 127) >> 8).max(0);
        let y0 = ((min_y + 127) >> 8).max(0);
        let x1 = ((max_x - 128) >> 8).min(self.width as i32 - 1);
        let y1 = ((max_y - 128) >> 8).min(self.height as i32 - 1);
        (x0 <= x1 && y0 <= y1).then_some((x0 as u32, y0 as u32, x1 as u32, y1 as u32))
    }

    /// Number of pixels.
    pub fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }
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
