//! A triangle's occluders decided without a boolean when their union
//! either covers it entirely or misses its interior.
//!
//! Across an edge shared by two occluders in opposite directions (the
//! common edge of two mesh neighbours, both positively oriented) the number
//! of occluders covering a point does not change; it changes only across
//! the other, *unmatched* edges. So when no unmatched edge meets the open
//! polygon, the count is the same all over its interior, and one interior
//! point tells whether the polygon is buried or untouched. This is what
//! happens to most hidden triangles of a closed mesh (the back faces,
//! behind a patch of front faces whose inner edges all match), and it
//! costs a few exact orientation tests instead of a polygon boolean.

use i_overlay::i_float::int::point::IntPoint;

/// What the occluders do to a polygon, when it can be decided cheaply.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cover {
    /// Every point of the polygon is under some occluder.
    Buried,
    /// No occluder meets the polygon's interior.
    Clear,
}

/// A grid point in `i64`.
pub type P = (i64, i64);

fn p(v: IntPoint) -> P {
    (i64::from(v.x), i64::from(v.y))
}

/// The sign of the turn `a -> b -> c`, exact.
fn orient(a: P, b: P, c: P) -> i32 {
    let d = i128::from(b.0 - a.0) * i128::from(c.1 - a.1)
        - i128::from(b.1 - a.1) * i128::from(c.0 - a.0);
    d.signum() as i32
}

/// Twice the signed area (positive counter-clockwise, the way `i_overlay`
/// writes outer contours), exact.
pub(crate) fn signed_area2(poly: &[IntPoint]) -> i128 {
    let n = poly.len();
    (0..n)
        .map(|k| {
            let (a, b) = (p(poly[k]), p(poly[(k + 1) % n]));
            i128::from(a.0) * i128::from(b.1) - i128::from(b.0) * i128::from(a.1)
        })
        .sum()
}

/// The directed edges of `occluders` (convex, positively oriented) that
/// are not cancelled by an opposite copy: `k` copies of `a -> b` and `m`
/// of `b -> a` leave `k - m` of the first (or `m - k` of the second). The
/// winding number of every point is the same for these edges as for the
/// occluders, so they bound the same union. `None` when an occluder is
/// not positively oriented.
pub fn unmatched_edges(occluders: &[Vec<IntPoint>]) -> Option<Vec<(P, P)>> {
    // One integer key per undirected edge (the grid stays within 2^29, so
    // four non-negative coordinates pack into 128 bits) and its direction.
    let mut keys: Vec<(u128, bool)> = Vec::with_capacity(occluders.len() * 3);
    for o in occluders {
        if signed_area2(o) <= 0 {
            return None;
        }
        let n = o.len();
        keys.extend((0..n).map(|k| {
            let (a, b) = (o[k], o[(k + 1) % n]);
            let forward = (a.x, a.y) <= (b.x, b.y);
            let (lo, hi) = if forward { (a, b) } else { (b, a) };
            let key = [lo.x, lo.y, hi.x, hi.y]
                .iter()
                .fold(0u128, |key, &v| (key << 32) | u128::from(v as u32));
            (key, forward)
        }));
    }
    keys.sort_unstable();
    let unpack = |key: u128, shift: u32| i64::from((key >> shift) as u32 as i32);
    let mut out = Vec::new();
    let mut k = 0;
    while k < keys.len() {
        let key = keys[k].0;
        let mut j = k + 1;
        while j < keys.len() && keys[j].0 == key {
            j += 1;
        }
        let forward = keys[k..j].iter().filter(|e| e.1).count();
        let backward = (j - k) - forward;
        let lo = (unpack(key, 96), unpack(key, 64));
        let hi = (unpack(key, 32), unpack(key, 0));
        let (edge, copies) = if forward >= backward {
            ((lo, hi), forward - backward)
        } else {
            ((hi, lo), backward - forward)
        };
        out.extend(std::iter::repeat_n(edge, copies));
        k = j;
    }
    Some(out)
}

/// Decides `polygon` (convex, positively oriented, at least three
/// vertices) against `occluders` (convex, positively oriented, with
/// `unmatched` their [`unmatched_edges`]) when no unmatched edge meets the
/// polygon's interior; `None` otherwise.
pub fn decide(
    polygon: &[IntPoint],
    unmatched: &[(P, P)],
    occluders: &[Vec<IntPoint>],
) -> Option<Cover> {
    if signed_area2(polygon) <= 0 {
        return None;
    }
    let crossing = unmatched
        .iter()
        .filter(|&&e| meets_interior(polygon, e))
        .count();
    let inside = interior_point(polygon)?;
    // How many occluders hold the point, on their closed or open side.
    let holding = |strict: bool| {
        occluders
            .iter()
            .filter(|o| {
                let n = o.len();
                (0..n).all(|k| {
                    let (a, b) = (p(o[k]), p(o[(k + 1) % n]));
                    let side = orient((3 * a.0, 3 * a.1), (3 * b.0, 3 * b.1), inside);
                    if strict { side > 0 } else { side >= 0 }
                })
            })
            .count()
    };
    if crossing == 0 {
        return Some(if holding(false) > 0 {
            Cover::Buried
        } else {
            Cover::Clear
        });
    }
    // From the point to any other point of the convex polygon a straight
    // path crosses each unmatched edge at most once, and only those
    // crossings lower the count: more occluders over the point than
    // unmatched edges across the polygon leave none of it uncovered.
    (holding(true) > crossing).then_some(Cover::Buried)
}

/// The unmatched edges chained into closed loops (every point has as many
/// edges out as in, so every walk closes): contours with the occluders'
/// winding numbers and far fewer edges when the occluders are a mesh
/// patch.
pub fn loops(unmatched: &[(P, P)]) -> Vec<Vec<IntPoint>> {
    let mut from: std::collections::HashMap<P, Vec<usize>> = std::collections::HashMap::new();
    for (k, e) in unmatched.iter().enumerate() {
        from.entry(e.0).or_default().push(k);
    }
    let mut used = vec![false; unmatched.len()];
    let mut out = Vec::new();
    for start in 0..unmatched.len() {
        if used[start] {
            continue;
        }
        let mut contour = Vec::new();
        let mut k = start;
        loop {
            used[k] = true;
            let (a, b) = unmatched[k];
            contour.push(IntPoint::new(a.0 as i32, a.1 as i32));
            let next = from
                .get(&b)
                .and_then(|list| list.iter().copied().find(|&j| !used[j]));
            match next {
                Some(j) => k = j,
                None => break,
            }
        }
        out.push(contour);
    }
    out
}

/// Whether segment `e` meets the open convex `polygon`: not separated by
/// a polygon edge (both ends on its closed outer side) nor by the
/// segment's own line (all vertices on one closed side).
fn meets_interior(polygon: &[IntPoint], e: (P, P)) -> bool {
    let n = polygon.len();
    let by_edge = (0..n).any(|k| {
        let (a, b) = (p(polygon[k]), p(polygon[(k + 1) % n]));
        orient(a, b, e.0) <= 0 && orient(a, b, e.1) <= 0
    });
    if by_edge {
        return false;
    }
    let sides: Vec<i32> = polygon.iter().map(|&v| orient(e.0, e.1, p(v))).collect();
    !(sides.iter().all(|&s| s >= 0) || sides.iter().all(|&s| s <= 0))
}

/// Three times a point strictly inside the convex polygon: the centroid of
/// a fan triangle of positive area.
fn interior_point(polygon: &[IntPoint]) -> Option<P> {
    let v0 = p(polygon[0]);
    (1..polygon.len() - 1).find_map(|k| {
        let (a, b) = (p(polygon[k]), p(polygon[k + 1]));
        (orient(v0, a, b) > 0).then_some((v0.0 + a.0 + b.0, v0.1 + a.1 + b.1))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly(points: &[(i32, i32)]) -> Vec<IntPoint> {
        points.iter().map(|&(x, y)| IntPoint::new(x, y)).collect()
    }

    /// Two triangles sharing a diagonal: a square.
    fn square(offset: i32) -> Vec<Vec<IntPoint>> {
        let o = offset;
        vec![
            poly(&[(o, o), (o + 10, o), (o + 10, o + 10)]),
            poly(&[(o, o), (o + 10, o + 10), (o, o + 10)]),
        ]
    }

    #[test]
    fn a_triangle_under_two_neighbours_is_buried() {
        let t = poly(&[(2, 1), (8, 2), (5, 8)]);
        assert_eq!(
            decide(&t, &unmatched_edges(&square(0)).unwrap(), &square(0)),
            Some(Cover::Buried)
        );
    }

    #[test]
    fn occluders_off_the_interior_leave_it_clear() {
        let t = poly(&[(2, 1), (8, 2), (5, 8)]);
        assert_eq!(
            decide(&t, &unmatched_edges(&square(100)).unwrap(), &square(100)),
            Some(Cover::Clear)
        );
        // Touching along an edge only is still clear.
        let below = vec![poly(&[(0, -5), (10, -5), (10, 1), (0, 1)])];
        let t = poly(&[(0, 1), (10, 1), (5, 8)]);
        assert_eq!(
            decide(&t, &unmatched_edges(&below).unwrap(), &below),
            Some(Cover::Clear)
        );
    }

    #[test]
    fn more_layers_than_edges_across_bury_the_polygon() {
        let t = poly(&[(2, 1), (8, 2), (5, 8)]);
        // A square and half of another: the half's diagonal crosses the
        // triangle, but two layers lie over its interior point.
        let mut occluders = square(0);
        occluders.push(square(0).remove(0));
        let edges = unmatched_edges(&occluders).unwrap();
        assert_eq!(edges.iter().filter(|&&e| meets_interior(&t, e)).count(), 1);
        assert_eq!(decide(&t, &edges, &occluders), Some(Cover::Buried));
    }

    #[test]
    fn an_unmatched_edge_across_the_interior_needs_the_boolean() {
        let t = poly(&[(2, 1), (8, 2), (5, 8)]);
        let half = vec![square(0).remove(0)];
        assert_eq!(decide(&t, &unmatched_edges(&half).unwrap(), &half), None);
    }
}
