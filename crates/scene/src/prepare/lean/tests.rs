//! The lean front end against `prepare`: the same triangles in the same
//! order, the same counts and the same colours, with clipping, culling,
//! both precisions, a small guard band and in parallel.

use glam::DVec3;
use hider_geom::Camera;

use super::*;
use crate::model::{Light, Mesh};
use crate::prepare::{PrepareOptions, TransformPrecision, prepare};
use crate::procedural;
use crate::shade::{ShadeMode, prim_color};
use crate::view::View;

/// Asserts that the lean front end gives `prepare`'s triangles, counts and
/// colours for `scene` seen by `view` with `options`.
fn check(scene: &Scene, view: &View, options: &PrepareOptions) {
    let full = prepare(scene, view, options).unwrap();
    let mut lean = LeanScene::new();
    // Twice into the same scene: memory reuse changes nothing.
    for _ in 0..2 {
        prepare_lean_into(scene, view, options, &mut lean).unwrap();
        let want: Vec<LeanTri> = full.tris.iter().map(LeanTri::from).collect();
        assert_eq!(lean.tris().len(), want.len());
        assert!(lean.tris() == want.as_slice(), "triangles differ");
        assert_eq!(lean.stats, full.stats);
        assert_eq!(lean.viewport, full.viewport);
    }
    for prim in 0..scene.triangle_count() as u32 {
        for mode in [ShadeMode::Lambert, ShadeMode::Ids] {
            let (a, b) = (
                lean.prim_color(scene, prim, mode),
                prim_color(&full, prim, mode),
            );
            assert_eq!(a.0.map(f32::to_bits), b.0.map(f32::to_bits), "prim {prim}");
            assert_eq!(a.1.to_bits(), b.1.to_bits());
        }
        assert_eq!(
            lean.material_index(scene, prim),
            full.prims[prim as usize].material
        );
    }
}

/// Cameras that see the scene whole, from inside it (the near plane and
/// the guard band cut triangles) and from beside it.
fn views(scene: &Scene) -> Vec<View> {
    let inside = Camera::perspective(
        DVec3::new(0.1, 0.2, 0.3),
        DVec3::new(0.0, 0.0, -1.0),
        0.05,
        3.0,
    );
    let beside = Camera::perspective(DVec3::new(3.0, 0.5, 0.4), DVec3::ZERO, 2.0, 3.5);
    vec![
        View::for_scene(scene, 97, 61).unwrap(),
        View::new(inside, 80, 80).unwrap(),
        View::new(beside, 64, 40).unwrap(),
    ]
}

#[test]
fn lean_front_end_is_prepare_bit_for_bit() {
    let mut lit = procedural::uv_sphere(20);
    lit.lights.push(Light::Point {
        position: DVec3::new(2.0, 3.0, 4.0),
        color: [0.9, 0.8, 0.7],
    });
    lit.lights.push(Light::Directional {
        direction: DVec3::new(-1.0, -0.5, -0.2),
        color: [0.3, 0.3, 0.4],
    });
    // A second mesh with no material and an empty mesh between.
    let mut two = procedural::random_soup(300, 5);
    two.push_mesh(Mesh::default(), None);
    let cube = procedural::cube();
    two.push_mesh(
        Mesh {
            positions: cube.meshes[0].positions.clone(),
            indices: cube.meshes[0].indices.clone(),
            ..Mesh::default()
        },
        None,
    );
    let scenes = [
        lit,
        two,
        procedural::random_soup(1500, 11),
        procedural::intersecting_pair(),
        procedural::cyclic_triple(),
    ];
    for scene in &scenes {
        for view in views(scene) {
            for precision in [TransformPrecision::F64, TransformPrecision::F32] {
                for cull in [false, true] {
                    let options = PrepareOptions::default()
                        .with_precision(precision)
                        .with_cull_back_faces(cull);
                    check(scene, &view, &options);
                    check(scene, &view, &options.with_guard_band_pixels(4));
                }
            }
        }
    }
}

#[cfg(feature = "parallel")]
#[test]
fn lean_front_end_in_parallel_is_prepare() {
    // Above the size where both front ends split the work.
    let scene = procedural::random_soup(40_000, 3);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(3)
        .build()
        .unwrap();
    pool.install(|| {
        for view in views(&scene) {
            check(
                &scene,
                &view,
                &PrepareOptions::default().with_parallel(true),
            );
        }
    });
}

/// A sink of the lean front end's own (here, the triangles as they come):
/// a run of sinks takes `prepare`'s triangles in order, one contiguous
/// run of primitive ids per sink, each sink told the frame's viewport
/// first; the lean scene keeps the counters and colours and no triangle.
#[cfg(feature = "parallel")]
#[derive(Default)]
struct Counted {
    tris: Vec<LeanTri>,
    begun: Option<(u32, u32)>,
}

#[cfg(feature = "parallel")]
impl LeanSink for Counted {
    fn clear(&mut self) {
        self.tris.clear();
    }

    fn push(&mut self, tri: LeanTri) {
        assert!(self.begun.is_some(), "a triangle before the frame began");
        self.tris.push(tri);
    }

    fn len(&self) -> usize {
        self.tris.len()
    }
}

#[cfg(feature = "parallel")]
#[test]
fn sinks_take_prepares_triangles_in_runs() {
    let scene = procedural::random_soup(40_000, 8);
    let view = View::for_scene(&scene, 120, 90).unwrap();
    let full = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
    let want: Vec<LeanTri> = full.tris.iter().map(LeanTri::from).collect();
    let mut lean = LeanScene::new();
    let mut sinks: Vec<Counted> = Vec::new();
    for threads in [1, 3, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let options = PrepareOptions::default().with_parallel(true);
        pool.install(|| {
            prepare_lean_sinks(
                &scene,
                &view,
                &options,
                &mut lean,
                &mut sinks,
                |front, s| {
                    s.begun = Some((front.viewport.width, front.viewport.height));
                },
            )
        })
        .unwrap();
        assert_eq!(sinks.len(), threads, "one sink per run");
        assert!(sinks.iter().all(|s| s.begun == Some((120, 90))));
        let got: Vec<LeanTri> = sinks.iter().flat_map(|s| s.tris.clone()).collect();
        assert!(got == want, "{threads} runs: the triangles differ");
        assert!(lean.tris().is_empty(), "{threads} runs: triangles kept");
        assert_eq!(lean.stats, full.stats, "{threads} runs");
        assert_eq!(
            lean.prim_color(&scene, 77, ShadeMode::Lambert),
            prim_color(&full, 77, ShadeMode::Lambert),
            "{threads} runs"
        );
    }
}

/// One lean scene reused across frames that split the work differently
/// (serial, 2 and 3 runs, a small scene that does not split), with a
/// failed frame between them, gives `prepare`'s triangles every time: the
/// output trades buffers with the first run, and the runs change in number.
#[cfg(feature = "parallel")]
#[test]
fn a_reused_lean_scene_follows_every_split() {
    let big = procedural::random_soup(40_000, 5);
    let small = procedural::cube();
    let mut broken = procedural::cube();
    broken.meshes[0].indices[3][1] = 99;
    let pools: Vec<rayon::ThreadPool> = [2, 3]
        .map(|n| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap()
        })
        .into();
    let mut lean = LeanScene::new();
    let mut frame = |scene: &Scene, pool: Option<&rayon::ThreadPool>, parallel: bool| {
        // The broken cube has no bounds: it is seen as the cube is.
        let framed = if std::ptr::eq(scene, &broken) {
            &small
        } else {
            scene
        };
        let view = View::for_scene(framed, 97, 61).unwrap();
        let options = PrepareOptions::default().with_parallel(parallel);
        let run = |lean: &mut LeanScene| prepare_lean_into(scene, &view, &options, lean);
        let result = match pool {
            Some(pool) => pool.install(|| run(&mut lean)),
            None => run(&mut lean),
        };
        if result.is_ok() {
            let want: Vec<LeanTri> = prepare(scene, &view, &options)
                .unwrap()
                .tris
                .iter()
                .map(LeanTri::from)
                .collect();
            assert!(lean.tris() == want.as_slice(), "triangles differ");
        }
        result
    };
    let (two, three) = (Some(&pools[0]), Some(&pools[1]));
    for (scene, pool, parallel) in [
        (&big, two, true),
        (&big, two, true),
        (&big, None, false),
        (&big, three, true),
        (&small, three, true),
        (&big, two, true),
        (&big, three, false),
        (&big, three, true),
    ] {
        frame(scene, pool, parallel).unwrap();
        // A failed frame in between changes nothing that follows.
        assert!(frame(&broken, pool, parallel).is_err());
    }
}

#[test]
fn bad_input_is_an_error_naming_it() {
    let mut scene = procedural::cube();
    scene.meshes[0].indices[3][1] = 99;
    let view = View::for_scene(&procedural::cube(), 32, 32).unwrap();
    let mut lean = LeanScene::new();
    let e = prepare_lean_into(&scene, &view, &PrepareOptions::default(), &mut lean).unwrap_err();
    assert_eq!(
        e.to_string(),
        prepare(&scene, &view, &PrepareOptions::default())
            .unwrap_err()
            .to_string()
    );
    let mut scene = procedural::cube();
    scene.meshes[0].positions[2].y = f64::NAN;
    let e = prepare_lean_into(&scene, &view, &PrepareOptions::default(), &mut lean).unwrap_err();
    assert!(e.to_string().contains("mesh"), "{e}");
}
