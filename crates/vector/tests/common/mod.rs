//! Measures shared by the integration tests.

use std::iter::Sum;

use i_overlay::i_float::int::point::IntPoint;
use i_overlay::i_shape::int::shape::IntShapes;

/// `f` of every edge `(a, b)` of every contour of `shapes`, the closing
/// edge included, summed per contour and then over the contours (the
/// order matters for a float sum).
pub fn edge_sum<T: Sum>(shapes: &IntShapes<i32>, f: impl Fn(IntPoint, IntPoint) -> T) -> T {
    shapes
        .iter()
        .flatten()
        .map(|c| {
            (0..c.len())
                .map(|k| f(c[k], c[(k + 1) % c.len()]))
                .sum::<T>()
        })
        .sum()
}

/// Twice the signed area of a polygon set (outer contours positive, holes
/// negative), exact in `i128`: grid coordinates reach 2^29, so one cross
/// product takes up to 59 bits and a sum of them can overflow `i64`.
pub fn area2(shapes: &IntShapes<i32>) -> i128 {
    edge_sum(shapes, |a, b| {
        i128::from(a.x) * i128::from(b.y) - i128::from(b.x) * i128::from(a.y)
    })
}
