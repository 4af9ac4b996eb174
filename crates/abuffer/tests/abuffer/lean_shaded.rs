//! Scenes shaded per point go through the lean front end too, and change
//! nothing there: a textured model (the bundled spider, and the checker
//! plane), a smooth-shaded
//! sphere (vertex normals) and a sphere with vertex colours give the
//! frame, the sample ids and the counters of rendering `prepare`'s output,
//! bit for bit, in every configuration, at 1 and 3 threads. Each render
//! through `render_scene` also checks that the caller's prepared scene
//! was left empty: the lean front end ran, not `prepare`. One hider
//! alternating between such scenes keeps nothing of a frame's primitive
//! data for the next.

use std::path::PathBuf;

use glam::DVec3;
use hider_abuffer::{ABuffer, ABufferOptions, DepthMode};
use hider_scene::prepare::lean::{LeanScene, prepare_lean_into};
use hider_scene::{Hider, PrepareOptions, Scene, View, load_obj, prepare, procedural};

use crate::common::{lists, with_opacity};
use crate::lean::{lean_is_prepared, render_lean};

/// A scene from the repository's `assets/`.
fn asset(path: &str) -> Scene {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets")
        .join(path);
    load_obj(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()))
}

/// A UV sphere with a normal at each vertex (its direction from the
/// centre): smooth shading interpolates them.
fn smooth_sphere(segments: u32) -> Scene {
    let mut scene = procedural::uv_sphere(segments);
    for mesh in &mut scene.meshes {
        mesh.normals = mesh
            .positions
            .iter()
            .map(|p| p.normalize().as_vec3())
            .collect();
    }
    scene
}

/// A UV sphere with a colour at each vertex (from its position).
fn coloured_sphere(segments: u32) -> Scene {
    let mut scene = procedural::uv_sphere(segments);
    for mesh in &mut scene.meshes {
        mesh.colors = mesh
            .positions
            .iter()
            .map(|p| {
                let c = (*p * 0.5 + DVec3::splat(0.5)).as_vec3();
                [c.x, c.y, c.z]
            })
            .collect();
    }
    scene
}

/// The configurations a per-point scene is rendered in.
fn configurations() -> [(ABufferOptions, &'static str); 4] {
    [
        (ABufferOptions::default(), "default"),
        (ABufferOptions::carpenter(), "carpenter"),
        (lists(), "lists"),
        (
            ABufferOptions::default().with_depth(DepthMode::MinMax),
            "min/max",
        ),
    ]
}

#[test]
fn the_textured_spider_is_the_same_through_the_lean_front_end() {
    let spider = asset("spider/spider.obj");
    assert!(spider.is_textured() && spider.varies_per_point());
    for (options, what) in configurations() {
        lean_is_prepared(&spider, options, &format!("spider, {what}"));
    }
}

#[test]
fn the_checker_plane_is_the_same_through_the_lean_front_end() {
    let plane = asset("checker_plane.obj");
    assert!(plane.is_textured());
    lean_is_prepared(&plane, ABufferOptions::default(), "checker plane");
    lean_is_prepared(&with_opacity(plane, 0.5), lists(), "translucent plane");
}

#[test]
fn smooth_and_vertex_coloured_spheres_are_the_same_through_the_lean_front_end() {
    let smooth = smooth_sphere(24);
    let coloured = coloured_sphere(24);
    assert!(smooth.varies_per_point() && coloured.varies_per_point());
    for (options, what) in configurations() {
        lean_is_prepared(&smooth, options, &format!("smooth sphere, {what}"));
        lean_is_prepared(&coloured, options, &format!("coloured sphere, {what}"));
    }
    let glass = with_opacity(smooth_sphere(16), 0.4);
    lean_is_prepared(&glass, ABufferOptions::default(), "smooth glass");
}

/// The lean front end's per-primitive data is `prepare`'s, bit for bit,
/// whether it keeps per-vertex attributes (point shading asked for, on
/// one thread or in parallel runs) or transforms per corner; a flat
/// scene keeps none even when asked.
#[test]
fn lean_primitive_data_is_prepares() {
    // Meshes with uvs and materials, with normals (enough vertices for
    // the attributes to be transformed in parallel), and with colours.
    let mut scene = asset("spider/spider.obj");
    scene.meshes.push(smooth_sphere(200).meshes.remove(0));
    scene.meshes.push(coloured_sphere(8).meshes.remove(0));
    assert!(scene.meshes[scene.meshes.len() - 2].positions.len() > 32 * 1024);
    let view = View::for_scene(&scene, 64, 48).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    for (shading, parallel) in [(true, false), (true, true), (false, false)] {
        let options = PrepareOptions::default().with_parallel(parallel);
        let screen = prepare(&scene, &view, &options).unwrap();
        let mut lean = LeanScene::new();
        lean.set_point_shading(shading);
        pool.install(|| prepare_lean_into(&scene, &view, &options, &mut lean))
            .unwrap();
        assert_eq!(lean.shades_per_point(), shading);
        for prim in 0..scene.triangle_count() as u32 {
            assert!(
                lean.prim_info(&scene, prim) == screen.prims[prim as usize],
                "{prim}"
            );
        }
    }
    let mut lean = LeanScene::new();
    lean.set_point_shading(true);
    let flat = procedural::uv_sphere(12);
    let view = View::for_scene(&flat, 32, 32).unwrap();
    prepare_lean_into(&flat, &view, &PrepareOptions::default(), &mut lean).unwrap();
    assert!(!flat.varies_per_point() && !lean.shades_per_point());
}

/// One hider alternating between per-point scenes (their primitive ids
/// overlap) gives each frame as a fresh hider does: nothing of one
/// frame's primitive data is read in the next.
#[test]
fn alternating_shaded_scenes_on_one_hider_changes_nothing() {
    let scenes = [
        asset("spider/spider.obj"),
        smooth_sphere(20),
        coloured_sphere(14),
    ];
    let (w, h) = (120, 90);
    let mut mixed = ABuffer::new(ABufferOptions::default().with_threads(2));
    for k in [0, 1, 2, 0, 2, 1] {
        let scene = &scenes[k];
        let (want, _) = render_lean(&mut ABuffer::new(ABufferOptions::default()), scene, w, h);
        assert!(render_lean(&mut mixed, scene, w, h).0 == want, "scene {k}");
    }
}
