//! The bundled textured asset (`assets/checker_plane.*`, `assets/checker.png`)
//! stays what `hider_scene::shade::texture` generates (`HIDER_BLESS=1` rewrites
//! it), renders with correct perspective, and without its texture skips
//! the texture stage.

use std::path::{Path, PathBuf};

use glam::DVec3;
use hider_oracle::RayCastOracle;
use hider_plan::{RenderOptions, analyze};
use hider_scene::geom::Camera;
use hider_scene::shade::texture::{self, Filter};
use hider_scene::shade::{Mapping, Prims, Shader, ShaderOptions, Stages};
use hider_scene::{Frame, NO_ID, PrepareOptions, ScreenScene, View, load_obj, prepare};

fn assets() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets")
}

#[test]
fn checker_asset_matches_its_generator() {
    let dir = assets();
    let (obj, mtl) = texture::checker_plane_text("checker_plane.mtl", texture::CHECKER_PNG);
    let (side, rgb) = texture::checker_texture();
    if std::env::var_os("HIDER_BLESS").is_some() {
        std::fs::write(dir.join("checker_plane.obj"), &obj).unwrap();
        std::fs::write(dir.join("checker_plane.mtl"), &mtl).unwrap();
        image::save_buffer(
            dir.join(texture::CHECKER_PNG),
            &rgb,
            side,
            side,
            image::ExtendedColorType::Rgb8,
        )
        .unwrap();
    }
    let read = |name: &str| {
        std::fs::read_to_string(dir.join(name))
            .unwrap_or_else(|e| panic!("{name}: {e} (run with HIDER_BLESS=1)"))
    };
    assert_eq!(
        read("checker_plane.obj"),
        obj,
        "stale: run with HIDER_BLESS=1"
    );
    assert_eq!(
        read("checker_plane.mtl"),
        mtl,
        "stale: run with HIDER_BLESS=1"
    );
    let png = image::open(dir.join(texture::CHECKER_PNG))
        .unwrap()
        .to_rgb8();
    assert_eq!((png.width(), png.height()), (side, side));
    assert_eq!(
        png.as_raw(),
        &rgb,
        "checker.png is stale: run with HIDER_BLESS=1"
    );
}

/// A camera low over the near edge, looking along the plane: the far edge
/// is about three times as far as the near one.
fn grazing_camera() -> Camera {
    Camera::perspective(DVec3::new(0.0, 0.5, 2.0), DVec3::ZERO, 0.1, 10.0)
}

/// The visible primitive at every pixel centre, from the exact oracle.
fn ids(screen: &ScreenScene) -> Frame {
    hider_testkit::render(&mut RayCastOracle::default(), screen).0
}

/// Per row, the x positions (pixel boundaries) where the checker switches
/// between light and dark, for rows that cross all 7 inner u-lines.
fn transitions(frame: &Frame) -> Vec<(f64, Vec<f64>)> {
    let mut rows = Vec::new();
    for y in 0..frame.height() {
        let class = |x: u32| {
            let k = frame.index(x, y);
            (frame.ids[k] != NO_ID).then(|| frame.color[k][0] > 128)
        };
        let mut xs = Vec::new();
        for x in 0..frame.width() - 1 {
            if let (Some(a), Some(b)) = (class(x), class(x + 1))
                && a != b
            {
                xs.push(f64::from(x + 1));
            }
        }
        if xs.len() == 7 {
            rows.push((f64::from(y) + 0.5, xs));
        }
    }
    rows
}

/// The largest distance of the k-th transition from its least-squares line
/// `x = a + b y`, over all k.
fn worst_line_residual(rows: &[(f64, Vec<f64>)]) -> f64 {
    (0..7)
        .map(|k| {
            let pts: Vec<(f64, f64)> = rows.iter().map(|(y, xs)| (*y, xs[k])).collect();
            let n = pts.len() as f64;
            let (my, mx) = (
                pts.iter().map(|p| p.0).sum::<f64>() / n,
                pts.iter().map(|p| p.1).sum::<f64>() / n,
            );
            let sxy: f64 = pts.iter().map(|p| (p.0 - my) * (p.1 - mx)).sum();
            let syy: f64 = pts.iter().map(|p| (p.0 - my) * (p.0 - my)).sum();
            let b = sxy / syy;
            pts.iter()
                .map(|p| (p.1 - (mx + b * (p.0 - my))).abs())
                .fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

fn load_plane() -> hider_scene::Scene {
    load_obj(assets().join("checker_plane.obj")).unwrap()
}

#[test]
fn grazing_checkerboard_keeps_straight_lines_straight() {
    let scene = load_plane();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let options = RenderOptions::default()
        .with_size(256, 256)
        .with_camera(Some(grazing_camera()));
    let effects = analyze(&scene, &options).unwrap();
    assert!(effects.textures.present, "{}", effects.textures.detail);
    assert!(effects.lighting.present, "Lambert shading: the head light");
    // Lighting off, so the texels show as they are and the edge detection
    // below sees the texture alone.
    let stages = Stages {
        lighting: false,
        ..effects.stages()
    };
    let view = options.view(&scene).unwrap();
    let screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
    let mut frame = ids(&screen);
    // The texture decodes on first use, once: the second pass finds it.
    let render = |frame: &mut Frame, mapping: Mapping, decodes: u64| {
        let mut shader = Shader::new(
            ShaderOptions::default()
                .with_filter(Filter::Nearest)
                .with_mapping(mapping),
        );
        let trace = shader.shade(Prims::Screen(&screen), frame, &stages);
        assert_eq!(trace.ran, vec!["texture"]);
        assert_eq!(trace.textures_loaded, decodes);
        assert_eq!(trace.texture_samples, trace.pixels);
        worst_line_residual(&transitions(frame))
    };
    let rows = {
        render(&mut frame, Mapping::PerspectiveCorrect, 1);
        transitions(&frame)
    };
    assert!(rows.len() > 60, "only {} rows cross all lines", rows.len());
    let correct = worst_line_residual(&rows);
    // Pixel quantisation of an edge position is at most one pixel.
    assert!(
        correct <= 1.0,
        "perspective-correct lines bend by {correct} px"
    );
    // The same test catches screen-space (affine) interpolation: the lines
    // kink where the two triangles meet.
    let affine = render(&mut frame, Mapping::Affine, 0);
    eprintln!(
        "checker lines over {} rows: worst residual {correct:.2} px perspective-correct, \
         {affine:.2} px affine",
        rows.len()
    );
    assert!(
        affine > 3.0,
        "affine mapping should bend lines, residual {affine} px"
    );
}

#[test]
fn without_its_texture_the_texture_stage_is_skipped() {
    let mut scene = load_plane();
    let options = RenderOptions::default().with_size(64, 64);
    let with = analyze(&scene, &options).unwrap();
    assert!(with.textures.present);
    assert_eq!(with.textures.count, 2);
    for m in &mut scene.materials {
        m.diffuse_texture = None;
    }
    let without = analyze(&scene, &options).unwrap();
    assert!(!without.textures.present, "{}", without.textures.detail);
    let stages = without.stages();
    assert!(!stages.texture);
    let view = View::for_scene(&scene, 64, 64).unwrap();
    let screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
    let mut frame = ids(&screen);
    let trace = Shader::default().shade(Prims::Screen(&screen), &mut frame, &stages);
    assert_eq!(trace.ran, vec!["lighting"]);
    assert_eq!((trace.texture_samples, trace.textures_loaded), (0, 0));
    assert!(trace.pixels > 0);
    // A texture that does not load is reported and not used.
    scene.materials[0].diffuse_texture = Some(Path::new("/no/such/checker.png").into());
    let broken = analyze(&scene, &options).unwrap();
    assert!(!broken.textures.present);
    assert!(
        broken.textures.detail.contains("/no/such/checker.png"),
        "{}",
        broken.textures.detail
    );
}
