//! Occluders around a star (the centre of a fan, a cone's apex seen end
//! on), found by their sectors there instead of by bins.
//!
//! Bins cannot tell a star's triangles apart: `N` spokes of a fan meet at
//! the centre and spread out to the rim, so a bin anywhere holds about
//! `sqrt(N)` of them (they are `N` times longer than they are wide) and a
//! short rim edge would look at all of them, `N^1.5` over the rim. A
//! triangle lies inside the wedge its corner spans at any of its vertices,
//! so an occluder at a star can reach a segment's neighbourhood (a convex
//! polygon not holding the star's centre) only when its sector there
//! meets the polygon's directions from the centre, one arc under a half
//! turn: sorted by start, the sectors starting in the arc are one run of
//! that order, and those holding its first direction are the last one
//! starting before it and that one's partners (a sector holding a
//! direction holds every later start up to it; [`crate::stars`]).

use std::cmp::Ordering;

use hider_geom::star::{AngularPoint, Sector, compare};
use i_overlay::i_float::int::point::IntPoint;

use crate::grid::Grid;
use crate::stars::StarPairs;

/// A point in grid units, wide enough for any screen triangle's corners
/// on a refined grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct GridPt {
    x: i64,
    y: i64,
}

impl GridPt {
    pub fn new(x: i64, y: i64) -> Self {
        Self { x, y }
    }
}

impl AngularPoint for GridPt {
    fn orient(a: Self, b: Self, c: Self) -> i8 {
        let d = i128::from(b.x - a.x) * i128::from(c.y - a.y)
            - i128::from(b.y - a.y) * i128::from(c.x - a.x);
        d.signum() as i8
    }

    fn upper_of(self, apex: Self) -> bool {
        self.y > apex.y || (self.y == apex.y && self.x > apex.x)
    }
}

/// One star's occluders: the triangles binned under it (its group), by
/// the start of their sectors at its centre.
pub(super) struct StarOccluders {
    apex: GridPt,
    /// Triangles, ascending by sector start.
    members: Vec<u32>,
    /// Their sectors, in the same order.
    sectors: Vec<Sector<GridPt>>,
    /// The group the members are binned under.
    group: u32,
}

impl StarOccluders {
    /// The star of group `group` made of `members` (triangles of `grid`
    /// whose corners are `corners`), or `None` when they share no single
    /// corner (a group of one or two triangles of a star whose other
    /// triangles belong to earlier stars): its members are then binned
    /// one by one.
    pub fn new(
        grid: &Grid,
        corners: &[[hider_geom::FixedPt; 3]],
        group: u32,
        members: &[u32],
    ) -> Option<Self> {
        let points = |t: u32| {
            corners[t as usize]
                .map(|p| GridPt::new(i64::from(p.x) << grid.shift, i64::from(p.y) << grid.shift))
        };
        let mut common: Vec<GridPt> = points(*members.first()?).to_vec();
        for &t in &members[1..] {
            let v = points(t);
            common.retain(|c| v.contains(c));
        }
        // The partners are of sectors at the star's centre: with two or
        // more common corners the centre is not known.
        let [apex] = common[..] else {
            return None;
        };
        let mut order: Vec<(u32, Sector<GridPt>)> = members
            .iter()
            .map(|&t| {
                let v = points(t);
                let i = v.iter().position(|&c| c == apex).expect("a common corner");
                Sector::around(apex, v[(i + 1) % 3], v[(i + 2) % 3]).map(|s| (t, s))
            })
            .collect::<Option<_>>()?;
        order.sort_by(|a, b| compare(apex, a.1.start, b.1.start).then(a.0.cmp(&b.0)));
        Some(Self {
            apex,
            members: order.iter().map(|m| m.0).collect(),
            sectors: order.iter().map(|m| m.1).collect(),
            group,
        })
    }

    /// Calls `visit` with every member whose sector meets the directions
    /// of the convex polygon `poly` from the centre (every member when
    /// the polygon holds the centre); a member may come more than once.
    /// `partners` are the star pairs the members' groups come from.
    pub fn query(
        &self,
        poly: &[IntPoint],
        partners: &StarPairs,
        group_of: impl Fn(u32) -> u32,
        mut visit: impl FnMut(u32),
    ) {
        let a = self.apex;
        let pts: Vec<GridPt> = poly
            .iter()
            .map(|p| GridPt::new(i64::from(p.x), i64::from(p.y)))
            .collect();
        let Some(arc) = directions(a, &pts) else {
            self.members.iter().for_each(|&t| visit(t));
            return;
        };
        let n = self.members.len();
        let before = |d: GridPt| move |k: &Sector<GridPt>| compare(a, k.start, d) == Ordering::Less;
        let lo = self.sectors.partition_point(before(arc.start));
        let hi = self
            .sectors
            .partition_point(|k| compare(a, k.start, arc.end) != Ordering::Greater);
        if compare(a, arc.start, arc.end) != Ordering::Greater {
            self.members[lo..hi.max(lo)].iter().for_each(|&t| visit(t));
        } else {
            // The arc crosses the x axis: the end of the order, then its
            // beginning.
            self.members[lo..].iter().for_each(|&t| visit(t));
            self.members[..hi].iter().for_each(|&t| visit(t));
        }
        // The last sector starting at or before the arc's first direction
        // (circularly): every sector holding that direction holds its
        // start, so is it or one of its partners.
        let last = self
            .sectors
            .partition_point(|k| compare(a, k.start, arc.start) != Ordering::Greater);
        let j = self.members[(last + n - 1) % n];
        visit(j);
        for &t in partners.partners(j as usize) {
            if group_of(t) == self.group {
                visit(t);
            }
        }
    }
}

/// The closed arc of directions from `apex` of the convex polygon
/// `pts` (from its most clockwise corner counter-clockwise to its most
/// counter-clockwise one), `None` when the polygon holds `apex` (inside
/// or on its boundary) or has no corner.
fn directions(apex: GridPt, pts: &[GridPt]) -> Option<Sector<GridPt>> {
    let n = pts.len();
    if n == 0 {
        return None;
    }
    // Inside or on a convex polygon: on no edge's outer side, whichever
    // way it turns (a degenerate polygon, all collinear, holds only the
    // points of its segment).
    let sides: Vec<i8> = (0..n)
        .map(|k| GridPt::orient(pts[k], pts[(k + 1) % n], apex))
        .collect();
    let holds = if sides.iter().all(|&s| s == 0) {
        on_hull_segment(apex, pts)
    } else {
        sides.iter().all(|&s| s >= 0) || sides.iter().all(|&s| s <= 0)
    };
    if holds {
        return None;
    }
    // Outside a convex polygon its directions span less than a half turn,
    // so the corner no other one is clockwise of starts the arc.
    let start = *pts
        .iter()
        .find(|&&p| pts.iter().all(|&q| GridPt::orient(apex, p, q) >= 0))?;
    let end = *pts
        .iter()
        .find(|&&p| pts.iter().all(|&q| GridPt::orient(apex, p, q) <= 0))?;
    Some(Sector { start, end })
}

/// Whether `apex` lies between the extreme points of collinear `pts`
/// (collinear with them too).
fn on_hull_segment(apex: GridPt, pts: &[GridPt]) -> bool {
    let key = |p: &GridPt| (p.x, p.y);
    let (lo, hi) = (
        pts.iter().min_by_key(|p| key(p)).expect("a corner"),
        pts.iter().max_by_key(|p| key(p)).expect("a corner"),
    );
    (key(lo)..=key(hi)).contains(&key(&apex))
}

/// The convex hull of `points` (counter-clockwise in the y-up sense,
/// collinear points left out; Andrew's monotone chain): one polygon
/// holding a whole star for the bins.
pub(super) fn convex_hull(mut points: Vec<IntPoint>) -> Vec<IntPoint> {
    points.sort_unstable_by_key(|p| (p.x, p.y));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let cross = |o: IntPoint, a: IntPoint, b: IntPoint| {
        i64::from(a.x - o.x) * i64::from(b.y - o.y) - i64::from(a.y - o.y) * i64::from(b.x - o.x)
    };
    let mut hull: Vec<IntPoint> = Vec::with_capacity(points.len() + 1);
    for pass in [
        &points[..],
        &points.iter().rev().copied().collect::<Vec<_>>()[..],
    ] {
        let floor = hull.len();
        for &p in pass {
            while hull.len() >= floor + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

#[cfg(test)]
mod tests {
    use hider_geom::FixedPt;
    use proptest::prelude::*;

    use super::*;
    use crate::grid::bins::tests::meet;
    use crate::stars::star_pairs;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        /// Every triangle of a star that meets a convex query polygon
        /// comes from the star's query: fans of random spokes around a
        /// centre, with triangles overlapping them, and margin-sized or
        /// large query polygons anywhere (holding the centre or not).
        #[test]
        fn a_star_finds_every_member_meeting_the_query(
            centre in (20_000i32..80_000, 20_000i32..80_000),
            spokes in prop::collection::vec((0.0f64..std::f64::consts::TAU, 100.0f64..20_000.0), 12..60),
            extra in prop::collection::vec((0usize..60, 0usize..60), 0..6),
            queries in prop::collection::vec(
                (0i32..100_000, 0i32..100_000, -3_000i32..3_000, -3_000i32..3_000, 1i32..40), 1..20),
        ) {
            let grid = Grid { shift: 0, width: 100_000, height: 100_000 };
            let c = FixedPt { x: centre.0, y: centre.1 };
            let mut spokes = spokes;
            spokes.sort_by(|a, b| a.0.total_cmp(&b.0));
            let tip = |k: usize| {
                let (a, r) = spokes[k % spokes.len()];
                FixedPt { x: c.x + (r * a.cos()) as i32, y: c.y + (r * a.sin()) as i32 }
            };
            let mut tris: Vec<[FixedPt; 3]> = (0..spokes.len()).map(|k| [c, tip(k), tip(k + 1)]).collect();
            tris.extend(extra.iter().map(|&(i, j)| [c, tip(i), tip(j + 1)]));
            let on = vec![true; tris.len()];
            let pairs = star_pairs(&tris, &on);
            let polys: Vec<Vec<IntPoint>> = tris
                .iter()
                .map(|t| t.iter().map(|p| IntPoint::new(p.x, p.y)).collect())
                .collect();
            let groups: Vec<u32> = (0..tris.len()).map(|t| pairs.group(t)).collect();
            let star = StarOccluders::new(&grid, &tris, 0, &(0..tris.len() as u32).filter(|&t| groups[t as usize] == 0).collect::<Vec<_>>());
            let Some(star) = star else { return Ok(()) };
            for &(x, y, dx, dy, m) in &queries {
                // The margin hexagon of a segment, as the index builds it.
                let (p, q) = ((x, y), (x + dx, y + dy));
                let (p, q) = if p.0 <= q.0 { (p, q) } else { (q, p) };
                let s = if q.1 >= p.1 { 1 } else { -1 };
                let poly: Vec<IntPoint> = [
                    (p.0 - m, p.1 - s * m), (p.0 + m, p.1 - s * m), (q.0 + m, q.1 - s * m),
                    (q.0 + m, q.1 + s * m), (q.0 - m, q.1 + s * m), (p.0 - m, p.1 + s * m),
                ]
                .iter()
                .map(|&(a, b)| IntPoint::new(a, b))
                .collect();
                let mut found = vec![false; tris.len()];
                star.query(&poly, &pairs, |t| groups[t as usize], |t| found[t as usize] = true);
                for (t, tri) in polys.iter().enumerate() {
                    if groups[t] == 0 && crate::sweep::orient(tri[0], tri[1], tri[2]) != 0 {
                        prop_assert!(!meet(tri, &poly) || found[t], "member {t} {tri:?} meets {poly:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn the_hull_holds_every_point_and_only_turns_one_way() {
        let pts: Vec<IntPoint> = [(0, 0), (10, 0), (5, 5), (10, 10), (0, 10), (5, 0), (3, 7)]
            .iter()
            .map(|&(x, y)| IntPoint::new(x, y))
            .collect();
        let hull = convex_hull(pts.clone());
        assert_eq!(hull.len(), 4, "{hull:?}");
        let g = |p: IntPoint| GridPt::new(i64::from(p.x), i64::from(p.y));
        for k in 0..hull.len() {
            let (a, b) = (g(hull[k]), g(hull[(k + 1) % hull.len()]));
            for &p in &pts {
                assert!(GridPt::orient(a, b, g(p)) >= 0, "{p:?} outside {hull:?}");
            }
        }
    }

    #[test]
    fn the_arc_of_a_square_seen_from_outside() {
        let sq = [(2, -1), (4, -1), (4, 1), (2, 1)].map(|(x, y)| GridPt::new(x, y));
        let o = GridPt::new(0, 0);
        let arc = directions(o, &sq).expect("outside");
        assert_eq!((arc.start, arc.end), (sq[0], sq[3]));
        assert!(directions(GridPt::new(3, 0), &sq).is_none());
        assert!(directions(GridPt::new(2, 0), &sq).is_none());
        assert!(directions(GridPt::new(4, 1), &sq).is_none());
    }
}
