//! The two searches over pairs of triangles, as evidence: which pairs
//! interpenetrate (or tie) in space, and whether the "in front of" graph on
//! the screen has cycles or disagrees with a naive sort.

use std::collections::HashSet;

use glam::DVec3;
use hider_geom::Viewport;
use hider_scene::{Scene, ScreenTri};

use super::effects::Evidence;
use super::evidence::InView;
use super::{intersect, overlap};

/// What the intersection search found.
pub(crate) struct Crossings {
    /// Interpenetrating pairs in view.
    pub(crate) intersections: Evidence,
    /// Coplanar overlapping pairs in view (depth ties).
    pub(crate) coplanar: Evidence,
    /// The interpenetrating pairs, `(smaller id, larger id)`: they have no
    /// order, so the overlap graph leaves them out.
    pub(crate) crossing: HashSet<(u32, u32)>,
}

/// The first `ex` pairs as example groups.
fn pair_examples(pairs: &[(u32, u32)], ex: usize) -> Vec<Vec<u32>> {
    pairs.iter().take(ex).map(|&(a, b)| vec![a, b]).collect()
}

/// `""`, or the note that a search stopped at its budget.
fn budget_note(complete: bool) -> &'static str {
    if complete { "" } else { ", budget exhausted" }
}

/// Searches the triangles of `scene` whose primitives are `in_view` for
/// interpenetrating and coplanar overlapping pairs, in world space.
pub(crate) fn intersections(scene: &Scene, in_view: &InView, budget: u64, ex: usize) -> Crossings {
    let world: Vec<(u32, [DVec3; 3])> = scene
        .triangles()
        .filter(|&(id, _, _)| in_view.contains(id))
        .map(|(id, m, t)| (id, scene.triangle_positions(m, t)))
        .collect();
    let pairs = intersect::find_pairs(&world, budget);
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
            budget_note(pairs.complete)
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
    let crossing = pairs.interpenetrating.iter().copied().collect();
    Crossings {
        intersections,
        coplanar,
        crossing,
    }
}

/// What the overlap graph says about painting in depth order.
pub(crate) struct Order {
    /// Cycles of the "in front of" relation.
    pub(crate) cyclic: Evidence,
    /// Pairs a farthest-vertex sort paints in the wrong order.
    pub(crate) naive_violations: Evidence,
}

/// Builds the overlap graph of `tris` in a window `viewport`, leaving out
/// the `crossing` pairs, and reads its cycles and naive-order violations.
pub(crate) fn order(
    tris: &[ScreenTri],
    viewport: Viewport,
    crossing: &HashSet<(u32, u32)>,
    budget: u64,
    ex: usize,
) -> Order {
    let graph = overlap::overlap_graph(
        tris,
        viewport,
        |a, b| crossing.contains(&(a.min(b), a.max(b))),
        budget,
        ex,
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
            budget_note(graph.complete)
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
    }
}
