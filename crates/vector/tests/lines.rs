//! Hidden-line drawings: every drawn point lies on the nearest surface,
//! every hidden part really is hidden, and the classic pictures come out
//! right (a cube's nine lines, a torus's silhouette, two planes'
//! intersection segment).
//!
//! The depth check is the brute force the oracle's window-depth reference
//! does per pixel centre, done at the sampled points: every triangle
//! covering the point, its window-depth plane evaluated in `f64`.

use glam::DVec3;
use hider_scene::{Material, Mesh, Scene, ScreenScene, ShadeMode, procedural};
use hider_testkit::cameras::look_at;
use hider_testkit::{hard_cases, screen_with};
use hider_vector::{LineDrawing, LineKind, Polyline, VectorOptions, hidden_lines, visible_regions};

/// Window-depth tolerance of the check for drawn points: the lines'
/// depths and the triangles' planes agree to rounding, far below this.
const DEPTH_TOLERANCE: f64 = 1e-6;
/// A point this close to a triangle's edge (pixels) lies on it: lines are
/// projected from the mesh unsnapped, triangles snapped to 1/256 pixel.
const ON_EDGE: f64 = 1e-2;

fn drawing(s: &ScreenScene, options: &VectorOptions) -> LineDrawing {
    let map = visible_regions(s, options, ShadeMode::Lambert).unwrap();
    hidden_lines(s, &map, options).unwrap()
}

/// The nearest window depth at `p` over the triangles that hold `p` at
/// least `margin` pixels inside all their edges (a negative margin takes
/// points just outside too).
fn nearest(s: &ScreenScene, p: (f64, f64), margin: f64) -> f64 {
    let mut nearest = f64::INFINITY;
    for t in &s.tris {
        let v = t.v.map(|q| q.to_pixels());
        let inside = (0..3).all(|k| {
            let (a, b) = (v[k], v[(k + 1) % 3]);
            let len = (b.0 - a.0).hypot(b.1 - a.1);
            ((b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0)) / len >= margin
        });
        if inside {
            nearest = nearest.min(t.depth.eval(p.0, p.1));
        }
    }
    nearest
}

/// Points at a quarter and three quarters of every segment, with the
/// line's window depth there.
fn samples(lines: &[Polyline]) -> Vec<((f64, f64), f64)> {
    let mut out = Vec::new();
    for line in lines {
        for k in 1..line.points.len() {
            let (a, b) = (line.points[k - 1], line.points[k]);
            let (za, zb) = (line.depths[k - 1], line.depths[k]);
            for f in [0.25, 0.75] {
                out.push((
                    (a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1)),
                    za + f * (zb - za),
                ));
            }
        }
    }
    out
}

fn inside_image(s: &ScreenScene, p: (f64, f64)) -> bool {
    p.0 > 0.0
        && p.1 > 0.0
        && p.0 < f64::from(s.viewport.width)
        && p.1 < f64::from(s.viewport.height)
}

#[test]
fn drawn_edge_points_are_on_the_nearest_surface_and_hidden_ones_are_not() {
    let options = VectorOptions::default().with_dashed_hidden(true);
    // Generic views: no hidden edge projects onto a drawn one (where the
    // check could not tell which of the two a sample belongs to).
    let camera = look_at(DVec3::new(3.1, 2.3, 4.2), DVec3::ZERO, 0.5, 50.0);
    let scenes = [
        ("cube", procedural::cube()),
        ("torus", hard_cases::torus(24, 12, 1.0, 0.4)),
        ("uv_sphere", procedural::uv_sphere(12)),
        ("boxes", hard_cases::interpenetrating_boxes(3, 5)),
    ];
    for (name, scene) in scenes {
        let s = screen_with(&scene, camera, 128, 128);
        let d = drawing(&s, &options);
        let (mut shown, mut hidden) = (0, 0);
        for (p, z) in samples(&d.visible)
            .into_iter()
            .filter(|&(p, _)| inside_image(&s, p))
        {
            // No surface clearly around the point is nearer.
            let front = nearest(&s, p, ON_EDGE);
            assert!(
                front >= z - DEPTH_TOLERANCE,
                "{name}: drawn point {p:?} at depth {z} is behind {front}"
            );
            shown += 1;
        }
        for (p, z) in samples(&d.hidden)
            .into_iter()
            .filter(|&(p, _)| inside_image(&s, p))
        {
            // Some surface at the point is nearer, or as near to within
            // the check's tolerance: the lines decide in camera space
            // against the unsnapped triangles, these depths are the
            // snapped ones (tests/reference.rs checks the hidden parts
            // exactly, against a ray cast in camera space).
            let front = nearest(&s, p, -ON_EDGE);
            assert!(
                front < z + DEPTH_TOLERANCE,
                "{name}: hidden point {p:?} at depth {z} is in front ({front})"
            );
            hidden += 1;
        }
        eprintln!("{name}: {shown} drawn and {hidden} hidden sample points checked");
        assert!(shown > 0, "{name}: nothing drawn");
        // A convex sphere hides none of its lines; the others do.
        assert_eq!(
            hidden == 0,
            name == "uv_sphere",
            "{name}: {hidden} hidden samples"
        );
    }
}

#[test]
fn a_cube_from_a_corner_shows_nine_lines() {
    let camera = look_at(DVec3::new(3.1, 2.3, 4.2), DVec3::ZERO, 0.5, 50.0);
    let s = screen_with(&procedural::cube(), camera, 200, 200);
    let d = drawing(&s, &VectorOptions::default());
    assert_eq!(d.visible_segments(), 9, "{:?}", d.visible);
    // Six silhouette segments around, three creases meeting in the corner.
    let count = |k| {
        d.visible
            .iter()
            .filter(|l| l.kind == k)
            .map(|l| l.points.len() - 1)
            .sum::<usize>()
    };
    assert_eq!(count(LineKind::Silhouette), 6);
    assert_eq!(count(LineKind::Crease), 3);
}

#[test]
fn a_torus_shows_its_silhouette() {
    let camera = look_at(DVec3::new(0.0, 2.2, 2.6), DVec3::ZERO, 0.5, 50.0);
    let s = screen_with(&hard_cases::torus(48, 24, 1.0, 0.4), camera, 200, 200);
    let d = drawing(&s, &VectorOptions::default());
    let silhouette: f64 = d
        .visible
        .iter()
        .filter(|l| l.kind == LineKind::Silhouette)
        .flat_map(|l| {
            l.points
                .windows(2)
                .map(|w| (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1))
        })
        .sum();
    // Seen from above at about 40 degrees, the outer rim alone is an
    // ellipse over 300 pixels round; the inner rim adds to it.
    assert!(silhouette > 300.0, "silhouette only {silhouette} px long");
    // Smooth tube: no creases at the default 30 degrees with 24 segments.
    assert!(d.visible.iter().all(|l| l.kind != LineKind::Crease));
}

fn quad(name: &str, corners: [DVec3; 4], colour: [f32; 3]) -> (Mesh, Material) {
    let mesh = Mesh {
        name: name.into(),
        positions: corners.to_vec(),
        indices: vec![[0, 1, 2], [0, 2, 3]],
        ..Mesh::default()
    };
    (
        mesh,
        Material {
            name: name.into(),
            diffuse: colour,
            ..Material::default()
        },
    )
}

#[test]
fn two_intersecting_planes_show_their_intersection_segment() {
    let mut scene = Scene::default();
    let p = DVec3::new;
    let (m, mat) = quad(
        "floor",
        [
            p(-1.0, 0.0, -1.0),
            p(1.0, 0.0, -1.0),
            p(1.0, 0.0, 1.0),
            p(-1.0, 0.0, 1.0),
        ],
        [0.8, 0.3, 0.2],
    );
    scene.push_mesh(m, Some(mat));
    let (m, mat) = quad(
        "wall",
        [
            p(-1.0, -1.0, 0.0),
            p(1.0, -1.0, 0.0),
            p(1.0, 1.0, 0.0),
            p(-1.0, 1.0, 0.0),
        ],
        [0.2, 0.3, 0.8],
    );
    scene.push_mesh(m, Some(mat));
    let camera = look_at(p(2.0, 1.5, 3.5), DVec3::ZERO, 0.5, 50.0);
    let s = screen_with(&scene, camera, 200, 200);
    let d = drawing(&s, &VectorOptions::default());
    let cuts: Vec<_> = d
        .visible
        .iter()
        .filter(|l| l.kind == LineKind::Intersection)
        .collect();
    assert_eq!(cuts.len(), 1, "{cuts:?}");
    assert_eq!(
        cuts[0].points.len(),
        2,
        "one straight segment: {:?}",
        cuts[0]
    );
    // Its ends are the projections of (-1, 0, 0) and (1, 0, 0).
    let project = |q: DVec3| {
        let c = s.projection_matrix * (s.view_matrix * q.extend(1.0));
        let w = s.viewport.ndc_to_window(c.truncate() / c.w);
        (w.x, w.y)
    };
    let (a, b) = (project(p(-1.0, 0.0, 0.0)), project(p(1.0, 0.0, 0.0)));
    let ends = [cuts[0].points[0], cuts[0].points[1]];
    let near = |u: (f64, f64), v: (f64, f64)| (u.0 - v.0).hypot(u.1 - v.1) < 0.02;
    assert!(
        (near(ends[0], a) && near(ends[1], b)) || (near(ends[0], b) && near(ends[1], a)),
        "{ends:?} vs {a:?} {b:?}"
    );
}

#[test]
fn every_hard_case_gives_finite_lines() {
    let options = VectorOptions::default().with_dashed_hidden(true);
    for (name, scene) in hard_cases::all(4) {
        let s = hider_testkit::screen(&scene, 64, 64);
        let d = drawing(&s, &options);
        for line in d.visible.iter().chain(&d.hidden) {
            assert!(line.points.len() >= 2, "{name}: {line:?}");
            assert_eq!(line.points.len(), line.depths.len(), "{name}");
            let finite = line
                .points
                .iter()
                .all(|p| p.0.is_finite() && p.1.is_finite());
            assert!(
                finite && line.depths.iter().all(|z| z.is_finite()),
                "{name}: {line:?}"
            );
        }
    }
}

#[test]
fn lines_from_the_pairs_alone_equal_lines_from_the_regions() {
    // `line_pairs` skips the regions' booleans; the drawing must not
    // change.
    let options = VectorOptions::default().with_dashed_hidden(true);
    for (name, scene) in hard_cases::all(3) {
        let s = hider_testkit::screen(&scene, 64, 64);
        let full = drawing(&s, &options);
        let map = hider_vector::line_pairs(&s, &options).unwrap();
        assert!(map.prims.is_empty() && map.groups.is_empty());
        let alone = hidden_lines(&s, &map, &options).unwrap();
        assert_eq!(full.visible, alone.visible, "{name}");
        assert_eq!(full.hidden, alone.hidden, "{name}");
    }
}
