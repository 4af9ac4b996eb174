//! Point-in-polygon tests from the lecture on image-space hidden-surface
//! algorithms (one of the documents the project started from):
//! the crossing number with the half-open vertex rule, and the winding
//! number by quadrant counting. Both work on integer coordinates, so they
//! are exact; for simple polygons they agree, which the tests check.

/// A point with integer coordinates (e.g. fixed-point window units).
pub type IPoint = (i64, i64);

/// Crossing-number test: cast a ray from `p` towards +x and count the
/// polygon edges it crosses; odd means inside.
///
/// The half-open rule makes vertices on the ray count once: an edge counts
/// when one end point is strictly above the ray's line and the other on or
/// below it (`(a.y > p.y) != (b.y > p.y)`), so an edge ending on the ray is
/// counted for exactly one of its two edges, and horizontal edges never.
pub fn crossing_number_inside(polygon: &[IPoint], p: IPoint) -> bool {
    let n = polygon.len();
    let mut inside = false;
    for i in 0..n {
        let a = polygon[i];
        let b = polygon[(i + 1) % n];
        if (a.1 > p.1) != (b.1 > p.1) {
            // x of the crossing compared to p.x without division:
            // cross_x > p.x  <=>  (b.x - a.x)(p.y - a.y) / (b.y - a.y) + a.x > p.x.
            let lhs = i128::from(b.0 - a.0) * i128::from(p.1 - a.1);
            let rhs = i128::from(p.0 - a.0) * i128::from(b.1 - a.1);
            let right_of_p = if b.1 > a.1 { lhs > rhs } else { lhs < rhs };
            if right_of_p {
                inside = !inside;
            }
        }
    }
    inside
}

/// Winding number of the polygon around `p` by quadrant counting: each
/// vertex is given the quadrant (0..4) it lies in around `p`; stepping to
/// the next vertex adds +1 or -1 quarter turns, and a jump across two
/// quadrants is resolved by which side of `p` the edge passes. The total
/// divided by four is the winding number. The lecture leaves points exactly on
/// the boundary open, and so does this function: test them separately.
pub fn winding_number(polygon: &[IPoint], p: IPoint) -> i32 {
    let quadrant = |q: IPoint| -> i32 {
        let (dx, dy) = (q.0 - p.0, q.1 - p.1);
        match (dx >= 0, dy >= 0) {
            (true, true) => 0,
            (false, true) => 1,
            (false, false) => 2,
            (true, false) => 3,
        }
    };
    let n = polygon.len();
    if n == 0 {
        return 0;
    }
    let mut quarter_turns = 0;
    for i in 0..n {
        let a = polygon[i];
        let b = polygon[(i + 1) % n];
        let (qa, qb) = (quadrant(a), quadrant(b));
        let delta = match (qb - qa).rem_euclid(4) {
            0 => 0,
            1 => 1,
            3 => -1,
            _ => {
                // Diagonal jump: the edge passes either side of p. The sign
                // of the cross product (a - p) x (b - p) says which way.
                let cross = i128::from(a.0 - p.0) * i128::from(b.1 - p.1)
                    - i128::from(a.1 - p.1) * i128::from(b.0 - p.0);
                if cross > 0 { 2 } else { -2 }
            }
        };
        quarter_turns += delta;
    }
    quarter_turns / 4
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn square_inside_and_outside() {
        let sq = [(0, 0), (10, 0), (10, 10), (0, 10)];
        assert!(crossing_number_inside(&sq, (5, 5)));
        assert!(!crossing_number_inside(&sq, (15, 5)));
        assert_eq!(winding_number(&sq, (5, 5)), 1);
        assert_eq!(winding_number(&sq, (-5, 5)), 0);
        let rev: Vec<_> = sq.iter().rev().copied().collect();
        assert_eq!(winding_number(&rev, (5, 5)), -1);
    }

    #[test]
    fn ray_through_a_vertex_counts_once() {
        // The ray from (0, 5) to +x passes exactly through vertex (10, 5).
        let diamond = [(10, 0), (20, 5), (10, 10), (5, 5)];
        assert!(crossing_number_inside(&diamond, (8, 5)));
        assert!(!crossing_number_inside(&diamond, (0, 5)));
        // A spike whose tip touches the ray: 0 or 2 crossings, never 1.
        let spike = [(0, 0), (10, 5), (20, 0), (20, -10), (0, -10)];
        assert!(!crossing_number_inside(&spike, (-5, 5)));
    }

    fn star_shaped() -> impl Strategy<Value = Vec<IPoint>> {
        // Vertices at increasing angles around the origin with random radii:
        // always a simple polygon.
        prop::collection::vec(10i64..1000, 3..12).prop_map(|radii| {
            let n = radii.len();
            radii
                .iter()
                .enumerate()
                .map(|(k, r)| {
                    let a = std::f64::consts::TAU * k as f64 / n as f64;
                    ((*r as f64 * a.cos()) as i64, (*r as f64 * a.sin()) as i64)
                })
                .collect()
        })
    }

    proptest! {
        #[test]
        fn crossing_and_winding_agree_off_the_boundary(poly in star_shaped(), px in -1100i64..1100, py in -1100i64..1100) {
            // Skip points exactly on an edge, where the lecture's two methods
            // make different (both documented) choices.
            let n = poly.len();
            let on_edge = (0..n).any(|i| {
                let a = poly[i];
                let b = poly[(i + 1) % n];
                let cross = (b.0 - a.0) * (py - a.1) - (b.1 - a.1) * (px - a.0);
                cross == 0 && px >= a.0.min(b.0) && px <= a.0.max(b.0) && py >= a.1.min(b.1) && py <= a.1.max(b.1)
            });
            prop_assume!(!on_edge);
            let inside = crossing_number_inside(&poly, (px, py));
            let w = winding_number(&poly, (px, py));
            prop_assert_eq!(inside, w != 0);
        }
    }
}
