//! Exact comparison of two triangles' window depths at a pixel centre.
//!
//! What every exact hider compares at a pixel centre is the window depth of
//! each covering triangle: the affine function of window position through
//! the three snapped corners `(x_k, y_k)` (integers in 1/256 pixel) with the
//! window depths `z_k` (`f64`) the front end computed. In barycentric form,
//! at the centre `p` (also an integer point in 1/256 pixel),
//!
//! ```text
//! z(p) = (E_0(p) z_0 + E_1(p) z_1 + E_2(p) z_2) / A
//! ```
//!
//! with `E_k(p)` twice the signed area of the triangle `p, v_{k+1}, v_{k+2}`
//! and `A = E_0 + E_1 + E_2` twice the triangle's area: integers, exact in
//! `i128`. Comparing two triangles `a` and `b` is then the sign of
//!
//! ```text
//! A_b * sum_k E^a_k z^a_k  -  A_a * sum_k E^b_k z^b_k
//! ```
//!
//! a sum of six products of an integer (`< 2^128`) and an `f64`. Each
//! product is an integer times a power of two, so the sum is computed
//! exactly in a fixed-point big integer with `2^-1074` (the smallest
//! subnormal) as its unit ([`Big`]).
//!
//! That is slow, so a filter decides first: at a covered centre every
//! `E_k >= 0`, and with `z_k >= 0` the `f64` estimate
//! `sum(E_k as f64 * z_k) / A` has no cancellation; its relative error is at
//! most `7 u` (`u = 2^-53`: three conversions or products, two sums, the
//! conversion of `A` and the division each contribute at most one rounding
//! of relative size `u`). When the two estimates differ by more than
//! [`FILTER`] (`2^-46`, about `18 u`) of the larger one, their order is the
//! exact order; otherwise the exact sum decides.

use std::cmp::Ordering;

use hider_geom::fixed::FixedPt;
use hider_scene::ScreenTri;

/// Relative difference of two filter estimates above which their order is
/// certain: `2^-46`, above the `2 x 7 u = 14 u` two estimates can err by
/// together (see the module documentation).
pub(crate) const FILTER: f64 = 1.0 / (1u64 << 46) as f64;

/// Smallest estimate the relative filter is trusted for: below it products
/// with subnormal depths lose relative precision, so the exact sum decides.
const FILTER_FLOOR: f64 = 1e-290;

/// A triangle's window depth at one pixel centre: the unnormalised
/// barycentric weights, twice the area and the `f64` estimate.
#[derive(Clone, Copy, Debug)]
pub(crate) struct DepthAt {
    weights: [i128; 3],
    area: i128,
    z: [f64; 3],
    /// `sum(weights[k] * z[k]) / area` in `f64` (see [`FILTER`]).
    pub(crate) estimate: f64,
}

fn orient(a: FixedPt, b: FixedPt, c: (i64, i64)) -> i128 {
    let (ax, ay) = (i128::from(a.x), i128::from(a.y));
    (i128::from(b.x) - ax) * (i128::from(c.1) - ay)
        - (i128::from(b.y) - ay) * (i128::from(c.0) - ax)
}

impl DepthAt {
    /// `tri`'s window depth at the fixed-point sample `(x, y)`.
    pub(crate) fn new(tri: &ScreenTri, x: i64, y: i64) -> Self {
        let v = tri.v;
        let p = (x, y);
        let weights = [
            orient(v[1], v[2], p),
            orient(v[2], v[0], p),
            orient(v[0], v[1], p),
        ];
        let area = weights[0] + weights[1] + weights[2];
        let sum: f64 = (0..3).map(|k| weights[k] as f64 * tri.z[k]).sum();
        Self {
            weights,
            area,
            z: tri.z,
            estimate: sum / area as f64,
        }
    }

    /// Whether the filter's error bound holds: non-negative weights and
    /// depths, a positive area.
    fn filterable(&self) -> bool {
        self.area > 0 && self.weights.iter().all(|&w| w >= 0) && self.z.iter().all(|&z| z >= 0.0)
    }

    /// The filter key: the estimate where the filter's bound holds, NaN
    /// (never decided by [`filter`]) elsewhere.
    pub(crate) fn key(&self) -> f64 {
        if self.filterable() {
            self.estimate
        } else {
            f64::NAN
        }
    }
}

/// The order of two filter keys when the filter can decide it: keys are
/// [`DepthAt::key`]s (estimates, NaN where the filter's bound does not
/// hold).
pub(crate) fn filter(ka: f64, kb: f64) -> Option<Ordering> {
    let m = ka.max(kb);
    (m > FILTER_FLOOR && (ka - kb).abs() > FILTER * m).then(|| ka.total_cmp(&kb))
}

/// The exact order of the two window depths (`Less`: `a` is nearer).
/// Non-finite depths (a hand-built scene) compare by their estimates.
pub(crate) fn compare(a: &DepthAt, b: &DepthAt) -> Ordering {
    filter(a.key(), b.key()).unwrap_or_else(|| compare_exactly(a, b))
}

/// [`compare`] without the filter.
pub(crate) fn compare_exactly(a: &DepthAt, b: &DepthAt) -> Ordering {
    exact(a, b).unwrap_or_else(|| {
        a.estimate
            .partial_cmp(&b.estimate)
            .unwrap_or(Ordering::Equal)
    })
}

/// Whether [`compare`] needs the exact sum for these two.
#[cfg(test)]
pub(crate) fn needs_exact(a: &DepthAt, b: &DepthAt) -> bool {
    filter(a.key(), b.key()).is_none()
}

/// The exact sign of `A_b * sum E^a z^a - A_a * sum E^b z^b` (see the
/// module documentation), or `None` for a non-finite depth or an
/// intermediate beyond `u128`.
fn exact(a: &DepthAt, b: &DepthAt) -> Option<Ordering> {
    // z_a - z_b has the sign of `sum_k E^a_k |A_b| sgn(A_a) z^a_k - (the
    // same for b)`: both areas are positive for a set-up triangle, and a
    // negative one flips the sense of its own terms.
    let (mut left, mut right) = (Big::ZERO, Big::ZERO);
    for (d, other_area, mine_left) in [(a, b.area, true), (b, a.area, false)] {
        if other_area == 0 || d.area == 0 {
            return None;
        }
        for k in 0..3 {
            let z = d.z[k];
            if !z.is_finite() {
                return None;
            }
            if z == 0.0 || d.weights[k] == 0 {
                continue;
            }
            let c = d.weights[k].checked_mul(other_area.abs())?;
            // Positive when the term adds to its own side.
            let positive = ((c > 0) == (z > 0.0)) == (d.area > 0);
            let onto_left = positive == mine_left;
            let (mantissa, shift) = decompose(z.abs());
            let target = if onto_left { &mut left } else { &mut right };
            target.add_product(c.unsigned_abs(), mantissa, shift)?;
        }
    }
    Some(left.cmp(&right))
}

/// `x = mantissa * 2^(shift - 1074)` for a finite non-negative `x`.
fn decompose(x: f64) -> (u64, u32) {
    let bits = x.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as u32;
    let fraction = bits & ((1u64 << 52) - 1);
    if exponent == 0 {
        (fraction, 0)
    } else {
        (fraction | (1u64 << 52), exponent - 1)
    }
}

/// A bound on the error of evaluating `tri`'s window-depth plane in `f64`
/// at the centre of pixel `(i, j)` as the hiders do
/// (`tri.depth.at_pixel(i, j)`, `PlaneEq::eval` on the coefficients
/// `PlaneEq::from_points` rounded).
///
/// With `u = 2^-53`, `M_x = (|d_1 y_2| + |d_2 y_1|) / |det|` and `M_y`
/// likewise (the sizes of the terms of `dx` and `dy`), the coefficients
/// are off by at most `4 u M_x` and `4 u M_y` (one rounding each in
/// `z_k - z_0`, the product, the difference and the division; `det` and
/// the position differences are exact for 1/256-pixel positions), and the
/// evaluation `value + dx Δx + dy Δy` adds at most `3 u` of
/// `|value| + |dx Δx| + |dy Δy|`. The bound returned is twice the first-order
/// sum, `8 u (|value| + (|dx| + M_x)|Δx| + (|dy| + M_y)|Δy|)`, which covers
/// the second-order terms and the rounding of computing it.
pub fn plane_rounding_bound(tri: &ScreenTri, i: u32, j: u32) -> f64 {
    let p = tri.v.map(|q| q.to_pixels());
    let (x1, y1) = (p[1].0 - p[0].0, p[1].1 - p[0].1);
    let (x2, y2) = (p[2].0 - p[0].0, p[2].1 - p[0].1);
    let det = (x1 * y2 - x2 * y1).abs();
    let (d1, d2) = ((tri.z[1] - tri.z[0]).abs(), (tri.z[2] - tri.z[0]).abs());
    let (mx, my) = if det > 0.0 {
        (
            (d1 * y2.abs() + d2 * y1.abs()) / det,
            (x1.abs() * d2 + x2.abs() * d1) / det,
        )
    } else {
        (0.0, 0.0)
    };
    let plane = &tri.depth;
    let ex = (f64::from(i) + 0.5 - plane.x0).abs();
    let ey = (f64::from(j) + 0.5 - plane.y0).abs();
    let u = f64::EPSILON / 2.0;
    8.0 * u * (plane.value.abs() + (plane.dx.abs() + mx) * ex + (plane.dy.abs() + my) * ey)
}

/// Limbs of [`Big`]: the largest term is below `2^128 * 2^53 * 2^2045`, six
/// of them below `2^2229`.
const LIMBS: usize = 36;

/// A non-negative fixed-point number in units of `2^-1074`, little-endian
/// 64-bit limbs.
#[derive(Clone, Copy, PartialEq, Eq)]
struct Big([u64; LIMBS]);

impl Big {
    const ZERO: Self = Self([0; LIMBS]);

    /// Adds `c * m * 2^shift`; `None` on overflow (impossible for finite
    /// depths, see [`LIMBS`]).
    fn add_product(&mut self, c: u128, m: u64, shift: u32) -> Option<()> {
        // c * m in three limbs.
        let lo = (c as u64 as u128) * u128::from(m);
        let hi = (c >> 64) * u128::from(m);
        let l0 = lo as u64;
        let mid = (lo >> 64) + (hi as u64 as u128);
        let l1 = mid as u64;
        let l2 = ((mid >> 64) + (hi >> 64)) as u64;
        // Shift by `shift` bits into four limbs.
        let (offset, bit) = ((shift / 64) as usize, shift % 64);
        let limbs = if bit == 0 {
            [l0, l1, l2, 0]
        } else {
            [
                l0 << bit,
                (l1 << bit) | (l0 >> (64 - bit)),
                (l2 << bit) | (l1 >> (64 - bit)),
                l2 >> (64 - bit),
            ]
        };
        let mut carry = 0u64;
        for (k, limb) in self.0.iter_mut().enumerate().skip(offset) {
            let add = limbs.get(k - offset).copied().unwrap_or(0);
            if add == 0 && carry == 0 && k >= offset + 4 {
                return Some(());
            }
            let (s, o1) = limb.overflowing_add(add);
            let (s, o2) = s.overflowing_add(carry);
            *limb = s;
            carry = u64::from(o1) + u64::from(o2);
        }
        (carry == 0).then_some(())
    }
}

impl PartialOrd for Big {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Big {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.iter().rev().cmp(other.0.iter().rev())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_geom::plane::PlaneEq;

    fn tri(v: [(i32, i32); 3], z: [f64; 3]) -> ScreenTri {
        let v = v.map(|(x, y)| FixedPt::new(x, y));
        ScreenTri {
            v,
            z,
            w: [1.0; 3],
            depth: PlaneEq::from_points(&v, z).unwrap(),
            inv_w: PlaneEq::constant(1.0),
            prim: 0,
            front_facing: true,
        }
    }

    #[test]
    fn big_adds_and_orders_exactly() {
        let (mut a, mut b) = (Big::ZERO, Big::ZERO);
        a.add_product(u128::MAX, u64::MAX, 2000).unwrap();
        b.add_product(u128::MAX, u64::MAX, 1999).unwrap();
        b.add_product(u128::MAX, u64::MAX, 1999).unwrap();
        assert_eq!(a.cmp(&b), Ordering::Equal);
        b.add_product(1, 1, 0).unwrap();
        assert_eq!(a.cmp(&b), Ordering::Less);
        assert_eq!(decompose(1.0), (1 << 52, 1022));
        assert_eq!(decompose(f64::from_bits(1)), (1, 0));
    }

    #[test]
    fn equal_planes_tie_and_one_ulp_does_not() {
        let big = [(0, 0), (4096, 0), (0, 4096)];
        let other = [(0, 0), (4096, 4096), (0, 4096)];
        // Two different triangles on the same tilted plane z = 0.25 + x/2^14.
        let z = |(x, _y): (i32, i32)| 0.25 + f64::from(x) / 16384.0;
        let a = tri(big, big.map(z));
        let b = tri(other, other.map(z));
        let (x, y) = (1000, 3000);
        let (da, db) = (DepthAt::new(&a, x, y), DepthAt::new(&b, x, y));
        assert_eq!(compare(&da, &db), Ordering::Equal);
        assert!(needs_exact(&da, &db));
        // Move one corner of b one ulp nearer: b is nearer everywhere it
        // has weight.
        let mut zb = other.map(z);
        zb[1] = f64::from_bits(zb[1].to_bits() - 1);
        let b = tri(other, zb);
        let db = DepthAt::new(&b, x, y);
        assert_eq!(compare(&da, &db), Ordering::Greater);
        assert_eq!(compare(&db, &da), Ordering::Less);
    }

    #[test]
    fn filter_decides_clear_cases() {
        let v = [(0, 0), (4096, 0), (0, 4096)];
        let a = DepthAt::new(&tri(v, [0.5; 3]), 100, 100);
        let b = DepthAt::new(&tri(v, [0.5005; 3]), 100, 100);
        assert!(!needs_exact(&a, &b));
        assert_eq!(compare(&a, &b), Ordering::Less);
    }

    proptest::proptest! {
        /// On depths that are multiples of 2^-20 the comparison is integer
        /// arithmetic in i128: the filter and the big sum must agree with it.
        #[test]
        fn agrees_with_integer_arithmetic_on_dyadic_depths(
            va in proptest::array::uniform3((0i32..2048, 0i32..2048)),
            vb in proptest::array::uniform3((0i32..2048, 0i32..2048)),
            za in proptest::array::uniform3(0u32..(1 << 20)),
            zb in proptest::array::uniform3(0u32..(1 << 20)),
            same in proptest::bool::ANY,
            (x, y) in (0i64..2048, 0i64..2048),
        ) {
            let orient = |v: [(i32, i32); 3]| {
                let p = v.map(|(x, y)| FixedPt::new(x, y));
                hider_geom::orient2d(p[0], p[1], p[2])
            };
            let fix = |v: [(i32, i32); 3]| if orient(v) < 0 { [v[0], v[2], v[1]] } else { v };
            let (va, vb) = (fix(va), fix(vb));
            proptest::prop_assume!(orient(va) > 0 && orient(vb) > 0);
            // Same depths (a possible exact tie on the same plane) or not.
            let zb = if same { za } else { zb };
            let scale = (1u64 << 20) as f64;
            let a = tri(va, za.map(|z| f64::from(z) / scale));
            let b = tri(if same { va } else { vb }, zb.map(|z| f64::from(z) / scale));
            let (da, db) = (DepthAt::new(&a, x, y), DepthAt::new(&b, x, y));
            let num = |d: &DepthAt, z: [u32; 3]| (0..3).map(|k| d.weights[k] * i128::from(z[k])).sum::<i128>();
            let want = (num(&da, za) * db.area).cmp(&(num(&db, zb) * da.area));
            proptest::prop_assert_eq!(compare(&da, &db), want);
        }
    }
}
