//! The lean front end ([`prepare_depth_into`]) against its brute-force
//! definition over the shared front end's triangles: the same triangles
//! and pixel fragments, bit for bit and in order, and the same counters,
//! on random scenes in both precisions, with clipping and culling, serial
//! and parallel.

use glam::DVec3;
use hider_geom::{Camera, Viewport};
use hider_scene::{PrepareOptions, Scene, TransformPrecision, View, prepare, procedural};
use hider_testkit::lean_reference;
use hider_zbuffer::{DepthFragment, DepthScene, DepthTri, prepare_depth_into};
use proptest::prelude::*;

fn scene_of(points: &[(f64, f64, f64)], shared: bool) -> Scene {
    let positions: Vec<DVec3> = points
        .iter()
        .map(|&(x, y, z)| DVec3::new(x, y, z))
        .collect();
    let n = positions.len() as u32;
    let indices = if shared {
        // A strip: neighbouring triangles share vertices, as meshes do.
        (0..n.saturating_sub(2))
            .map(|i| [i, i + 1, i + 2])
            .collect()
    } else {
        (0..n / 3).map(|i| [3 * i, 3 * i + 1, 3 * i + 2]).collect()
    };
    Scene::from_mesh(positions, indices)
}

fn view(size: u32, near: f64) -> View {
    View {
        viewport: Viewport::new(size, size),
        camera: Camera::perspective(DVec3::new(0.0, 0.0, 3.0), DVec3::ZERO, near, 6.0),
    }
}

fn check(scene: &Scene, view: &View, options: &PrepareOptions) {
    let full = prepare(scene, view, options).unwrap();
    let (want, want_fragments) = lean_reference(&full);
    let mut lean = DepthScene::new();
    prepare_depth_into(scene, view, options, &mut lean).unwrap();
    let got: Vec<DepthTri> = lean.tris().copied().collect();
    assert_eq!(got, want);
    let got_fragments: Vec<DepthFragment> = lean.fragments().flatten().copied().collect();
    assert_eq!(got_fragments, want_fragments);
    let s = lean.stats;
    assert_eq!(s.input, full.stats.input);
    assert_eq!(s.culled, full.stats.culled);
    assert_eq!(s.clipped, full.stats.clipped);
    assert_eq!(s.degenerate, full.stats.degenerate);
    assert_eq!(s.back_faces, full.stats.back_faces);
    assert_eq!(s.output + s.empty + s.fragmented, full.stats.output);
}

proptest! {
    /// Random triangles around and through the view volume (behind the
    /// eye, across the near plane, beyond the far plane, far outside the
    /// image), both precisions, with and without back-face culling.
    #[test]
    fn lean_equals_prepare(
        points in prop::collection::vec(
            (-4.0f64..4.0, -4.0f64..4.0, -6.0f64..5.0), 3..60),
        shared in any::<bool>(),
        f32_precision in any::<bool>(),
        cull in any::<bool>(),
        size in 1u32..96,
        near in prop::sample::select(vec![0.05, 0.5, 2.0]),
    ) {
        let scene = scene_of(&points, shared);
        let precision = if f32_precision { TransformPrecision::F32 } else { TransformPrecision::F64 };
        let options = PrepareOptions::default()
            .with_precision(precision)
            .with_cull_back_faces(cull);
        check(&scene, &view(size, near), &options);
    }
}

#[test]
fn parallel_runs_concatenate_to_the_serial_result() {
    let scene = procedural::uv_sphere(140);
    // Above the lean front end's parallel threshold (32k triangles).
    assert!(scene.triangle_count() >= 32 * 1024);
    let v = View::for_scene(&scene, 300, 300).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(3)
        .build()
        .unwrap();
    let mut serial = DepthScene::new();
    prepare_depth_into(&scene, &v, &PrepareOptions::default(), &mut serial).unwrap();
    let mut parallel = DepthScene::new();
    pool.install(|| {
        prepare_depth_into(
            &scene,
            &v,
            &PrepareOptions::default().with_parallel(true),
            &mut parallel,
        )
    })
    .unwrap();
    assert_eq!(parallel.parts().len(), 3);
    assert_eq!(serial.parts().len(), 1);
    assert!(parallel.tris().eq(serial.tris()));
    assert!(
        parallel
            .fragments()
            .flatten()
            .eq(serial.fragments().flatten())
    );
    assert_eq!(parallel.stats, serial.stats);
    // The dense sphere has triangles of every kind.
    let s = serial.stats;
    assert!(s.output > 0 && s.empty > 0 && s.fragmented > 0, "{s:?}");
    check(&scene, &v, &PrepareOptions::default());
}

#[test]
fn several_meshes_and_reuse() {
    let mut scene = procedural::uv_sphere(12);
    let cube = procedural::cube();
    for mut m in cube.meshes {
        m.material = None;
        scene.push_mesh(m, None);
    }
    let v = View::for_scene(&scene, 64, 64).unwrap();
    check(&scene, &v, &PrepareOptions::default());
    // Reusing the buffers for a smaller scene leaves nothing stale.
    let mut lean = DepthScene::new();
    prepare_depth_into(&scene, &v, &PrepareOptions::default(), &mut lean).unwrap();
    let small = procedural::cube();
    prepare_depth_into(&small, &v, &PrepareOptions::default(), &mut lean).unwrap();
    let want = prepare(&small, &v, &PrepareOptions::default()).unwrap();
    let s = lean.stats;
    assert_eq!(
        lean.len() as u64,
        want.tris.len() as u64 - s.empty - s.fragmented
    );
}

#[test]
fn clipped_culled_and_empty_triangles_are_counted() {
    let scene = scene_of(
        &[
            // Across the near plane (eye at z = 3, near 0.5): clipped.
            (-1.0, -1.0, 0.0),
            (1.0, -1.0, 0.0),
            (0.0, 1.0, 5.0),
            // Behind the eye: culled.
            (-1.0, 0.0, 4.0),
            (1.0, 0.0, 4.0),
            (0.0, 1.0, 4.0),
            // Tiny, between pixel centres: empty.
            (0.01, 0.01, 0.0),
            (0.06, 0.01, 0.0),
            (0.01, 0.06, 0.0),
        ],
        false,
    );
    let v = view(8, 0.5);
    let mut lean = DepthScene::new();
    prepare_depth_into(&scene, &v, &PrepareOptions::default(), &mut lean).unwrap();
    assert_eq!(lean.stats.clipped, 1);
    assert_eq!(lean.stats.culled, 1);
    assert_eq!(lean.stats.empty, 1);
    assert!(!lean.is_empty());
    check(&scene, &v, &PrepareOptions::default());
}

#[test]
fn bad_input_is_an_error() {
    let mut scene = scene_of(
        &[(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (f64::NAN, 1.0, 0.0)],
        false,
    );
    let v = view(16, 0.5);
    let mut lean = DepthScene::new();
    assert!(prepare_depth_into(&scene, &v, &PrepareOptions::default(), &mut lean).is_err());
    scene.meshes[0].positions[2] = DVec3::Y;
    let mut bad = v;
    bad.viewport = Viewport::new(0, 16);
    assert!(prepare_depth_into(&scene, &bad, &PrepareOptions::default(), &mut lean).is_err());
}
