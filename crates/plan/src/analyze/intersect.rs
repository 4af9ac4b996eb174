//! Interpenetrating triangles: exact triangle–triangle tests, accelerated
//! by a uniform grid.
//!
//! Two triangles *interpenetrate* when each one has corners strictly on
//! both sides of the other's plane and the two segments in which they cross
//! the common line `L` of the planes overlap over a positive length
//! (Möller, "A fast triangle-triangle intersection test", 1997; the side
//! tests are the robust [`orient3d`] of Guigue & Devillers, 2003). That is
//! the case hidden-surface removal cares about: along `L` the two surfaces
//! swap depth order, so no per-triangle order exists (the painter's
//! failure the software-renderer tutorial, chapter 8, shows). Triangles
//! that only touch — mesh neighbours sharing an edge or a vertex, a fin
//! standing on a face — keep one side of each other's plane and are not
//! counted; thanks to the exact predicate a shared vertex is exactly on
//! the plane, never "a little across".
//!
//! Only the interval overlap along `L` is computed in floating point; it
//! must exceed [`OVERLAP_TOLERANCE`] times the intervals' extent, which
//! separates a shared endpoint (overlap exactly 0) from a real crossing.
//! Coplanar pairs whose interiors overlap are reported apart: they are
//! depth ties (z-fighting), not interpenetrations. "Coplanar" is not left
//! to the exact predicate alone: two triangles in a tilted plane such as
//! `x + 2y + 3z = 0` have corners that round off the plane, so `orient3d`
//! sees them a hair apart (or straddling, a false crossing). A pair is
//! *near-coplanar* when every corner of each lies within
//! [`COPLANAR_TOLERANCE`] times the pair's longest edge of the other's
//! plane, whatever the plane's orientation; its overlap is then a depth
//! tie that a depth buffer resolves by rounding (stripes), not an order.
//!
//! Candidate pairs come from a uniform grid over the scene's bounds with
//! about one cell per triangle; a pair is tested only in the first cell
//! its bounding boxes share, so no pair is tested twice and no set of
//! tested pairs is kept. Large triangles would each fill a great many such
//! cells, and every cell would list most of the scene again, which made
//! the pairs enumerated grow as the cube of the triangles (1,000 random
//! triangles across a cube: 0.5 s, 2,000: 3 s); so the cells grow until
//! the triangles cover at most [`MAX_CELLS_PER_TRIANGLE`] cells each on
//! average, and the enumeration stays within a small factor of the pairs
//! whose boxes meet.

use glam::DVec3;
use hider_scene::Cancel;

use hider_geom::star::{NO_STAR, Stars};

use super::predicates::{orient2d, orient3d};
use super::stars;

/// Relative length below which the two crossing segments are taken to
/// touch rather than overlap (see the module documentation).
pub const OVERLAP_TOLERANCE: f64 = 1e-12;

/// Relative distance below which two overlapping triangles are a depth
/// tie: every corner of each within this times the pair's longest edge of
/// the other's plane (see the module documentation). `1e-5` is the
/// oracle's tie tolerance; a 2-unit pair 10^-6 apart ties, 10^-2 apart
/// is ordered.
pub const COPLANAR_TOLERANCE: f64 = 1e-5;

/// Most grid cells (or screen tiles) a triangle covers on average: the
/// bins grow until the triangles' bounding boxes cover no more, so a pair
/// of large triangles is listed together in a few bins, not in thousands
/// (see the module documentation).
pub const MAX_CELLS_PER_TRIANGLE: u64 = 8;

/// How two triangles meet.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Contact {
    /// They do not meet, or only touch.
    None,
    /// They pierce each other along a segment.
    Interpenetrate,
    /// They lie in one plane and their interiors overlap.
    CoplanarOverlap,
}

/// Classifies a pair of triangles (see the module documentation).
pub fn contact(a: &[DVec3; 3], b: &[DVec3; 3]) -> Contact {
    let sa = a.map(|p| orient3d(b[0], b[1], b[2], p));
    if sa == [0, 0, 0] || near_coplanar(a, b) {
        return if coplanar_overlap(a, b) {
            Contact::CoplanarOverlap
        } else {
            Contact::None
        };
    }
    if !straddles(sa) {
        return Contact::None;
    }
    let sb = b.map(|p| orient3d(a[0], a[1], a[2], p));
    if !straddles(sb) {
        return Contact::None;
    }
    let na = (a[1] - a[0]).cross(a[2] - a[0]);
    let nb = (b[1] - b[0]).cross(b[2] - b[0]);
    let dir = na.cross(nb);
    let (a0, a1) = interval(a, sa, nb, b[0], dir);
    let (b0, b1) = interval(b, sb, na, a[0], dir);
    let overlap = a1.min(b1) - a0.max(b0);
    let extent = (a1 - a0).max(b1 - b0);
    if overlap > OVERLAP_TOLERANCE * extent {
        Contact::Interpenetrate
    } else {
        Contact::None
    }
}

/// Whether every corner of each triangle lies within
/// [`COPLANAR_TOLERANCE`] times the pair's longest edge of the other's
/// plane. Triangles without area have no plane and are never coplanar.
pub fn near_coplanar(a: &[DVec3; 3], b: &[DVec3; 3]) -> bool {
    let longest = |t: &[DVec3; 3]| {
        (0..3)
            .map(|i| (t[(i + 1) % 3] - t[i]).length())
            .fold(0.0, f64::max)
    };
    let tolerance = COPLANAR_TOLERANCE * longest(a).max(longest(b));
    let within = |t: &[DVec3; 3], other: &[DVec3; 3]| {
        let n = (t[1] - t[0]).cross(t[2] - t[0]);
        let len = n.length();
        // Distances along the unit normal; the comparison is multiplied
        // out so that no division by a tiny normal is needed.
        len > 0.0
            && len.is_finite()
            && other
                .iter()
                .all(|&q| n.dot(q - t[0]).abs() <= tolerance * len)
    };
    tolerance > 0.0 && within(a, b) && within(b, a)
}

/// Whether the corners lie strictly on both sides.
fn straddles(s: [i8; 3]) -> bool {
    s.contains(&1) && s.contains(&-1)
}

/// The segment in which a triangle crosses the other's plane (normal `n`
/// through `p`), as parameters along `dir`.
fn interval(t: &[DVec3; 3], s: [i8; 3], n: DVec3, p: DVec3, dir: DVec3) -> (f64, f64) {
    let dist = t.map(|q| n.dot(q - p));
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    let mut take = |q: DVec3| {
        let x = dir.dot(q);
        lo = lo.min(x);
        hi = hi.max(x);
    };
    for i in 0..3 {
        let j = (i + 1) % 3;
        if s[i] == 0 {
            take(t[i]);
        }
        if s[i] * s[j] < 0 {
            let k = dist[i] / (dist[i] - dist[j]);
            take(t[i] + (t[j] - t[i]) * k);
        }
    }
    (lo, hi)
}

/// Whether two coplanar triangles' interiors overlap: no edge of either
/// separates them (exact, in the projection that keeps the plane's
/// largest normal component).
fn coplanar_overlap(a: &[DVec3; 3], b: &[DVec3; 3]) -> bool {
    let drop = drop_axis(a);
    let p = |q: DVec3| project(q, drop);
    let mut a2 = a.map(p);
    let mut b2 = b.map(p);
    for t in [&mut a2, &mut b2] {
        if orient2d(t[0], t[1], t[2]) < 0 {
            t.swap(1, 2);
        }
        if orient2d(t[0], t[1], t[2]) == 0 {
            return false; // degenerate: no interior
        }
    }
    let separates = |t: &[[f64; 2]; 3], other: &[[f64; 2]; 3]| {
        (0..3).any(|i| {
            let (u, v) = (t[i], t[(i + 1) % 3]);
            other.iter().all(|&q| orient2d(u, v, q) <= 0)
        })
    };
    !separates(&a2, &b2) && !separates(&b2, &a2)
}

/// The axis of the largest component of `a`'s normal (as computed in
/// floating point), which [`coplanar_overlap`] drops to compare a pair in
/// `a`'s plane.
pub(crate) fn drop_axis(a: &[DVec3; 3]) -> usize {
    let n = (a[1] - a[0]).cross(a[2] - a[0]).abs();
    if n.x >= n.y && n.x >= n.z {
        0
    } else if n.y >= n.z {
        1
    } else {
        2
    }
}

/// `q` without its coordinate `drop` (exact).
pub(crate) fn project(q: DVec3, drop: usize) -> [f64; 2] {
    match drop {
        0 => [q.y, q.z],
        1 => [q.z, q.x],
        _ => [q.x, q.y],
    }
}

/// What the grid search found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PairSearch {
    /// Every interpenetrating pair found, `(lower id, higher id)`.
    pub interpenetrating: Vec<(u32, u32)>,
    /// Every coplanar overlapping pair found, `(lower id, higher id)`.
    pub coplanar: Vec<(u32, u32)>,
    /// Exact triangle–triangle tests run (after the bounding-box check).
    pub tests: u64,
    /// Candidate pairs listed by the grid (two triangles in one cell),
    /// before the bounding-box check: the enumeration's work.
    pub candidates: u64,
    /// Whether every candidate pair was tested (false when the budget ran
    /// out).
    pub complete: bool,
}

/// Finds interpenetrating and coplanar-overlapping pairs among `tris`
/// (primitive id and world-space corners), testing at most `budget` pairs
/// exactly. Pairs sharing a vertex of a star come from the star (sectors
/// around the shared vertex, `stars.rs`), the others from the grid; the
/// pairs found are listed in the grid's order (first shared cell, then the
/// two indices), whichever found them.
pub fn find_pairs(tris: &[(u32, [DVec3; 3])], budget: u64, cancel: Cancel) -> PairSearch {
    let mut out = PairSearch {
        complete: true,
        ..PairSearch::default()
    };
    if tris.len() < 2 {
        return out;
    }
    let boxes: Vec<(DVec3, DVec3)> = tris
        .iter()
        .map(|(_, t)| (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2])))
        .collect();
    let lo = boxes.iter().fold(DVec3::INFINITY, |m, b| m.min(b.0));
    let hi = boxes.iter().fold(DVec3::NEG_INFINITY, |m, b| m.max(b.1));
    let grid = Grid::new(lo, hi, &boxes);
    let mut stars = stars::world_stars(tris);
    // Before the cells: dense stars are dissolved into them.
    let star_pairs = stars::world_star_pairs(tris, &mut stars);
    let starred = !stars.is_empty();
    // With stars, (first shared cell, lower index, higher index, contact)
    // of each pair found, sorted at the end; without, the pairs go to
    // `out` as found, already in the cells' order.
    let mut found: Vec<(usize, u32, u32, Contact)> = Vec::new();
    // Tests one pair (indices in either order). A macro rather than a
    // closure: in the cells' loop a call per pair cost a third of
    // `hider analyze gen:sphere:2000`.
    macro_rules! test_pair {
        ($ka:expr, $kb:expr, $search:lifetime) => {{
            let (ka, kb): (u32, u32) = ($ka, $kb);
            let (ka, kb) = (ka.min(kb), ka.max(kb));
            if out.tests >= budget {
                out.complete = false;
                break $search;
            }
            out.tests += 1;
            let contact = contact(&tris[ka as usize].1, &tris[kb as usize].1);
            if contact != Contact::None {
                if starred {
                    let (ba, bb) = (boxes[ka as usize], boxes[kb as usize]);
                    found.push((grid.cell_of(ba.0.max(bb.0)), ka, kb, contact));
                } else {
                    record(&mut out, tris[ka as usize].0, tris[kb as usize].0, contact);
                }
            }
        }};
    }
    'search: {
        for (k, &(ka, kb)) in star_pairs.iter().enumerate() {
            if cancel.poll_every(k).is_err() {
                out.complete = false;
                break 'search;
            }
            out.candidates += 1;
            // Out of line, so that the cells' loop below keeps the one
            // inlined copy of the test it had before the stars.
            let Some(contact) = star_test(tris, (ka, kb), budget, &mut out) else {
                break 'search;
            };
            if contact != Contact::None {
                let (ba, bb) = (boxes[ka as usize], boxes[kb as usize]);
                found.push((grid.cell_of(ba.0.max(bb.0)), ka, kb, contact));
            }
        }
        let (start, items, groups) = grid.cell_lists(&boxes, starred.then_some(&stars));
        for c in 0..grid.cell_count() {
            // Stopped like an exhausted budget; the analysis returns the error.
            if cancel.poll_every(c).is_err() {
                out.complete = false;
                break 'search;
            }
            let list = &items[start[c]..start[c + 1]];
            let groups = groups.get(start[c]..start[c + 1]).unwrap_or(&[]);
            let mut block_end = 0;
            for (i, &ka) in list.iter().enumerate() {
                let group = groups.get(i).copied().unwrap_or(NO_STAR);
                // The rest of this star's block shares its hub: those pairs
                // are the star's.
                let rest = if group == NO_STAR {
                    i + 1
                } else {
                    if block_end <= i {
                        block_end = i + 1;
                        while block_end < list.len() && groups[block_end] == group {
                            block_end += 1;
                        }
                    }
                    block_end
                };
                let ba = boxes[ka as usize];
                for &kb in &list[rest..] {
                    let bb = boxes[kb as usize];
                    out.candidates += 1;
                    let both = (ba.0.max(bb.0), ba.1.min(bb.1));
                    if both.0.cmpgt(both.1).any()
                        || grid.cell_of(both.0) != c
                        || (group != NO_STAR && stars.share(ka as usize, kb as usize))
                    {
                        continue;
                    }
                    test_pair!(ka, kb, 'search);
                }
            }
        }
    }
    if starred {
        found.sort_unstable_by_key(|&(c, ka, kb, _)| (c, ka, kb));
        for (_, ka, kb, contact) in found {
            record(&mut out, tris[ka as usize].0, tris[kb as usize].0, contact);
        }
    }
    out
}

/// Tests the star pair `(ka, kb)` (`ka < kb`) within `budget`: `None`
/// when the budget is used up.
#[inline(never)]
fn star_test(
    tris: &[(u32, [DVec3; 3])],
    (ka, kb): (u32, u32),
    budget: u64,
    out: &mut PairSearch,
) -> Option<Contact> {
    if out.tests >= budget {
        out.complete = false;
        return None;
    }
    out.tests += 1;
    Some(contact(&tris[ka as usize].1, &tris[kb as usize].1))
}

/// Lists the pair of primitives `a`, `b` under `contact`.
fn record(out: &mut PairSearch, a: u32, b: u32, contact: Contact) {
    let pair = (a.min(b), a.max(b));
    match contact {
        Contact::None => {}
        Contact::Interpenetrate => out.interpenetrating.push(pair),
        Contact::CoplanarOverlap => out.coplanar.push(pair),
    }
}

/// A uniform grid over a box.
pub(super) struct Grid {
    lo: DVec3,
    inv_cell: DVec3,
    dims: [usize; 3],
}

impl Grid {
    /// About one cell per box over `[lo, hi]`, cube-ish cells (flat boxes
    /// get one layer along their thin axis), coarser until `boxes` cover
    /// at most [`MAX_CELLS_PER_TRIANGLE`] cells each on average.
    pub(super) fn new(lo: DVec3, hi: DVec3, boxes: &[(DVec3, DVec3)]) -> Self {
        let n = boxes.len();
        let size = (hi - lo).max(DVec3::splat(1e-300));
        let volume_side = (size.x * size.y * size.z / n.max(1) as f64).cbrt();
        // Flat scenes (a plane, a single layer) have zero volume: fall back
        // to the area of the two largest sides.
        let mut sides = [size.x, size.y, size.z];
        sides.sort_by(f64::total_cmp);
        let area_side = (sides[1] * sides[2] / n.max(1) as f64).sqrt();
        let mut cell = volume_side.max(area_side * 0.5).max(1e-300);
        // At most ~4 cells per triangle and 2^22 in all, so the cell table
        // stays small next to the triangles themselves.
        let cap = (4 * n.max(1)).min(1 << 22) as f64;
        let dims_for = |cell: f64| {
            [size.x, size.y, size.z].map(|s| ((s / cell).ceil() as usize).clamp(1, 1024))
        };
        let mut grid = loop {
            let dims = dims_for(cell);
            if (dims[0] * dims[1] * dims[2]) as f64 <= cap {
                break Self::with_dims(lo, size, dims);
            }
            cell *= 1.25;
        };
        let most = MAX_CELLS_PER_TRIANGLE.saturating_mul(n as u64);
        while grid.cell_count() > 1 && grid.covered(boxes) > most {
            cell *= 1.25;
            grid = Self::with_dims(lo, size, dims_for(cell));
        }
        grid
    }

    fn with_dims(lo: DVec3, size: DVec3, dims: [usize; 3]) -> Self {
        Self {
            lo,
            inv_cell: DVec3::new(
                dims[0] as f64 / size.x,
                dims[1] as f64 / size.y,
                dims[2] as f64 / size.z,
            ),
            dims,
        }
    }

    /// The boxes' indices listed per cell in one flat array (counting
    /// sort): cell `c` holds `items[start[c]..start[c + 1]]`, sorted by
    /// star group, then index, with each entry's group beside it in
    /// `groups` (empty without `stars`: read sequentially, not looked up
    /// per pair).
    fn cell_lists(
        &self,
        boxes: &[(DVec3, DVec3)],
        stars: Option<&Stars>,
    ) -> (Vec<usize>, Vec<u32>, Vec<u32>) {
        let group = |k: usize| stars.map_or(NO_STAR, |s| s.group(k));
        let cells = self.cell_count();
        let mut start = vec![0usize; cells + 1];
        for b in boxes {
            self.for_cells(b, |c| start[c + 1] += 1);
        }
        for c in 0..cells {
            start[c + 1] += start[c];
        }
        let mut order: Vec<u32> = (0..boxes.len() as u32).collect();
        if stars.is_some() {
            order.sort_by_key(|&k| (group(k as usize), k));
        }
        let mut fill = start.clone();
        let mut items = vec![0u32; start[cells]];
        let mut groups = vec![NO_STAR; if stars.is_some() { start[cells] } else { 0 }];
        for k in order {
            let g = group(k as usize);
            self.for_cells(&boxes[k as usize], |c| {
                items[fill[c]] = k;
                if let Some(slot) = groups.get_mut(fill[c]) {
                    *slot = g;
                }
                fill[c] += 1;
            });
        }
        (start, items, groups)
    }

    /// The cells `boxes` cover, summed (without listing them).
    fn covered(&self, boxes: &[(DVec3, DVec3)]) -> u64 {
        boxes
            .iter()
            .map(|b| {
                let (a, c) = (self.coords(b.0), self.coords(b.1));
                (0..3).map(|k| (c[k] - a[k] + 1) as u64).product::<u64>()
            })
            .sum()
    }

    fn cell_count(&self) -> usize {
        self.dims[0] * self.dims[1] * self.dims[2]
    }

    fn coords(&self, p: DVec3) -> [usize; 3] {
        let q = (p - self.lo) * self.inv_cell;
        let c = |v: f64, d: usize| (v.max(0.0) as usize).min(d - 1);
        [
            c(q.x, self.dims[0]),
            c(q.y, self.dims[1]),
            c(q.z, self.dims[2]),
        ]
    }

    pub(super) fn cell_of(&self, p: DVec3) -> usize {
        let [x, y, z] = self.coords(p);
        (z * self.dims[1] + y) * self.dims[0] + x
    }

    fn for_cells(&self, b: &(DVec3, DVec3), mut f: impl FnMut(usize)) {
        let a = self.coords(b.0);
        let c = self.coords(b.1);
        for z in a[2]..=c[2] {
            for y in a[1]..=c[1] {
                for x in a[0]..=c[0] {
                    f((z * self.dims[1] + y) * self.dims[0] + x);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(p: [[f64; 3]; 3]) -> [DVec3; 3] {
        p.map(DVec3::from_array)
    }

    #[test]
    fn crossing_touching_and_coplanar_pairs() {
        let base = t([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]]);
        // Pierces the base through its interior.
        let pierce = t([[0.5, 0.5, -1.0], [0.5, 0.5, 1.0], [1.5, 0.2, 0.0]]);
        assert_eq!(contact(&base, &pierce), Contact::Interpenetrate);
        assert_eq!(contact(&pierce, &base), Contact::Interpenetrate);
        // A fin standing on the base: touches along a segment, one side.
        let fin = t([[0.2, 0.2, 0.0], [1.0, 0.2, 0.0], [0.5, 0.5, 1.0]]);
        assert_eq!(contact(&base, &fin), Contact::None);
        // A mesh neighbour sharing an edge, folded.
        let neighbour = t([[2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [2.0, 2.0, 0.7]]);
        assert_eq!(contact(&base, &neighbour), Contact::None);
        // Crosses the base's plane but beside the triangle.
        let beside = t([[3.0, 3.0, -1.0], [3.0, 3.0, 1.0], [4.0, 3.0, 0.0]]);
        assert_eq!(contact(&base, &beside), Contact::None);
        // Coplanar and overlapping; coplanar and apart.
        let over = t([[0.5, 0.5, 0.0], [3.0, 0.5, 0.0], [0.5, 3.0, 0.0]]);
        assert_eq!(contact(&base, &over), Contact::CoplanarOverlap);
        let apart = t([[5.0, 5.0, 0.0], [6.0, 5.0, 0.0], [5.0, 6.0, 0.0]]);
        assert_eq!(contact(&base, &apart), Contact::None);
    }

    #[test]
    fn shared_vertex_pairs_of_a_fan_do_not_interpenetrate() {
        // Two triangles of a bent fan meeting only at the apex.
        let a = t([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.3]]);
        let b = t([[0.0, 0.0, 0.0], [0.0, 1.0, 0.1], [-1.0, 1.0, -0.2]]);
        assert_eq!(contact(&a, &b), Contact::None);
    }

    #[test]
    fn grid_search_finds_each_pair_once() {
        // Ten crossing pairs spread along x, plus far-away clutter.
        let mut tris = Vec::new();
        for k in 0..10 {
            let x = k as f64 * 5.0;
            tris.push((
                2 * k,
                t([[x, 0.0, 0.0], [x + 2.0, 0.0, 0.0], [x, 2.0, 0.0]]),
            ));
            tris.push((
                2 * k + 1,
                t([
                    [x + 0.5, 0.5, -1.0],
                    [x + 0.5, 0.5, 1.0],
                    [x + 1.5, 0.2, 0.0],
                ]),
            ));
        }
        for k in 0..50 {
            let z = 10.0 + k as f64;
            tris.push((100 + k, t([[0.0, 0.0, z], [1.0, 0.0, z], [0.0, 1.0, z]])));
        }
        let found = find_pairs(&tris, u64::MAX, Cancel::default());
        assert!(found.complete);
        let mut pairs = found.interpenetrating.clone();
        pairs.sort_unstable();
        assert_eq!(
            pairs,
            (0..10).map(|k| (2 * k, 2 * k + 1)).collect::<Vec<_>>()
        );
        // A budget of one test stops early and says so.
        let partial = find_pairs(&tris, 1, Cancel::default());
        assert!(!partial.complete);
        assert_eq!(partial.tests, 1);
    }
}
