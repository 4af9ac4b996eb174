//! The memory bound, the overflow policy, culling, merging and reuse.

use glam::DVec3;
use hider_abuffer::{
    ABuffer, ABufferOptions, MergePolicy, OverflowPolicy, SortedTransparencyZBuffer, SsaaOptions,
    SupersampledZBuffer,
};
use hider_scene::{Error, Frame, Hider, HiderStats, Mesh, Scene, procedural};
use hider_testkit::{render, screen};

use crate::common::{lists, max_color_diff};

#[test]
fn pixel_table_over_budget_is_refused_before_allocating() {
    let s = screen(&procedural::cube(), 64, 64);
    let mut a = ABuffer::new(lists().with_max_bytes(1000));
    let mut f = Frame::new(64, 64).unwrap();
    let e = a.render(&s, &mut f).unwrap_err();
    assert!(
        matches!(
            e,
            Error::Budget {
                value: 65_536,
                limit: 1000,
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn fragment_pool_over_budget_is_a_limit_error() {
    let s = screen(&procedural::random_soup(200, 1), 64, 64);
    let budget = 64 * 64 * 16 + 100 * 184;
    let mut a = ABuffer::new(lists().with_max_bytes(budget));
    let mut f = Frame::new(64, 64).unwrap();
    let e = a.render(&s, &mut f).unwrap_err();
    assert!(
        matches!(e, Error::Budget { limit, .. } if limit == budget),
        "{e}"
    );
    // Within budget the same hider renders, and stays within it.
    let full = lists();
    let mut a = ABuffer::new(full);
    let st = a.render(&s, &mut f).unwrap();
    assert!(st.bytes > budget && st.bytes <= full.max_bytes);
}

#[test]
fn list_overflow_errors_or_drops_the_farthest() {
    // A translucent soup: nothing can be culled or pruned.
    let scene = crate::common::with_opacity(procedural::random_soup(300, 4), 0.5);
    let s = screen(&scene, 32, 32);
    let unbounded = ABuffer::new(lists());
    let mut probe = unbounded.clone();
    let longest = render(&mut probe, &s).1.max_list_len as u32;
    assert!(longest > 4, "{longest}");

    let limited = lists().with_max_list_len(4);
    let mut a = ABuffer::new(limited.with_overflow(OverflowPolicy::Error));
    let mut f = Frame::new(32, 32).unwrap();
    let e = a.render(&s, &mut f).unwrap_err().to_string();
    assert!(e.contains("max_list_len") && e.contains("pixel ("), "{e}");

    let mut a = ABuffer::new(limited);
    let st = render(&mut a, &s).1;
    assert!(st.dropped > 0 && st.max_list_len == 4, "{st:?}");
}

/// Twenty opaque unit squares stacked along the view axis, each as two
/// triangles; nearer squares look bigger and hide the farther ones.
fn stack(back_to_front: bool) -> Scene {
    let mut s = Scene::default();
    // Layer 0 (z = 0) is the nearest to the camera on +z.
    let mut layers: Vec<u32> = (0..20).collect();
    if back_to_front {
        layers.reverse();
    }
    for k in layers {
        let z = -0.1 * f64::from(k);
        let p = |x: f64, y: f64| DVec3::new(x, y, z);
        s.push_mesh(
            Mesh {
                name: format!("layer {k}"),
                positions: vec![p(-0.5, -0.5), p(0.5, -0.5), p(0.5, 0.5), p(-0.5, 0.5)],
                indices: vec![[0, 1, 2], [0, 2, 3]],
                ..Mesh::default()
            },
            None,
        );
    }
    s
}

#[test]
fn opaque_layers_fit_short_lists_exactly() {
    for back_to_front in [true, false] {
        // In submission order (layers arriving back to front are pruned,
        // front to back culled), and in the default front-to-back order
        // (culled whatever the submission order).
        for sorted in [false, true] {
            let s = screen(&stack(back_to_front), 48, 48);
            let full = render(&mut ABuffer::new(lists()), &s).0;
            let limited = lists()
                .with_max_list_len(3)
                .with_overflow(OverflowPolicy::Error);
            let mut a = ABuffer::new(limited.with_front_to_back(sorted));
            let (small, st) = render(&mut a, &s);
            assert_eq!(st.dropped, 0);
            assert!(max_color_diff(&full, &small) <= 1);
            assert_eq!(full.ids, small.ids);
            assert_eq!(full.coverage, small.coverage);
            if back_to_front && !sorted {
                assert!(st.pruned > 0, "{st:?}");
            } else {
                assert!(st.culled > 0, "{st:?}");
            }
        }
    }
}

#[test]
fn merging_saves_fragments_on_planar_quads() {
    let s = screen(&procedural::cube(), 64, 64);
    let mut on = ABuffer::new(lists());
    let mut off = ABuffer::new(lists().with_merge(MergePolicy::Off));
    let (a, on_stats) = render(&mut on, &s);
    let (b, off_stats) = render(&mut off, &s);
    assert!(on_stats.merged > 0, "{on_stats:?}");
    assert!(on_stats.mean_list_len < off_stats.mean_list_len);
    assert!(max_color_diff(&a, &b) <= 1);
    assert_eq!(a.coverage, b.coverage);
    // Carpenter's policy merges across shading differences too.
    let mut surface = ABuffer::new(ABufferOptions::carpenter());
    let (_, surface_stats) = render(&mut surface, &screen(&procedural::uv_sphere(24), 64, 64));
    assert!(surface_stats.merged > 0);
}

#[test]
fn scratch_memory_is_reused_across_frames_and_sizes() {
    let big = screen(&procedural::uv_sphere(12), 48, 48);
    let small = screen(&procedural::cube(), 16, 24);
    let mut a = ABuffer::new(lists());
    let first = render(&mut a, &small).0;
    render(&mut a, &big);
    let again = render(&mut a, &small).0;
    assert_eq!(first, again);
    let mut wrong = Frame::new(10, 10).unwrap();
    assert!(matches!(
        a.render(&small, &mut wrong),
        Err(Error::Render { .. })
    ));
}

#[test]
fn stats_add_up() {
    let s = screen(&procedural::uv_sphere(12), 40, 40);
    let mut a = ABuffer::new(lists());
    let st = a.render(&s, &mut Frame::new(40, 40).unwrap()).unwrap();
    let table = st.table();
    let fragments = table.counters.iter().find(|(name, _)| *name == "fragments");
    assert_eq!(fragments.map(|c| c.1), Some(st.fragments));
    assert!(st.full_coverage > 0 && st.full_coverage < st.fragments);
    // Every fragment was merged, culled, or took a slot (some later pruned).
    assert!(st.merged + st.culled + st.pool_fragments <= st.fragments);
    assert!(st.mean_list_len >= 1.0 && st.max_list_len as f64 >= st.mean_list_len);
    assert_eq!(table.peak_bytes, st.bytes);
}

#[test]
fn check_size_refuses_what_render_refuses_before_a_frame_exists() {
    // `Hider::check_size` is the size's part of each budget: the same error
    // as `render` at that size, from the size alone, so that a caller can
    // refuse before allocating the frame; a size within budget passes.
    let s = screen(&procedural::cube(), 64, 64);
    let ssaa = SsaaOptions::default().with_max_bytes(20_000);
    type Dyn = dyn hider_scene::DynHider;
    let hiders: Vec<Box<Dyn>> = vec![
        Box::new(ABuffer::new(lists().with_max_bytes(1000))),
        Box::new(SupersampledZBuffer::new(ssaa)),
        Box::new(SortedTransparencyZBuffer::new(ssaa)),
    ];
    for mut hider in hiders {
        let name = Dyn::name(&*hider).to_owned();
        let refused = Dyn::check_size(&*hider, 64, 64).unwrap_err();
        assert!(matches!(refused, Error::Budget { .. }), "{refused}");
        let mut frame = Frame::new(64, 64).unwrap();
        let rendered = Dyn::render(&mut *hider, &s, &mut frame).unwrap_err();
        assert_eq!(refused.to_string(), rendered.to_string(), "{name}");
        Dyn::check_size(&*hider, 4, 4).unwrap();
        let small = screen(&procedural::cube(), 4, 4);
        Dyn::render(&mut *hider, &small, &mut Frame::new(4, 4).unwrap()).unwrap();
    }
}
