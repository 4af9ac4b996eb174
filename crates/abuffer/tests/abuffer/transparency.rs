//! Order-independent transparency, and what sorting by triangle gets wrong.

use hider_abuffer::{
    ABuffer, ABufferOptions, MergePolicy, SamplePattern, SortedTransparencyZBuffer, SsaaOptions,
};
use hider_scene::{Hider, procedural};
use hider_testkit::{render, screen};
use proptest::prelude::*;

use crate::common::{
    DEPTH_MODES, brute_force_colors, max_color_diff, max_diff_to, same_image, three_glass,
    with_opacity,
};

const ORDERS: [[usize; 3]; 6] = [
    [0, 1, 2],
    [0, 2, 1],
    [1, 0, 2],
    [1, 2, 0],
    [2, 0, 1],
    [2, 1, 0],
];

/// Order independence: three overlapping translucent triangles submitted in
/// all 6 orders give the same image within 1/255, in every depth mode.
#[test]
fn three_translucent_triangles_in_all_six_orders() {
    for depth in DEPTH_MODES {
        let opts = ABufferOptions::default().with_depth(depth);
        let first = render(
            &mut ABuffer::new(opts),
            &screen(&three_glass(ORDERS[0]), 64, 64),
        )
        .0;
        assert!(first.coverage.iter().any(|&c| c > 0.0 && c < 1.0));
        for order in &ORDERS[1..] {
            let f = render(
                &mut ABuffer::new(opts),
                &screen(&three_glass(*order), 64, 64),
            )
            .0;
            assert!(max_color_diff(&first, &f) <= 1, "{depth:?} order {order:?}");
            assert_eq!(first.coverage, f.coverage);
        }
    }
}

/// Per-sample compositing equals an independent brute-force per-sample
/// reference on the translucent triangles (which pierce each other).
#[test]
fn per_sample_transparency_matches_brute_force() {
    for pattern in [
        SamplePattern::Centre,
        SamplePattern::Grid8,
        SamplePattern::Grid32,
    ] {
        let s = screen(&three_glass([2, 0, 1]), 48, 48);
        let f = render(
            &mut ABuffer::new(ABufferOptions::default().with_pattern(pattern)),
            &s,
        )
        .0;
        assert!(
            max_diff_to(&f, &brute_force_colors(&s, pattern)) <= 1,
            "{pattern:?}"
        );
    }
}

/// The sorted-transparency z-buffer is right when translucent triangles
/// are separated in depth, and wrong where they pierce each other.
#[test]
fn sorted_transparency_fails_where_triangles_intersect() {
    let s = screen(&with_opacity(procedural::intersecting_pair(), 0.5), 48, 48);
    let reference = brute_force_colors(&s, SamplePattern::Grid32);
    let sorted = render(
        &mut SortedTransparencyZBuffer::new(SsaaOptions::default()),
        &s,
    )
    .0;
    let a = render(&mut ABuffer::new(ABufferOptions::default()), &s).0;
    assert!(max_diff_to(&a, &reference) <= 1);
    assert!(
        max_diff_to(&sorted, &reference) > 20,
        "sorting by triangle should fail here"
    );
    // Coverage and ids do not depend on the blend order.
    assert_eq!(sorted.coverage, a.coverage);
    assert_eq!(sorted.ids, a.ids);

    // Opaque scenes: the sorted z-buffer is an ordinary supersampled one.
    let s = screen(&procedural::cyclic_triple(), 48, 48);
    let sorted = render(
        &mut SortedTransparencyZBuffer::new(SsaaOptions::default()),
        &s,
    )
    .0;
    assert!(max_diff_to(&sorted, &brute_force_colors(&s, SamplePattern::Grid32)) <= 1);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]

    /// Shuffling the submission order of a translucent soup does not change
    /// the A-buffer's image (any merge policy), coverage or ids.
    #[test]
    fn shuffled_submission_gives_the_same_image(
        count in 2u32..40,
        seed in any::<u64>(),
        shuffle in any::<u64>(),
        merge_index in 0usize..3,
    ) {
        let s = screen(&with_opacity(procedural::random_soup(count, seed), 0.45), 32, 32);
        let mut shuffled = s.clone();
        let mut rng = hider_scene::procedural::SplitMix64::new(shuffle);
        for k in (1..shuffled.tris.len()).rev() {
            let j = (rng.next_u64() % (k as u64 + 1)) as usize;
            shuffled.tris.swap(k, j);
        }
        let merge = [MergePolicy::Off, MergePolicy::SameColor, MergePolicy::SameSurface][merge_index];
        let opts = ABufferOptions::default().with_merge(merge);
        let a = render(&mut ABuffer::new(opts), &s).0;
        let b = render(&mut ABuffer::new(opts), &shuffled).0;
        same_image(&a, &b)?;
    }
}
