//! `hider analyze` plans for the view and request `hider render` renders:
//! the same flags give the same plan line, on every hard case and on
//! textured, translucent and mixed scenes, from the fit camera, from
//! behind, and with the other flags that change a plan.

use std::path::{Path, PathBuf};

use glam::DVec3;
use hider::geom::Projection;
use hider::scene::{Material, Mesh, Scene, fit_camera, procedural, save_obj};
use hider_testkit::hard_cases;

mod cli_support;
use cli_support::{assert_success, hider, temp_dir};

/// The plan line of `hider analyze MODEL FLAGS`.
fn analyze_plan(model: &str, flags: &[String]) -> String {
    let mut args = vec!["analyze".to_owned(), model.to_owned()];
    args.extend_from_slice(flags);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let out = hider(&args);
    assert_success(&out);
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    stdout
        .lines()
        .find(|l| l.starts_with("auto, asked for"))
        .unwrap_or_else(|| panic!("no plan line from analyze {args:?}: {stdout}"))
        .to_owned()
}

/// The plan line `hider render MODEL -o PNG FLAGS` prints on stderr.
fn render_plan(model: &str, png: &Path, flags: &[String]) -> String {
    let mut args = vec![
        "render".to_owned(),
        model.to_owned(),
        "-o".to_owned(),
        png.to_string_lossy().into_owned(),
    ];
    args.extend_from_slice(flags);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let err = assert_success(&hider(&args));
    err.lines()
        .find(|l| l.starts_with("auto, asked for"))
        .unwrap_or_else(|| panic!("no plan line from render {args:?}: {err}"))
        .to_owned()
}

fn v3(v: DVec3) -> String {
    format!("{:?},{:?},{:?}", v.x, v.y, v.z)
}

/// The camera flags of the scene's own camera (perspective ones; others
/// are left to the fit camera, as both commands do), and those of the fit
/// camera turned around to look from behind.
fn camera_flag_sets(scene: &Scene) -> Vec<Vec<String>> {
    let s = |x: &str| x.to_owned();
    let mut sets = vec![Vec::new()];
    if let Some(c) = scene.camera
        && let Projection::Perspective {
            fovy_degrees,
            near,
            far,
        } = c.projection
    {
        sets.push(vec![
            s("--eye"),
            v3(c.eye),
            s("--target"),
            v3(c.target),
            s("--up"),
            v3(c.up),
            s("--fovy"),
            format!("{fovy_degrees:?}"),
            s("--near"),
            format!("{near:?}"),
            s("--far"),
            format!("{far:?}"),
        ]);
    } else {
        let c = fit_camera(scene);
        let behind = c.target * 2.0 - c.eye;
        sets.push(vec![s("--eye"), v3(behind), s("--target"), v3(c.target)]);
    }
    sets
}

/// The extra request flags of run `k`: every third scene anti-aliased,
/// some ids-only, f32, two threads, non-square, or the painter's SVG.
fn request_flags(k: usize, svg: &Path) -> (Vec<String>, Vec<String>) {
    let s = |x: &str| x.to_owned();
    let both = match k % 6 {
        0 => vec![s("--aa")],
        1 => vec![s("--shade"), s("ids")],
        2 => vec![s("--precision"), s("f32"), s("--threads"), s("2")],
        3 => vec![s("--width"), s("80"), s("--height"), s("48")],
        _ => Vec::new(),
    };
    if k % 6 == 4 {
        // The painter's ordered polygons: render needs a file to write.
        let mut render = vec![s("--svg"), svg.to_string_lossy().into_owned()];
        render.extend([s("--svg-mode"), s("painter")]);
        return (vec![s("--svg-mode"), s("painter")], render);
    }
    (both.clone(), both)
}

/// One mesh, one material: a unit cube and a small inside-out one.
fn mixed_orientation() -> Scene {
    let unit = procedural::cube();
    let m = &unit.meshes[0];
    let mut mesh = Mesh {
        name: "mixed".into(),
        positions: m.positions.clone(),
        indices: m.indices.clone(),
        ..Mesh::default()
    };
    let base = mesh.positions.len() as u32;
    mesh.positions.extend(
        m.positions
            .iter()
            .map(|&p| DVec3::new(2.2, 0.3, 0.5) + p * 0.5),
    );
    mesh.indices.extend(
        m.indices
            .iter()
            .map(|t| [t[0] + base, t[2] + base, t[1] + base]),
    );
    let mut scene = Scene::default();
    scene.push_mesh(mesh, Some(Material::default()));
    scene
}

/// A translucent triangle sealed in an opaque cube, and a translucent cube
/// beside it.
fn translucent() -> Scene {
    let mut scene = procedural::cube();
    let glass = Material {
        name: "glass".into(),
        opacity: 0.4,
        ..Material::default()
    };
    scene.push_mesh(
        Mesh {
            name: "sealed".into(),
            positions: vec![
                DVec3::new(-0.5, -0.5, 0.0),
                DVec3::new(0.5, -0.3, 0.0),
                DVec3::new(0.0, 0.5, 0.0),
            ],
            indices: vec![[0, 1, 2]],
            ..Mesh::default()
        },
        Some(glass.clone()),
    );
    let mut beside = procedural::cube().meshes.remove(0);
    for p in &mut beside.positions {
        *p = *p * 0.5 + DVec3::new(2.5, 0.0, 0.0);
    }
    scene.push_mesh(beside, Some(glass));
    scene
}

#[test]
fn analyze_and_render_plan_the_same() {
    let dir = temp_dir("plans-agree");
    let png = dir.join("out.png");
    let svg = dir.join("out.svg");
    let mut models: Vec<(String, PathBuf, Scene)> = Vec::new();
    let mut scenes: Vec<(&str, Scene)> = hard_cases::all(36);
    scenes.push(("mixed_orientation", mixed_orientation()));
    scenes.push(("translucent", translucent()));
    for (name, scene) in scenes {
        let path = dir.join(format!("{name}.obj"));
        save_obj(&scene, &path).unwrap();
        models.push((name.to_owned(), path, scene));
    }
    let checker = Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/checker_plane.obj");
    let scene = hider::scene::load_model(checker.to_str().unwrap()).unwrap();
    models.push(("checker_plane".to_owned(), checker, scene));

    let mut compared = 0;
    for (k, (name, path, scene)) in models.iter().enumerate() {
        let model = path.to_string_lossy();
        for (c, camera) in camera_flag_sets(scene).into_iter().enumerate() {
            let (analyze_extra, render_extra) = request_flags(k + c, &svg);
            let sized = |extra: &[String]| {
                let mut f = camera.clone();
                if !extra.iter().any(|x| x == "--width") {
                    f.extend(["--size".to_owned(), "64".to_owned()]);
                }
                f.extend_from_slice(extra);
                f
            };
            let a = analyze_plan(&model, &sized(&analyze_extra));
            let r = render_plan(&model, &png, &sized(&render_extra));
            assert_eq!(a, r, "{name} with {camera:?} {analyze_extra:?}");
            compared += 1;
        }
    }
    assert!(compared >= 50, "only {compared} comparisons");
}

#[test]
fn a_scene_seen_from_behind_plans_the_same() {
    // The case of the issue: the cube seen from behind (where analyze,
    // without camera flags, assumed the fit camera).
    let dir = temp_dir("plans-behind");
    let png = dir.join("out.png");
    let flags: Vec<String> = ["--eye", "0.3,-0.5,-6", "--target", "0,0,0", "--size", "64"]
        .map(str::to_owned)
        .to_vec();
    let a = analyze_plan("gen:cube", &flags);
    let r = render_plan("gen:cube", &png, &flags);
    assert_eq!(a, r);
}
