//! Vector output: the SVG of the ordered pieces, read back and checked for
//! order and geometry, not only as text.

use std::path::Path;

use hider_oracle::{DEFAULT_TIE_TOLERANCE, Reference};
use hider_painter::{NaivePainter, Painter, PainterOptions};
use hider_scene::{Error, Frame, Hider, NO_ID, Result, Scene, ScreenScene, ShadeMode, procedural};
use hider_testkit::reference;

/// Square images throughout.
fn screen(scene: &Scene, size: u32) -> ScreenScene {
    hider_testkit::screen(scene, size, size)
}

/// Renders `s` with `hider`, then writes the vector output of that frame
/// to `path`: the one way to get a painter's SVG.
fn render_svg<H: Hider>(
    hider: &mut H,
    s: &ScreenScene,
    path: &Path,
    mode: ShadeMode,
) -> Result<H::Stats> {
    let mut frame = Frame::new(s.viewport.width, s.viewport.height)?;
    let stats = hider.render(s, &mut frame)?;
    hider
        .ordered_polygons()
        .expect("painters have vector output")
        .write_svg(s, path, mode)?;
    Ok(stats)
}

fn oracle(s: &ScreenScene) -> Reference {
    reference::ray_cast(s)
}

/// `(prim, polygon)` of every `<path>`, in document (paint) order.
fn parse_paths(svg: &str) -> Vec<(u32, Vec<(f64, f64)>)> {
    svg.lines()
        .filter(|l| l.starts_with("<path"))
        .map(|l| {
            let attr = |name: &str| {
                let start = l.find(&format!(r#"{name}=""#)).unwrap() + name.len() + 2;
                let end = start + l[start..].find('"').unwrap();
                &l[start..end]
            };
            let prim = attr("data-prim").parse().unwrap();
            let poly = attr("d")
                .split_whitespace()
                .filter(|t| *t != "Z")
                .map(|t| {
                    let (x, y) = t[1..].split_once(',').unwrap();
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect();
            (prim, poly)
        })
        .collect()
}

/// Signed distances of `p` from the edges of a positively oriented convex
/// polygon (positive inside); the smallest one.
fn inside_margin(poly: &[(f64, f64)], p: (f64, f64)) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|k| {
            let (a, b) = (poly[k], poly[(k + 1) % n]);
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            (dx * (p.1 - a.1) - dy * (p.0 - a.0)) / dx.hypot(dy)
        })
        .fold(f64::INFINITY, f64::min)
}

/// What a vector renderer shows at each pixel centre: the last path that
/// contains it. Returns (pixels checked, pixels disagreeing with the
/// oracle off ties). Centres within 1e-6 pixel of a path outline are
/// skipped: their colour is up to the renderer's anti-aliasing.
fn score_svg(paths: &[(u32, Vec<(f64, f64)>)], reference: &Reference) -> (usize, usize) {
    let (mut checked, mut wrong) = (0, 0);
    for j in 0..reference.height {
        'pixel: for i in 0..reference.width {
            let k = (j * reference.width + i) as usize;
            let p = (f64::from(i) + 0.5, f64::from(j) + 0.5);
            let mut top = NO_ID;
            for (prim, poly) in paths {
                let m = inside_margin(poly, p);
                if m.abs() < 1e-6 {
                    continue 'pixel;
                }
                if m > 0.0 {
                    top = *prim;
                }
            }
            if reference.ids[k] == NO_ID || reference.gap[k] < DEFAULT_TIE_TOLERANCE {
                continue;
            }
            checked += 1;
            if top != reference.ids[k] {
                wrong += 1;
            }
        }
    }
    (checked, wrong)
}

fn temp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("hider-painter-svg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn intersecting_pair_svg_has_split_pieces_in_the_right_order() {
    let s = screen(&procedural::intersecting_pair(), 64);
    let path = temp("pair.svg");
    let stats = render_svg(&mut Painter::default(), &s, &path, ShadeMode::Lambert).unwrap();
    assert!(stats.splits >= 1);
    let svg = std::fs::read_to_string(&path).unwrap();
    assert!(svg.starts_with("<?xml") && svg.trim_end().ends_with("</svg>"));
    let paths = parse_paths(&svg);
    assert_eq!(paths.len() as u64, stats.pieces_out);
    // The pieces interleave: some piece of one triangle is painted between
    // two pieces of the other, which no whole-triangle order can do.
    let prims: Vec<u32> = paths.iter().map(|(p, _)| *p).collect();
    let interleaved = (0..prims.len()).any(|a| {
        (a + 1..prims.len())
            .any(|b| (b + 1..prims.len()).any(|c| prims[a] == prims[c] && prims[a] != prims[b]))
    });
    assert!(interleaved, "paint order {prims:?}");
    // Geometry and order together: the last path over each pixel centre is
    // the oracle's visible primitive.
    let reference = oracle(&s);
    let (checked, wrong) = score_svg(&paths, &reference);
    assert!(checked > 300, "only {checked} pixels checked");
    assert_eq!(wrong, 0);
    // A plain depth sort, as plotting libraries do, gets part of it wrong.
    let naive_path = temp("pair-naive.svg");
    render_svg(
        &mut NaivePainter::default(),
        &s,
        &naive_path,
        ShadeMode::Ids,
    )
    .unwrap();
    let naive = parse_paths(&std::fs::read_to_string(&naive_path).unwrap());
    assert_eq!(naive.len(), 2);
    let (_, naive_wrong) = score_svg(&naive, &reference);
    assert!(naive_wrong > 0);
}

#[test]
fn cyclic_triple_svg_matches_the_oracle() {
    let s = screen(&procedural::cyclic_triple(), 64);
    let path = temp("cycle.svg");
    render_svg(&mut Painter::default(), &s, &path, ShadeMode::Ids).unwrap();
    let paths = parse_paths(&std::fs::read_to_string(&path).unwrap());
    let (checked, wrong) = score_svg(&paths, &oracle(&s));
    assert!(checked > 100);
    assert_eq!(wrong, 0);
}

#[test]
fn dropping_hidden_pieces_keeps_the_picture() {
    let s = screen(&procedural::uv_sphere(12), 48);
    let reference = oracle(&s);
    let (all, some) = (temp("sphere-all.svg"), temp("sphere-visible.svg"));
    render_svg(&mut Painter::default(), &s, &all, ShadeMode::Lambert).unwrap();
    let mut dropping = Painter::new(PainterOptions::default().with_svg_drop_hidden(true));
    render_svg(&mut dropping, &s, &some, ShadeMode::Lambert).unwrap();
    let all = parse_paths(&std::fs::read_to_string(&all).unwrap());
    let some = parse_paths(&std::fs::read_to_string(&some).unwrap());
    // The back of the sphere is hidden: roughly half the pieces go.
    assert!(
        some.len() < all.len() * 3 / 4,
        "{} of {}",
        some.len(),
        all.len()
    );
    for paths in [&all, &some] {
        let (checked, wrong) = score_svg(paths, &reference);
        assert!(checked > 200, "only {checked} pixels checked");
        assert_eq!(wrong, 0);
    }
}

#[test]
fn failed_write_is_an_error_and_leaves_no_file() {
    let s = screen(&procedural::intersecting_pair(), 16);
    let missing = temp("no-such-dir").join("out.svg");
    let err = render_svg(&mut Painter::default(), &s, &missing, ShadeMode::Lambert).unwrap_err();
    assert!(matches!(err, Error::Io { .. }), "{err}");
    assert!(!missing.exists());
}

#[test]
fn svg_before_a_render_or_after_a_failed_one_is_an_error() {
    let s = screen(&procedural::intersecting_pair(), 16);
    let path = temp("never.svg");
    for hider in [
        &Painter::default() as &dyn hider_scene::DynHider,
        &NaivePainter::default(),
    ] {
        let err = hider
            .ordered_polygons()
            .unwrap()
            .write_svg(&s, &path, ShadeMode::Lambert)
            .unwrap_err();
        assert!(matches!(err, Error::Render { .. }), "{err}");
        assert!(!path.exists());
    }
    // A render that runs out of splits leaves nothing to write.
    let mut painter = Painter::new(PainterOptions::default().with_max_splits(0));
    let mut frame = Frame::new(16, 16).unwrap();
    assert!(painter.render(&s, &mut frame).is_err());
    assert_eq!(painter.ordered_pieces().len(), 0);
    let err = painter
        .ordered_polygons()
        .unwrap()
        .write_svg(&s, &path, ShadeMode::Lambert)
        .unwrap_err();
    assert!(matches!(err, Error::Render { .. }), "{err}");
    // Nor is another scene than the one rendered accepted.
    let mut painter = Painter::default();
    painter.render(&s, &mut frame).unwrap();
    let other = screen(&procedural::cube(), 16);
    let err = painter
        .ordered_polygons()
        .unwrap()
        .write_svg(&other, &path, ShadeMode::Lambert)
        .unwrap_err();
    assert!(
        err.to_string().contains("not the one last rendered"),
        "{err}"
    );
    assert!(!path.exists());
}

/// Ordering without painting gives the pieces and the SVG a render gives,
/// with no pixel written; hidden pieces cannot be dropped from it, since
/// only painting tells which they are.
#[test]
fn ordering_alone_gives_the_pieces_of_a_render() {
    let s = screen(&procedural::cyclic_triple(), 48);
    let mut rendered = Painter::default();
    let mut frame = Frame::new(48, 48).unwrap();
    let stats = rendered.render(&s, &mut frame).unwrap();
    let mut ordered = Painter::default();
    let order_stats = ordered.order(&s).unwrap();
    assert!(stats.splits > 0 && stats.pixels_painted > 0);
    assert_eq!(order_stats.pixels_painted, 0);
    assert_eq!(
        order_stats,
        hider_painter::PainterStats {
            pixels_painted: 0,
            ..stats
        }
    );
    assert!(rendered.ordered_pieces().eq(ordered.ordered_pieces()));
    let (a, b) = (temp("order-render.svg"), temp("order-only.svg"));
    render_svg(&mut rendered, &s, &a, ShadeMode::Lambert).unwrap();
    ordered
        .ordered_polygons()
        .unwrap()
        .write_svg(&s, &b, ShadeMode::Lambert)
        .unwrap();
    assert_eq!(
        std::fs::read_to_string(&a).unwrap(),
        std::fs::read_to_string(&b).unwrap()
    );
    let mut dropping = Painter::new(PainterOptions::default().with_svg_drop_hidden(true));
    dropping.order(&s).unwrap();
    let never = temp("order-drop.svg");
    let err = dropping
        .ordered_polygons()
        .unwrap()
        .write_svg(&s, &never, ShadeMode::Lambert)
        .unwrap_err();
    assert!(
        err.to_string().contains("ordered without painting"),
        "{err}"
    );
    assert!(!never.exists());
}
