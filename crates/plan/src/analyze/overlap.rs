//! The screen-space "in front of" graph and its cycles: what decides
//! whether a painter's order exists.
//!
//! Newell, Newell & Sancha (1972) paint polygons back to front; that works
//! when the relation "A hides part of B" between polygons whose projections
//! overlap has no cycle. This module builds that relation on the prepared
//! [`hider_scene::ScreenScene`]: candidate pairs from a tile grid over the
//! window, an exact test that their projections' interiors overlap
//! (separating edges with the shared integer `orient2d` on the snapped
//! vertices), and the
//! depth order at a point inside the overlap (the triangles' affine
//! window-depth planes, the same ones the hiders interpolate). Pairs that
//! interpenetrate in space are left out here — they are reported by
//! [`super::intersect`] — and so are pairs whose depths at that point are
//! equal (coplanar ties). A cycle is a strongly connected component of
//! more than one primitive (Tarjan's algorithm, iterative).
//!
//! The same edges also say whether a *naive* painter — one sort key per
//! triangle, the farthest vertex, stable by primitive id, as
//! `hider-painter`'s `painter-naive` does — already paints every hidden
//! triangle before the one hiding it; when it does, that painter is exact
//! without any of Newell's tests.

use hider_geom::{FixedPt, Viewport, orient2d};

use hider_scene::{Cancel, ScreenTri};

use hider_geom::star::{NO_STAR, Stars};

use super::intersect::MAX_CELLS_PER_TRIANGLE;
use super::stars;

/// Window depths closer than this at the test point are a tie, not an
/// order.
const DEPTH_TIE: f64 = 1e-12;

/// What the graph search found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct OverlapGraph {
    /// Pairs of screen triangles whose projections overlap (different
    /// primitives, not interpenetrating).
    pub overlapping_pairs: u64,
    /// "In front of" edges: `(behind, in front)` primitive ids.
    pub edges: u64,
    /// Pairs whose depths tie at the test point (coplanar overlaps).
    pub ties: u64,
    /// Strongly connected components of more than one primitive.
    pub cycles: u64,
    /// Primitives on some cycle.
    pub prims_on_cycles: u64,
    /// One cycle per component, as the primitive ids along it, up to the
    /// example limit.
    pub examples: Vec<Vec<u32>>,
    /// Edges the naive farthest-vertex sort paints in the wrong order.
    pub naive_violations: u64,
    /// One wrongly ordered pair `(behind, in front)`, if any.
    pub naive_example: Option<(u32, u32)>,
    /// Candidate pairs listed by the tiles (two triangles in one tile),
    /// before the bounding-box check: the enumeration's work.
    pub candidates: u64,
    /// Candidate pairs examined exactly (after the box check; what the
    /// budget counts).
    pub examined: u64,
    /// Whether every candidate pair was examined (false when the budget
    /// ran out).
    pub complete: bool,
}

/// Builds the graph over the screen triangles `tris` of a window `vp`
/// (those of a [`hider_scene::ScreenScene`], or the front faces only when
/// back faces will be culled), skipping the primitive pairs for which
/// `interpenetrate(a, b)` holds, examining at most `budget` candidate
/// pairs.
pub fn overlap_graph(
    tris: &[ScreenTri],
    vp: Viewport,
    interpenetrate: impl Fn(u32, u32) -> bool,
    budget: u64,
    max_examples: usize,
    cancel: Cancel,
) -> OverlapGraph {
    let stars = stars::screen_stars(tris);
    graph(
        tris,
        vp,
        stars,
        interpenetrate,
        budget,
        max_examples,
        cancel,
    )
}

/// [`overlap_graph`] with the pairs sharing a hub of `stars` taken from
/// the stars (none: every pair from the tiles; a dense star is dissolved
/// into the tiles).
pub(super) fn graph(
    tris: &[ScreenTri],
    vp: Viewport,
    mut stars: Stars,
    interpenetrate: impl Fn(u32, u32) -> bool,
    budget: u64,
    max_examples: usize,
    cancel: Cancel,
) -> OverlapGraph {
    let mut out = OverlapGraph {
        complete: true,
        ..OverlapGraph::default()
    };
    if tris.len() < 2 {
        return out;
    }
    // Before the tiles: dense stars are dissolved into them.
    let star_pairs = stars::screen_star_pairs(tris, &mut stars);
    let starred = !stars.is_empty();
    let TileBins {
        tiles,
        tiles_x,
        bounds,
        start,
        items,
    } = TileBins::new(tris, vp, |k| stars.group(k));
    // The "in front of" edges `(behind, in front)`, in the tiles' order:
    // pushed as found without stars; with stars, kept with their places
    // (first shared tile, lower index, higher index) and sorted at the
    // end.
    let mut edges: Vec<(u32, u32)> = Vec::new();
    let mut ordered: Vec<(usize, u32, u32, u32, u32)> = Vec::new();
    let mut examined = 0u64;
    let key = |k: u32| tris[k as usize].z.iter().copied().fold(f64::MIN, f64::max);
    // Whether a farthest-vertex sort paints `behind` first.
    let naive_ok = |behind: u32, front: u32| {
        let (kb, kf) = (key(behind), key(front));
        kb > kf || (kb == kf && behind < front)
    };
    // Examines the pair of screen triangles `a`, `b` (indices `ka < kb`)
    // in the tiles' loop or the stars' (`continue` goes to its next pair).
    // A macro rather than a function: the tiles' loop is the analysis's
    // hottest, and a function here, even inlined, made the whole graph
    // 25% slower on `gen:soup:30000`.
    macro_rules! examine {
        ($a:expr, $b:expr, $ka:expr, $kb:expr, $c:expr, $starred:literal, $search:lifetime) => {{
            if examined >= budget {
                out.complete = false;
                break $search;
            }
            examined += 1;
            let (a, b, ka, kb): (&ScreenTri, &ScreenTri, u32, u32) = ($a, $b, $ka, $kb);
            if !interiors_overlap(&a.v, &b.v) || interpenetrate(a.prim, b.prim) {
                continue;
            }
            out.overlapping_pairs += 1;
            let Some((x, y)) = overlap_point(&a.v, &b.v) else {
                continue;
            };
            let (da, db) = (a.depth.eval(x, y), b.depth.eval(x, y));
            if (da - db).abs() <= DEPTH_TIE {
                out.ties += 1;
                continue;
            }
            let (behind, front) = if da > db { (ka, kb) } else { (kb, ka) };
            if $starred {
                ordered.push(($c, ka, kb, behind, front));
            } else {
                edges.push((behind, front));
                if !naive_ok(behind, front) {
                    out.naive_violations += 1;
                    out.naive_example
                        .get_or_insert((tris[behind as usize].prim, tris[front as usize].prim));
                }
            }
        }};
    }
    // The pairs sharing a tile, compiled once without the stars' checks
    // and once with them.
    macro_rules! tile_pairs {
        ($starred:literal, $search:lifetime) => {
            for c in 0..tiles {
                // Stopped like an exhausted budget; the analysis returns the error.
                if cancel.check().is_err() {
                    out.complete = false;
                    break $search;
                }
                let list = &items[start[c]..start[c + 1]];
                let mut block_end = 0;
                for (i, &ka) in list.iter().enumerate() {
                    // The rest of a star's block shares its hub: those pairs
                    // are the star's.
                    let group = if $starred {
                        stars.group(ka as usize)
                    } else {
                        NO_STAR
                    };
                    let rest = if group == NO_STAR {
                        i + 1
                    } else {
                        if block_end <= i {
                            block_end = i + 1;
                            while block_end < list.len()
                                && stars.group(list[block_end] as usize) == group
                            {
                                block_end += 1;
                            }
                        }
                        block_end
                    };
                    let (a, ba) = (&tris[ka as usize], bounds[ka as usize].unwrap_or_default());
                    for &kb in &list[rest..] {
                        let (b, bb) = (&tris[kb as usize], bounds[kb as usize].unwrap_or_default());
                        out.candidates += 1;
                        let first = [ba[0].max(bb[0]), ba[1].max(bb[1])];
                        if a.prim == b.prim
                            || first[0] > ba[2].min(bb[2])
                            || first[1] > ba[3].min(bb[3])
                            || first[1] * tiles_x + first[0] != c
                            || ($starred
                                && group != NO_STAR
                                && stars.share(ka as usize, kb as usize))
                        {
                            continue;
                        }
                        // Star blocks make the lists' order (star, index).
                        let (x, y) = if ka < kb { (a, b) } else { (b, a) };
                        examine!(x, y, ka.min(kb), ka.max(kb), c, $starred, $search);
                    }
                }
            }
        };
    }
    'search: {
        for (k, &(ka, kb)) in star_pairs.iter().enumerate() {
            if cancel.poll_every(k).is_err() {
                out.complete = false;
                break 'search;
            }
            out.candidates += 1;
            // The first tile both boxes meet, if they meet and are two
            // primitives.
            let (a, b) = (&tris[ka as usize], &tris[kb as usize]);
            let (Some(ba), Some(bb)) = (bounds[ka as usize], bounds[kb as usize]) else {
                continue;
            };
            let first = [ba[0].max(bb[0]), ba[1].max(bb[1])];
            if a.prim == b.prim || first[0] > ba[2].min(bb[2]) || first[1] > ba[3].min(bb[3]) {
                continue;
            }
            examine!(a, b, ka, kb, first[1] * tiles_x + first[0], true, 'search);
        }
        if starred {
            tile_pairs!(true, 'search);
        } else {
            tile_pairs!(false, 'search);
        }
    }
    if starred {
        ordered.sort_unstable_by_key(|&(c, ka, kb, _, _)| (c, ka, kb));
        for &(_, _, _, behind, front) in &ordered {
            edges.push((behind, front));
            if !naive_ok(behind, front) {
                out.naive_violations += 1;
                out.naive_example
                    .get_or_insert((tris[behind as usize].prim, tris[front as usize].prim));
            }
        }
    }
    out.examined = examined;
    out.edges = edges.len() as u64;
    let prim_edges: Vec<(u32, u32)> = edges
        .iter()
        .map(|&(b, f)| (tris[b as usize].prim, tris[f as usize].prim))
        .collect();
    let (cycles, on_cycles, examples) = find_cycles(&prim_edges, max_examples);
    out.cycles = cycles;
    out.prims_on_cycles = on_cycles;
    out.examples = examples;
    out
}

/// The screen triangles binned into square tiles of about one triangle
/// each, larger when the triangles are (at most
/// [`MAX_CELLS_PER_TRIANGLE`] tiles per triangle on average, as the
/// intersection grid): the candidate pairs for overlap are those sharing a
/// tile.
struct TileBins {
    /// Number of tiles.
    tiles: usize,
    /// Tiles per row.
    tiles_x: usize,
    /// Per triangle, its tile box `[x0, y0, x1, y1]` (inclusive), `None`
    /// when it covers no pixel of the window.
    bounds: Vec<Option<[usize; 4]>>,
    /// Where each tile's list starts in `items` (one more than `tiles`).
    start: Vec<usize>,
    /// The triangle indices of every tile, tile after tile.
    items: Vec<u32>,
}

impl TileBins {
    /// The bins of `tris`, each tile's list sorted by `(group(k), k)`.
    fn new(tris: &[ScreenTri], vp: Viewport, group: impl Fn(usize) -> u32) -> Self {
        let n = tris.len();
        // Tiles of about one triangle each, 4 to 256 pixels wide, then
        // wider while the triangles cover too many: a window full of large
        // triangles otherwise lists most pairs in hundreds of tiles each.
        let mut side =
            ((f64::from(vp.width) * f64::from(vp.height) / n as f64).sqrt() as u32).clamp(4, 256);
        let pixel_boxes: Vec<Option<(u32, u32, u32, u32)>> = tris
            .iter()
            .map(|t| pixel_box(t, vp.width, vp.height))
            .collect();
        let most = MAX_CELLS_PER_TRIANGLE.saturating_mul(n as u64);
        let covered = |side: u32| -> u64 {
            pixel_boxes
                .iter()
                .flatten()
                .map(|&(x0, y0, x1, y1)| {
                    u64::from(x1 / side - x0 / side + 1) * u64::from(y1 / side - y0 / side + 1)
                })
                .sum()
        };
        let widest = vp.width.max(vp.height);
        while side < widest && covered(side) > most {
            side = (side + side / 4).min(widest);
        }
        let tiles_x = vp.width.div_ceil(side) as usize;
        let tiles_y = vp.height.div_ceil(side) as usize;
        let tiles = tiles_x * tiles_y;
        let bounds: Vec<Option<[usize; 4]>> = pixel_boxes
            .iter()
            .map(|b| {
                let (x0, y0, x1, y1) = (*b)?;
                Some([x0, y0, x1, y1].map(|v| (v / side) as usize))
            })
            .collect();
        let mut start = vec![0usize; tiles + 1];
        let for_tiles = |b: &[usize; 4], f: &mut dyn FnMut(usize)| {
            for ty in b[1]..=b[3] {
                for tx in b[0]..=b[2] {
                    f(ty * tiles_x + tx);
                }
            }
        };
        for b in bounds.iter().flatten() {
            for_tiles(b, &mut |c| start[c + 1] += 1);
        }
        for c in 0..tiles {
            start[c + 1] += start[c];
        }
        let mut fill = start.clone();
        let mut items = vec![0u32; start[tiles]];
        let mut order: Vec<u32> = (0..n as u32).collect();
        order.sort_by_key(|&k| (group(k as usize), k));
        for k in order {
            if let Some(b) = &bounds[k as usize] {
                for_tiles(b, &mut |c| {
                    items[fill[c]] = k;
                    fill[c] += 1;
                });
            }
        }
        Self {
            tiles,
            tiles_x,
            bounds,
            start,
            items,
        }
    }
}

/// The inclusive pixel box of a triangle's extent (not only its sample
/// centres), clamped to the window.
fn pixel_box(t: &ScreenTri, w: u32, h: u32) -> Option<(u32, u32, u32, u32)> {
    let lo_x = t.v.iter().map(|p| p.x).min()?.div_euclid(256);
    let hi_x = t.v.iter().map(|p| p.x).max()?.div_euclid(256);
    let lo_y = t.v.iter().map(|p| p.y).min()?.div_euclid(256);
    let hi_y = t.v.iter().map(|p| p.y).max()?.div_euclid(256);
    if hi_x < 0 || hi_y < 0 || lo_x >= w as i32 || lo_y >= h as i32 {
        return None;
    }
    let c = |v: i32, m: u32| v.clamp(0, m as i32 - 1) as u32;
    Some((c(lo_x, w), c(lo_y, h), c(hi_x, w), c(hi_y, h)))
}

/// Whether the interiors of two positively oriented snapped triangles
/// overlap: exactly when no edge of either has the other wholly on its
/// closed outer side (separating axis theorem for convex polygons).
pub fn interiors_overlap(a: &[FixedPt; 3], b: &[FixedPt; 3]) -> bool {
    let separates = |t: &[FixedPt; 3], other: &[FixedPt; 3]| {
        (0..3).any(|i| {
            let (u, v) = (t[i], t[(i + 1) % 3]);
            other.iter().all(|&q| orient2d(u, v, q) <= 0)
        })
    };
    !separates(a, b) && !separates(b, a)
}

/// A point strictly inside the overlap of two triangles (in pixels): the
/// vertex average of `a` clipped by `b`'s three half-planes.
fn overlap_point(a: &[FixedPt; 3], b: &[FixedPt; 3]) -> Option<(f64, f64)> {
    // A triangle clipped by three half-planes keeps at most six corners;
    // fixed arrays, since this runs once per overlapping pair.
    let mut poly = [(0.0, 0.0); 6];
    let mut len = 3;
    for (k, p) in a.iter().enumerate() {
        poly[k] = p.to_pixels();
    }
    let bp = b.map(|p| p.to_pixels());
    for i in 0..3 {
        let (u, v) = (bp[i], bp[(i + 1) % 3]);
        // Positive inside, as orient2d of the y-down fixed-point frame.
        let side = |p: (f64, f64)| (v.0 - u.0) * (p.1 - u.1) - (v.1 - u.1) * (p.0 - u.0);
        let mut next = [(0.0, 0.0); 6];
        let mut n = 0;
        for k in 0..len {
            let (p, q) = (poly[k], poly[(k + 1) % len]);
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 && n < 6 {
                next[n] = p;
                n += 1;
            }
            if ((sp > 0.0 && sq < 0.0) || (sp < 0.0 && sq > 0.0)) && n < 6 {
                let t = sp / (sp - sq);
                next[n] = (p.0 + (q.0 - p.0) * t, p.1 + (q.1 - p.1) * t);
                n += 1;
            }
        }
        (poly, len) = (next, n);
        if len < 3 {
            return None;
        }
    }
    let k = len as f64;
    let (sx, sy) = poly[..len]
        .iter()
        .fold((0.0, 0.0), |s, p| (s.0 + p.0, s.1 + p.1));
    Some((sx / k, sy / k))
}

/// Strongly connected components of more than one node (Tarjan, with an
/// explicit stack): their number, the nodes on them, and one cycle from
/// each of the first `max_examples`.
fn find_cycles(edges: &[(u32, u32)], max_examples: usize) -> (u64, u64, Vec<Vec<u32>>) {
    let Some(max) = edges.iter().map(|&(a, b)| a.max(b)).max() else {
        return (0, 0, Vec::new());
    };
    let n = max as usize + 1;
    let mut start = vec![0usize; n + 1];
    for &(a, _) in edges {
        start[a as usize + 1] += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut adj = vec![0u32; edges.len()];
    for &(a, b) in edges {
        adj[fill[a as usize]] = b;
        fill[a as usize] += 1;
    }
    const UNSEEN: u32 = u32::MAX;
    let mut index = vec![UNSEEN; n];
    let mut low = vec![0u32; n];
    let mut on_stack = vec![false; n];
    let mut stack: Vec<u32> = Vec::new();
    let mut comp = vec![UNSEEN; n];
    let mut next_index = 0u32;
    let (mut cycles, mut on_cycles, mut examples) = (0u64, 0u64, Vec::new());
    for root in 0..n as u32 {
        if index[root as usize] != UNSEEN || start[root as usize] == start[root as usize + 1] {
            continue;
        }
        // (node, next edge position) frames.
        let mut call: Vec<(u32, usize)> = vec![(root, start[root as usize])];
        index[root as usize] = next_index;
        low[root as usize] = next_index;
        next_index += 1;
        stack.push(root);
        on_stack[root as usize] = true;
        while let Some(&mut (v, ref mut pos)) = call.last_mut() {
            let vu = v as usize;
            if *pos < start[vu + 1] {
                let w = adj[*pos];
                *pos += 1;
                let wu = w as usize;
                if index[wu] == UNSEEN {
                    index[wu] = next_index;
                    low[wu] = next_index;
                    next_index += 1;
                    stack.push(w);
                    on_stack[wu] = true;
                    call.push((w, start[wu]));
                } else if on_stack[wu] {
                    low[vu] = low[vu].min(index[wu]);
                }
                continue;
            }
            call.pop();
            if let Some(&(parent, _)) = call.last() {
                low[parent as usize] = low[parent as usize].min(low[vu]);
            }
            if low[vu] == index[vu] {
                let mut members = Vec::new();
                while let Some(w) = stack.pop() {
                    on_stack[w as usize] = false;
                    comp[w as usize] = v;
                    members.push(w);
                    if w == v {
                        break;
                    }
                }
                if members.len() > 1 {
                    cycles += 1;
                    on_cycles += members.len() as u64;
                    if examples.len() < max_examples {
                        examples.push(cycle_through(v, &comp, &start, &adj));
                    }
                }
            }
        }
    }
    (cycles, on_cycles, examples)
}

/// A cycle through `v` inside its component (breadth-first search back to
/// `v`).
fn cycle_through(v: u32, comp: &[u32], start: &[usize], adj: &[u32]) -> Vec<u32> {
    let c = comp[v as usize];
    let mut parent: std::collections::HashMap<u32, u32> = std::collections::HashMap::new();
    let mut queue = std::collections::VecDeque::from([v]);
    while let Some(u) = queue.pop_front() {
        for &w in &adj[start[u as usize]..start[u as usize + 1]] {
            if comp[w as usize] != c {
                continue;
            }
            if w == v {
                let mut path = vec![u];
                let mut x = u;
                while x != v {
                    x = parent[&x];
                    path.push(x);
                }
                path.reverse();
                return path;
            }
            if let std::collections::hash_map::Entry::Vacant(e) = parent.entry(w) {
                e.insert(u);
                queue.push_back(w);
            }
        }
    }
    vec![v]
}

#[cfg(test)]
mod tests;
