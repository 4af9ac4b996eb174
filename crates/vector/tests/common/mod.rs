//! Measures shared by the integration tests.

use i_overlay::i_shape::int::shape::IntShapes;

/// Twice the signed area of a polygon set (outer contours positive, holes
/// negative), exact in `i128`: grid coordinates reach 2^29, so one cross
/// product takes up to 59 bits and a sum of them can overflow `i64`.
pub fn area2(shapes: &IntShapes) -> i128 {
    shapes
        .iter()
        .flatten()
        .map(|c| {
            (0..c.len())
                .map(|k| {
                    let (a, b) = (c[k], c[(k + 1) % c.len()]);
                    i128::from(a.x) * i128::from(b.y) - i128::from(b.x) * i128::from(a.y)
                })
                .sum::<i128>()
        })
        .sum()
}
