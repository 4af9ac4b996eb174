//! Conservative lower bounds of a triangle's computed depths, for
//! hierarchical depth rejection.
//!
//! The reference z-buffer computes a pixel's depth as
//! `fl(fl(value + fl(dx * X)) + fl(dy * Y))` with `X = x - x0`, `Y = y - y0`
//! ([`hider_geom::PlaneEq::eval`]); `X` and `Y` are exact (multiples of
//! 1/256 below 2^16). The standard bound on a sum of three rounded terms
//! (Higham, *Accuracy and Stability of Numerical Algorithms*, 2002, §3.1)
//! gives `|computed - f| <= γ₃ · S` with `f` the exact affine function of
//! the stored coefficients, `S = |value| + |dx·X| + |dy·Y|` and
//! `γ₃ = 3u / (1 - 3u) < 3.4e-16` (u = 2^-53).
//!
//! We use the much larger `E = 2^-40 · S_max + 2^-1022`, with
//! `S_max = |value| + |dx|·max|X| + |dy|·max|Y|`, the maxima over the
//! triangle's vertices; it bounds `S` at every point of the triangle's
//! bounding box, where all the pixel centres we evaluate lie:
//! - the exact minimum of `f` over the triangle is at a vertex, and over a
//!   rectangle at the corner the gradient signs pick;
//! - that corner's computed value `c` is within `E` of its exact value, and
//!   every pixel's computed depth within `E` of its exact one, so every
//!   computed depth is `>= c - 2E`;
//! - `fl(c - 3E) <= c - 2E`: `E` exceeds `c`'s rounding unit by a factor
//!   of about 2^12, so rounding the subtraction cannot eat the third `E`.
//!
//! (The 2^-1022 term keeps `E` above the absolute error of subnormal
//! results.) The margin is ~1e-12 of the depth, four orders of magnitude
//! below one f32 step of window depth, so it costs no rejections.

use hider_geom::PlaneEq;
use hider_geom::fixed::FixedPt;

const TWO_POW_MINUS_40: f64 = 1.0 / (1u64 << 40) as f64;

/// The per-triangle depth bounds.
#[derive(Clone, Copy, Debug)]
pub(crate) struct DepthBounds {
    plane: PlaneEq,
    /// Three times the error bound `E`.
    margin: f64,
    /// Lower bound of every computed depth of the triangle.
    pub tri_low: f64,
}

impl DepthBounds {
    /// Bounds of the triangle `v` with depth plane `plane`; `None` if the
    /// plane is not finite (then nothing may be rejected).
    #[inline(always)]
    pub(crate) fn new(v: &[FixedPt; 3], plane: &PlaneEq) -> Option<Self> {
        let p = v.map(|q| q.to_pixels());
        let (mut max_x, mut max_y) = (0.0f64, 0.0f64);
        let mut low = f64::INFINITY;
        for &(x, y) in &p {
            max_x = max_x.max((x - plane.x0).abs());
            max_y = max_y.max((y - plane.y0).abs());
            low = low.min(plane.eval(x, y));
        }
        // S for any point of the triangle's bounding box.
        let s_max = plane.value.abs() + plane.dx.abs() * max_x + plane.dy.abs() * max_y;
        let margin = 3.0 * (s_max * TWO_POW_MINUS_40 + f64::MIN_POSITIVE);
        let tri_low = low - margin;
        (tri_low.is_finite() && margin.is_finite()).then_some(Self {
            plane: *plane,
            margin,
            tri_low,
        })
    }

    /// [`Self::tri_low`] rounded down to `f32`, for the compact bin
    /// entries; minus infinity when the plane gives no bound. Every depth
    /// key encoding is monotone, so a smaller bound is still a bound.
    pub(crate) fn low_f32(v: &[FixedPt; 3], plane: &PlaneEq) -> f32 {
        let Some(b) = Self::new(v, plane) else {
            return f32::NEG_INFINITY;
        };
        let f = b.tri_low as f32;
        if f64::from(f) <= b.tri_low {
            return f;
        }
        // One step down (f32::next_down, stable only since Rust 1.86): f is
        // finite, since tri_low is and rounding overshot it.
        let bits = f.to_bits();
        if f > 0.0 {
            f32::from_bits(bits - 1)
        } else if f == 0.0 {
            -f32::from_bits(1)
        } else {
            f32::from_bits(bits + 1)
        }
    }

    /// Lower bound of the computed depths at the pixel centres of columns
    /// `x0..=x1`, rows `y0..=y1` (a rectangle inside the triangle's box).
    #[inline(always)]
    pub(crate) fn rect_low(&self, x0: u32, y0: u32, x1: u32, y1: u32) -> f64 {
        let x = if self.plane.dx >= 0.0 { x0 } else { x1 };
        let y = if self.plane.dy >= 0.0 { y0 } else { y1 };
        let corner = self.plane.at_pixel(x, y) - self.margin;
        corner.max(self.tri_low)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_geom::fixed::pixel_center;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        /// The bound is below every computed pixel depth of the triangle's
        /// bounding box rectangle (a superset of its covered pixels).
        #[test]
        fn bounds_are_below_every_computed_depth(
            pts in proptest::array::uniform3((0i32..64 * 256, 0i32..64 * 256)),
            z in proptest::array::uniform3(0.0f64..1.0),
            sub in (0u32..64, 0u32..64, 0u32..64, 0u32..64),
        ) {
            let v = pts.map(|(x, y)| FixedPt::new(x, y));
            let Some(plane) = PlaneEq::from_points(&v, z) else { return Ok(()); };
            let Some(b) = DepthBounds::new(&v, &plane) else { return Ok(()); };
            let lo = |a: i32| ((a - 128).max(0) as u32).div_ceil(256);
            let hi = |a: i32| ((a - 128).max(0) as u32) / 256;
            let (bx0, bx1) = (lo(v.iter().map(|p| p.x).min().unwrap()), hi(v.iter().map(|p| p.x).max().unwrap()));
            let (by0, by1) = (lo(v.iter().map(|p| p.y).min().unwrap()), hi(v.iter().map(|p| p.y).max().unwrap()));
            prop_assume!(bx0 <= bx1 && by0 <= by1);
            let (rx0, rx1) = (bx0.max(sub.0.min(sub.1)).min(bx1), bx1.min(sub.0.max(sub.1)).max(bx0));
            let (ry0, ry1) = (by0.max(sub.2.min(sub.3)).min(by1), by1.min(sub.2.max(sub.3)).max(by0));
            let low = b.rect_low(rx0, ry0, rx1, ry1);
            for y in ry0..=ry1 {
                for x in rx0..=rx1 {
                    // Pixels of the box outside the triangle may be below the
                    // triangle bound; the rectangle bound alone must hold.
                    let d = plane.at_pixel(x, y);
                    let inside = hider_geom::edge::triangle_covers(
                        &v, pixel_center(x as i32).into(), pixel_center(y as i32).into());
                    if inside {
                        prop_assert!(d >= low, "{d} < {low} at {x},{y}");
                    }
                    let corner_only = {
                        let cx = if plane.dx >= 0.0 { rx0 } else { rx1 };
                        let cy = if plane.dy >= 0.0 { ry0 } else { ry1 };
                        plane.at_pixel(cx, cy) - b.margin
                    };
                    prop_assert!(d >= corner_only);
                }
            }
        }
    }
}
