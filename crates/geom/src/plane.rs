//! Affine screen-space planes: window depth and 1/w.
//!
//! After the perspective divide, window depth `z/w` is an affine function of
//! the window position, and so is `1/w`; camera-space depth is *not* (it is
//! the reciprocal of an affine function). This is the lesson of
//! scratchapixel's depth-buffer lesson: interpolate `1/z`, never `z`.
//! [`perspective_correct`] and [`screen_linear`] show both on the lesson's
//! worked example.

use crate::fixed::FixedPt;

/// An affine function `f(x, y) = value + dx * (x - x0) + dy * (y - y0)` of
/// window position in pixels. Storing the origin keeps the evaluation
/// well-conditioned far from the window origin.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PlaneEq {
    /// x of the reference point, pixels.
    pub x0: f64,
    /// y of the reference point, pixels.
    pub y0: f64,
    /// Value at the reference point.
    pub value: f64,
    /// Change per pixel in x.
    pub dx: f64,
    /// Change per pixel in y.
    pub dy: f64,
}

impl PlaneEq {
    /// The plane through three window-space points (fixed point) with the
    /// given values. Returns `None` when the points are collinear.
    pub fn from_points(v: &[FixedPt; 3], values: [f64; 3]) -> Option<Self> {
        let p = v.map(|q| q.to_pixels());
        let (x0, y0) = p[0];
        let (x1, y1) = (p[1].0 - x0, p[1].1 - y0);
        let (x2, y2) = (p[2].0 - x0, p[2].1 - y0);
        let det = x1 * y2 - x2 * y1;
        if det == 0.0 {
            return None;
        }
        let d1 = values[1] - values[0];
        let d2 = values[2] - values[0];
        Some(Self {
            x0,
            y0,
            value: values[0],
            dx: (d1 * y2 - d2 * y1) / det,
            dy: (x1 * d2 - x2 * d1) / det,
        })
    }

    /// A constant function.
    pub fn constant(value: f64) -> Self {
        Self {
            value,
            ..Self::default()
        }
    }

    /// The value at window position `(x, y)` in pixels.
    #[inline]
    pub fn eval(&self, x: f64, y: f64) -> f64 {
        self.value + self.dx * (x - self.x0) + self.dy * (y - self.y0)
    }

    /// The value at the centre of pixel `(i, j)`.
    #[inline]
    pub fn at_pixel(&self, i: u32, j: u32) -> f64 {
        self.eval(f64::from(i) + 0.5, f64::from(j) + 0.5)
    }
}

/// Camera-space depth at screen-space fraction `t` along a segment whose
/// end points have depths `z0` and `z1`, interpolated correctly: `1/z` is
/// linear in screen space, so `z = 1 / ((1 - t)/z0 + t/z1)`.
pub fn perspective_correct(z0: f64, z1: f64, t: f64) -> f64 {
    1.0 / ((1.0 - t) / z0 + t / z1)
}

/// Camera-space depth interpolated linearly in screen space: *wrong* under
/// perspective, kept to demonstrate the error the lesson warns about.
pub fn screen_linear(z0: f64, z1: f64, t: f64) -> f64 {
    z0 + (z1 - z0) * t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_worked_example_one_over_z() {
        // The depth-buffer lesson's worked example: V0 = (x -4, z 2),
        // V1 = (x 2, z 5), canvas at distance 1. Projected x' = x / z: -2 and 0.4. Pixel at x' = 0 lies at
        // t = (0 - -2) / (0.4 - -2) along the projected segment.
        let (x0, z0, x1, z1) = (-4.0, 2.0, 2.0, 5.0);
        let (p0, p1) = (x0 / z0, x1 / z1);
        let t = (0.0 - p0) / (p1 - p0);
        let z = perspective_correct(z0, z1, t);
        assert!(
            (z - 4.0).abs() < 1e-12,
            "1/z interpolation gives 4, got {z}"
        );
        let wrong = screen_linear(z0, z1, t);
        assert!(
            (wrong - 4.5).abs() < 1e-12,
            "linear z gives 4.5, got {wrong}"
        );
        // The correct answer is the true intersection: the line x = 0 meets
        // the segment V0 V1 at z = 4 (x = -4 + 6s = 0 -> s = 2/3, z = 2 + 3s).
        assert!((2.0 + 3.0 * (2.0 / 3.0) - z).abs() < 1e-12);
    }

    #[test]
    fn plane_reproduces_its_three_values() {
        let v = [
            FixedPt::new(0, 0),
            FixedPt::new(2560, 256),
            FixedPt::new(512, 3000),
        ];
        let vals = [0.25, 0.75, 0.5];
        let p = PlaneEq::from_points(&v, vals).unwrap();
        for (q, want) in v.iter().zip(vals) {
            let (x, y) = q.to_pixels();
            assert!((p.eval(x, y) - want).abs() < 1e-12);
        }
    }

    #[test]
    fn collinear_points_have_no_plane() {
        let v = [
            FixedPt::new(0, 0),
            FixedPt::new(256, 256),
            FixedPt::new(512, 512),
        ];
        assert!(PlaneEq::from_points(&v, [0.0, 1.0, 2.0]).is_none());
    }
}
