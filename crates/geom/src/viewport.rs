//! The viewport transform: normalised device coordinates to window pixels.

use glam::DVec3;

/// A window of `width x height` pixels with GL's default depth range [0, 1].
///
/// Window coordinates have their origin at the top-left corner, x right and
/// y *down* (NDC y is flipped), so buffers are row-major, top row first.
/// Pixel `(i, j)` covers `[i, i+1) x [j, j+1)` and is sampled at its centre.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
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

    /// Number of pixels.
    pub fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
