//! The small-box set-ups the lean front end makes (`SmallSetup`): each is
//! none or the scalar definition, and a frame drawn with them is the frame
//! drawn without them, bit for bit and counter for counter.

use hider_geom::Viewport;
use hider_scene::{Frame, Hider, PrepareOptions, Scene, View, procedural};
use proptest::prelude::*;

use crate::depth_scene::{DepthFragment, DepthTri, SmallSetup};
use crate::{DepthFormat, DepthScene, TiledZBuffer, TiledZBufferOptions, prepare_depth_into};

/// A view from inside the soup's cube (clipping, culling, corners far
/// outside the image) or one that frames the scene.
fn view(scene: &Scene, size: (u32, u32), inside: bool) -> View {
    if !inside {
        return View::for_scene(scene, size.0, size.1).unwrap();
    }
    // Inside the soup's cube, looking along (0.41, 0.27, -0.91).
    let camera = super::tests::inside_camera(0.42);
    View::new(camera, size.0, size.1).unwrap()
}

/// The lean front end's output for `scene`, on one thread or in runs.
fn lean(scene: &Scene, view: &View, parallel: bool) -> DepthScene {
    let mut lean = DepthScene::new();
    let options = PrepareOptions::default().with_parallel(parallel);
    prepare_depth_into(scene, view, &options, &mut lean).unwrap();
    lean
}

/// Draws `lean` with its set-ups (or without) and reads the frame back.
fn draw(lean: &DepthScene, options: TiledZBufferOptions, setups: bool) -> (Frame, String) {
    let mut z = TiledZBuffer::new(options);
    let parts: Vec<&[DepthTri]> = lean.parts().collect();
    let fragments: Vec<&[DepthFragment]> = lean.fragments().collect();
    let stats = if setups {
        z.draw_depth_scene(lean).unwrap()
    } else {
        z.run((&parts, &fragments), (lean.viewport, false), None)
            .unwrap()
    };
    let mut frame = Frame::new(lean.viewport.width, lean.viewport.height).unwrap();
    z.read_into(&mut frame).unwrap();
    (frame, format!("{stats:?}"))
}

/// Asserts that every triangle's set-up is none or [`SmallSetup::new`]'s;
/// returns how many have one.
fn check_setups(lean: &DepthScene) -> usize {
    let mut ready = 0;
    for t in lean.tris() {
        if t.setup != SmallSetup::NONE {
            assert_eq!(t.setup, SmallSetup::new(&t.v, lean.viewport), "{t:?}");
            ready += 1;
        }
    }
    ready
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    #[test]
    fn set_ups_are_the_definition_and_change_no_pixel(
        sphere in prop::option::of(8u32..80),
        seed in any::<u64>(),
        size in (1u32..160, 1u32..160),
        inside in any::<bool>(),
        tile in prop::sample::select(vec![8u32, 16, 24, 64]),
        format in prop::sample::select(DepthFormat::ALL.to_vec()),
    ) {
        let scene = match sphere {
            Some(n) => procedural::uv_sphere(n),
            None => procedural::random_soup(300, seed),
        };
        let view = view(&scene, size, inside && sphere.is_none());
        let lean = lean(&scene, &view, false);
        check_setups(&lean);
        let options = TiledZBufferOptions::default()
            .with_tile_size(tile)
            .with_depth_format(format)
            .with_threads(1);
        let (with, with_stats) = draw(&lean, options, true);
        let (without, without_stats) = draw(&lean, options, false);
        prop_assert!(with == without);
        prop_assert_eq!(with_stats, without_stats);
    }
}

#[test]
fn a_dense_mesh_has_set_ups_in_every_run() {
    // Above the front end's parallel threshold, triangles of a few pixels.
    let scene = procedural::uv_sphere(130);
    let view = View::for_scene(&scene, 700, 650).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(3)
        .build()
        .unwrap();
    let lean = pool.install(|| lean(&scene, &view, true));
    assert!(lean.parts().len() > 1);
    let ready = check_setups(&lean);
    assert!(ready * 2 > lean.len(), "{ready} of {}", lean.len());
    for tile in [8, 64] {
        let options = TiledZBufferOptions::default().with_tile_size(tile);
        assert!(draw(&lean, options, true) == draw(&lean, options, false));
    }
}

#[test]
fn a_viewport_changed_by_hand_draws_without_set_ups() {
    // The stored boxes are clipped to the image the front end made them
    // for: a smaller one must not bin by them.
    let scene = procedural::uv_sphere(130);
    let view = View::for_scene(&scene, 700, 650).unwrap();
    let mut lean = lean(&scene, &view, false);
    assert!(lean.setups_valid() && check_setups(&lean) > 0);
    lean.viewport = Viewport::new(350, 325);
    assert!(!lean.setups_valid());
    let options = TiledZBufferOptions::default().with_tile_size(16);
    assert!(draw(&lean, options, true) == draw(&lean, options, false));
}
