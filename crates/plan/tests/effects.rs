//! Effects compose with every hider that resolves colour itself, and with
//! the planner's choice: texture, lighting and transparency, alone and
//! combined, against a reference made by supersampling the same stages.
//!
//! The reference is brute force: every triangle is tested at every sample
//! (the front end's exact edge functions and depth planes), the surfaces
//! found at a sample are sorted by depth and composited front to back with
//! their textured, lit colour, and the samples are averaged. It uses the
//! hider's own sample positions (one at the centre for pixel-centre
//! hiders) and its shading rate: supersampling textures every sample, the
//! A-buffer and anti-aliased Warnock texture a surface once per pixel at
//! its centre, as multisample rasterisers shade. What remains is how
//! colour is composited, so the bounds are tight: a mean of 0.25 levels
//! (8-bit sRGB) and 3 levels on any channel of any pixel (rounding of
//! `f32` sums), 12 for `abuffer-carpenter`, whose blender estimates the
//! order of fragments that overlap in depth. Ignoring an effect costs far
//! more: the test checks that the image without its effects differs from
//! the reference by more than 4 levels on average (16 times the mean bound),
//! so the bounds can fail.
//!
//! Supersampling (`ssaa-N`) and anti-aliased Warnock keep one surface per
//! sample: they draw translucent surfaces opaque, are compared on opaque
//! scenes only, and `hider render` warns when they meet a translucent
//! one (the planner picks the A-buffer for transparency).

use std::path::{Path, PathBuf};

use glam::DVec3;
use hider_abuffer::{ABufferOptions, SamplePattern, SsaaOptions};
use hider_plan::{HiderConfig, RenderOptions, registry};
use hider_scene::geom::Camera;
use hider_scene::geom::fixed::pixel_center;
use hider_scene::geom::triangle_covers;
use hider_scene::shade::{Prims, ScenePrims, Shader, Stages, TextureSampler, prim_color, to_srgb8};
use hider_scene::{
    Frame, Light, Material, PrepareOptions, Scene, ScreenScene, ShadeMode, View, load_obj, prepare,
};

const SIZE: u32 = 48;

/// Mean absolute difference allowed, in 8-bit sRGB levels per channel.
const MEAN_LEVELS: f64 = 0.25;
/// Largest difference allowed on any channel of any pixel.
const WORST_LEVELS: u8 = 3;
/// The same for `abuffer-carpenter`, whose blender estimates where two
/// fragments overlapping in depth cross from their zmin and zmax
/// (Carpenter's paper) instead of ordering every sample: translucent
/// fragments of one plane that share a pixel are blended approximately.
const CARPENTER_WORST_LEVELS: u8 = 12;

fn assets() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets")
}

/// The bundled checkerboard plane (texture), with a unit cube behind it.
fn textured_plane_over_cube() -> Scene {
    let mut scene = load_obj(assets().join("checker_plane.obj")).unwrap();
    let material = scene.materials.len();
    scene.materials.push(Material {
        name: "orange".into(),
        diffuse: [0.9, 0.4, 0.1],
        ..Material::default()
    });
    let mut cube = hider_scene::procedural::cube();
    for p in &mut cube.meshes[0].positions {
        *p = *p * 0.5 + DVec3::new(0.0, -0.6, -0.4);
    }
    cube.meshes[0].material = Some(material);
    scene.meshes.push(cube.meshes.remove(0));
    // From above, so the plane fills much of the image (the fit camera sees
    // it at a grazing angle).
    scene.camera = Some(Camera::perspective(
        DVec3::new(0.3, 1.8, 1.5),
        DVec3::new(0.0, -0.3, 0.0),
        0.1,
        10.0,
    ));
    scene
}

fn with_light(mut scene: Scene) -> Scene {
    scene.lights.push(Light::Directional {
        direction: DVec3::new(-1.0, -2.0, -0.5),
        color: [0.9, 0.85, 0.8],
    });
    scene
}

fn translucent(mut scene: Scene) -> Scene {
    // The plane's material only: the cube behind stays opaque.
    scene.materials[0].opacity = 0.6;
    scene
}

fn untextured(mut scene: Scene) -> Scene {
    for m in &mut scene.materials {
        m.diffuse_texture = None;
    }
    scene
}

/// A UV sphere of `n` segments with outward vertex normals (smooth
/// shading), under `material`.
fn smooth_sphere(n: u32, material: Material) -> Scene {
    let mut scene = hider_scene::procedural::uv_sphere(n);
    let mesh = &mut scene.meshes[0];
    mesh.normals = mesh
        .positions
        .iter()
        .map(|p| p.normalize().as_vec3())
        .collect();
    scene.materials = vec![material];
    mesh.material = Some(0);
    scene
}

/// The same sphere with a colour per vertex (from its position).
fn coloured_sphere() -> Scene {
    let mut scene = hider_scene::procedural::uv_sphere(16);
    let mesh = &mut scene.meshes[0];
    mesh.colors = mesh
        .positions
        .iter()
        .map(|p| [(0.5 + 0.5 * p.x) as f32, (0.5 + 0.5 * p.y) as f32, 0.3])
        .collect();
    scene
}

/// Every effect of the materials and meshes off: flat, unlit, untextured,
/// opaque, no vertex attributes, no emission or highlights.
fn plain(scene: &Scene) -> Scene {
    let mut plain = untextured(scene.clone());
    plain.lights.clear();
    for m in &mut plain.materials {
        m.opacity = 1.0;
        m.emission = [0.0; 3];
        m.specular = [0.0; 3];
        m.ambient = None;
    }
    for mesh in &mut plain.meshes {
        mesh.normals.clear();
        mesh.colors.clear();
    }
    plain
}

/// The effect x scene matrix: name, scene, whether it is translucent.
fn scenes() -> Vec<(&'static str, Scene, bool)> {
    let plane = textured_plane_over_cube();
    let mut lit_cube = with_light(hider_scene::procedural::cube());
    lit_cube.materials[0].diffuse = [0.3, 0.7, 0.9];
    let mut glass = hider_scene::procedural::cube();
    glass.materials[0].opacity = 0.5;
    vec![
        ("texture", plane.clone(), false),
        ("lighting", lit_cube, false),
        ("transparency", glass, true),
        ("texture+lighting", with_light(plane.clone()), false),
        ("texture+transparency", translucent(plane.clone()), true),
        ("all three", with_light(translucent(plane)), true),
        (
            "smooth (vn)",
            // Coarse, so that smooth and faceted differ by far.
            with_light(smooth_sphere(
                6,
                Material {
                    diffuse: [0.2, 0.6, 0.9],
                    ..Material::default()
                },
            )),
            false,
        ),
        (
            "highlights (Ks, Ns)",
            smooth_sphere(
                16,
                Material {
                    diffuse: [0.5, 0.2, 0.2],
                    // A broad highlight, so that it moves the mean by far.
                    specular: [0.8, 0.8, 0.8],
                    shininess: 4.0,
                    ..Material::default()
                },
            ),
            false,
        ),
        (
            "emission (Ke) + ambient (Ka)",
            smooth_sphere(
                16,
                Material {
                    diffuse: [0.1, 0.1, 0.1],
                    ambient: Some([1.0, 1.0, 0.0]),
                    emission: [0.0, 0.5, 0.9],
                    ..Material::default()
                },
            ),
            false,
        ),
        ("vertex colours", coloured_sphere(), false),
    ]
}

fn screen(scene: &Scene) -> ScreenScene {
    let view = View::for_scene(scene, SIZE, SIZE).unwrap();
    prepare(scene, &view, &PrepareOptions::default()).unwrap()
}

/// [`screen`], for the reference (textures decode on first use).
fn textured_screen(scene: &Scene) -> ScreenScene {
    screen(scene)
}

/// Where a surface's texture is looked up for a sample.
#[derive(Clone, Copy, PartialEq)]
enum Rate {
    /// At the sample (supersampling).
    PerSample,
    /// At the pixel centre, once per surface and pixel (the A-buffer and
    /// anti-aliased Warnock, as multisample rasterisers shade).
    PerPixel,
}

/// How `hider` shades textures.
fn rate_of(name: &str) -> Rate {
    if name.starts_with("ssaa") {
        Rate::PerSample
    } else {
        Rate::PerPixel
    }
}

/// A `side x side` grid of sample positions, in 1/256 pixel from the
/// pixel's top-left corner.
fn grid(side: i32) -> Vec<(i32, i32)> {
    let at = |a: i32| (2 * a + 1) * 128 / side;
    (0..side)
        .flat_map(|b| (0..side).map(move |a| (at(a), at(b))))
        .collect()
}

/// The sample positions `hider` uses (1/256 pixel from the pixel's corner),
/// so the reference differs from it only in how colour is composited.
fn samples_of(name: &str) -> Vec<(i32, i32)> {
    let pattern = match name {
        "ssaa-4" => SamplePattern::Grid4,
        "ssaa-8" => SamplePattern::Grid8,
        "ssaa-16" => SamplePattern::Grid16,
        "ssaa-32" | "ssaa-sorted" => SsaaOptions::default().pattern,
        "abuffer" | "abuffer-carpenter" => ABufferOptions::default().pattern,
        "warnock-4x4" => return grid(4),
        _ => return grid(1),
    };
    pattern.positions().to_vec()
}

/// Colour at the given sample positions, composited exactly, averaged per
/// pixel.
fn reference(screen: &ScreenScene, samples: &[(i32, i32)], rate: Rate) -> Vec<[u8; 4]> {
    let (w, h) = (screen.viewport.width, screen.viewport.height);
    let mut out = Vec::with_capacity((w * h) as usize);
    let mut hits: Vec<(f64, u32)> = Vec::new();
    let sampler = TextureSampler::new(screen, Default::default());
    for j in 0..h {
        for i in 0..w {
            let mut sum = [0.0f64; 3];
            for &(sx, sy) in samples {
                {
                    let (ox, oy) = (i64::from(sx) - 128, i64::from(sy) - 128);
                    let px = i64::from(pixel_center(i as i32)) + ox;
                    let py = i64::from(pixel_center(j as i32)) + oy;
                    let x = f64::from(i) + 0.5 + ox as f64 / 256.0;
                    let y = f64::from(j) + 0.5 + oy as f64 / 256.0;
                    hits.clear();
                    hits.extend(
                        screen
                            .tris
                            .iter()
                            .filter(|t| triangle_covers(&t.v, px, py))
                            .map(|t| (t.depth.eval(x, y), t.prim)),
                    );
                    hits.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                    let mut transmitted = 1.0f64;
                    for &(_, prim) in &hits {
                        let (rgb, alpha) = prim_color(screen, prim, ShadeMode::Lambert);
                        let rgb = match rate {
                            Rate::PerSample => screen.surface_rgb(&sampler, prim, rgb, x, y),
                            Rate::PerPixel => screen.surface_rgb(
                                &sampler,
                                prim,
                                rgb,
                                f64::from(i) + 0.5,
                                f64::from(j) + 0.5,
                            ),
                        };
                        let alpha = f64::from(alpha.clamp(0.0, 1.0));
                        for k in 0..3 {
                            sum[k] += transmitted * alpha * f64::from(rgb[k]);
                        }
                        transmitted *= 1.0 - alpha;
                        if transmitted <= 0.0 {
                            break;
                        }
                    }
                }
            }
            let n = samples.len() as f64;
            let c = sum.map(|s| to_srgb8((s / n) as f32));
            out.push([c[0], c[1], c[2], 255]);
        }
    }
    out
}

/// Mean absolute difference per channel, and the largest, in 8-bit levels.
fn difference(a: &[[u8; 4]], b: &[[u8; 4]]) -> (f64, u8) {
    let mut total = 0u64;
    let mut worst = 0u8;
    for (p, q) in a.iter().zip(b) {
        for k in 0..3 {
            let d = p[k].abs_diff(q[k]);
            total += u64::from(d);
            worst = worst.max(d);
        }
    }
    (total as f64 / (3 * a.len()) as f64, worst)
}

/// The bound every hider meets against the reference at its own samples.
fn check(effect: &str, hider: &str, got: &[[u8; 4]], expected: &[[u8; 4]]) {
    let (mean, worst) = difference(got, expected);
    eprintln!("{effect:22} {hider:18} mean {mean:.3} worst {worst}");
    let allowed = if hider == "abuffer-carpenter" {
        CARPENTER_WORST_LEVELS
    } else {
        WORST_LEVELS
    };
    assert!(
        mean <= MEAN_LEVELS && worst <= allowed,
        "{effect}: {hider} differs from the reference by {mean:.2} levels on average, {worst} at worst"
    );
}

/// Renders `scene` with `hider` as `hider render` does: one call of the
/// hider's own pipeline (`render_scene`), then, unless the hider resolved
/// colour itself, the colour pass over the ids with the stages the scene
/// calls for, reading the primitives from the world-space scene.
fn render(hider: &mut dyn hider_scene::DynHider, scene: &Scene, stages: &Stages) -> Vec<[u8; 4]> {
    let view = View::for_scene(scene, SIZE, SIZE).unwrap();
    let mut screen = ScreenScene::empty(&view);
    let mut frame = Frame::new(SIZE, SIZE).unwrap();
    hider
        .render_scene(
            scene,
            &view,
            &PrepareOptions::default(),
            &mut screen,
            &mut frame,
        )
        .unwrap();
    if !hider.resolves_color() {
        let prims = ScenePrims::new(scene, &view).unwrap();
        let trace = Shader::default().shade(Prims::Scene(&prims), &mut frame, stages);
        assert!(
            trace.texture_failures.is_empty(),
            "{:?}",
            trace.texture_failures
        );
    }
    frame.color
}

/// The anti-aliasing hiders that draw translucent surfaces opaque (they
/// keep one surface per sample): compared on opaque scenes only.
const OPAQUE_ONLY: &[&str] = &["ssaa-4", "ssaa-8", "ssaa-16", "ssaa-32", "warnock-4x4"];

#[test]
fn every_colour_resolving_hider_applies_the_stages_the_scene_calls_for() {
    let config = HiderConfig::default();
    let mut checked = 0;
    for (effect, scene, see_through) in scenes() {
        let stages = Stages::for_scene(&scene, true);
        let shaded = textured_screen(&scene);
        // Without its effects the image must miss the bound by far, or the
        // comparison could not tell.
        let flat = reference(&textured_screen(&plain(&scene)), &grid(8), Rate::PerSample);
        let fine = reference(&shaded, &grid(8), Rate::PerSample);
        let (miss, _) = difference(&flat, &fine);
        assert!(
            miss > 4.0,
            "{effect}: the effect changes the image by only {miss:.2} levels"
        );
        for entry in registry::all() {
            let mut hider = entry.build(&config).unwrap();
            if !hider.resolves_color() || (see_through && OPAQUE_ONLY.contains(&entry.name)) {
                continue;
            }
            let got = render(hider.as_mut(), &scene, &stages);
            let expected = reference(&shaded, &samples_of(entry.name), rate_of(entry.name));
            check(effect, entry.name, &got, &expected);
            checked += 1;
        }
    }
    assert!(checked >= 60, "only {checked} hider x effect pairs checked");
}

#[test]
fn the_planners_choice_applies_the_stages_the_scene_calls_for() {
    for (effect, scene, _) in scenes() {
        let options = RenderOptions::default().with_size(SIZE, SIZE);
        let planned = hider_plan::auto(&scene, &options).unwrap();
        let mut hider = planned.plan.build(&HiderConfig::default()).unwrap();
        let stages = planned.plan.stages;
        assert_eq!(
            stages,
            Stages::for_scene(&scene, true),
            "{effect}: the analysis and the quick look disagree"
        );
        let got = render(hider.as_mut(), &scene, &stages);
        let algo = planned.plan.algo;
        let expected = reference(&textured_screen(&scene), &samples_of(algo), rate_of(algo));
        check(effect, algo, &got, &expected);
    }
}
