//! The hot pixels of snap rounding, indexed so that an edge finds the ones
//! it passes through at a cost that follows where they are, not how long
//! the edge is.
//!
//! A uniform grid of cells sized for the hot points makes a long edge walk
//! `length / cell` cells, about `sqrt(H)` for `H` hot points spread over
//! the image: on a fan (a disc's triangulation, hot points on its rim
//! only) `N` spokes walk `N^1.5` cells, nearly all empty. A point
//! quadtree (Finkel and Bentley, "Quad trees", 1974) whose leaves hold a
//! few points each and whose nodes keep their points' tight box leaves
//! empty space in a few large nodes: an edge descends only into the nodes
//! whose box, widened by the half unit of a hot pixel, it meets, decided
//! exactly (a separating-axis test in doubled integer coordinates).

use i_overlay::i_float::int::point::IntPoint;

use crate::sweep::orient;

/// Points per leaf.
const LEAF: usize = 8;

/// A node: the tight box of its points, doubled and widened by one (the
/// half unit of a hot pixel), and either its children or its points.
struct Node {
    lo: IntPoint,
    hi: IntPoint,
    /// Children's indices, or `None` for a leaf.
    children: Option<Vec<u32>>,
    /// The leaf's points in [`HotPixels::points`].
    range: (u32, u32),
}

/// Hot pixel centres in a point quadtree.
pub struct HotPixels {
    nodes: Vec<Node>,
    points: Vec<IntPoint>,
}

impl HotPixels {
    /// The index of `points` (grid coordinates within `2^29`).
    pub fn new(points: &[IntPoint]) -> Self {
        let mut index = Self {
            nodes: Vec::new(),
            points: points.to_vec(),
        };
        if !points.is_empty() {
            index.build(0, points.len());
        }
        index
    }

    /// Builds the node of `points[start..end]`, returning its index.
    fn build(&mut self, start: usize, end: usize) -> u32 {
        let part = &mut self.points[start..end];
        let (lo, hi) = part.iter().fold(
            (
                IntPoint::new(i32::MAX, i32::MAX),
                IntPoint::new(i32::MIN, i32::MIN),
            ),
            |(lo, hi), p| {
                (
                    IntPoint::new(lo.x.min(p.x), lo.y.min(p.y)),
                    IntPoint::new(hi.x.max(p.x), hi.y.max(p.y)),
                )
            },
        );
        let k = self.nodes.len();
        self.nodes.push(Node {
            lo: IntPoint::new(2 * lo.x - 1, 2 * lo.y - 1),
            hi: IntPoint::new(2 * hi.x + 1, 2 * hi.y + 1),
            children: None,
            range: (start as u32, end as u32),
        });
        if part.len() <= LEAF || lo == hi {
            return k as u32;
        }
        // Quadrants about the box's middle; a box one unit wide in some
        // axis still halves in the other, or at the unit itself.
        let (mx, my) = (lo.x + ((hi.x - lo.x) >> 1), lo.y + ((hi.y - lo.y) >> 1));
        part.sort_unstable_by_key(|p| (p.x > mx, p.y > my));
        let mut children = Vec::with_capacity(4);
        let mut from = 0;
        for quadrant in [(false, false), (false, true), (true, false), (true, true)] {
            let to = from + part[from..].partition_point(|p| (p.x > mx, p.y > my) <= quadrant);
            if to > from {
                children.push((start + from, start + to));
            }
            from = to;
            if from == part.len() {
                break;
            }
        }
        let children = children
            .into_iter()
            .map(|(s, e)| self.build(s, e))
            .collect();
        self.nodes[k].children = Some(children);
        k as u32
    }

    /// The hot pixel centres strictly between `a` and `b` that the segment
    /// passes through (closed unit square around each centre), in order
    /// from `a`; `None` when there are none. Adds the quadtree nodes
    /// visited to `visited`.
    pub fn chain(&self, a: IntPoint, b: IntPoint, visited: &mut u64) -> Option<Vec<IntPoint>> {
        if self.nodes.is_empty() {
            return None;
        }
        // Doubled coordinates put the squares' corners on integers.
        let (a2, b2) = (double(a), double(b));
        let (lo, hi) = (
            IntPoint::new(a2.x.min(b2.x), a2.y.min(b2.y)),
            IntPoint::new(a2.x.max(b2.x), a2.y.max(b2.y)),
        );
        let mut found: Vec<(i128, IntPoint)> = Vec::new();
        let mut stack = vec![0u32];
        while let Some(k) = stack.pop() {
            *visited += 1;
            let node = &self.nodes[k as usize];
            if !meets(a2, b2, (lo, hi), (node.lo, node.hi)) {
                continue;
            }
            if let Some(children) = &node.children {
                stack.extend(children);
                continue;
            }
            for &h in &self.points[node.range.0 as usize..node.range.1 as usize] {
                if h == a || h == b {
                    continue;
                }
                let h2 = double(h);
                if !meets(
                    a2,
                    b2,
                    (lo, hi),
                    (
                        IntPoint::new(h2.x - 1, h2.y - 1),
                        IntPoint::new(h2.x + 1, h2.y + 1),
                    ),
                ) {
                    continue;
                }
                let t = i128::from(h.x - a.x) * i128::from(b.x - a.x)
                    + i128::from(h.y - a.y) * i128::from(b.y - a.y);
                found.push((t, h));
            }
        }
        if found.is_empty() {
            return None;
        }
        found.sort_unstable_by_key(|&(t, h)| (t, h.x, h.y));
        Some(found.into_iter().map(|(_, h)| h).collect())
    }
}

/// Whether the segment `a -> b` (with box `(lo, hi)`) meets the closed
/// box `(blo, bhi)`: the boxes overlap and the box's corners are not all
/// strictly on one side of the segment's line (the separating axes of a
/// segment and a box).
fn meets(
    a: IntPoint,
    b: IntPoint,
    (lo, hi): (IntPoint, IntPoint),
    (blo, bhi): (IntPoint, IntPoint),
) -> bool {
    if hi.x < blo.x || lo.x > bhi.x || hi.y < blo.y || lo.y > bhi.y {
        return false;
    }
    let sides = [
        (blo.x, blo.y),
        (bhi.x, blo.y),
        (bhi.x, bhi.y),
        (blo.x, bhi.y),
    ]
    .map(|(x, y)| orient(a, b, IntPoint::new(x, y)));
    !(sides.iter().all(|&s| s > 0) || sides.iter().all(|&s| s < 0))
}

/// A point with both coordinates doubled (the grid stays within 2^29, so
/// this fits in `i32`).
fn double(p: IntPoint) -> IntPoint {
    IntPoint::new(2 * p.x, 2 * p.y)
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    /// The hot pixels `a -> b` passes, by testing every hot pixel.
    fn every_pixel(hot: &[IntPoint], a: IntPoint, b: IntPoint) -> Option<Vec<IntPoint>> {
        let (a2, b2) = (double(a), double(b));
        let mut found: Vec<(i128, IntPoint)> = hot
            .iter()
            .filter(|&&h| h != a && h != b)
            .filter(|&&h| {
                let h2 = double(h);
                let sides = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
                    .map(|(dx, dy)| orient(a2, b2, IntPoint::new(h2.x + dx, h2.y + dy)));
                let box_ok = h.x >= a.x.min(b.x)
                    && h.x <= a.x.max(b.x)
                    && h.y >= a.y.min(b.y)
                    && h.y <= a.y.max(b.y);
                box_ok && !(sides.iter().all(|&s| s > 0) || sides.iter().all(|&s| s < 0))
            })
            .map(|&h| {
                let t = i128::from(h.x - a.x) * i128::from(b.x - a.x)
                    + i128::from(h.y - a.y) * i128::from(b.y - a.y);
                (t, h)
            })
            .collect();
        found.sort_unstable_by_key(|&(t, h)| (t, h.x, h.y));
        (!found.is_empty()).then(|| found.into_iter().map(|(_, h)| h).collect())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// The quadtree finds the hot pixels testing them all finds
        /// (the test the uniform bins made), squares touched at a side
        /// or a corner included: on a fine lattice many squares' sides
        /// lie on nodes' sides.
        #[test]
        fn the_quadtree_finds_every_hot_pixel(
            points in prop::collection::vec((0i32..40, 0i32..40), 2..150),
            ends in prop::collection::vec((0usize..1000, 0usize..1000), 1..30),
            scale in prop_oneof![Just(1), Just(2), Just(7), Just(1 << 20)],
        ) {
            let mut hot: Vec<IntPoint> =
                points.iter().map(|&(x, y)| IntPoint::new(x * scale, y * scale)).collect();
            hot.sort_unstable_by_key(|p| (p.x, p.y));
            hot.dedup();
            let index = HotPixels::new(&hot);
            for (i, j) in ends {
                let (a, b) = (hot[i % hot.len()], hot[j % hot.len()]);
                if a == b {
                    continue;
                }
                let mut visited = 0;
                prop_assert_eq!(index.chain(a, b, &mut visited), every_pixel(&hot, a, b));
            }
        }
    }

    #[test]
    fn a_spoke_of_a_fan_visits_few_nodes() {
        // Hot points on a circle (a fan's rim) and its centre: a spoke
        // crosses the empty inside in a few large nodes.
        let n: u32 = 4_000;
        let r = 1e6;
        let mut hot: Vec<IntPoint> = (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * f64::from(k) / f64::from(n);
                IntPoint::new((r + r * a.cos()) as i32, (r + r * a.sin()) as i32)
            })
            .collect();
        let centre = IntPoint::new(r as i32, r as i32);
        hot.push(centre);
        let index = HotPixels::new(&hot);
        let mut visited = 0;
        for &h in &hot[..n as usize] {
            assert_eq!(index.chain(centre, h, &mut visited), None);
        }
        assert!(
            visited < 200 * u64::from(n),
            "{visited} nodes for {n} spokes"
        );
    }
}
