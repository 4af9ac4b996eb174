//! The sample buffer of opaque tiles gives what the fragment lists give:
//! with merging off, the same colours, coverage, ids, depths and sample
//! ids, bit for bit, on every hard case and on random soups (opaque,
//! translucent, mixed: tiles with a translucent triangle keep their lists),
//! at several frame sizes and thread counts; with the default same-colour
//! merging, whose averaged colours the lists show, the same coverage, ids
//! and depths and colours within one 8-bit step.

use glam::DVec3;
use hider_abuffer::{ABuffer, ABufferOptions, ABufferStats, MergePolicy, SamplePattern};
use hider_scene::{Frame, Hider, Mesh, Scene, procedural};
use hider_testkit::{hard_cases, render, screen};
use proptest::prelude::*;

use crate::common::{max_color_diff, with_opacity};

/// Frame sizes around the 64-pixel tiles and 32-row passes.
const SIZES: [(u32, u32); 4] = [(150, 90), (70, 131), (64, 33), (1, 77)];

/// Renders `scene` at every size through the sample buffer (at `threads`)
/// and through lists only, with `merge`, and compares.
fn samples_equal_lists(scene: &Scene, merge: MergePolicy, threads: usize, what: &str) {
    let options = ABufferOptions::default().with_merge(merge);
    samples_equal_lists_with(scene, options, threads, what);
}

/// [`samples_equal_lists`] with `options` (merging from them).
fn samples_equal_lists_with(scene: &Scene, options: ABufferOptions, threads: usize, what: &str) {
    let merge = options.merge;
    for (w, h) in SIZES {
        let s = screen(scene, w, h);
        let mut sampled = ABuffer::new(options.with_threads(threads));
        let mut listed = ABuffer::new(options.with_sample_tiles(false).with_threads(1));
        let (a, sa): (Frame, ABufferStats) = render(&mut sampled, &s);
        let (b, sb): (Frame, ABufferStats) = render(&mut listed, &s);
        assert_eq!(sb.sample_tiles, 0, "{what}");
        if sb.dropped > 0 {
            // The lists lost fragments the sample buffer keeps.
            continue;
        }
        assert_eq!(a.coverage, b.coverage, "{what} {w}x{h}: coverage");
        assert_eq!(a.ids, b.ids, "{what} {w}x{h}: ids");
        assert_eq!(a.depth, b.depth, "{what} {w}x{h}: depth");
        assert_eq!(sampled.sample_ids(), listed.sample_ids(), "{what} {w}x{h}");
        if merge == MergePolicy::Off {
            assert_eq!(a.color, b.color, "{what} {w}x{h}: colour");
        } else {
            assert!(max_color_diff(&a, &b) <= 1, "{what} {w}x{h}: colour");
        }
        let opaque = scene
            .meshes
            .iter()
            .all(|m| m.material.is_none_or(|k| scene.materials[k].opacity >= 1.0));
        if opaque && !b.ids.iter().all(|&id| id == hider_scene::NO_ID) {
            assert!(sa.sample_tiles > 0, "{what} {w}x{h}: {sa:?}");
        }
    }
}

#[test]
fn every_hard_case_resolves_from_samples_as_from_lists() {
    for (name, scene) in hard_cases::all(13) {
        for threads in [1, 3] {
            samples_equal_lists(&scene, MergePolicy::Off, threads, name);
        }
        samples_equal_lists(&scene, MergePolicy::SameColor, 2, name);
    }
}

#[test]
fn procedural_meshes_resolve_from_samples_as_from_lists() {
    for (name, scene) in [
        ("sphere", procedural::uv_sphere(40)),
        ("cube", procedural::cube()),
        ("pair", procedural::intersecting_pair()),
    ] {
        samples_equal_lists(&scene, MergePolicy::Off, 1, name);
        samples_equal_lists(&scene, MergePolicy::SameColor, 2, name);
    }
}

/// `scene` at `w x h` through the sample buffer (default options, one
/// thread) and through lists only with merging off: frames and counters.
fn sampled_and_listed(
    scene: &Scene,
    (w, h): (u32, u32),
) -> ((Frame, ABufferStats), (Frame, ABufferStats)) {
    let s = screen(scene, w, h);
    let mut sampled = ABuffer::new(ABufferOptions::default().with_threads(1));
    let mut listed = ABuffer::new(
        ABufferOptions::default()
            .with_sample_tiles(false)
            .with_merge(MergePolicy::Off),
    );
    (render(&mut sampled, &s), render(&mut listed, &s))
}

/// Pixels covered whole by one front triangle are held whole (and counted
/// in `whole_pixels`, which only the sample buffer makes); where two large
/// triangles pierce each other, the second one taken is in front of the
/// first one's whole pixels on one side of the line they cross on (it
/// takes them whole), behind on the other (culled), and along the line
/// in front at some samples only (it expands them to samples); the image
/// is the lists' bit for bit.
#[test]
fn whole_pixels_are_kept_and_expanded_as_the_lists_say() {
    let scene = procedural::intersecting_pair();
    let ((a, sa), (b, sb)) = sampled_and_listed(&scene, (128, 128));
    assert!(sa.whole_pixels > 1000, "{sa:?}");
    assert!(sa.full_coverage > sa.whole_pixels, "{sa:?}");
    assert_eq!(sb.whole_pixels, 0, "{sb:?}");
    assert_eq!(a.color, b.color);
    assert_eq!((a.coverage, a.ids, a.depth), (b.coverage, b.ids, b.depth));
}

/// Vertical bars side by side, each its own primitive pair, with
/// horizontal bars in front: where a shared edge falls between two
/// pixels' samples, whole pixels of different primitives meet in a row,
/// and the rows' runs of whole pixels split by primitive.
fn bars() -> Scene {
    let mut scene = Scene::default();
    let quad = |x0: f64, y0: f64, x1: f64, y1: f64, z: f64| Mesh {
        name: format!("bar {x0} {y0}"),
        positions: vec![
            DVec3::new(x0, y0, z),
            DVec3::new(x1, y0, z),
            DVec3::new(x1, y1, z),
            DVec3::new(x0, y1, z),
        ],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        ..Mesh::default()
    };
    for k in 0..23 {
        let x = -1.0 + 2.0 * f64::from(k) / 23.0;
        scene.push_mesh(quad(x, -1.0, x + 2.0 / 23.0, 1.0, 0.0), None);
    }
    for k in 0..5 {
        let y = -0.9 + 0.37 * f64::from(k);
        scene.push_mesh(
            quad(-0.8, y, 0.7, y + 0.21, 0.1 + 0.05 * f64::from(k)),
            None,
        );
    }
    scene
}

/// A row's whole pixels resolve as runs of one primitive: where runs of
/// several primitives meet, the frame is the lists' bit for bit (the
/// scene is checked to have such meetings: fully covered neighbours of
/// different ids in a row).
#[test]
fn runs_of_whole_pixels_resolve_as_the_lists_say() {
    let scene = bars();
    for (w, h) in [(300, 200), (199, 101), (512, 300)] {
        let ((a, sa), (b, _)) = sampled_and_listed(&scene, (w, h));
        let meetings = (0..a.ids.len() - 1)
            .filter(|&p| (p + 1) % w as usize != 0)
            .filter(|&p| a.coverage[p] == 1.0 && a.coverage[p + 1] == 1.0)
            .filter(|&p| a.ids[p] != a.ids[p + 1])
            .count();
        assert!(meetings > h as usize, "{w}x{h}: {meetings} meetings");
        assert!(sa.whole_pixels > u64::from(w * h) / 20, "{w}x{h}: {sa:?}");
        assert_eq!(a.color, b.color, "{w}x{h}");
        assert_eq!(
            (&a.coverage, &a.ids, &a.depth),
            (&b.coverage, &b.ids, &b.depth),
            "{w}x{h}"
        );
    }
}

/// The smaller patterns take the portable depth test (the 8 x 4 grid the
/// AVX2 one where the CPU has it): the same answer as the lists too.
#[test]
fn every_pattern_resolves_from_samples_as_from_lists() {
    let scenes = [
        ("sphere", procedural::uv_sphere(24)),
        ("pair", procedural::intersecting_pair()),
        ("soup", procedural::random_soup(300, 9)),
    ];
    for pattern in [
        SamplePattern::Centre,
        SamplePattern::Grid4,
        SamplePattern::Grid8,
        SamplePattern::Grid16,
        SamplePattern::Grid32,
    ] {
        for (name, scene) in &scenes {
            let options = ABufferOptions::default()
                .with_merge(MergePolicy::Off)
                .with_pattern(pattern);
            samples_equal_lists_with(scene, options, 1, name);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Random soups, opaque or partly translucent (the translucent tiles
    /// keep lists, the others take samples: the frame is the lists').
    #[test]
    fn random_soups_resolve_from_samples_as_from_lists(
        n in 1u32..500,
        seed in any::<u64>(),
        glass in prop::sample::select(vec![1.0f32, 1.0, 0.5]),
        threads in 1usize..4,
    ) {
        let scene = with_opacity(procedural::random_soup(n, seed), glass);
        samples_equal_lists(&scene, MergePolicy::Off, threads, "soup");
    }
}

/// Culling in the sample buffer (per block, per pixel) changes nothing:
/// the same frame and sample ids with it off, and it does reject work.
#[test]
fn sample_buffer_culling_changes_nothing() {
    // The sphere's far side lies behind its near side: whole blocks of it
    // are hidden.
    let mut scene = procedural::uv_sphere(48);
    for mesh in procedural::random_soup(2000, 5).meshes {
        scene.push_mesh(mesh, None);
    }
    let s = screen(&scene, 200, 140);
    let mut culled = ABuffer::new(ABufferOptions::default().with_merge(MergePolicy::Off));
    let mut all = ABuffer::new(
        ABufferOptions::default()
            .with_merge(MergePolicy::Off)
            .with_occlusion_culling(false),
    );
    let (a, sa) = render(&mut culled, &s);
    let (b, sb) = render(&mut all, &s);
    assert!(sa.culled > 0 && sa.culled_blocks > 0, "{sa:?}");
    assert_eq!((sb.culled, sb.culled_blocks), (0, 0));
    assert!(sa.sample_tiles > 0 && sa.fragments < sb.fragments);
    assert_eq!(a, b);
    assert_eq!(culled.sample_ids(), all.sample_ids());
}

/// One A-buffer rendering frame after frame, its tiles switching between
/// lists (a translucent frame) and the sample buffer (an opaque one),
/// gives what a fresh one gives each time: no list of an earlier frame
/// survives into a sampled tile, nor a sampled pass into a list.
#[test]
fn tiles_switching_between_lists_and_samples_keep_no_stale_state() {
    let opaque = procedural::random_soup(400, 21);
    let glass = with_opacity(procedural::random_soup(400, 22), 0.5);
    let mut reused = ABuffer::new(ABufferOptions::default().with_threads(2));
    let frames = [
        (&opaque, true),
        (&glass, false),
        (&opaque, true),
        (&glass, false),
        (&glass, false),
        (&opaque, true),
    ];
    for (k, (scene, sampled)) in frames.into_iter().enumerate() {
        let s = screen(scene, 150, 90);
        let (a, sa) = render(&mut reused, &s);
        let mut fresh = ABuffer::new(ABufferOptions::default().with_threads(2));
        let (b, _) = render(&mut fresh, &s);
        assert_eq!(a, b, "frame {k}");
        assert_eq!(reused.sample_ids(), fresh.sample_ids(), "frame {k}");
        assert_eq!(sa.sample_tiles > 0, sampled, "frame {k}: {sa:?}");
    }
}

/// A textured model (the bundled spider, whose materials' textures decode
/// on first use): the sample buffer colours each primitive at the pixel
/// centre as the lists do, so the frames are the same bit for bit.
#[test]
fn textured_spider_resolves_from_samples_as_from_lists() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/spider/spider.obj");
    let scene = hider_scene::load_obj(path).expect("the bundled spider");
    for (w, h) in [(96, 96), (150, 90)] {
        let s = screen(&scene, w, h);
        assert!(scene.is_textured());
        let options = ABufferOptions::default().with_merge(MergePolicy::Off);
        let mut sampled = ABuffer::new(options);
        let mut listed = ABuffer::new(options.with_sample_tiles(false));
        let (a, sa) = render(&mut sampled, &s);
        let (b, _) = render(&mut listed, &s);
        assert!(sa.sample_tiles > 0, "{sa:?}");
        assert_eq!(a, b, "{w}x{h}");
        for m in &scene.materials {
            if let Some(t) = &m.diffuse_texture {
                assert!(t.error().is_none(), "{:?}", t.error());
            }
        }
    }
}
