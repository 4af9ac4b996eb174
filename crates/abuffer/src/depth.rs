//! Sample depths and their exact bounds over a fragment.
//!
//! Every hider of this crate computes the window depth of a triangle at a
//! sample with one expression ([`plane_depth`]), so that their depth
//! comparisons agree bit for bit; [`DepthBounds`] finds the nearest and
//! farthest of those values over a coverage mask from a few evaluations.

use hider_geom::PlaneEq;
use hider_geom::fixed::SUBPIXEL_SCALE;

use crate::coverage::Coverage;
use crate::pattern::SamplePattern;
use crate::select::pick_f64;

/// The window depth of a triangle whose depth plane is `plane` at sample
/// `(sx, sy)` (1/256 pixel) of pixel `(i, j)`: the plane evaluated in
/// `f64`. Every hider of this crate computes sample depths with this one
/// expression so that their depth comparisons agree bit for bit; at the
/// centre it is exactly `plane.at_pixel(i, j)`.
#[inline]
pub(crate) fn plane_depth(plane: &PlaneEq, i: u32, j: u32, (sx, sy): (i32, i32)) -> f64 {
    let scale = f64::from(SUBPIXEL_SCALE);
    plane.eval(
        f64::from(i) + f64::from(sx) / scale,
        f64::from(j) + f64::from(sy) / scale,
    )
}

/// The corner of the sample hull `hull` ([`SamplePattern::hull`]) where
/// `plane` is lowest: the one its slopes point away from (the plane is
/// monotonic in each coordinate, see [`DepthBounds`]).
#[inline]
pub(crate) fn near_corner(
    plane: &PlaneEq,
    (hx0, hy0, hx1, hy1): (i32, i32, i32, i32),
) -> (i32, i32) {
    (
        if plane.dx >= 0.0 { hx0 } else { hx1 },
        if plane.dy >= 0.0 { hy0 } else { hy1 },
    )
}

/// The corner of the sample hull `hull` where `plane` is highest: the one
/// opposite [`near_corner`] (an upper bound of the plane's computed value
/// at every sample and the centre of a pixel, by the same monotonicity).
#[inline]
pub(crate) fn far_corner(
    plane: &PlaneEq,
    (hx0, hy0, hx1, hy1): (i32, i32, i32, i32),
) -> (i32, i32) {
    near_corner(plane, (hx1, hy1, hx0, hy0))
}

/// A lower bound of `plane`'s value at every sample and centre of the
/// pixels `(x0, y0)` to `(x1, y1)`: its value at the near corner of the
/// sample hull `hull` of the rectangle's near pixel, exactly as
/// [`plane_depth`] computes it there (what the culling tests compare).
#[inline]
pub(crate) fn nearest_over(
    plane: &PlaneEq,
    (x0, y0, x1, y1): (u32, u32, u32, u32),
    hull: (i32, i32, i32, i32),
) -> f64 {
    let i = if plane.dx >= 0.0 { x0 } else { x1 };
    let j = if plane.dy >= 0.0 { y0 } else { y1 };
    plane_depth(plane, i, j, near_corner(plane, hull))
}

/// A signed key ordered like `f32::total_cmp` (the order sample depths are
/// sorted by): negative values flip their magnitude bits.
#[inline]
pub(crate) fn depth_key(z: f32) -> i32 {
    let b = z.to_bits() as i32;
    b ^ (((b >> 31) as u32) >> 1) as i32
}

/// Exact depth bounds of a fragment from a few plane evaluations.
///
/// [`plane_depth`] is monotonic in each coordinate: `x - x0`, the products
/// by `dx` and `dy` and the two sums are each rounded by a monotonic
/// rounding, so for a fixed row the computed depth never decreases along x
/// when `dx >= 0` and never increases when `dx < 0` (likewise along y).
/// Hence the nearest and farthest computed depths over any set of samples
/// of one grid row are at the row's first and last sample, and over a full
/// grid at two opposite corners: the bounds below are *equal* to the
/// minimum and maximum of the per-sample values, found with at most 4 (not
/// 32) evaluations each.
#[derive(Clone, Copy, Debug)]
pub(crate) struct DepthBounds {
    pattern: SamplePattern,
    /// Grid32 fast path applies (its rows are the grid's rows).
    grid: bool,
    /// Whether the computed depth never decreases along x / y.
    up_x: bool,
    up_y: bool,
    /// Full masks take the hull corners (min/max mode) instead of samples.
    hull_for_full: bool,
}

impl DepthBounds {
    /// Bounds for triangles with depth plane `plane`. With `hull_for_full`
    /// a full mask is bounded by the plane at the corners of the pattern's
    /// hull (which for the 8 x 4 grid are samples).
    #[inline]
    pub(crate) fn new(plane: &PlaneEq, pattern: SamplePattern, hull_for_full: bool) -> Self {
        Self {
            pattern,
            grid: pattern == SamplePattern::Grid32,
            up_x: plane.dx >= 0.0,
            up_y: plane.dy >= 0.0,
            hull_for_full,
        }
    }

    /// The nearest (`far == false`) or farthest computed depth over the
    /// samples of `c.mask` and, if covered, the centre (`centre_z`, which
    /// a full mask does not need: the centre lies inside the hull).
    #[inline(always)]
    pub(crate) fn bound(
        &self,
        plane: &PlaneEq,
        (i, j): (u32, u32),
        c: Coverage,
        centre_z: f64,
        far: bool,
    ) -> f64 {
        if c.full && (self.grid || self.hull_for_full) {
            // Along x (y) the bound is at the low end when the depth grows
            // in the direction we look for, i.e. when `up == far` is false.
            // The centre is inside the hull: it cannot pass the corner.
            let (x0, y0, x1, y1) = self.pattern.hull();
            let x = if self.up_x != far { x0 } else { x1 };
            let y = if self.up_y != far { y0 } else { y1 };
            return plane_depth(plane, i, j, (x, y));
        }
        self.bound_partial(plane, (i, j), c, centre_z, far)
    }

    /// Both bounds, `(nearest, farthest)`, in one pass: the same values as
    /// [`Self::bound`] with `far` false and true.
    #[inline(never)]
    pub(crate) fn range(
        &self,
        plane: &PlaneEq,
        (i, j): (u32, u32),
        c: Coverage,
        centre_z: f64,
    ) -> (f64, f64) {
        if c.full || !self.grid {
            return (
                self.bound(plane, (i, j), c, centre_z, false),
                self.bound(plane, (i, j), c, centre_z, true),
            );
        }
        // Branch-free: whether a row of a partial mask is empty, or holds
        // one sample, is a coin toss, and as branches those tests
        // mispredicted. Every row is evaluated at its first and last
        // covered column (an empty row at columns 7 and 0, whose values
        // are then not taken); a value is taken exactly when the `<` and
        // `>` of the comparisons one by one would take it.
        let (mut lo, mut hi) = (
            pick_f64(c.centre, centre_z, f64::INFINITY),
            pick_f64(c.centre, centre_z, f64::NEG_INFINITY),
        );
        let (xi, yj) = (f64::from(i), f64::from(j));
        for (r, y) in GRID_Y.into_iter().enumerate() {
            let row = (c.mask >> (8 * r)) as u8;
            let (first, last) = (row.trailing_zeros().min(7), 7 - row.leading_zeros().min(7));
            // Along the row the depth runs from `first` to `last`.
            let (near, far) = if self.up_x {
                (first, last)
            } else {
                (last, first)
            };
            let y = yj + y;
            let zn = plane.eval(xi + GRID_X[near as usize], y);
            let zf = plane.eval(xi + GRID_X[far as usize], y);
            let live = row != 0;
            lo = pick_f64(live & (zn < lo), zn, lo);
            hi = pick_f64(live & (zf > hi), zf, hi);
        }
        (lo, hi)
    }

    /// [`Self::bound`] of a partial mask (or any mask of a pattern whose
    /// hull corners are not samples).
    #[inline(never)]
    fn bound_partial(
        &self,
        plane: &PlaneEq,
        (i, j): (u32, u32),
        c: Coverage,
        centre_z: f64,
        far: bool,
    ) -> f64 {
        let low_x = self.up_x != far;
        let mut z = if c.centre {
            centre_z
        } else if far {
            f64::NEG_INFINITY
        } else {
            f64::INFINITY
        };
        // Plain comparisons: same value as `f64::min`/`max` for numbers.
        let mut pick = |v: f64| {
            if (far && v > z) || (!far && v < z) {
                z = v;
            }
        };
        if self.grid {
            let (xi, yj) = (f64::from(i), f64::from(j));
            let mut mask = c.mask;
            for y in GRID_Y {
                let row = mask as u8;
                mask >>= 8;
                if row != 0 {
                    let col = if low_x {
                        row.trailing_zeros()
                    } else {
                        7 - row.leading_zeros()
                    };
                    // Exactly `plane_depth`: the offsets are exact.
                    pick(plane.eval(xi + GRID_X[col as usize], yj + y));
                }
            }
            return z;
        }
        for (k, &pos) in self.pattern.positions().iter().enumerate() {
            if c.mask >> k & 1 == 1 {
                pick(plane_depth(plane, i, j, pos));
            }
        }
        z
    }
}

/// `x_c / 256` of the grid columns and `y_r / 256` of the grid rows
/// (exact in `f64`), as [`plane_depth`] adds them to the pixel corner.
const GRID_X: [f64; 8] = {
    let mut out = [0.0; 8];
    let mut c = 0;
    while c < 8 {
        out[c] = (c as f64 * 32.0 + 16.0) / SUBPIXEL_SCALE as f64;
        c += 1;
    }
    out
};
const GRID_Y: [f64; 4] = {
    let mut out = [0.0; 4];
    let mut r = 0;
    while r < 4 {
        out[r] = (r as f64 * 64.0 + 32.0) / SUBPIXEL_SCALE as f64;
        r += 1;
    }
    out
};

#[cfg(test)]
mod tests {
    use hider_geom::{FixedPt, PlaneEq};
    use hider_scene::ScreenTri;
    use proptest::prelude::*;

    use super::*;
    use crate::pattern::CENTRE;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        /// The bounds from a few evaluations equal the minimum and maximum
        /// of the per-sample depths (and the centre's) computed one by one,
        /// for every pattern, mask and plane (the monotonicity argument of
        /// `DepthBounds`), in both modes.
        #[test]
        fn depth_bounds_equal_the_extremes_of_the_sample_depths(
            plane in (-2.0f64..2.0, -0.5f64..0.5, -0.5f64..0.5, -300.0f64..300.0, -300.0f64..300.0),
            scale in prop_oneof![Just(1e-6f64), Just(1e-3), Just(1.0), Just(1e3)],
            ij in (0u32..2000, 0u32..2000),
            mask in any::<u32>(),
            centre in any::<bool>(),
            full in any::<bool>(),
            pattern_index in 0usize..5,
        ) {
            let plane = PlaneEq {
                x0: plane.3,
                y0: plane.4,
                value: plane.0,
                dx: plane.1 * scale,
                dy: plane.2 * scale,
            };
            let pattern = SamplePattern::ALL[pattern_index];
            let c = if full {
                Coverage { mask: pattern.full_mask(), centre: true, full: true }
            } else {
                Coverage { mask: mask & pattern.full_mask(), centre, full: false }
            };
            let (i, j) = ij;
            let centre_z = plane_depth(&plane, i, j, CENTRE);
            let cz = if c.centre { centre_z } else { f64::INFINITY };
            for hull_for_full in [false, true] {
                let b = DepthBounds::new(&plane, pattern, hull_for_full);
                // Brute force over the covered samples (all of the hull's
                // corners for a full mask in min/max mode) and the centre.
                let mut points: Vec<(i32, i32)> = pattern
                    .positions()
                    .iter()
                    .enumerate()
                    .filter(|(k, _)| c.mask >> k & 1 == 1)
                    .map(|(_, &p)| p)
                    .collect();
                if c.centre {
                    points.push(CENTRE);
                }
                if c.full && hull_for_full {
                    let (x0, y0, x1, y1) = pattern.hull();
                    points.extend([(x0, y0), (x1, y0), (x0, y1), (x1, y1)]);
                }
                let zs: Vec<f64> = points.iter().map(|&p| plane_depth(&plane, i, j, p)).collect();
                let lo = zs.iter().copied().fold(f64::INFINITY, f64::min);
                let hi = zs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                prop_assert_eq!(b.bound(&plane, (i, j), c, cz, false), lo);
                prop_assert_eq!(b.bound(&plane, (i, j), c, cz, true), hi);
                prop_assert_eq!(b.range(&plane, (i, j), c, cz), (lo, hi));
            }
        }
    }

    #[test]
    fn centre_sample_depth_is_the_pixel_centre_depth() {
        let t = ScreenTri {
            v: [
                FixedPt::new(0, 0),
                FixedPt::new(0, 2560),
                FixedPt::new(2560, 0),
            ],
            z: [0.5; 3],
            w: [1.0; 3],
            depth: PlaneEq {
                x0: 0.3,
                y0: 0.7,
                value: 0.25,
                dx: 0.013,
                dy: -0.007,
            },
            inv_w: PlaneEq::constant(1.0),
            prim: 0,
            front_facing: true,
        };
        assert_eq!(plane_depth(&t.depth, 3, 4, CENTRE), t.depth.at_pixel(3, 4));
    }
}
