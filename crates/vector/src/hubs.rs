//! Hubs: screen vertices shared by many triangles whose corners there do
//! not overlap (the centre of a fan, a disc's or a cylinder cap's
//! triangulation, a sphere's pole seen end on), so that the pair phase can
//! skip every pair of them without looking at it.
//!
//! A triangle lies inside the wedge its corner spans at any of its
//! vertices, so two triangles sharing a vertex whose wedges there have no
//! interior point in common have no interior point in common either. Bins
//! cannot tell such pairs apart: all `N` triangles of a fan meet the bin
//! of its centre at any bin size, and looking at every pair costs `N^2`.
//! When all the corners at a vertex are pairwise disjoint (checked exactly
//! by sorting them by angle), every pair of its triangles is disjoint.
//!
//! [`star_pairs`] generalises the rule to vertices whose corners do
//! overlap (two fans on one centre, a cone seen from the side through its
//! apex): `hider_geom::star`'s stars, whose pairs are those whose closed
//! sectors meet there, listed in `O(m log m + k)` for `m` triangles and
//! `k` such pairs, while the bins skip every pair sharing a star.

use std::cmp::Ordering;
use std::collections::HashMap;

use hider_geom::fixed::FixedPt;
use hider_geom::star::{Stars, fixed_star_pairs, fixed_stars};

/// No hub.
pub const NONE: u32 = u32::MAX;

// A star's "none" is the bins' "no group".
const _: () = assert!(NONE == hider_geom::star::NO_STAR);

/// Triangles a vertex must have to be a hub: below it the pairs are few.
const LEAST: usize = 16;

/// The hubs of the triangles (screen vertices, positively oriented) that
/// `on` marks: per triangle, the hub ids of
/// its vertices that are hubs ([`NONE`] elsewhere), the one with the most
/// triangles first.
pub fn hubs(tris: &[[FixedPt; 3]], on: &[bool]) -> Vec<[u32; 3]> {
    let mut at: HashMap<(i32, i32), Vec<(u32, u8)>> = HashMap::new();
    for (k, t) in tris.iter().enumerate().filter(|(k, _)| on[*k]) {
        for (i, v) in t.iter().enumerate() {
            at.entry((v.x, v.y)).or_default().push((k as u32, i as u8));
        }
    }
    let mut out = vec![[NONE; 3]; tris.len()];
    let mut sizes: Vec<usize> = Vec::new();
    for corners in at.into_values() {
        if corners.len() < LEAST || !disjoint(tris, &corners) {
            continue;
        }
        let id = sizes.len() as u32;
        sizes.push(corners.len());
        for (k, _) in corners {
            let slot = out[k as usize]
                .iter_mut()
                .find(|h| **h == NONE)
                .expect("three vertices");
            *slot = id;
        }
    }
    for ids in &mut out {
        ids.sort_by_key(|&h| std::cmp::Reverse(sizes.get(h as usize).copied().unwrap_or(0)));
    }
    out
}

/// The pairs of triangles sharing a vertex, found from their sectors
/// there: the bins skip every pair sharing a star ([`StarPairs::stars_of`],
/// grouped by [`StarPairs::group`]), and the pair phase visits
/// [`StarPairs::partners`] instead, a superset of the pairs sharing a
/// star whose interiors overlap.
#[allow(
    dead_code,
    reason = "the pair phase in regions.rs takes it in place of `hubs` (a hook its owner makes)"
)]
#[derive(Clone, Debug, Default)]
pub struct StarPairs {
    stars: Stars,
    /// Where each triangle's partners start in `partners` (one more than
    /// the triangles).
    start: Vec<usize>,
    partners: Vec<u32>,
}

#[allow(
    dead_code,
    reason = "the pair phase in regions.rs takes it in place of `hubs` (a hook its owner makes)"
)]
impl StarPairs {
    /// The group a triangle is kept under in the bins (its first star),
    /// [`NONE`] for none.
    pub fn group(&self, t: usize) -> u32 {
        self.stars.group(t)
    }

    /// The stars of triangle `t` (padded with [`NONE`]): the groups its
    /// bin query skips.
    pub fn stars_of(&self, t: usize) -> [u32; 3] {
        self.stars.stars_of(t)
    }

    /// The triangles sharing a star with `t` whose sectors meet there,
    /// ascending.
    pub fn partners(&self, t: usize) -> &[u32] {
        self.start
            .get(t..t + 2)
            .map_or(&[], |r| &self.partners[r[0]..r[1]])
    }

    /// All partner pairs, each once.
    pub fn pairs(&self) -> usize {
        self.partners.len() / 2
    }
}

/// The stars of the triangles (screen vertices, positively oriented) that
/// `on` marks, and their sector pairs (see [`StarPairs`]). Stars whose
/// sectors overlap so much that they would save nothing are dissolved
/// (`hider_geom::star::DENSE_PAIRS_PER_MEMBER`); so are all of them when
/// they pair fewer triangles than grouping the bins costs
/// (`Stars::pay_for`).
#[allow(
    dead_code,
    reason = "the pair phase in regions.rs takes it in place of `hubs` (a hook its owner makes)"
)]
pub fn star_pairs(tris: &[[FixedPt; 3]], on: &[bool]) -> StarPairs {
    let mut stars = fixed_stars(tris.len(), |k| on[k].then_some(tris[k]));
    if !stars.pay_for(tris.len()) {
        return StarPairs::default();
    }
    let pairs = fixed_star_pairs(&mut stars, |t| tris[t as usize]);
    let mut start = vec![0usize; tris.len() + 1];
    for &(a, b) in &pairs {
        start[a as usize + 1] += 1;
        start[b as usize + 1] += 1;
    }
    for k in 0..tris.len() {
        start[k + 1] += start[k];
    }
    let mut fill = start.clone();
    let mut partners = vec![0u32; 2 * pairs.len()];
    // Pairs are sorted, so each triangle's partners come out ascending.
    for &(a, b) in &pairs {
        partners[fill[a as usize]] = b;
        fill[a as usize] += 1;
    }
    for &(a, b) in &pairs {
        partners[fill[b as usize]] = a;
        fill[b as usize] += 1;
    }
    for k in 0..tris.len() {
        partners[start[k]..start[k + 1]].sort_unstable();
    }
    StarPairs {
        stars,
        start,
        partners,
    }
}

/// Whether the corners `(triangle, vertex)` at one point are pairwise
/// disjoint: sorted by the angle of their first side, each one's second
/// side comes no later than the next one's first (counterclockwise).
fn disjoint(tris: &[[FixedPt; 3]], corners: &[(u32, u8)]) -> bool {
    let sides = |&(k, i): &(u32, u8)| {
        let t = &tris[k as usize];
        let i = usize::from(i);
        let v = t[i];
        let d = |p: FixedPt| {
            (
                i64::from(p.x) - i64::from(v.x),
                i64::from(p.y) - i64::from(v.y),
            )
        };
        (d(t[(i + 1) % 3]), d(t[(i + 2) % 3]))
    };
    let mut wedges: Vec<((i64, i64), (i64, i64))> = corners.iter().map(sides).collect();
    // A corner without area (a zero-area triangle) makes no claim either
    // way: keep the rule simple and leave the vertex alone.
    if wedges.iter().any(|&(a, b)| cross(a, b) <= 0) {
        return false;
    }
    wedges.sort_by(|x, y| ccw_order((1, 0), x.0, y.0));
    let n = wedges.len();
    (0..n).all(|i| {
        let (start, end) = wedges[i];
        let next = wedges[(i + 1) % n].0;
        // The next corner starts at angle 0 from this one when both start
        // along one ray: they overlap.
        ccw_order(start, end, next) != Ordering::Greater && same_ray(start, next) == (n == 1)
    })
}

fn cross(a: (i64, i64), b: (i64, i64)) -> i128 {
    i128::from(a.0) * i128::from(b.1) - i128::from(a.1) * i128::from(b.0)
}

fn same_ray(a: (i64, i64), b: (i64, i64)) -> bool {
    cross(a, b) == 0 && i128::from(a.0) * i128::from(b.0) + i128::from(a.1) * i128::from(b.1) > 0
}

/// The order of the counterclockwise angles from `s` to `a` and to `b`,
/// each in `[0, 360)` degrees, exact.
fn ccw_order(s: (i64, i64), a: (i64, i64), b: (i64, i64)) -> Ordering {
    // Half 0: angles in [0, 180); half 1: [180, 360).
    let half = |x: (i64, i64)| {
        let c = cross(s, x);
        u8::from(!(c > 0 || same_ray(s, x)))
    };
    half(a).cmp(&half(b)).then_with(|| 0.cmp(&cross(a, b)))
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::pairs::corners_overlap;

    fn tri(p: [(i32, i32); 3]) -> [FixedPt; 3] {
        p.map(|(x, y)| FixedPt { x, y })
    }

    /// `n` triangles around the origin, corner `k` spanning the angles
    /// `[k, k + 1 + overlap]` of `n` steps.
    fn fan(n: u32, overlap: u32) -> Vec<[FixedPt; 3]> {
        let at = |k: u32| {
            let a = std::f64::consts::TAU * f64::from(k % n) / f64::from(n);
            ((1e5 * a.cos()) as i32, (1e5 * a.sin()) as i32)
        };
        (0..n)
            .map(|k| tri([(0, 0), at(k), at(k + 1 + overlap)]))
            .collect()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        /// Triangles around one centre, between random directions (a
        /// fan with gaps), some of them spanning several steps (so that
        /// corners may overlap), and others elsewhere: no two triangles
        /// of one hub overlap, and a plain fan is a hub.
        #[test]
        fn no_two_triangles_of_a_hub_overlap(
            centre in (-1000i32..1000, -1000i32..1000),
            rays in prop::collection::vec((-50i32..50, -50i32..50, 1i32..20), 16..40),
            spans in prop::collection::vec((0usize..40, 1usize..4), 0..3),
            skip in 0usize..3,
            others in prop::collection::vec(prop::array::uniform3((-1500i32..1500, -1500i32..1500)), 0..6),
        ) {
            let mut dirs: Vec<(i64, i64)> = rays
                .iter()
                .filter(|&&(x, y, _)| (x, y) != (0, 0))
                .map(|&(x, y, r)| (i64::from(x * r), i64::from(y * r)))
                .collect();
            dirs.sort_by(|&a, &b| ccw_order((1, 0), a, b));
            dirs.dedup_by(|a, b| same_ray(*a, *b));
            let n = dirs.len();
            prop_assume!(n >= 3);
            let at = |d: (i64, i64)| FixedPt { x: centre.0 + d.0 as i32, y: centre.1 + d.1 as i32 };
            let c = FixedPt { x: centre.0, y: centre.1 };
            let mut tris: Vec<[FixedPt; 3]> = Vec::new();
            let mut add = |a: (i64, i64), b: (i64, i64)| {
                if cross(a, b) > 0 {
                    tris.push([c, at(a), at(b)]);
                }
            };
            for k in (0..n).filter(|k| k % 7 != skip) {
                add(dirs[k], dirs[(k + 1) % n]);
            }
            for &(k, len) in &spans {
                add(dirs[k % n], dirs[(k + len) % n]);
            }
            for o in &others {
                let t = o.map(|(x, y)| FixedPt { x, y });
                if orient2d_sign(&t) > 0 {
                    tris.push(t);
                }
            }
            let h = hubs(&tris, &vec![true; tris.len()]);
            for i in 0..tris.len() {
                for j in i + 1..tris.len() {
                    let shared = h[i].iter().any(|&a| a != NONE && h[j].contains(&a));
                    prop_assert!(!(shared && corners_overlap(&tris[i], &tris[j])), "{:?} {:?}", tris[i], tris[j]);
                }
            }
            let plain = tris.iter().filter(|t| t[0] == c).count();
            if spans.is_empty() && plain >= LEAST {
                prop_assert!(h.iter().take(plain).all(|ids| ids[0] != NONE));
            }
        }
    }

    fn orient2d_sign(t: &[FixedPt; 3]) -> i64 {
        hider_geom::edge::orient2d(t[0], t[1], t[2]).signum()
    }

    /// Two fans of `n` triangles on one centre, the second turned half a
    /// step and squeezed along `x` (as a tilted fan projects), so that
    /// each of its triangles overlaps two of the first's.
    fn two_fans(n: u32) -> Vec<[FixedPt; 3]> {
        let at = |k: f64, squeeze: f64| {
            let a = std::f64::consts::TAU * k / f64::from(n);
            ((1e5 * squeeze * a.cos()) as i32, (1e5 * a.sin()) as i32)
        };
        let fan = |turn: f64, squeeze: f64| {
            (0..n).map(move |k| {
                let k = f64::from(k) + turn;
                tri([(0, 0), at(k, squeeze), at(k + 1.0, squeeze)])
            })
        };
        fan(0.0, 1.0).chain(fan(0.5, 0.8)).collect()
    }

    #[test]
    fn two_fans_pair_only_their_neighbours_and_every_overlap() {
        // Every overlapping pair is a partner pair (they all share the
        // centre), and no partner shares nothing.
        let tris = two_fans(60);
        let s = star_pairs(&tris, &vec![true; tris.len()]);
        for i in 0..tris.len() {
            for j in i + 1..tris.len() {
                let partner = s.partners(i).contains(&(j as u32));
                assert_eq!(partner, s.partners(j).contains(&(i as u32)));
                if corners_overlap(&tris[i], &tris[j]) {
                    assert!(partner, "{i} {j} overlap but are no partners");
                }
            }
        }
        // Work counter: the old hubs leave the centre alone (corners
        // overlap across the fans), so the bins pair all `2n` triangles
        // there; the star pairs grow with `n`.
        assert!(
            hubs(&tris, &vec![true; tris.len()])
                .iter()
                .all(|h| h[0] == NONE)
        );
        let count = |n: u32| {
            let tris = two_fans(n);
            star_pairs(&tris, &vec![true; tris.len()]).pairs()
        };
        let (a, b) = (count(1_000), count(2_000));
        assert!(
            a >= 2_000 && b < 3 * a,
            "{a} pairs at 1,000 per fan, {b} at 2,000"
        );
    }

    #[test]
    fn a_fan_is_a_hub_and_an_overlapping_one_is_not() {
        let plain = fan(40, 0);
        let h = hubs(&plain, &[true; 40]);
        assert!(h.iter().all(|ids| ids[0] == 0 && ids[1] == NONE), "{h:?}");
        let doubled = fan(40, 1);
        let h = hubs(&doubled, &[true; 40]);
        assert!(h.iter().all(|ids| ids[0] == NONE), "{h:?}");
        // One triangle twice: two corners on one ray.
        let mut twice = fan(40, 0);
        twice.push(twice[3]);
        let h = hubs(&twice, &[true; 41]);
        assert!(h.iter().all(|ids| ids[0] == NONE), "{h:?}");
        // A half fan is a hub too.
        let half: Vec<_> = fan(80, 0).into_iter().take(40).collect();
        let h = hubs(&half, &[true; 40]);
        assert!(h.iter().all(|ids| ids[0] == 0), "{h:?}");
    }
}
