//! The supersampled baselines take the A-buffer's lean front end from a
//! world-space scene: `render_scene` of the supersampled z-buffer (1, 8
//! and 32 samples) and of the sorted-transparency z-buffer gives the
//! frame, sample ids and counters of rendering `prepare`'s output, bit
//! for bit, on the textured spider, a smooth-shaded sphere, a sphere with
//! vertex colours, a translucent one and in false colours, and leaves the
//! caller's prepared scene empty (the lean front end ran, not `prepare`).
//! A scene with cut-outs (alpha-tested per sample from `prepare`'s
//! primitives) is prepared, and is the same too. Fails on the trait's
//! default `render_scene`, which prepares every scene.

use std::path::PathBuf;

use glam::DVec3;
use hider_abuffer::{SamplePattern, SortedTransparencyZBuffer, SsaaOptions, SupersampledZBuffer};
use hider_scene::shade::Texture;
use hider_scene::{
    Frame, Hider, PrepareOptions, Scene, ScreenScene, ShadeMode, TextureRef, View, load_obj,
    procedural,
};
use hider_testkit::screen;

use crate::common::with_opacity;

/// A scene from the repository's `assets/`.
fn asset(path: &str) -> Scene {
    let file = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets")
        .join(path);
    load_obj(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()))
}

/// A UV sphere with a normal at each vertex, and one with a colour at
/// each vertex.
fn shaded_spheres() -> [Scene; 2] {
    let mut smooth = procedural::uv_sphere(20);
    let mut coloured = procedural::uv_sphere(20);
    for mesh in &mut smooth.meshes {
        mesh.normals = mesh
            .positions
            .iter()
            .map(|p| p.normalize().as_vec3())
            .collect();
    }
    for mesh in &mut coloured.meshes {
        mesh.colors = mesh
            .positions
            .iter()
            .map(|p| {
                let c = (*p * 0.5 + DVec3::splat(0.5)).as_vec3();
                [c.x, c.y, c.z]
            })
            .collect();
    }
    [smooth, coloured]
}

/// The spider with a cut-out `map_Kd` on every other material (a checker
/// of opaque and transparent squares) and one of partial alpha on the
/// others.
fn cut_spider() -> Scene {
    let mut scene = asset("spider/spider.obj");
    let checker = |alpha: u8| {
        let texels: Vec<u8> = (0..32 * 32)
            .flat_map(|k| {
                let (x, y) = (k % 32 / 4, k / 32 / 4);
                [
                    (x * 30) as u8,
                    (y * 30) as u8,
                    128,
                    if (x + y) % 2 == 0 { 255 } else { alpha },
                ]
            })
            .collect();
        Texture::from_srgba8(32, 32, &texels).unwrap()
    };
    let (cut, partial) = (checker(0), checker(90));
    for (k, m) in scene.materials.iter_mut().enumerate() {
        let t = if k % 2 == 0 { &cut } else { &partial };
        m.diffuse_texture = Some(TextureRef::from_texture("checker.png", t.clone()));
    }
    scene
}

/// `hider`'s frame of `scene` at `w x h`: through `render_scene`, and
/// whether it left the caller's prepared scene empty.
fn from_scene<H: Hider>(
    hider: &mut H,
    scene: &Scene,
    (w, h): (u32, u32),
) -> (Frame, H::Stats, bool) {
    let view = View::for_scene(scene, w, h).unwrap();
    let mut screen = ScreenScene::empty(&view);
    let mut frame = Frame::new(w, h).unwrap();
    let stats = hider
        .render_scene(
            scene,
            &view,
            &PrepareOptions::default(),
            &mut screen,
            &mut frame,
        )
        .unwrap();
    (frame, stats, screen.tris.is_empty())
}

/// The frames are the same, the floats by their bits.
fn assert_same_frame(what: &str, a: &Frame, b: &Frame) {
    assert_eq!(a.color, b.color, "{what}: colour");
    assert_eq!(a.ids, b.ids, "{what}: ids");
    let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&a.depth), bits(&b.depth), "{what}: depth");
    assert_eq!(bits(&a.coverage), bits(&b.coverage), "{what}: coverage");
}

/// Both baselines at every pattern given render `scene` alike through
/// both front ends; `lean` says whether the lean one should run.
fn baselines_agree(scene: &Scene, what: &str, lean: bool) {
    let size = (96, 70);
    let prepared = screen(scene, size.0, size.1);
    for pattern in [
        SamplePattern::Centre,
        SamplePattern::Grid8,
        SamplePattern::Grid32,
    ] {
        for shade in [ShadeMode::Lambert, ShadeMode::Ids] {
            let options = SsaaOptions::default()
                .with_pattern(pattern)
                .with_shade(shade);
            let at = format!("{what}, {} samples, {shade:?}", pattern.count());
            let mut full = SupersampledZBuffer::new(options);
            let mut f1 = Frame::new(size.0, size.1).unwrap();
            let s1 = full.render(&prepared, &mut f1).unwrap();
            let mut from = SupersampledZBuffer::new(options);
            for round in 0..2 {
                let (f2, s2, empty) = from_scene(&mut from, scene, size);
                assert_eq!(empty, lean, "{at}: front end");
                assert_same_frame(&format!("{at}, round {round}"), &f1, &f2);
                assert_eq!(s1, s2, "{at}");
                assert_eq!(full.sample_ids(), from.sample_ids(), "{at}");
            }
            let mut full = SortedTransparencyZBuffer::new(options);
            let mut f1 = Frame::new(size.0, size.1).unwrap();
            let s1 = full.render(&prepared, &mut f1).unwrap();
            let (f2, s2, empty) =
                from_scene(&mut SortedTransparencyZBuffer::new(options), scene, size);
            assert_eq!(empty, lean, "{at}, sorted: front end");
            assert_same_frame(&format!("{at}, sorted"), &f1, &f2);
            assert_eq!(s1, s2, "{at}, sorted");
        }
    }
}

#[test]
fn the_baselines_take_the_lean_front_end() {
    let spider = asset("spider/spider.obj");
    assert!(spider.is_textured());
    baselines_agree(&spider, "textured spider", true);
    let [smooth, coloured] = shaded_spheres();
    baselines_agree(&smooth, "smooth sphere", true);
    baselines_agree(&coloured, "coloured sphere", true);
    baselines_agree(&with_opacity(smooth, 0.6), "translucent sphere", true);
    baselines_agree(&procedural::random_soup(60, 3), "soup", true);
}

#[test]
fn the_baselines_prepare_scenes_with_cutouts() {
    baselines_agree(&cut_spider(), "cut-out spider", false);
}
