//! Robust orientation predicates in `f64`: a fast floating-point answer
//! when it is certainly right, an exact one otherwise.
//!
//! This is Shewchuk's scheme ("Adaptive precision floating-point arithmetic
//! and fast robust geometric predicates", 1997) in its simplest form: the
//! determinant is evaluated in `f64` together with an upper bound on its
//! rounding error; if the value is farther from zero than the bound its sign
//! is returned, else the determinant is recomputed *exactly* with
//! floating-point expansions (sums of non-overlapping `f64`s built from
//! error-free transformations: `two_sum` and an FMA-based `two_product`).
//! The exact path runs only for (nearly) degenerate inputs — shared
//! vertices, coplanar faces — which is exactly where a tolerance would
//! guess.

use glam::DVec3;

/// Half an ulp of 1: the unit roundoff of `f64`.
const EPSILON: f64 = f64::EPSILON * 0.5;

/// Shewchuk's error bound for the floating-point 3x3 determinant of
/// differences: `(7 + 56 eps) eps` times the permanent.
const O3D_ERRBOUND: f64 = (7.0 + 56.0 * EPSILON) * EPSILON;

/// Shewchuk's error bound for the 2x2 determinant: `(3 + 16 eps) eps`.
const O2D_ERRBOUND: f64 = (3.0 + 16.0 * EPSILON) * EPSILON;

/// The sign of the orientation of `d` relative to the plane through `a`,
/// `b`, `c`: the sign of `det[a - d, b - d, c - d]`, positive when `d` lies
/// below the plane seen with `a, b, c` counter-clockwise (Shewchuk's
/// convention). Exact for every finite input.
pub fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> i8 {
    // A repeated point (mesh neighbours share vertices) makes the
    // determinant exactly zero; say so without the exact path.
    if d == a || d == b || d == c || a == b || b == c || a == c {
        return 0;
    }
    let (ad, bd, cd) = (a - d, b - d, c - d);
    let bc = bd.y * cd.z - bd.z * cd.y;
    let ca = cd.y * ad.z - cd.z * ad.y;
    let ab = ad.y * bd.z - ad.z * bd.y;
    let det = ad.x * bc + bd.x * ca + cd.x * ab;
    let permanent = ad.x.abs() * ((bd.y * cd.z).abs() + (bd.z * cd.y).abs())
        + bd.x.abs() * ((cd.y * ad.z).abs() + (cd.z * ad.y).abs())
        + cd.x.abs() * ((ad.y * bd.z).abs() + (ad.z * bd.y).abs());
    if det.abs() > O3D_ERRBOUND * permanent {
        return sign(det);
    }
    orient3d_exact(a, b, c, d)
}

/// The sign of the 2D orientation `det[a - c, b - c]` (positive for a
/// counter-clockwise turn in a y-up frame). Exact for every finite input.
pub fn orient2d(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> i8 {
    let l = (a[0] - c[0]) * (b[1] - c[1]);
    let r = (a[1] - c[1]) * (b[0] - c[0]);
    let det = l - r;
    if det.abs() > O2D_ERRBOUND * (l.abs() + r.abs()) {
        return sign(det);
    }
    orient2d_exact(a, b, c)
}

/// The exact sign of [`orient2d`]'s determinant through expansions (out
/// of line: the filter above settles nearly every call).
#[cold]
#[inline(never)]
fn orient2d_exact(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> i8 {
    let ax = two_diff(a[0], c[0]);
    let ay = two_diff(a[1], c[1]);
    let bx = two_diff(b[0], c[0]);
    let by = two_diff(b[1], c[1]);
    let left: Expansion<8> = mul(&ax, &by);
    let mut right: Expansion<8> = mul(&ay, &bx);
    right.negate();
    expansion_sign(&add::<16>(&left, &right))
}

fn sign(x: f64) -> i8 {
    if x > 0.0 {
        1
    } else if x < 0.0 {
        -1
    } else {
        0
    }
}

/// The exact determinant's sign through expansions (out of line: the
/// filter settles nearly every call).
#[cold]
#[inline(never)]
fn orient3d_exact(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> i8 {
    let diff = |p: DVec3| [two_diff(p.x, d.x), two_diff(p.y, d.y), two_diff(p.z, d.z)];
    let (ad, bd, cd) = (diff(a), diff(b), diff(c));
    let minor = |p: &[[f64; 2]; 3], q: &[[f64; 2]; 3]| -> Expansion<16> {
        // p.y * q.z - p.z * q.y
        let mut right: Expansion<8> = mul(&p[2], &q[1]);
        right.negate();
        add(&mul::<8>(&p[1], &q[2]), &right)
    };
    let bc = minor(&bd, &cd);
    let ca = minor(&cd, &ad);
    let ab = minor(&ad, &bd);
    let left: Expansion<128> = add(&mul::<64>(&ad[0], &bc), &mul::<64>(&bd[0], &ca));
    let det: Expansion<192> = add(&left, &mul::<64>(&cd[0], &ab));
    expansion_sign(&det)
}

/// A floating-point expansion of at most `N` components, on the stack:
/// the exact paths run for every pair of mesh neighbours that are nearly
/// coplanar (the two halves of a UV sphere's quads), and with a heap
/// vector per intermediate result `malloc` and `free` were 43% of `hider
/// analyze gen:sphere:300`. The longest, the 3x3 determinant, has 192.
struct Expansion<const N: usize> {
    len: usize,
    c: [f64; N],
}

impl<const N: usize> Expansion<N> {
    fn new() -> Self {
        Self {
            len: 0,
            c: [0.0; N],
        }
    }

    /// Shewchuk's `grow_expansion` in place: `self + b` exactly.
    fn grow(&mut self, b: f64) {
        let mut q = b;
        let mut w = 0;
        // `w <= i`: each component is read before its slot is written.
        for i in 0..self.len {
            let (s, h) = two_sum(q, self.c[i]);
            if h != 0.0 {
                self.c[w] = h;
                w += 1;
            }
            q = s;
        }
        self.c[w] = q;
        self.len = w + 1;
    }

    fn negate(&mut self) {
        for x in &mut self.c[..self.len] {
            *x = -*x;
        }
    }
}

impl<const N: usize> std::ops::Deref for Expansion<N> {
    type Target = [f64];

    fn deref(&self) -> &[f64] {
        &self.c[..self.len]
    }
}

/// `a - b` exactly, as a two-term expansion (small component first).
fn two_diff(a: f64, b: f64) -> [f64; 2] {
    let (s, e) = two_sum(a, -b);
    [e, s]
}

/// Knuth's error-free sum: `s + e == a + b` exactly, `s = fl(a + b)`.
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bv = s - a;
    let av = s - bv;
    (s, (a - av) + (b - bv))
}

/// Error-free product through the fused multiply-add: `p + e == a * b`.
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// `e + f` exactly (at most `N` components: `e.len() + f.len() <= N`).
fn add<const N: usize>(e: &[f64], f: &[f64]) -> Expansion<N> {
    let mut out = Expansion::new();
    out.c[..e.len()].copy_from_slice(e);
    out.len = e.len();
    for &x in f {
        out.grow(x);
    }
    out
}

/// `e * f` exactly (`2 e.len() f.len() <= N`; `e` of at most 8
/// components).
fn mul<const N: usize>(e: &[f64], f: &[f64]) -> Expansion<N> {
    let mut out = Expansion::new();
    for &x in f {
        // `e * x`, each product's two terms grown in, then added to `out`.
        let mut scaled = Expansion::<16>::new();
        for &y in e {
            let (p, err) = two_product(y, x);
            scaled.grow(err);
            scaled.grow(p);
        }
        for &y in scaled.iter() {
            out.grow(y);
        }
    }
    out
}

/// The sign of an expansion: the sign of its most significant non-zero
/// component, which is the last non-zero one.
fn expansion_sign(e: &[f64]) -> i8 {
    e.iter().rev().find(|x| **x != 0.0).map_or(0, |&x| sign(x))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn exact_i128(a: [i64; 3], b: [i64; 3], c: [i64; 3], d: [i64; 3]) -> i8 {
        let s = |p: [i64; 3]| [0, 1, 2].map(|k| i128::from(p[k] - d[k]));
        let (a, b, c) = (s(a), s(b), s(c));
        let det = a[0] * (b[1] * c[2] - b[2] * c[1])
            + b[0] * (c[1] * a[2] - c[2] * a[1])
            + c[0] * (a[1] * b[2] - a[2] * b[1]);
        det.signum() as i8
    }

    fn v(p: [i64; 3]) -> DVec3 {
        DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64)
    }

    #[test]
    fn nearly_coplanar_points_far_from_the_origin() {
        // Points on the plane x + y + z = 3e15 (exactly representable), and
        // one a single unit off it: the naive determinant is pure noise
        // here, the predicate must still answer exactly.
        let big = 1e15;
        let a = DVec3::new(big, big, big);
        let b = DVec3::new(big + 1.0, big - 1.0, big);
        let c = DVec3::new(big, big + 1.0, big - 1.0);
        assert_eq!(
            orient3d(a, b, c, DVec3::new(big + 3.0, big - 2.0, big - 1.0)),
            0
        );
        let off = orient3d(a, b, c, DVec3::new(big + 3.0, big - 2.0, big));
        let off_other = orient3d(a, b, c, DVec3::new(big + 3.0, big - 2.0, big - 2.0));
        assert_eq!(off, -off_other);
        assert_ne!(off, 0);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        #[test]
        fn matches_exact_integer_arithmetic(
            pts in proptest::array::uniform4(proptest::array::uniform3(-(1i64 << 40)..(1i64 << 40))),
            coplanar in any::<bool>(),
        ) {
            let [a, b, c, mut d] = pts;
            if coplanar {
                // d = a + (b - a) + (c - a): on the plane, exactly.
                d = [0, 1, 2].map(|k| b[k] + c[k] - a[k]);
            }
            prop_assert_eq!(orient3d(v(a), v(b), v(c), v(d)), exact_i128(a, b, c, d));
            let two = |p: [i64; 3]| [p[0] as f64, p[1] as f64];
            let e2 = {
                let (ax, ay) = (i128::from(a[0] - c[0]), i128::from(a[1] - c[1]));
                let (bx, by) = (i128::from(b[0] - c[0]), i128::from(b[1] - c[1]));
                (ax * by - ay * bx).signum() as i8
            };
            prop_assert_eq!(orient2d(two(a), two(b), two(c)), e2);
        }
    }
}
