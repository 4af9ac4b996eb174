//! The two searches over pairs of triangles, as evidence: which pairs
//! interpenetrate (or tie) in space, and whether the "in front of" graph on
//! the screen has cycles or disagrees with a naive sort.

use glam::DVec3;
use hider_geom::Viewport;
use hider_scene::{Scene, ScreenTri};

use super::effects::Evidence;
use super::evidence::InView;
use super::{intersect, overlap, splits};

/// What the intersection search found.
pub(crate) struct Crossings {
    /// Interpenetrating pairs in view.
    pub(crate) intersections: Evidence,
    /// Coplanar overlapping pairs in view (depth ties).
    pub(crate) coplanar: Evidence,
    /// The interpenetrating pairs, `(smaller id, larger id)`: they have no
    /// order, so the overlap graph leaves them out.
    pub(crate) crossing: Partners,
    /// Pairs the grid listed, and exact tests run.
    pub(crate) candidates: u64,
    /// Exact tests run.
    pub(crate) tests: u64,
    /// Splits the painter needs at least for the pairs found
    /// ([`splits::painter_splits_at_least`]).
    pub(crate) painter_splits_at_least: u64,
}

/// A symmetric set of primitive pairs as sorted partner lists per
/// primitive (compressed rows). The overlap graph asks it once per
/// overlapping pair; a hash set of 10^6 pairs made those look-ups, each a
/// cache miss, most of the analysis of 2,000 random crossing triangles,
/// where a search in one primitive's short sorted list stays in cache.
pub(crate) struct Partners {
    /// Where each primitive's partners start in `partners` (one more than
    /// the largest id plus one).
    start: Vec<usize>,
    /// Every primitive's partners, ascending, primitive after primitive.
    partners: Vec<u32>,
}

impl Partners {
    /// The set of `pairs` (either order).
    pub(crate) fn new(pairs: &[(u32, u32)]) -> Self {
        let n = pairs
            .iter()
            .map(|&(a, b)| a.max(b) as usize + 1)
            .max()
            .unwrap_or(0);
        let mut start = vec![0usize; n + 1];
        for &(a, b) in pairs {
            start[a as usize + 1] += 1;
            start[b as usize + 1] += 1;
        }
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut partners = vec![0u32; start[n]];
        for &(a, b) in pairs {
            for (x, y) in [(a, b), (b, a)] {
                partners[fill[x as usize]] = y;
                fill[x as usize] += 1;
            }
        }
        for i in 0..n {
            partners[start[i]..start[i + 1]].sort_unstable();
        }
        Self { start, partners }
    }

    /// Whether `(a, b)` (either order) is in the set.
    pub(crate) fn contains(&self, a: u32, b: u32) -> bool {
        let a = a as usize;
        a + 1 < self.start.len()
            && self.partners[self.start[a]..self.start[a + 1]]
                .binary_search(&b)
                .is_ok()
    }
}

/// The first `ex` pairs as example groups.
fn pair_examples(pairs: &[(u32, u32)], ex: usize) -> Vec<Vec<u32>> {
    pairs.iter().take(ex).map(|&(a, b)| vec![a, b]).collect()
}

/// `""`, or the note that a search stopped at its budget, naming the
/// flag that raises it.
fn budget_note(complete: bool, budget: u64) -> String {
    if complete {
        String::new()
    } else {
        format!(
            ", stopped at the pair budget of {budget} exact tests: raise it with --pair-budget \
             (RenderOptions::pair_budget)"
        )
    }
}

/// Searches the triangles of `scene` whose primitives are `in_view` for
/// interpenetrating and coplanar overlapping pairs, in world space.
pub(crate) fn intersections(
    scene: &Scene,
    in_view: &InView,
    budget: u64,
    ex: usize,
    cancel: hider_scene::Cancel,
) -> Crossings {
    let world: Vec<(u32, [DVec3; 3])> = scene
        .triangles()
        .filter(|&(id, _, _)| in_view.contains(id))
        .map(|(id, m, t)| (id, scene.triangle_positions(m, t)))
        .collect();
    let pairs = intersect::find_pairs(&world, budget, cancel);
    let intersections = Evidence {
        present: !pairs.interpenetrating.is_empty() || !pairs.complete,
        certain: pairs.complete,
        count: pairs.interpenetrating.len() as u64,
        examples: pair_examples(&pairs.interpenetrating, ex),
        detail: format!(
            "{} interpenetrating pairs among {} triangles in view ({} exact tests{})",
            pairs.interpenetrating.len(),
            world.len(),
            pairs.tests,
            budget_note(pairs.complete, budget)
        ),
    };
    let coplanar = Evidence {
        present: !pairs.coplanar.is_empty(),
        certain: pairs.complete,
        count: pairs.coplanar.len() as u64,
        examples: pair_examples(&pairs.coplanar, ex),
        detail: format!(
            "{} coplanar overlapping pairs (depth ties: corners within {:e} x the longest edge \
             of the other's plane, any orientation)",
            pairs.coplanar.len(),
            intersect::COPLANAR_TOLERANCE
        ),
    };
    // A pair the search did not reach is ordered like any other.
    let crossing = Partners::new(&pairs.interpenetrating);
    Crossings {
        intersections,
        coplanar,
        crossing,
        candidates: pairs.candidates,
        tests: pairs.tests,
        painter_splits_at_least: splits::painter_splits_at_least(&world, &pairs.interpenetrating),
    }
}

/// What the overlap graph says about painting in depth order.
pub(crate) struct Order {
    /// Cycles of the "in front of" relation.
    pub(crate) cyclic: Evidence,
    /// Pairs a farthest-vertex sort paints in the wrong order.
    pub(crate) naive_violations: Evidence,
    /// Pairs the tiles listed.
    pub(crate) candidates: u64,
    /// Pairs examined exactly.
    pub(crate) tests: u64,
}

/// Builds the overlap graph of `tris` in a window `viewport`, leaving out
/// the `crossing` pairs, and reads its cycles and naive-order violations.
pub(crate) fn order(
    tris: &[ScreenTri],
    viewport: Viewport,
    crossing: &Partners,
    budget: u64,
    ex: usize,
    cancel: hider_scene::Cancel,
) -> Order {
    let graph = overlap::overlap_graph(
        tris,
        viewport,
        |a, b| crossing.contains(a, b),
        budget,
        ex,
        cancel,
    );
    let cyclic = Evidence {
        present: graph.cycles > 0 || !graph.complete,
        certain: graph.complete,
        count: graph.cycles,
        examples: graph.examples.clone(),
        detail: format!(
            "{} cycles through {} triangles among {} overlapping pairs ({} ordered, {} ties{})",
            graph.cycles,
            graph.prims_on_cycles,
            graph.overlapping_pairs,
            graph.edges,
            graph.ties,
            budget_note(graph.complete, budget)
        ),
    };
    let naive_violations = Evidence {
        present: graph.naive_violations > 0 || !graph.complete,
        certain: graph.complete,
        count: graph.naive_violations,
        examples: graph
            .naive_example
            .map(|(a, b)| vec![a, b])
            .into_iter()
            .collect(),
        detail: format!(
            "{} overlapping pairs painted in the wrong order by a farthest-vertex sort",
            graph.naive_violations
        ),
    };
    Order {
        cyclic,
        naive_violations,
        candidates: graph.candidates,
        tests: graph.examined,
    }
}

#[cfg(test)]
mod tests {
    use super::Partners;

    #[test]
    fn partners_hold_each_pair_in_either_order() {
        let set = Partners::new(&[(0, 5), (2, 3), (5, 7), (3, 9)]);
        for (a, b) in [(0, 5), (5, 0), (3, 2), (9, 3), (7, 5)] {
            assert!(set.contains(a, b), "({a}, {b})");
        }
        for (a, b) in [(0, 7), (2, 9), (5, 5), (100, 3), (3, 100)] {
            assert!(!set.contains(a, b), "({a}, {b})");
        }
        assert!(!Partners::new(&[]).contains(0, 1));
    }
}
