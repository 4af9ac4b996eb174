//! The tiled z-buffer against the reference z-buffer: every pixel's id and
//! depth bits, on random soups, spheres, the hard-case generators and odd
//! image sizes, for every depth format, thread count and tile size.

use glam::DVec3;
use hider_geom::{Camera, Projection};
use hider_scene::{
    Frame, Hider, NO_ID, PrepareOptions, Scene, ScreenScene, View, prepare, procedural,
};
use proptest::prelude::*;

use crate::{
    DepthFormat, DepthScene, TiledZBuffer, TiledZBufferOptions, ZBuffer, ZBufferOptions,
    ZBufferStats, prepare_depth_into,
};

fn fit(scene: &Scene, w: u32, h: u32) -> ScreenScene {
    hider_testkit::screen(scene, w, h)
}

/// A camera inside the soup's cube: triangles crossing the near plane,
/// behind the eye, and huge on screen.
fn inside(scene: &Scene, w: u32, h: u32, yaw: f64) -> ScreenScene {
    hider_testkit::screen_with(scene, inside_camera(yaw), w, h)
}

/// The camera inside the soup's cube, turned by `yaw` (radians).
pub(super) fn inside_camera(yaw: f64) -> Camera {
    Camera {
        eye: DVec3::new(0.1, -0.05, 0.2),
        target: DVec3::new(yaw.sin(), 0.3 * yaw.cos(), -yaw.cos()),
        up: DVec3::Y,
        projection: Projection::Perspective {
            fovy_degrees: 70.0,
            near: 0.01,
            far: 10.0,
        },
        lens: hider_geom::Lens::CENTRED,
    }
}

fn reference(s: &ScreenScene, format: DepthFormat) -> (Frame, ZBufferStats) {
    let mut f = Frame::new(s.viewport.width, s.viewport.height).unwrap();
    let opts = ZBufferOptions::default().with_depth_format(format);
    let stats = ZBuffer::new(opts).render(s, &mut f).unwrap();
    (f, stats)
}

/// A frame full of garbage, so a pixel the tiled hider forgets shows.
fn dirty_frame(s: &ScreenScene) -> Frame {
    let mut f = Frame::new(s.viewport.width, s.viewport.height).unwrap();
    f.ids.fill(7);
    f.depth.fill(0.25);
    f.color.fill([1, 2, 3, 4]);
    f.coverage = vec![0.5; f.len()];
    f
}

/// Renders with the tiled hider and asserts equality with the reference,
/// bit for bit; returns the stats.
fn assert_same(s: &ScreenScene, options: TiledZBufferOptions) -> crate::TiledZBufferStats {
    let (want, want_stats) = reference(s, options.depth_format);
    let mut got = dirty_frame(s);
    let stats = TiledZBuffer::new(options).render(s, &mut got).unwrap();
    for i in 0..want.len() {
        let (x, y) = (i as u32 % s.viewport.width, i as u32 / s.viewport.width);
        assert_eq!(got.ids[i], want.ids[i], "id at ({x}, {y}) with {options:?}");
        assert_eq!(
            got.depth[i].to_bits(),
            want.depth[i].to_bits(),
            "depth at ({x}, {y}) with {options:?}"
        );
    }
    assert!(got == want, "colour or coverage differ with {options:?}");
    // Hierarchical depth skips only pixels that fail: the passes are the
    // reference's, one for one.
    assert_eq!(stats.depth_passes, want_stats.depth_passes, "{options:?}");
    assert!(stats.depth_tests <= want_stats.depth_tests);
    stats
}

fn options() -> impl Strategy<Value = TiledZBufferOptions> {
    (
        prop::sample::select(DepthFormat::ALL.to_vec()),
        prop::sample::select(vec![1usize, 2, 3]),
        prop::sample::select(vec![8u32, 16, 24, 64]),
        any::<bool>(),
    )
        .prop_map(|(f, t, s, h)| {
            TiledZBufferOptions::default()
                .with_depth_format(f)
                .with_threads(t)
                .with_tile_size(s)
                .with_hierarchical_z(h)
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn random_soups_match_the_reference(
        count in 1u32..400,
        seed in any::<u64>(),
        w in 1u32..200,
        h in 1u32..200,
        o in options(),
    ) {
        assert_same(&fit(&procedural::random_soup(count, seed), w, h), o);
    }

    #[test]
    fn soups_seen_from_inside_match_the_reference(
        count in 1u32..300,
        seed in any::<u64>(),
        w in 1u32..64,
        h in 1u32..64,
        yaw in 0.0f64..6.3,
        o in options(),
    ) {
        assert_same(&inside(&procedural::random_soup(count, seed), w, h, yaw), o);
    }

    #[test]
    fn spheres_match_the_reference(n in 3u32..40, size in 1u32..80, o in options()) {
        assert_same(&fit(&procedural::uv_sphere(n), size, size + 3), o);
    }
}

#[test]
fn hard_cases_and_odd_sizes_match_for_every_format() {
    let scenes = [
        procedural::cube(),
        procedural::intersecting_pair(),
        procedural::cyclic_triple(),
        procedural::coplanar_pair(),
    ];
    for scene in &scenes {
        for (w, h) in [(1, 1), (17, 3), (3, 17), (65, 63), (100, 37)] {
            let s = fit(scene, w, h);
            for format in DepthFormat::ALL {
                for (threads, tile) in [(1, 64), (2, 8), (3, 16)] {
                    let o = TiledZBufferOptions::default()
                        .with_depth_format(format)
                        .with_threads(threads)
                        .with_tile_size(tile);
                    assert_same(&s, o);
                }
            }
        }
    }
}

#[test]
fn hierarchical_depth_rejects_work_on_an_overdrawn_soup() {
    // 3000 triangles of about 25 pixels across: a dozen layers per pixel.
    let s = fit(&procedural::random_soup(3000, 5), 640, 640);
    let on = assert_same(&s, TiledZBufferOptions::default().with_threads(1));
    let off = assert_same(
        &s,
        TiledZBufferOptions::default()
            .with_threads(1)
            .with_hierarchical_z(false),
    );
    assert!(on.hiz_block_rejects > 0 && on.hiz_box_rejects > 0, "{on:?}");
    assert!(on.depth_tests < off.depth_tests, "{on:?} vs {off:?}");
    assert_eq!(
        (
            off.hiz_block_rejects,
            off.hiz_triangle_rejects,
            off.hiz_box_rejects
        ),
        (0, 0, 0)
    );
    assert!(on.blocks_inside > 0 && on.blocks_outside > 0, "{on:?}");
}

#[test]
fn a_triangle_behind_its_corner_of_the_tile_is_rejected_before_set_up() {
    // One tile: a far wall on the left half, a near wall on the right half,
    // then a triangle between the two depths inside the right half. The
    // tile's farthest key (the far wall's) does not reject it; the maxima
    // of the blocks its box meets (the near wall's) do, before any of its
    // blocks is visited.
    let wall = |x0: f64, x1: f64, z: f64| {
        [
            [x0, -10.0, z],
            [x1, -10.0, z],
            [x1, 10.0, z],
            [x0, -10.0, z],
            [x1, 10.0, z],
            [x0, 10.0, z],
        ]
    };
    let mut positions: Vec<[f64; 3]> = Vec::new();
    positions.extend(wall(-10.0, 0.0, -5.0));
    positions.extend(wall(0.0, 10.0, 0.5));
    positions.extend([[2.0, -2.0, 0.0], [6.0, -2.0, 0.0], [4.0, 2.0, 0.0]]);
    let mut scene = Scene::default();
    scene.push_mesh(
        hider_scene::Mesh {
            name: "walls".to_owned(),
            positions: positions.iter().map(|&p| DVec3::from_array(p)).collect(),
            indices: vec![[0, 1, 2], [3, 4, 5], [6, 7, 8], [9, 10, 11], [12, 13, 14]],
            ..hider_scene::Mesh::default()
        },
        None,
    );
    let s = fit(&scene, 64, 64);
    let options = TiledZBufferOptions::default().with_threads(1);
    let stats = assert_same(&s, options);
    assert_eq!(
        (stats.hiz_triangle_rejects, stats.hiz_box_rejects),
        (0, 1),
        "{stats:?}"
    );
    let off = assert_same(&s, options.with_hierarchical_z(false));
    assert_eq!(off.triangle_tiles, stats.triangle_tiles + 1, "{off:?}");
}

#[test]
fn tiles_nothing_meets_are_never_cleared() {
    // A small cube in the middle of a large image.
    let mut s = fit(&procedural::cube(), 256, 256);
    // Keep only the triangles that lie in the top-left quadrant.
    s.tris
        .retain(|t| t.v.iter().all(|p| p.x < 128 * 256 && p.y < 128 * 256));
    let stats = assert_same(&s, TiledZBufferOptions::default().with_threads(1));
    assert_eq!(stats.tiles_drawn + stats.tiles_skipped, 16);
    assert!(stats.tiles_skipped >= 12, "{stats:?}");
}

#[test]
fn large_triangles_interleave_with_binned_ones_in_primitive_order() {
    // A soup seen from inside has triangles covering most of the screen
    // (the shared large list) drawn between small ones (the tile bins);
    // 8-pixel tiles make "large" common.
    let s = inside(&procedural::random_soup(3000, 9), 128, 96, 0.4);
    let stats = assert_same(
        &s,
        TiledZBufferOptions::default()
            .with_threads(2)
            .with_tile_size(8),
    );
    assert!(
        stats.large_triangles > 0 && stats.bin_entries > 0,
        "{stats:?}"
    );
}

#[test]
fn buffers_are_reused_across_sizes_formats_and_scenes() {
    let mut z = TiledZBuffer::new(TiledZBufferOptions::default().with_threads(2));
    for (scene, size) in [
        (procedural::uv_sphere(12), 64),
        (procedural::random_soup(200, 3), 40),
        (procedural::uv_sphere(12), 64),
    ] {
        let s = fit(&scene, size, size);
        let (want, _) = reference(&s, DepthFormat::F32);
        let mut got = dirty_frame(&s);
        z.render(&s, &mut got).unwrap();
        assert!(got == want);
        z.render(&s, &mut got).unwrap();
        assert!(got == want);
    }
}

#[test]
fn bad_options_and_frames_are_typed_errors() {
    let s = fit(&procedural::cube(), 16, 16);
    let mut f = Frame::new(16, 16).unwrap();
    for tile in [0, 4, 12, 264, 512] {
        let e = TiledZBuffer::new(TiledZBufferOptions::default().with_tile_size(tile))
            .render(&s, &mut f)
            .unwrap_err();
        assert!(e.to_string().contains("tile size"), "{e}");
    }
    let e = TiledZBuffer::new(TiledZBufferOptions::default().with_threads(100_000))
        .render(&s, &mut f)
        .unwrap_err();
    assert!(e.to_string().contains("threads"), "{e}");
    let mut wrong = Frame::new(17, 16).unwrap();
    let e = TiledZBuffer::default().render(&s, &mut wrong).unwrap_err();
    assert!(e.to_string().contains("17x16"), "{e}");
    // Nothing was drawn into the frames of failed renders.
    assert!(f.ids.iter().all(|&id| id == NO_ID));
}

#[test]
fn names_say_the_format() {
    assert_eq!(TiledZBuffer::default().name(), "zbuffer-tiled");
    let z =
        TiledZBuffer::new(TiledZBufferOptions::default().with_depth_format(DepthFormat::Fixed24));
    assert_eq!(z.name(), "zbuffer-tiled-fixed24");
    assert!(TiledZBuffer::default().threads() >= 1);
}

/// The lean path: `render_scene` (the lean front end, then the draw with
/// the read-back), and `prepare_depth_into` then `draw_depth_scene`,
/// `read_into` and `pixel`, against the reference z-buffer on the full
/// front end's scene. The depth scene is prepared on one thread or in
/// `parts` runs.
fn assert_lean_same(scene: &Scene, view: &View, options: TiledZBufferOptions, parts: usize) {
    let mut screen = prepare(scene, view, &PrepareOptions::default()).unwrap();
    let (want, _) = reference(&screen, options.depth_format);
    let prepare_options = PrepareOptions::default().with_parallel(parts > 1);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(parts)
        .build()
        .unwrap();
    let mut z = TiledZBuffer::new(options);
    let mut got = dirty_frame(&screen);
    pool.install(|| z.render_scene(scene, view, &prepare_options, &mut screen, &mut got))
        .unwrap();
    assert!(got == want, "render_scene with {options:?}");

    let mut lean = DepthScene::new();
    pool.install(|| prepare_depth_into(scene, view, &prepare_options, &mut lean))
        .unwrap();

    let mut got = dirty_frame(&screen);
    z.draw_depth_scene(&lean).unwrap();
    z.read_into(&mut got).unwrap();
    assert!(got == want, "draw + read_into with {options:?}");
    let (w, h) = (view.viewport.width, view.viewport.height);
    for (x, y) in [(0, 0), (w - 1, h - 1), (w / 2, h / 2), (w / 3, h - 1)] {
        let i = (y * w + x) as usize;
        assert_eq!(z.pixel(x, y), Some((want.ids[i], want.depth[i])));
    }
    assert_eq!(z.pixel(w, 0), None);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn the_lean_path_matches_the_reference(
        count in 1u32..300,
        seed in any::<u64>(),
        w in 1u32..120,
        h in 1u32..120,
        yaw in prop::option::of(0.0f64..6.3),
        parts in 1usize..4,
        o in options(),
    ) {
        let scene = procedural::random_soup(count, seed);
        let view = match yaw {
            // From inside the soup: clipping, culling, huge triangles.
            Some(yaw) => View::new(inside_camera(yaw), w, h).unwrap(),
            None => View::for_scene(&scene, w, h).unwrap(),
        };
        assert_lean_same(&scene, &view, o, parts);
    }
}

#[test]
fn the_lean_path_matches_on_large_parallel_scenes() {
    // Above the lean front end's parallel threshold, so the depth scene
    // arrives in several runs.
    let scene = procedural::uv_sphere(130);
    let view = View::for_scene(&scene, 200, 170).unwrap();
    for format in DepthFormat::ALL {
        let o = TiledZBufferOptions::default()
            .with_depth_format(format)
            .with_threads(2);
        assert_lean_same(&scene, &view, o, 3);
    }
}

#[test]
fn stale_tiles_never_show_through() {
    // A big sphere, then a small cube, then nothing: each read-back shows
    // only the current frame although the tile buffers are kept.
    let mut z = TiledZBuffer::new(TiledZBufferOptions::default().with_threads(1));
    let view = View::for_scene(&procedural::uv_sphere(20), 96, 96).unwrap();
    for scene in [
        procedural::uv_sphere(20),
        procedural::cube(),
        Scene::default(),
    ] {
        let mut lean = DepthScene::new();
        prepare_depth_into(&scene, &view, &PrepareOptions::default(), &mut lean).unwrap();
        let screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
        let (want, _) = reference(&screen, DepthFormat::F32);
        z.draw_depth_scene(&lean).unwrap();
        let mut got = dirty_frame(&screen);
        z.read_into(&mut got).unwrap();
        assert!(got == want);
    }
}

#[test]
fn read_back_errors_are_typed() {
    let mut z = TiledZBuffer::default();
    let mut f = Frame::new(8, 8).unwrap();
    let e = z.read_into(&mut f).unwrap_err();
    assert!(e.to_string().contains("nothing has been drawn"), "{e}");
    // A depth scene never prepared has no image size.
    assert!(z.draw_depth_scene(&DepthScene::new()).is_err());
    assert_eq!(z.pixel(0, 0), None);
    let scene = procedural::cube();
    let view = View::for_scene(&scene, 16, 16).unwrap();
    let mut lean = DepthScene::new();
    prepare_depth_into(&scene, &view, &PrepareOptions::default(), &mut lean).unwrap();
    z.draw_depth_scene(&lean).unwrap();
    let e = z.read_into(&mut f).unwrap_err();
    assert!(e.to_string().contains("8x8"), "{e}");
    let mut screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
    let e = z
        .render_scene(
            &scene,
            &view,
            &PrepareOptions::default(),
            &mut screen,
            &mut f,
        )
        .unwrap_err();
    assert!(e.to_string().contains("16x16"), "{e}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// The baseline (SSE2) and the AVX2 kernel give the same frame, bit for
    /// bit (on a CPU without AVX2 both runs take the baseline).
    #[test]
    fn both_kernels_agree(
        count in 1u32..2000,
        seed in any::<u64>(),
        size in 1u32..200,
        inside_view in any::<bool>(),
        o in options(),
    ) {
        let scene = procedural::random_soup(count, seed);
        let s = if inside_view { inside(&scene, size, size, 0.7) } else { fit(&scene, size, size) };
        let mut wide = TiledZBuffer::new(o);
        let mut narrow = TiledZBuffer::new(o);
        narrow.wide_kernel = false;
        let (mut a, mut b) = (dirty_frame(&s), dirty_frame(&s));
        let sa = wide.render(&s, &mut a).unwrap();
        let sb = narrow.render(&s, &mut b).unwrap();
        prop_assert!(a == b);
        prop_assert_eq!(sa, sb);
    }
}

#[test]
fn every_hard_case_matches_the_reference_bit_for_bit() {
    for seed in 0..3 {
        for (_, scene) in hider_testkit::hard_cases::all(seed) {
            for (w, h) in [(64, 64), (97, 61)] {
                let view = View::for_scene(&scene, w, h).unwrap();
                let screen = prepare(&scene, &view, &PrepareOptions::default()).unwrap();
                for o in every_format_on_one_and_two_threads() {
                    assert_same(&screen, o);
                    assert_lean_same(&scene, &view, o, o.threads);
                }
            }
        }
    }
}

/// Fragments are applied after a tile's triangles, out of primitive order:
/// their test is LESS on `(key, prim)`, which must keep what LESS in
/// primitive order keeps, including on ties and against the background.
#[test]
fn fragments_keep_primitive_order_on_ties() {
    use super::tile::TileBuf;
    use crate::DepthFragment;
    let at = |depth: f64, prim: u32| DepthFragment {
        depth,
        x: 3,
        y: 5,
        prim,
    };
    // By default a pixel nothing has written accepts window depth 1, and
    // an equal depth from an earlier primitive still wins over it.
    let mut buf = TileBuf::<f32>::new(8);
    buf.start(0, 0, 8, 8);
    buf.fragment(&at(1.0, 4));
    assert_eq!(buf.get(3, 5), (4, 1.0));
    buf.fragment(&at(1.0, 2));
    assert_eq!(buf.get(3, 5), (2, 1.0));
    buf.fragment(&at(1.0, 6));
    assert_eq!(buf.get(3, 5), (2, 1.0));
    // Under GL's test window depth 1 fails LESS against the cleared far
    // value.
    let mut buf = TileBuf::<f32>::new(8);
    buf.set_test(crate::DepthTest::GlLess);
    buf.start(0, 0, 8, 8);
    buf.fragment(&at(1.0, 4));
    assert_eq!(buf.get(3, 5), (NO_ID, 1.0));
    buf.fragment(&at(0.5, 7));
    assert_eq!(buf.get(3, 5), (7, 0.5));
    // An equal depth from an earlier primitive was there first.
    buf.fragment(&at(0.5, 3));
    assert_eq!(buf.get(3, 5), (3, 0.5));
    // From a later one, it fails LESS.
    buf.fragment(&at(0.5, 9));
    assert_eq!(buf.get(3, 5), (3, 0.5));
    buf.fragment(&at(0.25, 10));
    assert_eq!(buf.get(3, 5), (10, 0.25));
    assert_eq!(buf.get(0, 0), (NO_ID, 1.0));
}

/// Confetti of sub-pixel triangles and a few large ones, all in one plane
/// facing the camera, so every covered pixel is a depth tie between
/// fragments and triangles: the lean path must keep the first primitive
/// everywhere, as the reference does.
#[test]
fn fragments_and_triangles_tie_as_in_the_reference() {
    let mut positions = Vec::new();
    let mut state = 0x9e37_79b9_7f4a_7c15_u64;
    let mut next = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    for k in 0..600 {
        let (cx, cy) = (next() * 1.5, next() * 1.5);
        // About 0.8 pixel across, and every 150th one a large triangle.
        let r = if k % 150 == 75 { 2.0 } else { 0.08 };
        for (dx, dy) in [(-r, -r), (r, -r), (0.0, r)] {
            positions.push(DVec3::new(cx + dx, cy + dy, 0.0));
        }
    }
    let scene = Scene::from_triangles(positions);
    let camera = hider_testkit::cameras::look_at(DVec3::new(0.0, 0.0, 5.0), DVec3::ZERO, 1.0, 10.0);
    let view = View::new(camera, 40, 36).unwrap();
    let mut lean = DepthScene::new();
    prepare_depth_into(&scene, &view, &PrepareOptions::default(), &mut lean).unwrap();
    assert!(
        lean.stats.fragmented > 100 && lean.len() >= 4,
        "{:?}",
        lean.stats
    );
    for o in every_format_on_one_and_two_threads() {
        assert_lean_same(&scene, &view, o, 1);
    }
}

/// Every depth format on 1 and on 2 threads, with 16-pixel tiles (so that
/// small images have several).
fn every_format_on_one_and_two_threads() -> impl Iterator<Item = TiledZBufferOptions> {
    DepthFormat::ALL.into_iter().flat_map(|format| {
        [1, 2].map(|threads| {
            TiledZBufferOptions::default()
                .with_depth_format(format)
                .with_threads(threads)
                .with_tile_size(16)
        })
    })
}
