//! Stars for the pair phase: screen vertices shared by many triangles
//! (the centre of a fan, a disc's or a cylinder cap's triangulation, a
//! sphere's pole seen end on, two fans on one centre, a cone seen from the
//! side through its apex), whose pairs the bins cannot tell apart: all
//! `N` triangles at such a vertex meet the bin of the vertex at any bin
//! size, and looking at every pair costs `N^2`.
//!
//! A triangle lies inside the wedge its corner spans at any of its
//! vertices, so two triangles sharing a vertex whose closed sectors there
//! do not meet have no interior point in common. [`star_pairs`] takes
//! `hider_geom::star`'s stars, whose pairs are those whose closed sectors
//! meet there, listed in `O(m log m + k)` for `m` triangles and `k` such
//! pairs, while the bins skip every pair sharing a star. On a plain fan
//! (corners pairwise disjoint) that leaves each triangle its two
//! neighbours.

use hider_geom::fixed::FixedPt;
use hider_geom::star::{Stars, fixed_star_pairs, fixed_stars};

/// No group in the bins: a triangle at no star.
pub const NONE: u32 = hider_geom::star::NO_STAR;

/// The pairs of triangles sharing a vertex, found from their sectors
/// there: the bins skip every pair sharing a star ([`StarPairs::stars_of`],
/// grouped by [`StarPairs::group`]), and the pair phase visits
/// [`StarPairs::partners`] instead, a superset of the pairs sharing a
/// star whose interiors overlap.
#[derive(Clone, Debug, Default)]
pub struct StarPairs {
    stars: Stars,
    /// Where each triangle's partners start in `partners` (one more than
    /// the triangles).
    start: Vec<usize>,
    partners: Vec<u32>,
}

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
    #[cfg(test)]
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pairs::corners_overlap;

    fn tri(p: [(i32, i32); 3]) -> [FixedPt; 3] {
        p.map(|(x, y)| FixedPt { x, y })
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
        // Work counter: corners overlap across the fans, so bins alone
        // pair all `2n` triangles at the centre; the star pairs grow
        // with `n`.
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
}
