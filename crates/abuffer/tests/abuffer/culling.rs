//! Occlusion culling (per pixel, per 8 x 8 block, pruning) and tiling never
//! change the answer: the culled A-buffer equals the same A-buffer with
//! culling off, and the 32-sample supersampled z-buffer, sample for sample,
//! on frames of several tiles (partial tiles included).

use hider_abuffer::{
    ABuffer, ABufferOptions, ABufferStats, MergePolicy, SsaaOptions, SupersampledZBuffer,
};
use hider_scene::{Frame, Hider, Material, Mesh, Scene, ScreenScene, procedural};
use hider_testkit::{render, screen};
use proptest::prelude::*;

use crate::common::{equals_supersampling, lists, max_color_diff, same_image};

/// Frame sizes around the 64-pixel tiles: several tiles, partial tiles,
/// one-pixel rows and columns.
const SIZES: [(u32, u32); 5] = [(150, 90), (70, 131), (64, 64), (129, 1), (1, 77)];

/// An opaque soup of `opaque` triangles plus a translucent one of
/// `glass` triangles (opacity 0.5) mixed in.
fn mixed_soup(opaque: u32, glass: u32, seed: u64) -> Scene {
    let mut s = procedural::random_soup(opaque.max(1), seed);
    if glass > 0 {
        let g = procedural::random_soup(glass, seed ^ 0x9e37);
        let material = Material {
            name: "glass".into(),
            diffuse: [0.2, 0.5, 0.9],
            opacity: 0.5,
            ..Material::default()
        };
        for mesh in g.meshes {
            s.push_mesh(mesh, Some(material.clone()));
        }
    }
    s
}

/// `n` large opaque triangles (spanning about half the view each, at
/// random depths and slopes, piercing one another) over a soup of small
/// ones: deep enough for whole blocks to be hidden.
fn big_triangles(n: u32, small: u32, seed: u64) -> Scene {
    let mut s = procedural::random_soup(small.max(1), seed);
    let mut rng = procedural::SplitMix64::new(seed);
    let mut next = move || rng.next_u64() as f64 / u64::MAX as f64 * 2.0 - 1.0;
    let mut positions = Vec::new();
    for _ in 0..n {
        let (cx, cy, cz) = (next() * 0.5, next() * 0.5, next());
        for _ in 0..3 {
            positions.push(glam::DVec3::new(
                cx + next(),
                cy + next(),
                cz + 0.3 * next(),
            ));
        }
    }
    s.push_mesh(
        Mesh {
            name: "big".into(),
            indices: (0..n).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect(),
            positions,
            ..Mesh::default()
        },
        None,
    );
    s
}

/// Renders `s` with the lists, merging off, with occlusion culling and
/// without, and checks (in a `proptest!` body, `?`) that culling changes no
/// sample: the same sample ids, coverage and centre ids, colours within one
/// 8-bit step. Returns the culled hider and frame, and the unculled frame
/// and counters, for each test's further checks.
fn culling_changes_no_sample(
    s: &ScreenScene,
) -> Result<(ABuffer, Frame, Frame, ABufferStats), TestCaseError> {
    let opts = lists().with_merge(MergePolicy::Off);
    let mut culled = ABuffer::new(opts);
    let mut reference = ABuffer::new(opts.with_occlusion_culling(false));
    let fc = render(&mut culled, s).0;
    let (fr, st) = render(&mut reference, s);
    prop_assert_eq!(culled.sample_ids(), reference.sample_ids());
    same_image(&fc, &fr)?;
    Ok((culled, fc, fr, st))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// Large piercing opaque triangles, where whole blocks are culled: the
    /// same samples as without culling and as the 32-sample z-buffer.
    #[test]
    fn block_culling_changes_no_sample(
        big in 1u32..40,
        small in 1u32..200,
        seed in any::<u64>(),
        size in 0usize..SIZES.len(),
    ) {
        let (w, h) = SIZES[size];
        let s = screen(&big_triangles(big, small, seed), w, h);
        let (culled, ..) = culling_changes_no_sample(&s)?;
        let mut ssaa = SupersampledZBuffer::new(SsaaOptions::default());
        render(&mut ssaa, &s);
        prop_assert_eq!(&culled.sample_ids(), ssaa.sample_ids());
    }

    /// With per-sample depth and merging off, culling on and off give the
    /// same sample ids (equal to the 32-sample z-buffer's), coverage and
    /// centre ids, and colours within one 8-bit step; with culling off
    /// nothing is culled, skipped or pruned.
    #[test]
    fn occlusion_culling_changes_no_sample(
        opaque in 1u32..400,
        glass in 0u32..40,
        seed in any::<u64>(),
        size in 0usize..SIZES.len(),
    ) {
        let (w, h) = SIZES[size];
        let s = screen(&mixed_soup(opaque, glass, seed), w, h);
        let (culled, fc, fr, st) = culling_changes_no_sample(&s)?;
        prop_assert_eq!((st.culled, st.culled_blocks, st.pruned), (0, 0, 0));
        prop_assert_eq!(&fc.depth, &fr.depth);
        equals_supersampling(&s, SsaaOptions::default(), &culled, &fc)?;
    }

    /// The default A-buffer (same-colour merging) likewise.
    #[test]
    fn occlusion_culling_changes_no_image(
        opaque in 1u32..400,
        glass in 0u32..40,
        seed in any::<u64>(),
        size in 0usize..SIZES.len(),
    ) {
        let (w, h) = SIZES[size];
        let s = screen(&mixed_soup(opaque, glass, seed), w, h);
        let fc = render(&mut ABuffer::new(lists()), &s).0;
        let fr = render(
            &mut ABuffer::new(lists().with_occlusion_culling(false)),
            &s,
        ).0;
        same_image(&fc, &fr)?;
    }
}

/// A quad: two triangles through the corners `c`, in order around it.
fn quad(name: String, c: [glam::DVec3; 4]) -> Mesh {
    Mesh {
        name,
        positions: c.to_vec(),
        indices: vec![[0, 1, 2], [0, 2, 3]],
        ..Mesh::default()
    }
}

/// Twelve opaque squares stacked along the view axis, nearest first, each
/// a little bigger than the one in front, plus a soup of small triangles
/// behind them all.
fn stack_and_soup() -> Scene {
    let mut s = procedural::random_soup(400, 5);
    for m in &mut s.meshes {
        for p in &mut m.positions {
            p.z -= 3.0;
        }
    }
    for k in 0..12 {
        let z = -0.2 * f64::from(k);
        let r = 1.2 + 0.1 * f64::from(k);
        let p = |x: f64, y: f64| glam::DVec3::new(x * r, y * r * 0.8, z);
        let corners = [p(-1.0, -1.0), p(1.0, -1.0), p(1.0, 1.0), p(-1.0, 1.0)];
        s.push_mesh(quad(format!("layer {k}"), corners), None);
    }
    s
}

/// Every culling stage fires on a deep opaque scene (culling per pixel,
/// skipping blocks, pruning), and the answer is the unculled one.
#[test]
fn every_culling_stage_fires_on_a_deep_scene() {
    for scene in [stack_and_soup(), procedural::random_soup(3000, 5)] {
        let s = screen(&scene, 200, 140);
        let opts = lists().with_merge(MergePolicy::Off);
        // Submission order: the soup arrives before the squares hiding it,
        // so it is inserted and then pruned.
        let mut a = ABuffer::new(opts.with_front_to_back(false));
        let mut r = ABuffer::new(opts.with_occlusion_culling(false));
        let (fa, st) = render(&mut a, &s);
        let (fr, st_r) = render(&mut r, &s);
        assert!(st.culled > 0 && st.pruned > 0, "{st:?}");
        assert!(st.mean_list_len < st_r.mean_list_len);
        assert_eq!(a.sample_ids(), r.sample_ids());
        assert_eq!(fa.coverage, fr.coverage);
        assert_eq!(fa.ids, fr.ids);
        assert!(max_color_diff(&fa, &fr) <= 1);
    }
    // The squares arrive after the soup they hide, but each square hides
    // the next ones: whole blocks of them are skipped. Front to back (the
    // default) the soup is skipped too, and nothing needs pruning.
    let s = screen(&stack_and_soup(), 200, 140);
    let mut a = ABuffer::new(lists().with_front_to_back(false));
    let (fa, submitted) = render(&mut a, &s);
    assert!(submitted.culled_blocks > 100, "{submitted:?}");
    let mut b = ABuffer::new(lists());
    let (fb, sorted) = render(&mut b, &s);
    assert!(sorted.culled_blocks > submitted.culled_blocks, "{sorted:?}");
    assert!(sorted.fragments < submitted.fragments, "{sorted:?}");
    assert_eq!(sorted.pruned, 0, "{sorted:?}");
    assert_eq!(fa.ids, fb.ids);
    assert_eq!(fa.coverage, fb.coverage);
    assert!(max_color_diff(&fa, &fb) <= 1);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Front to back or in submission order: the same samples, coverage
    /// and ids (merging off), colours within one step.
    #[test]
    fn processing_order_changes_no_sample(
        big in 1u32..30,
        small in 1u32..300,
        glass in 0u32..30,
        seed in any::<u64>(),
        size in 0usize..SIZES.len(),
    ) {
        let (w, h) = SIZES[size];
        let mut scene = big_triangles(big, small, seed);
        let extra = mixed_soup(1, glass, seed);
        for (mesh, material) in extra.meshes.into_iter().zip(extra.materials) {
            scene.push_mesh(mesh, Some(material));
        }
        let s = screen(&scene, w, h);
        let opts = lists().with_merge(MergePolicy::Off);
        let mut sorted = ABuffer::new(opts);
        let mut submitted = ABuffer::new(opts.with_front_to_back(false));
        let fs = render(&mut sorted, &s).0;
        let fu = render(&mut submitted, &s).0;
        prop_assert_eq!(sorted.sample_ids(), submitted.sample_ids());
        same_image(&fs, &fu)?;
    }
}

/// A hider reused across frame sizes (same pixel count in other shapes
/// included) renders each frame as a fresh one does: no list of an earlier
/// frame leaks into a later one.
#[test]
fn reuse_across_frame_sizes_equals_fresh_renders() {
    let scene = mixed_soup(300, 20, 9);
    let mut reused = ABuffer::new(lists());
    for (w, h) in [
        (150, 90),
        (90, 150),
        (150, 90),
        (13, 200),
        (200, 13),
        (150, 90),
    ] {
        let s = screen(&scene, w, h);
        let again = render(&mut reused, &s).0;
        let mut fresh = ABuffer::new(lists());
        let first = render(&mut fresh, &s).0;
        assert_eq!(again, first, "{w} x {h}");
        assert_eq!(reused.sample_ids(), fresh.sample_ids(), "{w} x {h}");
    }
    // A frame of one triangle after a full one: the emptied tiles are
    // cleared.
    let one = screen(&procedural::random_soup(1, 3), 150, 90);
    let after = render(&mut reused, &one).0;
    let fresh = render(&mut ABuffer::new(lists()), &one).0;
    assert_eq!(after, fresh);
}

/// Six opaque triangles (prims 0 to 5, depth 0.3) cover every sample of
/// pixel (2, 2) but leave a small hole around its centre; a triangle
/// behind (prim 6, depth 0.8) covers the whole frame. The samples are all
/// hidden, the centre is not: the opaque bound must wait for the centre,
/// or prim 6 would be culled there and the pixel would lose its id.
#[test]
fn a_pixel_whose_centre_is_open_keeps_the_surface_behind() {
    use hider_scene::geom::{FixedPt, PlaneEq, orient2d};
    use hider_scene::{NO_ID, ScreenTri};
    let mut s = screen(&procedural::random_soup(10, 1), 8, 8);
    assert!(s.prims.len() >= 7);
    let tri = |p: [(i32, i32); 3], z: f64, prim: u32| {
        let mut v = p.map(|(x, y)| FixedPt::new(x, y));
        if orient2d(v[0], v[1], v[2]) < 0 {
            v.swap(1, 2);
        }
        ScreenTri {
            v,
            z: [z; 3],
            w: [1.0; 3],
            depth: PlaneEq::constant(z),
            inv_w: PlaneEq::constant(1.0),
            prim,
            front_facing: true,
        }
    };
    let (a, b, c) = ((-8000, -8000), (16000, -8000), (-8000, 16000));
    // The hole: around the centre (640, 640) of pixel (2, 2), between its
    // samples (x = 624 | 656, y = 608 | 672).
    let (ha, hb, hc) = ((630, 630), (650, 630), (640, 650));
    let ring = [
        [a, b, hb],
        [a, hb, ha],
        [b, c, hc],
        [b, hc, hb],
        [c, a, ha],
        [c, ha, hc],
    ];
    s.tris = ring
        .iter()
        .enumerate()
        .map(|(k, &p)| tri(p, 0.3, k as u32))
        .collect();
    s.tris.push(tri([a, b, c], 0.8, 6));
    let p = 2 * 8 + 2;
    let mut ssaa = SupersampledZBuffer::new(SsaaOptions::default());
    let fz = render(&mut ssaa, &s).0;
    assert_eq!(fz.ids[p], 6, "the centre sees the far triangle");
    assert!(
        fz.ids
            .iter()
            .enumerate()
            .all(|(q, &id)| q == p || id != NO_ID && id < 6)
    );
    for opts in [
        lists(),
        lists().with_merge(MergePolicy::Off),
        ABufferOptions::carpenter(),
    ] {
        let mut a = ABuffer::new(opts);
        let fa = render(&mut a, &s).0;
        assert_eq!(fa.ids, fz.ids, "{opts:?}");
        assert_eq!(fa.coverage, fz.coverage, "{opts:?}");
        if opts.merge == MergePolicy::Off {
            assert_eq!(a.sample_ids(), ssaa.sample_ids());
        }
    }
}

/// A soup in front of a steep opaque wall that fills the view: the wall
/// is nearest by its nearest corner, so it is taken first in every tile
/// and closes it, while on its far side most of the soup lies in front of
/// it and must stay.
fn wall_and_soup() -> Scene {
    let mut s = procedural::random_soup(3000, 21);
    let p = |x: f64, y: f64| glam::DVec3::new(x, y, 0.6 * x);
    let corners = [p(-3.0, -3.0), p(3.0, -3.0), p(3.0, 3.0), p(-3.0, 3.0)];
    s.push_mesh(quad("wall".into(), corners), None);
    s
}

/// The tile's opaque bound rejects whole (triangle, tile) pairs once every
/// pixel of a tile has a bound, and changes no sample: behind the stack
/// of squares, on deep soups and behind large piercing triangles, the same
/// samples, coverage and ids as without culling, and as the 32-sample
/// z-buffer.
#[test]
fn tile_bound_rejects_hidden_triangles_and_changes_nothing() {
    let scenes = [
        stack_and_soup(),
        wall_and_soup(),
        procedural::random_soup(4000, 9),
        big_triangles(40, 2000, 3),
    ];
    for scene in &scenes {
        for (w, h) in SIZES {
            let s = screen(scene, w, h);
            let opts = lists().with_merge(MergePolicy::Off);
            let mut a = ABuffer::new(opts);
            let mut r = ABuffer::new(opts.with_occlusion_culling(false));
            let mut z = SupersampledZBuffer::new(SsaaOptions::default());
            let (fa, st) = render(&mut a, &s);
            let (fr, _) = render(&mut r, &s);
            let (fz, _) = render(&mut z, &s);
            assert!(st.culled_tiles <= st.culled_blocks, "{st:?}");
            assert!(a.sample_ids() == r.sample_ids(), "{w} x {h}");
            assert!(a.sample_ids() == z.sample_ids(), "{w} x {h}");
            assert!(fa.coverage == fr.coverage);
            assert!(fa.ids == fr.ids);
            assert!(fa.ids == fz.ids);
            assert!(max_color_diff(&fa, &fr) <= 1);
        }
    }
    // Tiles inside the squares or the wall close (every pixel gets a
    // bound) at this size: the triangles behind them are rejected a tile
    // at a time.
    for scene in &scenes[..2] {
        let s = screen(scene, 400, 300);
        let opts = lists().with_merge(MergePolicy::Off);
        let mut a = ABuffer::new(opts);
        let (fa, st) = render(&mut a, &s);
        let mut r = ABuffer::new(opts.with_occlusion_culling(false));
        let (fr, _) = render(&mut r, &s);
        assert!(st.culled_tiles > 20, "{st:?}");
        assert!(a.sample_ids() == r.sample_ids());
        assert!(fa.ids == fr.ids);
        assert!(max_color_diff(&fa, &fr) <= 1);
    }
}
