//! A star's candidate pairs around one axis for the whole star, for stars
//! whose sectors overlap in their members' own drop-axis projections.
//!
//! A steeply pleated fan (rim alternately above and below the apex) has
//! nearly vertical members: each asks along its own `x` or `y` drop axis,
//! where every member's sector spans most of a half turn, so the
//! per-member projections list all `n^2 / 2` pairs. Seen along the fan's
//! axis its sectors tile the circle. The two ways
//! [`super::super::intersect::contact`] reports a pair sharing the apex
//! `v` are bounded apart here:
//!
//! - **Crossing pairs.** The two triangles share a segment of `L`, their
//!   planes' common line, starting at `v` (their intersection is convex
//!   and holds `v`, an extreme point of both). That ray lies in both
//!   closed triangles and in both planes. Projected along any axis `n`
//!   not parallel to it, it is a ray in both projected closed sectors, so
//!   those meet. It is parallel to `n` only if both planes contain `n`
//!   (both members *edge-on*, flat seen along `n`); `contact` then asks
//!   each to have corners strictly on both sides of the other's plane (an
//!   exact test), so both are seen as opposite directions from `v`, half
//!   turns, and two closed half turns always meet. The projection
//!   is along the exact vector `w - v` for a point `w` near `v + n`, and
//!   every angular comparison is the exact sign of `orient3d(v, w, p,
//!   q)`, so the sectors' order is exact (as [`super::Flat`]'s is).
//! - **Near-coplanar pairs.** `contact` asks every corner of each within
//!   `t L` of the other's plane (`t` the
//!   [`super::super::intersect::COPLANAR_TOLERANCE`], `L` the pair's longest
//!   edge). With `b`'s edges from the apex `e1, e2` each within `t L` of
//!   `a`'s plane, the part of `b`'s normal `e1 x e2` across `a`'s normal is
//!   at most `t L (|e1| + |e2|)`, so the sine of the angle between the
//!   two planes is at most `t L (|e1| + |e2|) / |e1 x e2|`, and `L` is the
//!   longer member's own longest edge: the angle is within the window of
//!   the member with the longer edge (doubled here, and widened by the
//!   rounding of the normals: `16 eps |e1| |e2| / |e1 x e2|` each). Two
//!   unit normals that close have horizontal parts (across `n`) as close,
//!   so their azimuths around `n`, modulo a half turn, differ by at most
//!   `asin(window / |horizontal part|)`: each member lists the members
//!   within that of its azimuth ([`super::window_pairs`], as a book's
//!   pages are listed by their angle around the spine), and keeps those
//!   whose whole unit normals are that close (the azimuth forgets their
//!   height: a pleat and the one opposite have parallel horizontal
//!   parts). A pleat's normals
//!   are nearly horizontal and turn with the fan, so it lists none; a
//!   flat fan's are all vertical and would list every pair (its members'
//!   own projections serve it instead, and are tried first).
//!
//! The axis is the sum of the members' normals oriented by their winding
//! from the apex (a fan's, a cone's or a pleated fan's axis); any axis
//! keeps the candidates a superset, a poor one only makes the star dense.

use glam::DVec3;
use hider_geom::star::{AngularPoint, Sector, sector_pairs_within};

use super::super::intersect::COPLANAR_TOLERANCE;
use super::super::predicates::orient3d;
use super::window_pairs;

/// The exact frame of the projection: the apex `v`, a point `w` on the
/// axis (the axis is `w - v` exactly), and references `r` (angle 0) and
/// `r2` (a quarter turn counter-clockwise of it, or at least strictly
/// between 0 and a half turn).
#[derive(Debug, PartialEq)]
struct Frame {
    v: DVec3,
    w: DVec3,
    r: DVec3,
    r2: DVec3,
}

impl Frame {
    /// The sign of the turn from the direction of `b` to that of `c`
    /// around the axis, seen from its tip: `det(w - v, b - v, c - v)`.
    fn turn(&self, b: DVec3, c: DVec3) -> i8 {
        // Shewchuk's orient3d is det[v - c, w - c, b - c], the negative.
        -orient3d(self.v, self.w, b, c)
    }
}

/// A point seen along the frame's axis: its direction from the apex is
/// the angle around the axis (the apex itself when the point lies on the
/// axis's line, which [`Frame::point`] maps to `v`).
#[derive(Clone, Copy, Debug)]
struct Along<'f> {
    p: DVec3,
    frame: &'f Frame,
}

impl PartialEq for Along<'_> {
    fn eq(&self, other: &Self) -> bool {
        self.p == other.p
    }
}

impl AngularPoint for Along<'_> {
    fn orient(a: Self, b: Self, c: Self) -> i8 {
        // Every caller orients around the apex, the frame's `v`.
        debug_assert_eq!(a.p, a.frame.v);
        a.frame.turn(b.p, c.p)
    }

    fn upper_of(self, _apex: Self) -> bool {
        let f = self.frame;
        match f.turn(f.r, self.p) {
            1.. => true,
            ..0 => false,
            // On the reference's line: its own direction (angle 0) is
            // clockwise of `r2`, the opposite one counter-clockwise.
            0 => f.turn(f.r2, self.p) < 0,
        }
    }
}

impl Frame {
    /// The frame of the axis `n` (unit) at `v`, with points at distance
    /// `scale` (at least `v`'s largest coordinate, so that `v + n scale`
    /// differs from `v`); `None` when rounding left it degenerate.
    fn new(v: DVec3, n: DVec3, scale: f64) -> Option<Self> {
        let e1 = n.any_orthonormal_vector();
        let e2 = n.cross(e1);
        let mut f = Self {
            v,
            w: v + n * scale,
            r: v + e1 * scale,
            r2: v + e2 * scale,
        };
        if f.turn(f.r, f.r2) < 0 {
            f.r2 = v - e2 * scale;
        }
        (f.turn(f.r, f.r2) > 0).then_some(f)
    }

    /// `p` as seen along the axis: `v` itself when `p` lies on the axis's
    /// line (on the planes through it and `r`, and through it and `r2`,
    /// which meet only there), so that [`Sector::around`] sees it at the
    /// apex.
    fn point(&self, p: DVec3) -> Along<'_> {
        let on_axis = self.turn(self.r, p) == 0 && self.turn(self.r2, p) == 0;
        Along {
            p: if on_axis { self.v } else { p },
            frame: self,
        }
    }
}

/// Candidate pairs `(lower, higher)` (indices into `tris`) of the star of
/// `members` (triangle, corner at the hub) that
/// [`super::super::intersect::contact`] may report, found around one axis
/// for the whole star (see the module documentation), or `None` when more
/// than `most` are in sight around each axis tried. Not sorted.
pub(super) fn axis_pairs(
    tris: &[(u32, [DVec3; 3])],
    members: &[(u32, u8)],
    most: usize,
) -> Option<Vec<(u32, u32)>> {
    let (t0, i0) = *members.first()?;
    let v = tris[t0 as usize].1[usize::from(i0)];
    let normals = members.iter().map(|m| {
        let (p, q) = edges(tris, m);
        (p - v).cross(q - v)
    });
    // The members' normals summed by area, then as unit vectors (a few
    // large members off the axis tilt the first), then the coordinate
    // axes; the first around which the star is not dense.
    let by_area: DVec3 = normals.clone().sum();
    let by_count: DVec3 = normals.filter_map(DVec3::try_normalize).sum();
    let mut tried: Vec<DVec3> = Vec::new();
    for axis in [by_area, by_count, DVec3::X, DVec3::Y, DVec3::Z] {
        let Some(n) = axis.try_normalize() else {
            continue;
        };
        if tried.iter().any(|&m| m.dot(n) > 1.0 - 1e-6) {
            continue;
        }
        tried.push(n);
        if let Some(pairs) = around(tris, members, v, n, most) {
            return Some(pairs);
        }
    }
    None
}

/// A member's corners after the apex, in its winding.
fn edges(tris: &[(u32, [DVec3; 3])], &(t, i): &(u32, u8)) -> (DVec3, DVec3) {
    let c = &tris[t as usize].1;
    let i = usize::from(i);
    (c[(i + 1) % 3], c[(i + 2) % 3])
}

/// [`axis_pairs`] around the axis `n` (unit) through the apex `v`.
fn around(
    tris: &[(u32, [DVec3; 3])],
    members: &[(u32, u8)],
    v: DVec3,
    n: DVec3,
    most: usize,
) -> Option<Vec<(u32, u32)>> {
    let edges = |m: &(u32, u8)| edges(tris, m);
    let reach = members
        .iter()
        .map(|m| {
            let (p, q) = edges(m);
            (p - v).abs().max((q - v).abs()).max_element()
        })
        .fold(v.abs().max_element(), f64::max);
    let frame = Frame::new(v, n, reach.max(1.0))?;
    let apex = frame.point(v);

    // Crossing pairs: sectors around the axis.
    let mut who = Vec::with_capacity(members.len());
    let mut sectors = Vec::with_capacity(members.len());
    for (m, member) in members.iter().enumerate() {
        let (p, q) = edges(member);
        let (p, q) = (frame.point(p), frame.point(q));
        // A member with both corners on the axis's line is collinear in
        // space: `contact` reports nothing for it.
        if let Some(s) = Sector::around(apex, p, q) {
            who.push(m);
            sectors.push(s);
        }
    }
    let crossing = sector_pairs_within(apex, &sectors, |_| true, most)?;
    let mut out: Vec<(u32, u32)> = crossing
        .into_iter()
        .map(|(x, y)| {
            let (a, b) = (members[who[x as usize]].0, members[who[y as usize]].0);
            (a.min(b), a.max(b))
        })
        .collect();

    // Near-coplanar pairs: normals' azimuths around the axis.
    let (e1, e2) = {
        let e1 = n.any_orthonormal_vector();
        (e1, n.cross(e1))
    };
    let eps = f64::EPSILON;
    // Per member: unit normal and window (a chord between unit normals).
    let normals: Vec<(DVec3, f64)> = members
        .iter()
        .map(|member| {
            let (p, q) = edges(member);
            let (a, b) = (p - v, q - v);
            let normal = a.cross(b);
            let area = normal.length();
            let longest = a.length().max(b.length()).max((q - p).length());
            let tilt = COPLANAR_TOLERANCE * (1.0 + 1e-6) * longest * (a.length() + b.length());
            let rounding = 16.0 * eps * a.length() * b.length();
            // NaN without area: no normal to go by, every pair is listed.
            (
                normal / area,
                (3.0 * tilt + 2.0 * rounding) / area + 4.0 * eps,
            )
        })
        .collect();
    let azimuths: Vec<(f64, f64, u32)> = normals
        .iter()
        .enumerate()
        .map(|(m, &(unit, window))| {
            let across = unit - n * unit.dot(n);
            let reach = across.length();
            let half = if window < reach {
                (window / reach).asin() + 1e-9
            } else {
                std::f64::consts::FRAC_PI_2
            };
            let phi = across
                .dot(e2)
                .atan2(across.dot(e1))
                .rem_euclid(std::f64::consts::PI);
            (if phi.is_finite() { phi } else { 0.0 }, half, m as u32)
        })
        .collect();
    // The azimuths forget the normals' height along the axis (a pleat
    // and the one opposite have parallel horizontal parts): the pairs
    // listed keep only those whose whole normals are within the window.
    let ties = window_pairs(azimuths, most.checked_sub(out.len())?)?
        .into_iter()
        .filter(|&(x, y)| {
            let ((a, wa), (b, wb)) = (normals[x as usize], normals[y as usize]);
            let chord = (a - b).length().min((a + b).length());
            chord.is_nan() || chord <= wa.max(wb)
        })
        .map(|(x, y)| {
            let (a, b) = (members[x as usize].0, members[y as usize].0);
            (a.min(b), a.max(b))
        });
    out.extend(ties);
    (out.len() <= most).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turns_count_counter_clockwise_seen_from_the_axis_tip() {
        let f = Frame::new(DVec3::ZERO, DVec3::Z, 1.0).unwrap();
        assert_eq!(f.turn(DVec3::X, DVec3::Y), 1);
        assert_eq!(f.turn(DVec3::Y, DVec3::X), -1);
        // Heights along the axis do not count.
        assert_eq!(
            f.turn(DVec3::new(1.0, 0.0, 5.0), DVec3::new(0.0, 1.0, -3.0)),
            1
        );
        assert_eq!(f.point(DVec3::new(0.0, 0.0, 2.0)).p, DVec3::ZERO);
        // Angle 0 (the reference) is upper, a half turn from it is not.
        let r = f.point(f.r + DVec3::Z);
        let back = f.point(2.0 * f.v - f.r);
        let apex = f.point(f.v);
        assert!(r.upper_of(apex) && !back.upper_of(apex));
    }
}
