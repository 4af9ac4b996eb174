//! The lean front end changes nothing: rendering from the world-space
//! scene (`Hider::render_scene`, the lean front end) gives the frame, the
//! sample ids and the work counters of rendering `prepare`'s output
//! (`Hider::render`), bit for bit, on every hard case and on random soups
//! (opaque and translucent, every depth mode, lit or false-coloured), at 1
//! and several threads; through it the A-buffer still equals the 32-sample
//! supersampled z-buffer sample for sample, and the three translucent
//! triangles composite to the same image in all 6 orders.

use glam::DVec3;
use hider_abuffer::{ABuffer, ABufferOptions, ABufferStats, DepthMode, MergePolicy, SsaaOptions};
use hider_scene::prepare::lean::{LeanScene, LeanTri, prepare_lean_into};
use hider_scene::{
    Frame, Hider, Light, PrepareOptions, Scene, ScreenScene, ShadeMode, TransformPrecision, View,
    procedural,
};
use hider_testkit::front_end_input::{case_from_floats, soup_from_floats};
use hider_testkit::{hard_cases, render, screen};
use proptest::prelude::*;

use crate::common::{
    DEPTH_MODES, assert_same_render, equals_supersampling, max_color_diff, soup, three_glass,
    with_opacity,
};

/// Frame sizes: several bands, fewer bands than threads, partial tiles.
const SIZES: [(u32, u32); 3] = [(200, 330), (150, 90), (70, 20)];

/// Renders `scene` at `w x h` through the lean front end with `hider`.
pub fn render_lean(hider: &mut ABuffer, scene: &Scene, w: u32, h: u32) -> (Frame, ABufferStats) {
    let view = View::for_scene(scene, w, h).unwrap();
    let mut unused = ScreenScene::empty(&view);
    let mut frame = Frame::new(w, h).unwrap();
    let stats = hider
        .render_scene(
            scene,
            &view,
            &PrepareOptions::default(),
            &mut unused,
            &mut frame,
        )
        .unwrap();
    // The lean path leaves the caller's prepared scene alone.
    assert!(unused.tris.is_empty());
    (frame, stats)
}

/// Asserts that the lean front end and `prepare` give the same frames,
/// sample ids and counters for `scene` at every size, with 1 and 3
/// threads, twice on the same hider.
pub fn lean_is_prepared(scene: &Scene, options: ABufferOptions, what: &str) {
    for (w, h) in SIZES {
        let s = screen(scene, w, h);
        for threads in [1, 3] {
            let options = options.with_threads(threads);
            let mut full = ABuffer::new(options);
            let (f1, s1) = render(&mut full, &s);
            let ids1 = full.sample_ids();
            let mut lean = ABuffer::new(options);
            for round in 0..2 {
                let (f2, s2) = render_lean(&mut lean, scene, w, h);
                let at = format!("{what} at {w}x{h}, {threads} threads, round {round}");
                assert_same_render(&at, (&f1, &ids1, &s1), (&f2, &lean.sample_ids(), &s2));
            }
        }
    }
}

#[test]
fn every_hard_case_is_the_same_through_the_lean_front_end() {
    for (name, scene) in hard_cases::all(11) {
        lean_is_prepared(&scene, ABufferOptions::default(), name);
        lean_is_prepared(&scene, ABufferOptions::carpenter(), name);
    }
}

#[test]
fn lights_and_false_colours_are_the_same_through_the_lean_front_end() {
    let mut scene = procedural::uv_sphere(30);
    scene.lights.push(Light::Point {
        position: DVec3::new(2.0, 3.0, 4.0),
        color: [0.9, 0.8, 0.7],
    });
    scene.lights.push(Light::Directional {
        direction: DVec3::new(-1.0, -0.5, -0.2),
        color: [0.3, 0.3, 0.4],
    });
    lean_is_prepared(&scene, ABufferOptions::default(), "lit sphere");
    let ids = ABufferOptions::default().with_shade(ShadeMode::Ids);
    lean_is_prepared(&with_opacity(scene, 0.6), ids, "translucent sphere, ids");
}

#[test]
fn six_orders_of_glass_are_one_image_through_the_lean_front_end() {
    let orders = [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ];
    for depth in [DepthMode::PerSample, DepthMode::MinMax] {
        let options = ABufferOptions::default().with_depth(depth);
        let mut first: Option<Frame> = None;
        for order in orders {
            let scene = three_glass(order);
            lean_is_prepared(&scene, options, "three glass");
            let (frame, _) = render_lean(&mut ABuffer::new(options), &scene, 96, 96);
            match &first {
                None => first = Some(frame),
                Some(f) => assert!(max_color_diff(f, &frame) <= 1, "{depth:?} {order:?}"),
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10))]

    /// Random soups, opaque or translucent, in every depth mode.
    #[test]
    fn soups_are_the_same_through_the_lean_front_end(
        count in 1u32..400,
        seed in any::<u64>(),
        glass in any::<bool>(),
        mode in 0usize..3,
    ) {
        let options = ABufferOptions::default().with_depth(DEPTH_MODES[mode]);
        lean_is_prepared(&soup(count, seed, glass), options, "soup");
    }

    /// Through the lean front end, with several threads, per-sample depth
    /// and merging off, every sample's front-most primitive, the coverage
    /// and the centre ids are the 32-sample supersampled z-buffer's.
    #[test]
    fn lean_abuffer_equals_supersampling(count in 1u32..300, seed in any::<u64>()) {
        let scene = procedural::random_soup(count, seed);
        let s = screen(&scene, 150, 140);
        let mut a = ABuffer::new(
            ABufferOptions::default().with_merge(MergePolicy::Off).with_threads(3),
        );
        let fa = render_lean(&mut a, &scene, 150, 140).0;
        equals_supersampling(&s, SsaaOptions::default(), &a, &fa)?;
    }
}

/// A hider that renders a prepared scene and then the lean path (and
/// back) gives each frame as a fresh hider does.
#[test]
fn switching_paths_on_one_hider_changes_nothing() {
    let a = procedural::random_soup(200, 4);
    let b = with_opacity(procedural::uv_sphere(16), 0.5);
    let mut mixed = ABuffer::new(ABufferOptions::default().with_threads(2));
    for scene in [&a, &b, &a] {
        let s = screen(scene, 120, 100);
        let (want, _) = render(&mut ABuffer::new(ABufferOptions::default()), &s);
        assert!(render(&mut mixed, &s).0 == want);
        assert!(render_lean(&mut mixed, scene, 120, 100).0 == want);
    }
}

/// The transform precision a drawn flag picks.
fn precision(f32_front: bool) -> TransformPrecision {
    if f32_front {
        TransformPrecision::F32
    } else {
        TransformPrecision::F64
    }
}

/// The lean front end refuses what `prepare` refuses (with the same
/// message), and otherwise gives `prepare`'s triangles and counts, and
/// the A-buffer the same frame through both.
fn hostile_case_agrees(scene: &Scene, view: &View, options: &PrepareOptions) -> Result<(), String> {
    let full = hider_scene::prepare(scene, view, options);
    let mut lean = LeanScene::new();
    let lean_ok = prepare_lean_into(scene, view, options, &mut lean);
    let screen = match (full, lean_ok) {
        (Err(a), Err(b)) if a.to_string() == b.to_string() => return Ok(()),
        (Ok(screen), Ok(())) => screen,
        (a, b) => return Err(format!("prepare {:?}, lean {b:?}", a.map(|_| ()))),
    };
    let want: Vec<LeanTri> = screen.tris.iter().map(LeanTri::from).collect();
    if lean.tris() != want.as_slice() || lean.stats != screen.stats {
        return Err(format!(
            "lean {:?} {:?}\nprepare {want:?} {:?}",
            lean.tris(),
            lean.stats,
            screen.stats
        ));
    }
    let (w, h) = (screen.viewport.width, screen.viewport.height);
    let (a, _) = render(&mut ABuffer::new(ABufferOptions::default()), &screen);
    let mut b = Frame::new(w, h).map_err(|e| e.to_string())?;
    let mut unused = ScreenScene::empty(view);
    ABuffer::new(ABufferOptions::default())
        .render_scene(scene, view, options, &mut unused, &mut b)
        .map_err(|e| e.to_string())?;
    if a != b {
        return Err("the A-buffer's frames differ".to_owned());
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// Hostile scenes and cameras (any `f32`: huge, tiny, infinite, NaN;
    /// eyes inside the scene; degenerate cameras, refused by both).
    #[test]
    fn hostile_inputs_agree_through_the_lean_front_end(
        c in proptest::array::uniform13(any::<f32>()),
        corners in proptest::collection::vec(any::<f32>(), 0..45),
        size in (1u32..17, 1u32..17),
        f32_front in any::<bool>(),
    ) {
        if let Some(case) = case_from_floats(&c, &corners, size, precision(f32_front)) {
            let agrees = hostile_case_agrees(&case.scene, &case.view, &case.options);
            prop_assert!(agrees.is_ok(), "{:?}", agrees);
        }
    }

    /// The same with cameras that see the corners: a fit camera on
    /// corners of any magnitude and sign.
    #[test]
    fn hostile_corners_agree_through_the_lean_front_end(
        corners in proptest::collection::vec(-1e30f32..1e30, 9..45),
        scale in -30i32..30,
        size in (1u32..17, 1u32..17),
        f32_front in any::<bool>(),
    ) {
        let corners: Vec<f32> = corners.iter().map(|v| v * 10f32.powi(scale) * 1e-30).collect();
        let options = PrepareOptions::default().with_precision(precision(f32_front));
        let scene = soup_from_floats(&corners);
        if let Ok(view) = View::for_scene(&scene, size.0, size.1) {
            let agrees = hostile_case_agrees(&scene, &view, &options);
            prop_assert!(agrees.is_ok(), "{:?}", agrees);
        }
    }
}

/// The lean front end in parallel runs, each binning its triangles as it
/// sets them up, gives the frames, sample ids and counters of `prepare`'s
/// output rendered on one thread, in pools of 2 and 3 threads (scenes
/// large enough to be split); a scene with a non-finite position fails
/// part way between them and changes nothing after it.
#[test]
fn parallel_runs_bin_as_one_front_end() {
    let sphere = procedural::uv_sphere(130);
    let soup = procedural::random_soup(40_000, 9);
    let mut broken = procedural::random_soup(40_000, 3);
    broken.meshes[0].positions[30_000] = DVec3::new(f64::NAN, 0.0, 0.0);
    assert!(sphere.triangle_count() > 32 * 1024, "large enough to split");
    let (w, h) = (160, 120);
    let options = PrepareOptions::default().with_parallel(true);
    for threads in [2, 3] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let mut hider = ABuffer::new(ABufferOptions::default().with_threads(threads));
        for (k, scene) in [&sphere, &soup, &broken, &sphere].into_iter().enumerate() {
            let view = View::for_scene(scene, w, h).unwrap();
            let mut unused = ScreenScene::empty(&view);
            let mut frame = Frame::new(w, h).unwrap();
            let result = pool
                .install(|| hider.render_scene(scene, &view, &options, &mut unused, &mut frame));
            let at = format!("frame {k}, {threads} threads");
            if k == 2 {
                assert!(result.is_err(), "{at}: the broken scene renders");
                continue;
            }
            let stats = result.unwrap();
            let mut one = ABuffer::new(ABufferOptions::default().with_threads(1));
            let (want, want_stats) = render(&mut one, &screen(scene, w, h));
            assert_same_render(
                &at,
                (&want, &one.sample_ids(), &want_stats),
                (&frame, &hider.sample_ids(), &stats),
            );
        }
    }
}
