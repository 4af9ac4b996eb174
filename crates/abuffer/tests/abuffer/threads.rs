//! Threads change nothing: bands of tiles rendered by 2, 3 or 5 threads
//! give the frame, the sample ids and the work counters of one thread,
//! bit for bit, on every hard case and on random soups, opaque and
//! translucent, in every depth mode; and one thread equals the 32-sample
//! supersampled z-buffer sample for sample.

use hider_abuffer::{ABuffer, ABufferOptions, ABufferStats, MergePolicy, SsaaOptions};
use hider_scene::{Frame, Hider, Scene, procedural};
use hider_testkit::{hard_cases, render, screen};
use proptest::prelude::*;

use crate::common::{DEPTH_MODES, assert_same_render, equals_supersampling, lists, soup};

/// Frame sizes: several bands, fewer bands than threads, partial tiles.
const SIZES: [(u32, u32); 3] = [(200, 330), (150, 90), (70, 20)];

/// Renders `scene` at every size with 1 thread and with 2, 3 and 5, and
/// asserts identical frames, sample ids and counters.
fn same_at_every_thread_count(scene: &Scene, options: ABufferOptions, what: &str) {
    for (w, h) in SIZES {
        let s = screen(scene, w, h);
        let mut one = ABuffer::new(options.with_threads(1));
        let (f1, s1): (Frame, ABufferStats) = render(&mut one, &s);
        let ids1 = one.sample_ids();
        for threads in [2, 3, 5] {
            let mut many = ABuffer::new(options.with_threads(threads));
            let (fm, sm) = render(&mut many, &s);
            let at = format!("{what} at {w}x{h}, {threads} threads");
            assert_same_render(&at, (&f1, &ids1, &s1), (&fm, &many.sample_ids(), &sm));
            // A second frame reuses the pools and bands.
            let (again, _) = render(&mut many, &s);
            assert!(f1 == again, "{at}, reused");
        }
    }
}

#[test]
fn every_hard_case_is_the_same_at_every_thread_count() {
    for (name, scene) in hard_cases::all(11) {
        same_at_every_thread_count(&scene, ABufferOptions::default(), name);
        // The exact A-buffer's lists, which the default takes only for
        // translucent tiles.
        same_at_every_thread_count(&scene, lists(), name);
        same_at_every_thread_count(&scene, ABufferOptions::carpenter(), name);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    /// Random soups, opaque or translucent, in every depth mode.
    #[test]
    fn soups_are_the_same_at_every_thread_count(
        count in 1u32..400,
        seed in any::<u64>(),
        glass in any::<bool>(),
        mode in 0usize..3,
    ) {
        let options = ABufferOptions::default().with_depth(DEPTH_MODES[mode]);
        same_at_every_thread_count(&soup(count, seed, glass), options, "soup");
    }

    /// With several threads, per-sample depth and merging off, every
    /// sample's front-most primitive is the 32-sample supersampled
    /// z-buffer's, on frames of several bands.
    #[test]
    fn threaded_abuffer_equals_supersampling(count in 1u32..300, seed in any::<u64>()) {
        let s = screen(&procedural::random_soup(count, seed), 150, 140);
        let mut a = ABuffer::new(
            ABufferOptions::default().with_merge(MergePolicy::Off).with_threads(3),
        );
        let fa = render(&mut a, &s).0;
        equals_supersampling(&s, SsaaOptions::default(), &a, &fa)?;
    }
}

/// Each thread has a pixel table of the whole frame: with a budget of four
/// tables, four threads would have no room left for fragments, so two run
/// (before this bound, the frame failed with a memory limit error).
#[test]
fn threads_are_capped_by_the_memory_bound() {
    let s = screen(&procedural::random_soup(60, 5), 64, 256);
    let table = 64 * 256 * 16;
    let options = ABufferOptions::default().with_max_bytes(4 * table);
    let (one, _) = render(&mut ABuffer::new(options.with_threads(1)), &s);
    let mut four = ABuffer::new(options.with_threads(4));
    let mut frame = Frame::new(64, 256).unwrap();
    let stats = four.render(&s, &mut frame).unwrap();
    assert!(stats.bytes <= 4 * table, "{stats:?}");
    assert!(one == frame);
}

/// A frame that held another image is overwritten everywhere, also in the
/// bands the new scene leaves empty (each band is cleared by the thread
/// that renders it, not by a pass over the whole frame first): the same
/// frame as a fresh one, at 1, 2 and 3 threads.
#[test]
fn a_reused_frame_keeps_nothing_of_the_last_image() {
    let full = procedural::random_soup(600, 4);
    // One small triangle: a single band of tiles holds anything.
    let one = procedural::random_soup(1, 8);
    for threads in [1, 2, 3] {
        let mut hider = ABuffer::new(ABufferOptions::default().with_threads(threads));
        let a = screen(&full, 150, 330);
        let b = screen(&one, 150, 330);
        let (mut frame, _) = render(&mut hider, &a);
        assert!(frame.ids.iter().any(|&id| id != hider_scene::NO_ID));
        hider.render(&b, &mut frame).expect("renders");
        let (fresh, _) = render(&mut ABuffer::new(ABufferOptions::default()), &b);
        assert_eq!(frame, fresh, "{threads} threads");
    }
}
