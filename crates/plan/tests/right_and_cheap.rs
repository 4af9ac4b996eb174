//! Issue 36, "a planner that is right and cheap": back faces decided per
//! closed shell, transparency that no pixel shows does not force the
//! A-buffer, the plan names the stages that run, and near-coplanar
//! overlaps are found whatever the plane's orientation.

use glam::DVec3;
use hider_plan::{HiderConfig, RenderOptions, analyze, auto, registry};
use hider_scene::geom::Camera;
use hider_scene::{Frame, Material, Mesh, PrepareOptions, Scene, ScreenScene, View, procedural};

const SIDE: u32 = 96;

fn options() -> RenderOptions {
    RenderOptions::default().with_size(SIDE, SIDE)
}

/// A cube of half-size `h` centred at `c`, outward (`flip` false) or
/// inside-out.
fn cube_at(c: DVec3, h: f64, flip: bool) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let unit = procedural::cube();
    let m = &unit.meshes[0];
    let positions = m.positions.iter().map(|&p| c + p * h).collect();
    let indices = m
        .indices
        .iter()
        .map(|t| if flip { [t[0], t[2], t[1]] } else { *t })
        .collect();
    (positions, indices)
}

/// One mesh (one material) holding both cubes.
fn one_mesh(parts: &[(Vec<DVec3>, Vec<[u32; 3]>)]) -> Scene {
    let mut mesh = Mesh {
        name: "shells".into(),
        ..Mesh::default()
    };
    for (p, t) in parts {
        let base = mesh.positions.len() as u32;
        mesh.positions.extend(p);
        mesh.indices.extend(t.iter().map(|t| t.map(|i| i + base)));
    }
    let mut scene = Scene::default();
    scene.push_mesh(mesh, Some(Material::default()));
    scene
}

fn render(scene: &Scene, view: &View, algo: &str, prepare: &PrepareOptions) -> Frame {
    let mut hider = registry::find(algo)
        .unwrap()
        .build(&HiderConfig::default())
        .unwrap();
    let mut screen = ScreenScene::empty(view);
    let mut frame = Frame::new(view.viewport.width, view.viewport.height).unwrap();
    hider
        .render_scene(scene, view, prepare, &mut screen, &mut frame)
        .unwrap();
    frame
}

/// The plan's frame and `zbuffer`'s without culling: how many pixels show
/// another primitive.
fn differing_pixels(scene: &Scene, opts: &RenderOptions) -> usize {
    let planned = auto(scene, opts).unwrap();
    let ours = render(scene, &planned.view, planned.plan.algo, &planned.prepare);
    let reference = render(scene, &planned.view, "zbuffer", &PrepareOptions::default());
    ours.ids
        .iter()
        .zip(&reference.ids)
        .filter(|(a, b)| a != b)
        .count()
}

#[test]
fn an_inside_out_cube_in_the_mesh_of_an_outward_one_is_not_culled() {
    // The big outward cube's volume outweighs the small inside-out one's:
    // summed over the mesh, the volume is positive.
    let scene = one_mesh(&[
        cube_at(DVec3::ZERO, 1.0, false),
        cube_at(DVec3::new(2.2, 0.3, 0.5), 0.5, true),
    ]);
    let fx = analyze(&scene, &options()).unwrap();
    assert!(fx.back_faces.present, "{}", fx.back_faces.detail);
    assert!(!fx.cull_back_faces_exact);
    assert_eq!(differing_pixels(&scene, &options()), 0);
}

#[test]
fn two_outward_cubes_in_one_mesh_are_still_culled() {
    let scene = one_mesh(&[
        cube_at(DVec3::ZERO, 1.0, false),
        cube_at(DVec3::new(2.2, 0.3, 0.5), 0.5, false),
    ]);
    let fx = analyze(&scene, &options()).unwrap();
    assert!(fx.cull_back_faces_exact, "{}", fx.back_faces.detail);
    assert!(
        fx.back_faces.detail.contains("2 of 2 closed shells"),
        "{}",
        fx.back_faces.detail
    );
    assert_eq!(differing_pixels(&scene, &options()), 0);
}

#[test]
fn an_open_sheet_beside_a_closed_cube_keeps_its_back_faces() {
    let (mut p, mut t) = cube_at(DVec3::ZERO, 1.0, false);
    // A quad facing away from the camera: its back is what is seen.
    let base = p.len() as u32;
    p.extend([
        DVec3::new(2.0, -1.0, 0.0),
        DVec3::new(2.0, 1.0, 0.0),
        DVec3::new(4.0, 1.0, 0.0),
        DVec3::new(4.0, -1.0, 0.0),
    ]);
    t.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
    let scene = one_mesh(&[(p, t)]);
    let view = options().with_camera(Some(camera()));
    let fx = analyze(&scene, &view).unwrap();
    assert!(!fx.cull_back_faces_exact, "{}", fx.back_faces.detail);
    assert_eq!(differing_pixels(&scene, &view), 0);
}

fn camera() -> Camera {
    Camera::perspective(
        DVec3::new(0.5, 0.7, 8.0),
        DVec3::new(0.5, 0.0, 0.0),
        0.5,
        50.0,
    )
}

/// A mesh of its own material.
fn push(scene: &mut Scene, positions: Vec<DVec3>, indices: Vec<[u32; 3]>, opacity: f32) {
    let material = Material {
        name: format!("m{}", scene.materials.len()),
        opacity,
        ..Material::default()
    };
    scene.push_mesh(
        Mesh {
            name: material.name.clone(),
            positions,
            indices,
            ..Mesh::default()
        },
        Some(material),
    );
}

fn quad(z: f64, h: f64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    (
        vec![
            DVec3::new(-h, -h, z),
            DVec3::new(h, -h, z),
            DVec3::new(h, h, z),
            DVec3::new(-h, h, z),
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
}

fn triangle(z: f64, h: f64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    (
        vec![
            DVec3::new(-h, -h, z),
            DVec3::new(h, -h * 0.5, z),
            DVec3::new(0.0, h, z),
        ],
        vec![[0, 1, 2]],
    )
}

fn straight_on() -> RenderOptions {
    options().with_camera(Some(Camera::perspective(
        DVec3::new(0.0, 0.0, 6.0),
        DVec3::ZERO,
        0.5,
        50.0,
    )))
}

#[test]
fn a_translucent_triangle_behind_an_opaque_quad_does_not_force_the_abuffer() {
    let mut scene = Scene::default();
    let (p, t) = quad(1.0, 2.0);
    push(&mut scene, p, t, 1.0);
    let (p, t) = triangle(-1.0, 0.5);
    push(&mut scene, p, t, 0.4);
    let planned = auto(&scene, &straight_on()).unwrap();
    assert!(
        !planned.effects.transparency.present,
        "{}",
        planned.effects.transparency.detail
    );
    assert!(
        planned.effects.transparency.detail.contains("hidden"),
        "{}",
        planned.effects.transparency.detail
    );
    assert_eq!(planned.plan.algo, "zbuffer-tiled", "{}", planned.summary());
    assert!(!planned.plan.stages.transparency);
    assert_eq!(differing_pixels(&scene, &straight_on()), 0);

    // Moved in front of the quad, or sticking out from behind it, it shows.
    let mut front = Scene::default();
    let (p, t) = quad(1.0, 2.0);
    push(&mut front, p, t, 1.0);
    let (p, t) = triangle(2.0, 0.5);
    push(&mut front, p, t, 0.4);
    let planned = auto(&front, &straight_on()).unwrap();
    assert!(planned.effects.transparency.present);
    assert_eq!(planned.plan.algo, "abuffer");
    let mut out = Scene::default();
    let (p, t) = quad(1.0, 0.3);
    push(&mut out, p, t, 1.0);
    let (p, t) = triangle(-1.0, 0.5);
    push(&mut out, p, t, 0.4);
    assert!(
        auto(&out, &straight_on())
            .unwrap()
            .effects
            .transparency
            .present
    );
}

#[test]
fn a_translucent_triangle_sealed_in_an_opaque_cube_does_not_force_the_abuffer() {
    let mut scene = procedural::cube();
    let (p, t) = triangle(0.0, 0.5);
    push(&mut scene, p, t, 0.3);
    let planned = auto(&scene, &options()).unwrap();
    assert!(
        !planned.effects.transparency.present,
        "{}",
        planned.effects.transparency.detail
    );
    assert_eq!(planned.plan.algo, "zbuffer-tiled", "{}", planned.summary());
    assert_eq!(differing_pixels(&scene, &options()), 0);
}

#[test]
fn the_plan_line_says_anti_aliased_when_the_hider_anti_aliases() {
    let mut glass = procedural::cube();
    glass.materials[0].opacity = 0.5;
    let planned = auto(&glass, &options()).unwrap();
    assert_eq!(planned.plan.algo, "abuffer");
    assert!(
        planned.plan.stages_run().multisample,
        "{}",
        planned.summary()
    );
    assert!(
        planned.summary().contains("multisample"),
        "{}",
        planned.summary()
    );
    assert!(
        planned.summary().contains("anti-aliased"),
        "{}",
        planned.summary()
    );
    // The one-sample z-buffer runs no multisample stage.
    let planned = auto(&procedural::cube(), &options()).unwrap();
    assert!(!planned.plan.stages_run().multisample);
    assert!(
        !planned.summary().contains("anti-aliased"),
        "{}",
        planned.summary()
    );
}

/// Two overlapping triangles in the plane through `origin` with normal
/// (1, 2, 3), the second `gap` along the unit normal.
fn tilted_pair(gap: f64) -> Scene {
    let n = DVec3::new(1.0, 2.0, 3.0).normalize();
    let u = DVec3::new(2.0, -1.0, 0.0).normalize();
    let v = n.cross(u);
    let at = |a: f64, b: f64, off: f64| u * a + v * b + n * off;
    let mut scene = Scene::default();
    push(
        &mut scene,
        vec![at(-1.0, -1.0, 0.0), at(1.0, -1.0, 0.0), at(0.0, 1.0, 0.0)],
        vec![[0, 1, 2]],
        1.0,
    );
    push(
        &mut scene,
        vec![at(-0.7, -0.8, gap), at(1.3, -0.6, gap), at(0.2, 1.1, gap)],
        vec![[0, 1, 2]],
        1.0,
    );
    scene
}

#[test]
fn tilted_coplanar_and_near_coplanar_overlaps_are_found() {
    for gap in [0.0, 1e-6, -1e-6] {
        let fx = analyze(&tilted_pair(gap), &options()).unwrap();
        assert_eq!(
            fx.coplanar_overlaps.count, 1,
            "gap {gap}: {}",
            fx.coplanar_overlaps.detail
        );
        assert_eq!(fx.intersections.count, 0, "gap {gap}");
        assert!(
            fx.coplanar_overlaps.detail.contains("within"),
            "the tolerance is stated: {}",
            fx.coplanar_overlaps.detail
        );
    }
    // A gap of a hundredth of the size is an order, not a tie.
    let fx = analyze(&tilted_pair(1e-2), &options()).unwrap();
    assert_eq!(fx.coplanar_overlaps.count, 0);
}

#[test]
fn the_quick_raster_analysis_plans_as_the_full_one() {
    let mut scenes = hider_testkit::hard_cases::all(36);
    scenes.push(("soup", procedural::random_soup(3000, 5)));
    scenes.push(("sphere", procedural::uv_sphere(40)));
    for (name, scene, _) in hider_testkit::hard_cases::closed_meshes(36) {
        scenes.push((name, scene));
    }
    let mut quick = 0;
    for (name, scene) in scenes {
        for opts in [options(), options().with_antialiasing(true)] {
            let opts = opts.with_pair_searches(false);
            let full = hider_plan::plan(&analyze(&scene, &opts).unwrap());
            let planned = auto(&scene, &opts).unwrap();
            assert_eq!(planned.plan.algo, full.algo, "{name}");
            assert_eq!(planned.plan.cull_back_faces, full.cull_back_faces, "{name}");
            assert_eq!(planned.plan.stages, full.stages, "{name}");
            assert_eq!(
                planned.prepare,
                full.prepare_options(opts.prepare),
                "{name}"
            );
            quick += usize::from(planned.effects.back_faces.detail.starts_with("not counted"));
        }
    }
    assert!(quick >= 10, "the quick path ran {quick} times");
}
