//! The SVG files as their users meet them: regions without seams in an
//! anti-aliasing viewer (rasterised by resvg, a renderer independent of
//! this project), line drawings ordered for a pen plotter, layered by
//! kind and object, in pixel coordinates, without dots or doubled
//! segments.

use std::path::Path;

use hider_scene::{
    Hider, NO_ID, PrepareOptions, Scene, ScreenScene, ShadeMode, View, fit_camera, load_obj,
    prepare, procedural,
};
use hider_testkit::render;
use hider_vector::{
    LineKind, SvgInfo, VectorOptions, hidden_lines_in, lines_document, pen_up_travel,
    regions_document, visible_regions,
};
use hider_zbuffer::{ZBuffer, ZBufferOptions};

fn screen_of(scene: &Scene, size: u32) -> ScreenScene {
    let view = View::new(fit_camera(scene), size, size).unwrap();
    prepare(scene, &view, &PrepareOptions::default()).unwrap()
}

fn spider() -> Option<Scene> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/spider/spider.obj");
    path.exists().then(|| load_obj(&path).unwrap())
}

/// The alpha channel of `svg` rasterised by resvg at its own size.
fn alpha(svg: &str, w: u32, h: u32) -> Vec<u8> {
    let tree = resvg::usvg::Tree::from_str(svg, &resvg::usvg::Options::default()).unwrap();
    let mut pixmap = resvg::tiny_skia::Pixmap::new(w, h).unwrap();
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::identity(),
        &mut pixmap.as_mut(),
    );
    pixmap.pixels().iter().map(|p| p.alpha()).collect()
}

/// Mean coverage lost (255 - alpha) over the interior pixels: those whose
/// 5 x 5 neighbourhood the z-buffer covers entirely (the outline's
/// anti-aliased pixels are not interior).
fn interior_loss(s: &ScreenScene, alpha: &[u8]) -> (f64, usize) {
    let mut zbuffer = ZBuffer::new(ZBufferOptions::default());
    let (frame, _) = render(&mut zbuffer, s);
    let (w, h) = (s.viewport.width as i64, s.viewport.height as i64);
    let covered = |x: i64, y: i64| {
        x >= 0 && y >= 0 && x < w && y < h && frame.ids[(y * w + x) as usize] != NO_ID
    };
    let (mut lost, mut n) = (0u64, 0usize);
    for y in 0..h {
        for x in 0..w {
            let inside = (-2..=2).all(|dy| (-2..=2).all(|dx| covered(x + dx, y + dy)));
            if inside {
                lost += u64::from(255 - alpha[(y * w + x) as usize]);
                n += 1;
            }
        }
    }
    (lost as f64 / n as f64, n)
}

#[test]
fn regions_show_no_seams_in_an_anti_aliasing_viewer() {
    // The 200-segment sphere at 512: tens of thousands of abutting paths,
    // each its own shade. resvg composites them one after the other, as
    // rsvg and Chromium do.
    let s = screen_of(&procedural::uv_sphere(200), 512);
    let options = VectorOptions::default();
    let map = visible_regions(&s, &options, ShadeMode::Lambert).unwrap();
    let info = SvgInfo::default();
    let seamless = regions_document(&s, &map, &options, &info);
    let bare = regions_document(&s, &map, &options.clone().with_seam_stroke(0.0), &info);
    let (with, n) = interior_loss(&s, &alpha(&seamless, 512, 512));
    let (without, _) = interior_loss(&s, &alpha(&bare, 512, 512));
    eprintln!(
        "sphere 200 at 512, {n} interior pixels: mean coverage lost {without:.2}/255 bare, \
         {with:.3}/255 with the default seam stroke"
    );
    assert!(n > 30_000, "only {n} interior pixels");
    assert!(with < 2.0, "seams lose {with}/255 of coverage");
    // The bare regions do show seams: the test can see them.
    assert!(without > 2.0, "bare regions lose only {without}/255");
    // The stroke is clipped to the covered set: the outline does not grow.
    let (a, b) = (alpha(&seamless, 512, 512), alpha(&bare, 512, 512));
    let outside = a.iter().zip(&b).filter(|&(&x, &y)| x > 0 && y == 0).count();
    assert_eq!(outside, 0, "{outside} pixels drawn outside the regions");
}

#[test]
fn the_spiders_lines_are_ordered_for_a_plotter() {
    let Some(scene) = spider() else {
        eprintln!("assets/spider not present: skipped");
        return;
    };
    let s = screen_of(&scene, 1024);
    let options = VectorOptions::default();
    let map = visible_regions(&s, &options, ShadeMode::Lambert).unwrap();
    let info = SvgInfo::for_scene(&scene, "spider.obj", &s);
    let d = hidden_lines_in(&s, &map, &options, &info.groups).unwrap();
    let travel = d.pen_up_travel();
    // The file order is the drawing's: measure it on the file too.
    let svg = lines_document(&s, &d, &options, &info);
    let file_lines: Vec<Vec<(f64, f64)>> = svg
        .split("points=\"")
        .skip(1)
        .map(|rest| {
            rest[..rest.find('"').unwrap()]
                .split(' ')
                .map(|p| {
                    let (x, y) = p.split_once(',').unwrap();
                    (x.parse().unwrap(), y.parse().unwrap())
                })
                .collect()
        })
        .collect();
    let file_travel: f64 = file_lines
        .windows(2)
        .map(|w| {
            let (a, b) = (*w[0].last().unwrap(), w[1][0]);
            (b.0 - a.0).hypot(b.1 - a.1)
        })
        .sum();
    let drawn: f64 = d
        .visible
        .iter()
        .flat_map(|l| l.points.windows(2))
        .map(|w| (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1))
        .sum();
    eprintln!(
        "spider at 1024: {} polylines, {drawn:.0} px drawn, pen-up travel {travel:.0} px ({file_travel:.0} px in the file)",
        d.visible.len()
    );
    assert!(
        (travel - file_travel).abs() < 1.0,
        "{travel} vs {file_travel}"
    );
    assert!(travel < 3000.0, "pen-up travel {travel} px");
    // In the order of the pieces before ordering it is far longer.
    let mut unordered = d.visible.clone();
    unordered.sort_by(|a, b| a.points[0].0.total_cmp(&b.points[0].0).reverse());
    assert!(pen_up_travel(&unordered) > travel);
    // Layers: one per object, its lines grouped per kind.
    assert!(
        svg.contains(r#"inkscape:groupmode="layer" inkscape:label="Bein1Li""#),
        "{svg}"
    );
    assert!(svg.contains(r#"class="silhouette""#));
    assert!(svg.contains("<title>spider.obj</title>"));
    assert!(svg.contains("<desc>model spider.obj;"));
    assert!(!svg.contains("<rect"), "no background unless asked");
    assert!(!svg.contains("transform"));
    // No dots, no segment twice.
    let mut segments = Vec::new();
    for line in &d.visible {
        let length: f64 = line
            .points
            .windows(2)
            .map(|w| (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1))
            .sum();
        assert!(length >= options.min_fragment, "{line:?}");
        for w in line.points.windows(2) {
            let key = |p: (f64, f64)| ((p.0 * 1e3).round() as i64, (p.1 * 1e3).round() as i64);
            let (a, b) = (key(w[0]), key(w[1]));
            segments.push(if a < b { (a, b) } else { (b, a) });
        }
    }
    let n = segments.len();
    segments.sort_unstable();
    segments.dedup();
    assert_eq!(segments.len(), n, "a segment is drawn twice");
}

#[test]
fn lines_are_layered_by_object_and_kind() {
    // Two objects, each a cube (a generated cube twice, the second
    // shifted): every line in the layer of its own object.
    let mut scene = procedural::cube();
    let mut second = scene.meshes[0].clone();
    second.name = "second cube".into();
    for p in &mut second.positions {
        p.x += 3.0;
    }
    scene.meshes.push(second);
    let s = screen_of(&scene, 256);
    let options = VectorOptions::default();
    let map = visible_regions(&s, &options, ShadeMode::Lambert).unwrap();
    let info = SvgInfo::for_scene(&scene, "two cubes", &s);
    assert_eq!(info.groups.len(), 2);
    let d = hidden_lines_in(&s, &map, &options, &info.groups).unwrap();
    assert!(d.visible.iter().any(|l| l.group == 0));
    assert!(d.visible.iter().any(|l| l.group == 1));
    let svg = lines_document(&s, &d, &options, &info);
    assert!(svg.contains(r#"inkscape:label="second cube""#), "{svg}");
    assert!(
        svg.contains(r#"id="lines-1-second_cube-silhouette-1""#),
        "{svg}"
    );
    // Each object's lines are contiguous (one layer each).
    let groups: Vec<u32> = d.visible.iter().map(|l| l.group).collect();
    let mut runs = groups.clone();
    runs.dedup();
    assert_eq!(runs.len(), 2, "{groups:?}");
    assert!(d.visible.iter().any(|l| l.kind == LineKind::Silhouette));
    let regions = regions_document(&s, &map, &options, &info);
    assert!(regions.contains(r#"id="regions-1-second_cube""#));
}

#[test]
fn no_segment_is_drawn_twice_on_the_hard_cases() {
    // Mesh edges are keyed by their exact camera-space corners, so an
    // edge two triangles share is one line whatever its kind; distinct
    // edges projecting onto one line (slivers seen edge-on) overlap, and
    // the overlap is drawn once (before: 326 segments, 306 distinct, on
    // `slivers`).
    let options = VectorOptions::default().with_dashed_hidden(true);
    for (name, scene) in hider_testkit::hard_cases::all(1) {
        let s = hider_testkit::screen(&scene, 64, 64);
        let map = visible_regions(&s, &options, ShadeMode::Lambert).unwrap();
        let d = hidden_lines_in(&s, &map, &options, &SvgInfo::default().groups).unwrap();
        let key = |p: (f64, f64)| ((p.0 * 1e3).round() as i64, (p.1 * 1e3).round() as i64);
        let mut segments: Vec<_> = d
            .visible
            .iter()
            .chain(&d.hidden)
            .flat_map(|l| l.points.windows(2))
            .map(|w| {
                let (a, b) = (key(w[0]), key(w[1]));
                if a < b { (a, b) } else { (b, a) }
            })
            .filter(|(a, b)| a != b)
            .collect();
        let n = segments.len();
        segments.sort_unstable();
        segments.dedup();
        assert_eq!(segments.len(), n, "{name}: a segment is drawn twice");
    }
}
