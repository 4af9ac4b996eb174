//! Stars: the pairs of triangles around a vertex many of them share,
//! found by angle instead of by bins.
//!
//! Every triangle of a fan (a disk or a cylinder cap), of a cone, or of
//! the pole of a UV sphere contains the shared vertex, so every bin that
//! vertex falls in lists all of them, and a bin grid enumerates all
//! `n^2 / 2` pairs (`hider analyze` on a flat fan of 2,000 triangles: 2
//! million exact tests, 5.6 s). Two triangles sharing a vertex `v` meet,
//! if at all, arbitrarily close to `v` (their intersection is convex and
//! holds `v`), so only pairs whose angular sectors at `v` meet can meet;
//! [`hider_geom::star::sector_pairs`] lists those in `O(n log n + k)`.
//! The bins then skip every pair sharing such a vertex (a *hub*: at
//! least [`hider_geom::star::MIN_STAR`] triangles), and the candidates here are tested with
//! the same exact tests, so the pairs found are those of the bins alone.
//!
//! In space ([`world_star_pairs`]) the sectors are compared in a plane of
//! projection. [`super::intersect::contact`] decides a pair sharing `v`
//! in one of two ways, and each needs the pair's sectors to meet in
//! projection along the axis `d` that the first triangle `a`'s plane
//! crosses most steeply ([`drop_axis`]):
//! - near-coplanar pairs by their interiors overlapping in exactly that
//!   projection, which needs the projected sectors to overlap at `v`;
//! - crossing pairs by the segment of `L`, the planes' common line, that
//!   both contain. It starts at `v`, so a ray of `L` from `v` lies in both
//!   sectors; it lies in `a`'s plane, which is not parallel to axis `d`,
//!   so its projection along `d` is a ray too, in both projected sectors.
//!
//! So for each axis `d` the pairs with one triangle of drop axis `d` whose
//! closed sectors meet in projection along `d` are a superset of the pairs
//! `contact` can report (a triangle whose projection along its own drop
//! axis is flat, which rounding of its normal can cause, is asked along
//! all three). A star dense in those projections (a steeply pleated fan,
//! whose nearly vertical members each span most of a half turn seen along
//! `x` or `y`) is searched around one axis for the whole star instead
//! ([`axis`]). On the screen ([`screen_star_pairs`]) the snapped triangles
//! are compared directly.

use glam::DVec3;
use hider_geom::star::{AngularPoint, Sector, Stars, dense_limit, sector_pairs_within};
use hider_scene::ScreenTri;

use super::intersect::{COPLANAR_TOLERANCE, drop_axis, project};
use super::predicates::orient2d;

mod axis;

/// A point of a plane of projection, ordered exactly by [`orient2d`].
#[derive(Clone, Copy, Debug, PartialEq)]
struct Flat([f64; 2]);

impl AngularPoint for Flat {
    fn orient(a: Self, b: Self, c: Self) -> i8 {
        orient2d(a.0, b.0, c.0)
    }

    fn upper_of(self, apex: Self) -> bool {
        self.0[1] > apex.0[1] || (self.0[1] == apex.0[1] && self.0[0] > apex.0[0])
    }
}

/// The stars of world-space triangles (corners are the same vertex when
/// their coordinates are equal), books included, if they pay for a search
/// over their pairs ([`Stars::paying_with_books`]).
pub(crate) fn world_stars(tris: &[(u32, [DVec3; 3])]) -> Stars {
    // `+ 0.0` makes -0 and 0 one key.
    let key = |p: DVec3| [p.x + 0.0, p.y + 0.0, p.z + 0.0].map(f64::to_bits);
    Stars::paying_with_books(
        tris.len(),
        |k| Some(tris[k].1.map(key)),
        hider_geom::star::MIN_STAR,
    )
}

/// Candidate pairs `(i, j)`, `i < j` (indices into `tris`), of triangles
/// sharing a hub of `stars` whose sectors meet there in a projection
/// that [`super::intersect::contact`] may use (see the module
/// documentation): every pair sharing a hub that `contact` can report is
/// among them. Sorted, each once. A star dense in its members' own
/// projections is searched around one axis ([`axis`]); dense around
/// that too, it is dissolved first (its pairs go back to the bins, see
/// [`hider_geom::star::DENSE_PAIRS_PER_MEMBER`]).
pub(crate) fn world_star_pairs(tris: &[(u32, [DVec3; 3])], stars: &mut Stars) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    let mut dense = Vec::new();
    'stars: for h in 0..stars.len() {
        let before = out.len();
        let members = stars.members(h);
        if stars.is_book(h) {
            match book_pairs(tris, members) {
                Some(pairs) => out.extend(pairs),
                None => dense.push(h),
            }
            continue;
        }
        // The axes along which each member asks: its drop axis, or all
        // three when its projection along that one is flat.
        let asks: Vec<u8> = members
            .iter()
            .map(|&(t, _)| {
                let c = &tris[t as usize].1;
                let d = drop_axis(c);
                let p = c.map(|q| project(q, d));
                if orient2d(p[0], p[1], p[2]) == 0 {
                    0b111
                } else {
                    1 << d
                }
            })
            .collect();
        for d in 0..3 {
            if !asks.iter().any(|&a| a & (1 << d) != 0) {
                continue;
            }
            let mut who = Vec::with_capacity(members.len());
            let mut sectors = Vec::with_capacity(members.len());
            let mut apex = Flat([0.0; 2]);
            for (m, &(t, corner)) in members.iter().enumerate() {
                let c = tris[t as usize].1.map(|q| Flat(project(q, d)));
                let i = usize::from(corner);
                apex = c[i];
                // A member projecting to a point is collinear in space:
                // `contact` reports nothing for it.
                if let Some(s) = Sector::around(c[i], c[(i + 1) % 3], c[(i + 2) % 3]) {
                    who.push(m);
                    sectors.push(s);
                }
            }
            let asked = |k: usize| asks[who[k]] & (1 << d) != 0;
            let Some(pairs) = sector_pairs_within(apex, &sectors, asked, dense_limit(who.len()))
            else {
                out.truncate(before);
                // Sectors that overlap in the members' own projections
                // may still be apart around one axis for the whole star.
                match axis::axis_pairs(tris, members, dense_limit(members.len())) {
                    Some(pairs) => out.extend(pairs),
                    None => dense.push(h),
                }
                continue 'stars;
            };
            for (x, y) in pairs {
                let (a, b) = (members[who[x as usize]].0, members[who[y as usize]].0);
                out.push((a.min(b), a.max(b)));
            }
        }
    }
    if !dense.is_empty() {
        stars.retain(|h| dense.binary_search(&h).is_err());
        // A pair of a dissolved star that also shares a kept one stays.
        out.retain(|&(a, b)| stars.share(a as usize, b as usize));
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// The candidate pairs of a book's pages (`members`: triangle, corner
/// where the spine starts) that [`super::intersect::contact`] may report,
/// as pairs of triangles, or `None` for a dense book (see
/// [`hider_geom::star::DENSE_PAIRS_PER_MEMBER`]).
///
/// Two pages share two corners, each exactly on the other's plane, so
/// neither has corners strictly on both sides of the other: `contact`
/// reports a pair only through its coplanar test, which needs the third
/// corner `c_b` of each within `t L` of the other's plane (`t` the
/// [`super::intersect::COPLANAR_TOLERANCE`], `L` the pair's longest edge).
/// That distance is `r_b |sin(phi_a - phi_b)|`, where `r` is a page's
/// reach from the spine's line and `phi` its angle around it, so a pair
/// can be reported only if `|sin(phi_a - phi_b)| <= t L / max(r_a, r_b)
/// <= t max(s_a, s_b)`, `s = L / r` a page's own slenderness (its longest
/// edge over its reach). Sorted by angle modulo a half turn (opposite
/// pages are coplanar too), each page lists the pages within its own
/// window, twice as wide as that bound, plus `1e-9` for the rounding of
/// the angles: pages fanned around a spine then meet few others, and
/// the test runs on the near-coplanar pairs only.
fn book_pairs(tris: &[(u32, [DVec3; 3])], members: &[(u32, u8)]) -> Option<Vec<(u32, u32)>> {
    use std::f64::consts::{FRAC_PI_2, PI};
    let (t0, i0) = members[0];
    let c0 = &tris[t0 as usize].1;
    let (p, q) = (c0[usize::from(i0)], c0[(usize::from(i0) + 1) % 3]);
    let axis = (q - p).normalize();
    let e1 = axis.any_orthonormal_vector();
    let e2 = axis.cross(e1);
    // (angle modulo a half turn, half-width of the window, triangle).
    let pages: Vec<(f64, f64, u32)> = members
        .iter()
        .map(|&(t, i)| {
            let c = &tris[t as usize].1;
            let w = c[(usize::from(i) + 2) % 3] - p;
            let off = w - axis * w.dot(axis);
            let reach = off.length();
            let longest = (0..3)
                .map(|k| (c[(k + 1) % 3] - c[k]).length())
                .fold(0.0, f64::max);
            let slender = longest / reach;
            let sine = 2.0 * COPLANAR_TOLERANCE * slender + 1e-9;
            let half = if sine.is_finite() && sine < 1.0 {
                sine.asin() + 1e-9
            } else {
                FRAC_PI_2
            };
            let phi = off.dot(e2).atan2(off.dot(e1)).rem_euclid(PI);
            (if phi.is_finite() { phi } else { 0.0 }, half, t)
        })
        .collect();
    window_pairs(pages, dense_limit(members.len()))
}

/// The pairs `(lower, higher)` of `items` (angle modulo a half turn,
/// half-width of the item's window, triangle) in which one item's angle
/// lies within the other's window, each item listing those within its own
/// (a pair whose angles are within the wider of its two windows is
/// found); `None` once more than `most` are listed. Not deduplicated.
/// `O(n log n + k)` for `k` pairs listed.
fn window_pairs(mut items: Vec<(f64, f64, u32)>, most: usize) -> Option<Vec<(u32, u32)>> {
    use std::f64::consts::{FRAC_PI_2, PI};
    items.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    let mut out = Vec::new();
    let n = items.len();
    for (k, &(phi, half, t)) in items.iter().enumerate() {
        let mut take = |j: usize| {
            let u = items[j].2;
            out.push((t.min(u), t.max(u)));
        };
        if half >= FRAC_PI_2 {
            (0..n).filter(|&j| j != k).for_each(&mut take);
        } else {
            // Forward then backward around the circle of angles modulo
            // a half turn, while within the window (the distances grow
            // monotonically along each walk).
            let ahead = |j: usize| (items[j].0 - phi).rem_euclid(PI);
            let behind = |j: usize| (phi - items[j].0).rem_euclid(PI);
            let mut j = (k + 1) % n;
            while j != k && ahead(j) <= half {
                take(j);
                j = (j + 1) % n;
            }
            let mut j = (k + n - 1) % n;
            while j != k && behind(j) <= half {
                take(j);
                j = (j + n - 1) % n;
            }
        }
        if out.len() > most {
            return None;
        }
    }
    Some(out)
}

/// The stars of snapped screen triangles ([`hider_geom::star::fixed_stars`]),
/// if they pay for a search over their pairs ([`Stars::paying`]).
pub(crate) fn screen_stars(tris: &[ScreenTri]) -> Stars {
    hider_geom::star::fixed_stars_paying(tris.len(), |k| Some(tris[k].v))
}

/// Candidate pairs `(i, j)`, `i < j`, of screen triangles sharing a hub of
/// `stars` whose closed sectors meet there: a superset of the pairs whose
/// interiors overlap. Sorted, each once.
pub(crate) fn screen_star_pairs(tris: &[ScreenTri], stars: &mut Stars) -> Vec<(u32, u32)> {
    hider_geom::star::fixed_star_pairs(stars, |t| tris[t as usize].v)
}
