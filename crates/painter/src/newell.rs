//! The pair tests of Newell, Newell & Sancha (1972), in window space.
//!
//! The list is sorted far to near; P is the candidate to paint next and Q
//! another polygon still in the list. P may be painted before Q when any of
//! these holds, tried from cheapest to dearest:
//!
//! 1. their depth extents do not overlap (Q is entirely nearer);
//! 2. their x extents do not overlap;
//! 3. their y extents do not overlap;
//! 4. P lies entirely behind Q's plane (on the far side from the eye);
//! 5. Q lies entirely in front of P's plane;
//! 6. their projections on the screen do not overlap.
//!
//! Window space (x, y in pixels, z the window depth `z/w`) is a projective
//! image of camera space in which the viewing rays are parallel to the z
//! axis, so planes stay planes and "behind the plane of Q as seen from the
//! eye" becomes "larger window depth than Q's depth plane at the same
//! pixel": the plane tests compare affine depth functions at the
//! polygon's vertices (an affine function is extreme at the vertices of a
//! convex polygon).
//!
//! Tests 1 to 3 and 6 are exact for uncut triangles, whose vertices are
//! the front end's fixed-point positions and window depths (every product
//! below fits an `f64` mantissa), and touching is allowed there: under the
//! fill rule a pixel centre on a shared boundary belongs to at most
//! one of two triangles with disjoint interiors. Tests 4 and 5 are sign
//! questions answered exactly at every exact vertex, by Shewchuk's
//! adaptive `orient3d` on the front end's own coordinates.
//!
//! Cut pieces have rounded vertices, and splitting makes them touch all
//! the time (the pieces around the point where three planes meet touch at
//! that point). Two cut pieces whose boxes or outlines come within
//! [`TOUCH`] of each other are not taken as separated on the outlines'
//! word: the pixel centres in that thin band are looked at one by one
//! with the exact coverage rule of each piece. Centres
//! neither piece shares, or shares with the order asked for, let the pair
//! pass; only a shared centre where P is nearer blocks. Assuming instead
//! that a centre on both outlines lies on a line where the two were cut
//! by each other's planes (a tie) is wrong for exactly symmetric scenes,
//! where cut lines of different planes coincide on screen and run through
//! pixel centres.

use glam::DVec2;

use hider_geom::PlaneEq;
use hider_geom::fixed::pixel_center;
use hider_scene::ScreenScene;

use crate::piece::{Piece, edge_line};
use crate::sides::{Sides, sides};

/// Overlap (pixels) under which bounding boxes and projections of cut
/// pieces count as touching: many orders of magnitude above the rounding
/// of their vertices (about 1e-14 pixel), far below pixel spacing.
pub(crate) const TOUCH: f64 = 1e-9;

/// Margin (pixels) by which the rasteriser widens a cut piece's box, so
/// that no centre it covers is skipped.
pub(crate) const CUT_MARGIN: f64 = 1e-6;

/// Which test settled a pair.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Decided {
    /// Test 1: disjoint depth extents.
    Depth,
    /// Test 2: disjoint x extents.
    X,
    /// Test 3: disjoint y extents.
    Y,
    /// Test 4: P behind Q's plane.
    PBehind,
    /// Test 5: Q in front of P's plane.
    QInFront,
    /// Test 6: projections do not overlap.
    Projection,
    /// One of the two covers at most one pixel centre, and on it P is not
    /// nearer ([`crate::centres`]).
    Centre,
}

/// The outcome of testing whether P may be painted before Q.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Outcome {
    /// P may be painted before Q.
    Ok(Decided),
    /// Every test failed: painting P first might cover part of Q wrongly.
    Blocked(Blocked),
}

/// What the plane tests found for a blocked pair, for choosing between
/// moving Q and splitting.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Blocked {
    /// The sides of Q's plane P's vertices lie on.
    pub p: Sides,
    /// The sides of P's plane Q's vertices lie on.
    pub q: Sides,
    /// The two only touch, and Q is nowhere farther than P on the pixel
    /// centres they share: Q may go first.
    pub touch_reverse: bool,
}

impl Blocked {
    /// P is nearer than Q on the one pixel centre that matters (one of them
    /// covers no other): Q may go first, and no plane needs to cut.
    pub(crate) fn by_centre() -> Self {
        Self {
            p: Sides {
                front: true,
                behind: false,
            },
            q: Sides {
                front: false,
                behind: true,
            },
            touch_reverse: true,
        }
    }

    /// Whether Q may be painted before P instead (tests 4 and 5 with the
    /// roles swapped): Q behind P's plane, or P in front of Q's plane, or
    /// they only touch and Q is nearer where they do.
    pub(crate) fn reverse_ok(&self) -> bool {
        !self.q.front || !self.p.behind || self.touch_reverse
    }

    /// Whether Q's plane really cuts P (vertices strictly on both sides).
    pub(crate) fn q_plane_cuts_p(&self) -> bool {
        self.p.cut()
    }

    /// Whether P's plane really cuts Q.
    pub(crate) fn p_plane_cuts_q(&self) -> bool {
        self.q.cut()
    }
}

/// What tests 1 to 3 look at, small enough to keep inline in the sorted
/// list so that most pairs are settled without touching the pieces.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Extent {
    /// Nearest window depth.
    pub zmin: f64,
    /// Farthest window depth.
    pub zmax: f64,
    /// Bounding box, smallest corner.
    pub min: DVec2,
    /// Bounding box, largest corner.
    pub max: DVec2,
    /// Whether the piece is an uncut triangle (exact vertices).
    pub uncut: bool,
}

impl Extent {
    /// The extents of a piece.
    pub(crate) fn of(p: &Piece) -> Self {
        Self {
            zmin: p.zmin,
            zmax: p.zmax,
            min: p.min,
            max: p.max,
            uncut: p.is_uncut(),
        }
    }
}

/// Tests 1 to 3: whether disjoint depth, x or y extents let P be painted
/// before Q. Boxes of uncut triangles may touch; boxes of cut pieces must
/// be more than [`TOUCH`] apart (closer ones are left to test 6, which
/// looks at the centres between them).
#[inline]
pub(crate) fn extents_decide(p: &Extent, q: &Extent) -> Option<Decided> {
    if q.zmax <= p.zmin {
        return Some(Decided::Depth);
    }
    let gap = if p.uncut && q.uncut { 0.0 } else { -TOUCH };
    if p.max.x <= q.min.x + gap || q.max.x <= p.min.x + gap {
        return Some(Decided::X);
    }
    if p.max.y <= q.min.y + gap || q.max.y <= p.min.y + gap {
        return Some(Decided::Y);
    }
    None
}

/// Runs tests 1 to 6 on the pair (P, Q). (The ordering loop runs tests 1
/// to 3 on its inline [`Extent`]s and calls [`may_precede_by_planes`].)
#[cfg(test)]
pub(crate) fn may_precede(p: &Piece, q: &Piece, scene: &ScreenScene) -> Outcome {
    if let Some(d) = extents_decide(&Extent::of(p), &Extent::of(q)) {
        return Outcome::Ok(d);
    }
    may_precede_by_planes(p, q, scene)
}

/// Tests 4 to 6, for a pair whose extents overlap.
pub(crate) fn may_precede_by_planes(p: &Piece, q: &Piece, scene: &ScreenScene) -> Outcome {
    let ps = sides(p, q, &scene.tris);
    if !ps.front {
        return Outcome::Ok(Decided::PBehind);
    }
    let qs = sides(q, p, &scene.tris);
    if !qs.behind {
        return Outcome::Ok(Decided::QInFront);
    }
    let touch_reverse = match overlap(p, q, scene) {
        Overlap::Disjoint => return Outcome::Ok(Decided::Projection),
        Overlap::Touching { p_first: true, .. } => return Outcome::Ok(Decided::Projection),
        Overlap::Touching { q_first, .. } => q_first,
        Overlap::Overlapping => false,
    };
    Outcome::Blocked(Blocked {
        p: ps,
        q: qs,
        touch_reverse,
    })
}

/// How the screen projections of two pieces meet.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Overlap {
    /// No pixel centre is covered by both.
    Disjoint,
    /// The outlines only touch (within [`TOUCH`]), and these pixel centres
    /// on the contact are covered by both: `p_first` when P is nowhere
    /// nearer than Q on them, `q_first` when Q is nowhere nearer than P.
    Touching {
        /// P may be painted first.
        p_first: bool,
        /// Q may be painted first.
        q_first: bool,
    },
    /// The interiors may overlap.
    Overlapping,
}

/// How the projections of `a` and `b` meet: disjoint when a separating
/// line is found (one of the polygons' edges, the separating-axis theorem
/// for convex polygons) or both are pieces of one triangle (whose cuts
/// partition its centres). For cut pieces a separating line within
/// [`TOUCH`] of both is checked centre by centre ([`shared_centres`]).
pub(crate) fn overlap(a: &Piece, b: &Piece, scene: &ScreenScene) -> Overlap {
    if a.source == b.source {
        return Overlap::Disjoint;
    }
    let exact = a.is_uncut() && b.is_uncut();
    let mut contact = None;
    for (x, y) in [(a, b), (b, a)] {
        let n = x.polygon.len();
        for k in 0..n {
            let (p0, p1) = (x.polygon[k], x.polygon[(k + 1) % n]);
            let length = (p1 - p0).length();
            if length == 0.0 {
                continue;
            }
            // Any line with X on one side and Y on the other separates
            // them, so a rounded edge direction does no harm: both
            // polygons are measured against the same computed line.
            let line = edge_line(p0, p1);
            let inner = min_over(&x.polygon, |v| line.eval(v.x, v.y));
            let outer = -min_over(&y.polygon, |v| -line.eval(v.x, v.y));
            // The line's values are distances times `length`.
            let touch = if exact { 0.0 } else { TOUCH * length };
            if outer <= inner - touch {
                return Overlap::Disjoint;
            }
            if outer <= inner + touch && contact.is_none() {
                contact = Some((line, inner - touch, outer + touch));
            }
        }
    }
    match contact {
        Some(band) => shared_centres(a, b, band, scene),
        None => Overlap::Overlapping,
    }
}

/// The pixel centres covered by both `a` and `b`, which can only lie in the
/// band where `line` is between `lo` and `hi` (a band thinner than a
/// pixel, so one centre per column or row at most), and which of the two
/// is nearer on them.
fn shared_centres(
    a: &Piece,
    b: &Piece,
    (line, lo, hi): (PlaneEq, f64, f64),
    scene: &ScreenScene,
) -> Overlap {
    let (ta, tb) = (
        &scene.tris[a.source as usize],
        &scene.tris[b.source as usize],
    );
    let min = a.min.max(b.min) - DVec2::splat(CUT_MARGIN);
    let max = a.max.min(b.max) + DVec2::splat(CUT_MARGIN);
    let first = |m: f64| (m - 0.5).ceil().max(0.0);
    let last = |m: f64, n: u32| (m - 0.5).floor().min(f64::from(n) - 1.0);
    let (vp, mid) = (scene.viewport, 0.5 * (lo + hi));
    let (i0, i1) = (first(min.x), last(max.x, vp.width));
    let (j0, j1) = (first(min.y), last(max.y, vp.height));
    let (mut p_first, mut q_first, mut shared) = (true, true, false);
    let mut visit = |i: f64, j: f64| {
        if !(i0..=i1).contains(&i) || !(j0..=j1).contains(&j) {
            return;
        }
        let (x, y) = (i + 0.5, j + 0.5);
        let v = line.eval(x, y);
        let (fx, fy) = (pixel_center(i as i32).into(), pixel_center(j as i32).into());
        if v < lo || v > hi || !a.covers(ta, fx, fy) || !b.covers(tb, fx, fy) {
            return;
        }
        let (za, zb) = (ta.depth.eval(x, y), tb.depth.eval(x, y));
        shared = true;
        p_first &= za >= zb;
        q_first &= zb >= za;
    };
    // Walk along the line's longer screen direction; the band is thinner
    // than a pixel, so the centres next to the line's crossing are the
    // only candidates.
    if line.dy.abs() >= line.dx.abs() {
        let mut i = i0;
        while i <= i1 {
            let y = line.y0 + (mid - line.value - line.dx * (i + 0.5 - line.x0)) / line.dy;
            let j = (y - 0.5).round();
            for j in [j - 1.0, j, j + 1.0] {
                visit(i, j);
            }
            i += 1.0;
        }
    } else {
        let mut j = j0;
        while j <= j1 {
            let x = line.x0 + (mid - line.value - line.dy * (j + 0.5 - line.y0)) / line.dx;
            let i = (x - 0.5).round();
            for i in [i - 1.0, i, i + 1.0] {
                visit(i, j);
            }
            j += 1.0;
        }
    }
    if shared {
        Overlap::Touching { p_first, q_first }
    } else {
        Overlap::Disjoint
    }
}

fn min_over(poly: &[DVec2], f: impl Fn(DVec2) -> f64) -> f64 {
    poly.iter().map(|v| f(*v)).fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_geom::{FixedPt, PlaneEq};
    use hider_scene::{PrepareOptions, ScreenTri, View, prepare, procedural};

    fn screen_tri(v: [(i32, i32); 3], z: [f64; 3], prim: u32) -> ScreenTri {
        let v = v.map(|(x, y)| FixedPt::new(x * 256, y * 256));
        ScreenTri {
            v,
            z,
            w: [1.0; 3],
            depth: PlaneEq::from_points(&v, z).unwrap(),
            inv_w: PlaneEq::constant(1.0),
            prim,
            front_facing: true,
        }
    }

    /// A 32 x 32 screen holding `tris`, and their pieces.
    fn setup(tris: Vec<ScreenTri>) -> (ScreenScene, Vec<Piece>) {
        let cube = procedural::cube();
        let view = View::for_scene(&cube, 32, 32).unwrap();
        let mut s = prepare(&cube, &view, &PrepareOptions::default()).unwrap();
        s.tris = tris;
        let pieces = s
            .tris
            .iter()
            .enumerate()
            .map(|(k, t)| Piece::from_tri(t, k as u32))
            .collect();
        (s, pieces)
    }

    #[test]
    fn disjoint_depths_decide_first() {
        let (s, p) = setup(vec![
            screen_tri([(0, 0), (10, 0), (0, 10)], [0.8; 3], 0),
            screen_tri([(0, 0), (10, 0), (0, 10)], [0.2; 3], 1),
        ]);
        let (far, near) = (&p[0], &p[1]);
        assert!(matches!(
            may_precede(far, near, &s),
            Outcome::Ok(Decided::Depth)
        ));
        // The near one overlaps the far one in depth and on screen, lies in
        // front of its plane, so the far one blocks it.
        let Outcome::Blocked(b) = may_precede(near, far, &s) else {
            panic!("near before far must be blocked");
        };
        assert!(b.reverse_ok());
        assert!(!b.q_plane_cuts_p());
    }

    #[test]
    fn plane_tests_order_overlapping_depth_ranges() {
        // P is steep (0.1 .. 0.9), Q flat at 0.5 but entirely off P's
        // plane on the near side where they overlap on screen.
        let (s, pieces) = setup(vec![
            screen_tri([(0, 0), (10, 0), (0, 10)], [0.9, 0.9, 0.1], 0),
            screen_tri([(0, 0), (4, 0), (0, 1)], [0.5; 3], 1),
        ]);
        let (p, q) = (&pieces[0], &pieces[1]);
        // P's plane at Q's vertices: 0.9, 0.9, 0.82 -> Q in front.
        assert!(matches!(
            may_precede(p, q, &s),
            Outcome::Ok(Decided::QInFront)
        ));
        // Q first would need Q behind P's plane or P in front of Q's
        // plane: neither holds, so P blocks Q.
        assert!(matches!(may_precede(q, p, &s), Outcome::Blocked(_)));
    }

    #[test]
    fn touching_triangles_are_separated_exactly() {
        // Share the edge (10,0)-(0,10); opposite sides.
        let (s, p) = setup(vec![
            screen_tri([(0, 0), (10, 0), (0, 10)], [0.5; 3], 0),
            screen_tri([(10, 0), (10, 10), (0, 10)], [0.4; 3], 1),
        ]);
        assert_eq!(overlap(&p[0], &p[1], &s), Overlap::Disjoint);
        // Overlapping by one fixed-point unit is not separated.
        let mut c = p[1].clone();
        c.polygon[0].x -= 1.0 / 256.0;
        assert_eq!(overlap(&p[0], &c, &s), Overlap::Overlapping);
    }

    /// Two cut pieces touching along a line through pixel centres, each
    /// covering those centres under its own rounded cut: the contact is
    /// looked at centre by centre, and the nearer piece on it must go
    /// last.
    #[test]
    fn cut_pieces_touching_on_pixel_centres_are_ordered_there() {
        // Far triangle 0 and near triangle 1 overlap on screen; each is cut
        // along the diagonal x = y by a line of its own (different
        // coefficients, the same line), keeping opposite sides with the
        // centres on the diagonal in both.
        let (s, p) = setup(vec![
            screen_tri([(0, 0), (20, 0), (0, 20)], [0.8; 3], 0),
            screen_tri([(0, 0), (20, 0), (0, 20)], [0.2; 3], 1),
        ]);
        let diagonal = |scale: f64| PlaneEq {
            x0: 0.0,
            y0: 0.0,
            value: 0.0,
            dx: scale,
            dy: -scale,
        };
        // Below-left (x - y <= 0, centres on it included) of triangle 0,
        // above-right (x - y >= 0) of triangle 1.
        let far = p[0].split(diagonal(-1.0)).unwrap().1;
        let near = p[1].split(diagonal(3.0)).unwrap().1;
        let (ta, tb) = (&s.tris[0], &s.tris[1]);
        let c: i64 = pixel_center(4).into();
        assert!(far.covers(ta, c, c) && near.covers(tb, c, c));
        // Far before near: fine. Near before far: blocked, and far may go
        // first.
        assert!(matches!(
            overlap(&far, &near, &s),
            Overlap::Touching {
                p_first: true,
                q_first: false
            }
        ));
        assert!(matches!(may_precede(&far, &near, &s), Outcome::Ok(_)));
        let Outcome::Blocked(b) = may_precede(&near, &far, &s) else {
            panic!("the near piece may not be painted before the far one");
        };
        assert!(b.reverse_ok());
    }

    #[test]
    fn intersecting_triangles_block_both_ways_and_cut_each_other() {
        let (s, pieces) = setup(vec![
            screen_tri([(0, 0), (10, 0), (0, 10)], [0.2, 0.8, 0.5], 0),
            screen_tri([(0, 0), (10, 0), (0, 10)], [0.8, 0.2, 0.5], 1),
        ]);
        let Outcome::Blocked(b) = may_precede(&pieces[0], &pieces[1], &s) else {
            panic!("intersecting triangles must block");
        };
        assert!(!b.reverse_ok());
        assert!(b.q_plane_cuts_p() && b.p_plane_cuts_q());
    }
}
