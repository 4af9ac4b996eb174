//! The star candidates against all pairs: fans, cones, stars of several
//! fans, folded fans, books and clutter, in space and on the screen.

use glam::DVec3;
use hider_geom::star::Stars;
use hider_geom::{FixedPt, PlaneEq, Viewport};
use hider_scene::procedural::SplitMix64;
use hider_scene::{Cancel, ScreenTri};

use super::intersect::{Contact, Grid, PairSearch, contact, find_pairs};
use super::overlap::{OverlapGraph, graph, overlap_graph};

/// Every pair whose boxes meet, tested, listed in the grid's order (first
/// shared cell, then the indices): what the grid alone found.
fn all_pairs(tris: &[(u32, [DVec3; 3])]) -> PairSearch {
    let boxes: Vec<(DVec3, DVec3)> = tris
        .iter()
        .map(|(_, t)| (t[0].min(t[1]).min(t[2]), t[0].max(t[1]).max(t[2])))
        .collect();
    let lo = boxes.iter().fold(DVec3::INFINITY, |m, b| m.min(b.0));
    let hi = boxes.iter().fold(DVec3::NEG_INFINITY, |m, b| m.max(b.1));
    let grid = Grid::new(lo, hi, &boxes);
    let mut found = Vec::new();
    let mut tests = 0;
    for i in 0..tris.len() {
        for j in i + 1..tris.len() {
            let (ba, bb) = (boxes[i], boxes[j]);
            let both = (ba.0.max(bb.0), ba.1.min(bb.1));
            if both.0.cmpgt(both.1).any() {
                continue;
            }
            tests += 1;
            let c = contact(&tris[i].1, &tris[j].1);
            if c != Contact::None {
                found.push((grid.cell_of(both.0), i, j, c));
            }
        }
    }
    found.sort_by_key(|&(c, i, j, _)| (c, i, j));
    let mut out = PairSearch {
        complete: true,
        tests,
        ..PairSearch::default()
    };
    for (_, i, j, c) in found {
        let pair = (tris[i].0.min(tris[j].0), tris[i].0.max(tris[j].0));
        match c {
            Contact::Interpenetrate => out.interpenetrating.push(pair),
            _ => out.coplanar.push(pair),
        }
    }
    out
}

/// Coordinates rounded to a lattice of `step`, or left alone (`step` 0).
fn snap(p: DVec3, step: f64) -> DVec3 {
    if step > 0.0 {
        (p / step).round() * step
    } else {
        p
    }
}

/// A family of triangles sharing a vertex or an edge (see the module
/// documentation), appended to `tris`.
pub(super) fn family(r: &mut SplitMix64, kind: usize, tris: &mut Vec<[DVec3; 3]>) {
    let centre = snap(
        DVec3::new(r.range(-1.0, 1.0), r.range(-1.0, 1.0), r.range(-1.0, 1.0)),
        0.25,
    );
    let step = [0.0, 1.0 / 64.0, 1.0 / 8.0][r.below(3)];
    let n = 12 + r.below(40);
    let (u, v) = {
        let a = if r.below(3) == 0 {
            DVec3::Z
        } else {
            r.direction()
        };
        let u = a.any_orthonormal_vector();
        (u, a.cross(u))
    };
    let axis = u.cross(v);
    // Angles: in order around (a fan that tiles), or random (overlapping
    // sectors, coplanar overlaps).
    let ordered = r.below(2) == 0;
    let mut angles: Vec<f64> = (0..n)
        .map(|k| {
            if ordered {
                std::f64::consts::TAU * k as f64 / n as f64
            } else {
                r.range(0.0, std::f64::consts::TAU)
            }
        })
        .collect();
    if ordered {
        angles.push(angles[0]);
    }
    let rim = |a: f64, lift: f64| centre + u * a.cos() + v * a.sin() + axis * lift;
    match kind {
        // Flat fan, cone, folded fan.
        0..=2 => {
            for w in angles.windows(2) {
                let (l0, l1) = match kind {
                    0 => (0.0, 0.0),
                    1 => (-0.5, -0.5),
                    _ => (r.range(-0.3, 0.3), r.range(-0.3, 0.3)),
                };
                tris.push([centre, snap(rim(w[0], l0), step), snap(rim(w[1], l1), step)]);
            }
        }
        // A book: pages around the spine from the centre along `axis`,
        // some in the same plane.
        3 => {
            let tip = centre + axis;
            for k in 0..n {
                let a = angles[k.min(angles.len() - 1)];
                // Some in one plane (on one side, on the other, or off
                // it by less and by more than the coplanar tolerance).
                let a = match k % 6 {
                    0 => 0.0,
                    3 => [std::f64::consts::PI, 1e-7, 1e-3][r.below(3)],
                    _ => a,
                };
                let page = centre + axis * r.range(0.0, 1.0) + u * a.cos() + v * a.sin();
                tris.push([centre, tip, snap(page, step)]);
            }
        }
        // A pleated fan (rim alternately above and below the centre,
        // steep: its sectors overlap in every member's own projection),
        // with copies of some members turned by a little (ties within
        // the coplanar tolerance, crossings) or not at all; or a star
        // whose rim vertices have random heights.
        4 | 5 => {
            let pleat = r.range(0.05, 1.0);
            let lifts: Vec<f64> = (0..angles.len())
                .map(|k| match kind {
                    4 => [pleat, -pleat][k % 2],
                    _ => r.range(-1.0, 1.0),
                })
                .collect();
            for (k, w) in angles.windows(2).enumerate() {
                let (a, b) = (rim(w[0], lifts[k]), rim(w[1], lifts[k + 1]));
                tris.push([centre, snap(a, step), snap(b, step)]);
                if r.below(6) == 0 {
                    let turn: f64 = [0.0, 1e-9, 1e-6, 1e-3][r.below(4)];
                    let turned = |p: DVec3| {
                        let d = p - centre;
                        let (x, y) = (d.dot(u), d.dot(v));
                        let (s, c) = turn.sin_cos();
                        centre + u * (x * c - y * s) + v * (x * s + y * c) + axis * d.dot(axis)
                    };
                    tris.push([centre, turned(a), turned(b)]);
                }
            }
        }
        // A star of random triangles sharing the centre.
        _ => {
            for _ in 0..n {
                let (p, q) = (r.direction(), r.direction());
                tris.push([centre, snap(centre + p, step), snap(centre + q, step)]);
            }
        }
    }
}

/// A scene of one to three families, some sharing a centre, and clutter.
pub(super) fn scene(r: &mut SplitMix64) -> Vec<[DVec3; 3]> {
    let mut tris = Vec::new();
    for _ in 0..1 + r.below(3) {
        let kind = r.below(7);
        family(r, kind, &mut tris);
    }
    // A second fan around the first one's centre, in another plane.
    if r.below(2) == 0 {
        let c = tris[0][0];
        let mut more = Vec::new();
        let kind = [0, 1, 2, 4, 5][r.below(5)];
        family(r, kind, &mut more);
        let shift = c - more[0][0];
        tris.extend(more.iter().map(|t| t.map(|p| p + shift)));
    }
    for _ in 0..r.below(12) {
        let p = DVec3::new(r.range(-1.5, 1.5), r.range(-1.5, 1.5), r.range(-1.5, 1.5));
        tris.push([p, p + r.direction(), p + r.direction()]);
    }
    // Shuffle, so that star members are not consecutive.
    for k in (1..tris.len()).rev() {
        tris.swap(k, r.below(k + 1));
    }
    tris
}

#[test]
fn star_candidates_find_what_all_pairs_find() {
    let mut r = SplitMix64::new(2026);
    let (mut crossings, mut ties, mut tested, mut all) = (0, 0, 0, 0);
    for round in 0..300 {
        let tris: Vec<(u32, [DVec3; 3])> = scene(&mut r)
            .into_iter()
            .enumerate()
            .map(|(k, t)| (k as u32 * 3 + 1, t))
            .collect();
        let want = all_pairs(&tris);
        let got = find_pairs(&tris, u64::MAX, Cancel::default());
        assert!(got.complete);
        assert_eq!(got.interpenetrating, want.interpenetrating, "round {round}");
        assert_eq!(got.coplanar, want.coplanar, "round {round}");
        crossings += want.interpenetrating.len();
        ties += want.coplanar.len();
        (tested, all) = (tested + got.tests, all + want.tests);
    }
    // The families do produce both kinds of contact at shared vertices,
    // and the stars (those not dense) spare tests.
    assert!(crossings > 1000 && ties > 1000, "{crossings} {ties}");
    assert!(tested * 10 < all * 9, "{tested} of {all}");
}

/// A flat fan of `n` triangles around the origin, or a cone (the centre
/// lifted).
pub(super) fn fan(n: usize, lift: f64) -> Vec<(u32, [DVec3; 3])> {
    let rim = |k: usize| {
        let a = std::f64::consts::TAU * (k % n) as f64 / n as f64;
        DVec3::new(a.cos(), a.sin(), 0.0)
    };
    (0..n)
        .map(|k| (k as u32, [DVec3::new(0.0, 0.0, lift), rim(k), rim(k + 1)]))
        .collect()
}

/// Doubling a fan or a cone less than triples the pairs listed and
/// tested (all pairs sharing the centre were, before the stars: 4x).
#[test]
fn fan_pairs_grow_linearly() {
    for lift in [0.0, 0.5] {
        let work = |n| {
            let s = find_pairs(&fan(n, lift), u64::MAX, Cancel::default());
            assert!(s.complete && s.interpenetrating.is_empty() && s.coplanar.is_empty());
            (s.candidates, s.tests)
        };
        let (small, large) = (work(1000), work(2000));
        assert!(
            large.0 < 3 * small.0,
            "lift {lift}: listed {small:?} {large:?}"
        );
        assert!(
            large.1 < 3 * small.1,
            "lift {lift}: tested {small:?} {large:?}"
        );
    }
}

/// A fan of `n` triangles around the origin whose rim alternates between
/// `z = pleat` and `z = -pleat` (`n` even, so that the rim closes).
pub(super) fn pleated_fan(n: usize, pleat: f64) -> Vec<(u32, [DVec3; 3])> {
    let rim = |k: usize| {
        let a = std::f64::consts::TAU * (k % n) as f64 / n as f64;
        let z = if k.is_multiple_of(2) { pleat } else { -pleat };
        DVec3::new(a.cos(), a.sin(), z)
    };
    (0..n)
        .map(|k| (k as u32, [DVec3::ZERO, rim(k), rim(k + 1)]))
        .collect()
}

/// Doubling a steeply pleated fan less than triples the pairs listed and
/// tested: its members' sectors overlap in their own (x or y) drop-axis
/// projections, so the star was dense and every pair went to the grid
/// (499,500 and 1,999,000 tests at 1,000 and 2,000); around the fan's
/// axis only neighbours' sectors meet.
#[test]
fn pleated_fan_pairs_grow_linearly() {
    for pleat in [0.2, 0.05, 1.0] {
        let work = |n| {
            let s = find_pairs(&pleated_fan(n, pleat), u64::MAX, Cancel::default());
            assert!(s.complete && s.interpenetrating.is_empty() && s.coplanar.is_empty());
            (s.candidates, s.tests)
        };
        let (small, large) = (work(1000), work(2000));
        assert!(
            large.0 < 3 * small.0,
            "pleat {pleat}: listed {small:?} {large:?}"
        );
        assert!(
            large.1 < 3 * small.1,
            "pleat {pleat}: tested {small:?} {large:?}"
        );
        // Neighbours, whose closed sectors share an edge's direction.
        assert!(small.1 <= 2 * 1000, "pleat {pleat}: tested {small:?}");
    }
}

/// Two members nearly edge-on to a pleated fan's axis and within the
/// coplanar tolerance of each other, whose sectors seen along the axis are
/// apart (angles 0 to 1e-7 and 1.5e-7 to 2e-7) while their interiors
/// overlap seen along their drop axis: the tie is found by the normals'
/// azimuths, not by the sectors.
#[test]
fn ties_apart_around_the_axis_are_found() {
    let a = [
        DVec3::ZERO,
        DVec3::new(1.0, 0.0, 1.0),
        DVec3::new(1.0, 1e-7, -1.0),
    ];
    let b = [
        DVec3::ZERO,
        DVec3::new(1.0, 2e-7, 1.0),
        DVec3::new(2.0, 3e-7, -1.0),
    ];
    assert_eq!(contact(&a, &b), Contact::CoplanarOverlap);
    let mut tris = pleated_fan(200, 0.2);
    // With their copies turned by a half turn, so that the members'
    // normals still sum along z.
    let turned = |t: [DVec3; 3]| t.map(|p| DVec3::new(-p.x, -p.y, p.z));
    tris.extend([(1000, a), (1001, b), (1002, turned(a)), (1003, turned(b))]);
    let got = find_pairs(&tris, u64::MAX, Cancel::default());
    let want = all_pairs(&tris);
    assert!(want.coplanar.contains(&(1000, 1001)), "{:?}", want.coplanar);
    assert_eq!(got.coplanar, want.coplanar);
    assert_eq!(got.interpenetrating, want.interpenetrating);
    // The star was searched around its axis, not left to the grid.
    assert!(
        got.tests < want.tests / 10,
        "{} of {}",
        got.tests,
        want.tests
    );
}

/// Members edge-on to a pleated fan's axis (their planes hold it: their
/// sectors around it are a direction or a half turn), some in one plane
/// (ties), two crossing along the axis itself: what all pairs find.
#[test]
fn edge_on_members_around_the_axis() {
    let mut r = SplitMix64::new(5);
    let mut ties = 0;
    for round in 0..100 {
        let mut tris = pleated_fan(100, r.range(0.05, 1.0));
        for j in 0..3 + r.below(6) {
            // Three half-planes around the axis, two of them one plane.
            let a = [1.0, 4.0, 5.0][r.below(3)] * std::f64::consts::FRAC_PI_3;
            let (h1, h2) = (r.range(-1.0, 1.0), r.range(-1.0, 1.0));
            let p = DVec3::new(a.cos(), a.sin(), h1);
            let q = DVec3::new(2.0 * a.cos(), 2.0 * a.sin(), h2);
            tris.push((1000 + j as u32, [DVec3::ZERO, p, q]));
        }
        let up = |x: f64, y: f64| DVec3::new(x, y, 1.0);
        tris.push((2000, [DVec3::ZERO, up(1.0, 0.0), up(-1.0, 0.0)]));
        tris.push((2001, [DVec3::ZERO, up(0.0, 1.0), up(0.0, -1.0)]));
        let want = all_pairs(&tris);
        let got = find_pairs(&tris, u64::MAX, Cancel::default());
        assert!(want.interpenetrating.contains(&(2000, 2001)));
        ties += want.coplanar.len();
        assert_eq!(got.interpenetrating, want.interpenetrating, "round {round}");
        assert_eq!(got.coplanar, want.coplanar, "round {round}");
        assert!(
            got.tests * 4 < want.tests,
            "round {round}: {} of {}",
            got.tests,
            want.tests
        );
    }
    assert!(ties > 100, "{ties}");
}

/// A book of `n` pages around the spine from the origin along z, fanned
/// over a half turn (`ties`: every tenth page doubled, a coplanar tie).
fn book(n: usize, ties: bool) -> Vec<(u32, [DVec3; 3])> {
    let page = |k: usize| {
        let a = std::f64::consts::PI * (k as f64 + 0.5) / n as f64;
        DVec3::new(a.cos(), a.sin(), 0.5)
    };
    (0..n)
        .map(|k| if ties && k % 10 == 1 { k - 1 } else { k })
        .enumerate()
        .map(|(id, k)| (id as u32, [DVec3::ZERO, DVec3::Z, page(k)]))
        .collect()
}

/// A book's pairs listed and tested grow linearly (every pair of pages
/// was listed and tested before its pages were sorted by angle), and its
/// coplanar pages are found.
#[test]
fn book_pairs_grow_linearly() {
    for ties in [false, true] {
        let work = |n| {
            let tris = book(n, ties);
            let s = find_pairs(&tris, u64::MAX, Cancel::default());
            assert!(s.complete && s.interpenetrating.is_empty());
            let want = if ties { n / 10 } else { 0 };
            assert_eq!(s.coplanar.len(), want, "{n} pages");
            (s.candidates, s.tests)
        };
        // At most a pair per page: apart, the pages' windows hold no
        // other page; with ties, only the tied page.
        for n in [1000, 2000] {
            let (listed, tested) = work(n);
            assert!(
                listed <= n as u64 && tested <= n as u64,
                "{n}: {listed} {tested}"
            );
        }
    }
}

/// World triangles seen from above on a 64 x 64 window (x, y in `[-2,
/// 2]`), depth from z: shared corners stay shared after snapping.
pub(super) fn screen(tris: &[[DVec3; 3]]) -> Vec<ScreenTri> {
    let fixed = |p: DVec3| {
        let f = |c: f64| ((c + 2.0) * 16.0 * 256.0).round() as i32;
        FixedPt::new(f(p.x), f(p.y))
    };
    tris.iter()
        .enumerate()
        .filter_map(|(k, t)| {
            let mut v = t.map(fixed);
            let mut z = t.map(|p| 0.5 + p.z / 8.0);
            if hider_geom::orient2d(v[0], v[1], v[2]) < 0 {
                v.swap(1, 2);
                z.swap(1, 2);
            }
            Some(ScreenTri {
                v,
                z,
                w: [1.0; 3],
                depth: PlaneEq::from_points(&v, z)?,
                inv_w: PlaneEq::constant(1.0),
                prim: k as u32,
                front_facing: true,
            })
        })
        .collect()
}

#[test]
fn screen_star_candidates_find_what_the_tiles_find() {
    let mut r = SplitMix64::new(1972);
    let (mut edges, mut ties) = (0, 0);
    for round in 0..300 {
        let tris = screen(&scene(&mut r));
        let crossing = |a: u32, b: u32| (a + b).is_multiple_of(11);
        let vp = Viewport::new(64, 64);
        let cancel = Cancel::default();
        let want = graph(&tris, vp, Stars::default(), crossing, u64::MAX, 4, cancel);
        let got = overlap_graph(&tris, vp, crossing, u64::MAX, 4, cancel);
        let findings = |g: &OverlapGraph| OverlapGraph {
            candidates: 0,
            examined: 0,
            ..g.clone()
        };
        assert_eq!(findings(&got), findings(&want), "round {round}");
        edges += want.edges;
        ties += want.ties;
    }
    assert!(edges > 1000 && ties > 1000, "{edges} {ties}");
}

/// Doubling a fan or a cone on the screen less than triples the pairs
/// the overlap graph lists and examines.
#[test]
fn screen_fan_pairs_grow_linearly() {
    for lift in [0.0, 0.5] {
        let work = |n| {
            let world: Vec<[DVec3; 3]> = fan(n, lift).into_iter().map(|(_, t)| t).collect();
            let g = overlap_graph(
                &screen(&world),
                Viewport::new(64, 64),
                |_, _| false,
                u64::MAX,
                4,
                Cancel::default(),
            );
            assert!(g.complete && g.overlapping_pairs == 0, "{g:?}");
            (g.candidates, g.examined)
        };
        let (small, large) = (work(1000), work(2000));
        assert!(
            large.0 < 3 * small.0,
            "lift {lift}: listed {small:?} {large:?}"
        );
        assert!(
            large.1 < 3 * small.1,
            "lift {lift}: examined {small:?} {large:?}"
        );
    }
}

/// The pair budget still bounds the work on a star, and the evidence
/// names the flag that raises it.
#[test]
fn budget_stops_the_star_search_and_names_the_flag() {
    let positions: Vec<DVec3> = fan(2000, 0.5).into_iter().flat_map(|(_, t)| t).collect();
    let scene = hider_scene::Scene::from_triangles(positions);
    let options = super::RenderOptions {
        pair_searches: true,
        ..super::RenderOptions::default()
    }
    .with_pair_budget(100);
    let fx = super::analyze(&scene, &options).unwrap();
    assert!(fx.work.intersection_tests <= 100 && fx.work.overlap_tests <= 100);
    for e in [&fx.intersections, &fx.cyclic_overlap] {
        assert!(e.present && !e.certain, "{e:?}");
        assert!(e.detail.contains("--pair-budget"), "{}", e.detail);
    }
}
