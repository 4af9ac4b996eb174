//! The A-buffer against the supersampled z-buffer (same samples) and the
//! pixel-centre oracle.

use hider_abuffer::{
    ABuffer, ABufferOptions, MergePolicy, SamplePattern, SsaaOptions, SupersampledZBuffer,
};
use hider_oracle::DEFAULT_TIE_TOLERANCE;
use hider_scene::{Hider, procedural};
use hider_testkit::{hard_cases, reference, render, screen};
use proptest::prelude::*;

use crate::common::{DEPTH_MODES, equals_supersampling, max_color_diff, same_image};

/// A few procedural scenes and every hard case.
fn hard_scenes() -> Vec<hider_scene::Scene> {
    let mut scenes = vec![
        procedural::cube(),
        procedural::intersecting_pair(),
        procedural::cyclic_triple(),
        procedural::coplanar_pair(),
        procedural::uv_sphere(12),
    ];
    scenes.extend(hard_cases::all(7).into_iter().map(|(_, s)| s));
    scenes
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// With per-sample depth and merging off, every sample's front-most
    /// primitive equals the supersampled z-buffer's, for every pattern;
    /// coverage and centre ids are identical and colours agree to the
    /// 8-bit step.
    #[test]
    fn per_sample_abuffer_equals_supersampling(
        count in 1u32..60,
        seed in any::<u64>(),
        pattern_index in 0usize..5,
    ) {
        let s = screen(&procedural::random_soup(count, seed), 32, 32);
        let pattern = SamplePattern::ALL[pattern_index];
        let mut a = ABuffer::new(
            ABufferOptions::default().with_pattern(pattern).with_merge(MergePolicy::Off),
        );
        let fa = render(&mut a, &s).0;
        let fz = equals_supersampling(&s, SsaaOptions::default().with_pattern(pattern), &a, &fa)?;
        prop_assert!(max_color_diff(&fa, &fz) <= 1);
    }

    /// The default A-buffer (exact same-colour merging) gives the same
    /// image, coverage and ids as with merging off.
    #[test]
    fn same_color_merging_changes_nothing(count in 1u32..60, seed in any::<u64>()) {
        let s = screen(&procedural::random_soup(count, seed), 32, 32);
        let fa = render(&mut ABuffer::new(ABufferOptions::default()), &s).0;
        let fo = render(&mut ABuffer::new(ABufferOptions::default().with_merge(MergePolicy::Off)), &s).0;
        same_image(&fa, &fo)?;
    }
}

#[test]
fn thirty_two_samples_equal_the_32_sample_zbuffer_on_hard_cases() {
    for scene in hard_scenes() {
        let s = screen(&scene, 48, 40);
        let mut a = ABuffer::new(ABufferOptions::default().with_merge(MergePolicy::Off));
        let mut z = SupersampledZBuffer::new(SsaaOptions::default());
        let fa = render(&mut a, &s).0;
        let fz = render(&mut z, &s).0;
        assert_eq!(a.sample_ids(), z.sample_ids());
        assert_eq!(fa.coverage, fz.coverage);
        assert!(max_color_diff(&fa, &fz) <= 1);
        // With merging on, the image is the same too.
        let fm = render(&mut ABuffer::new(ABufferOptions::default()), &s).0;
        assert!(max_color_diff(&fm, &fz) <= 1);
        assert_eq!(fm.coverage, fz.coverage);
    }
}

/// Ids and depth are the front-most surface at the pixel centre: the
/// oracle's answer on every non-tie pixel with identical coverage, in every
/// depth mode and pattern (they do not depend on the masks).
#[test]
fn centre_ids_equal_the_oracle() {
    let mut scenes = hard_scenes();
    scenes.push(procedural::random_soup(80, 3));
    for scene in scenes {
        let s = screen(&scene, 40, 40);
        let reference = reference::ray_cast(&s);
        for (k, pattern) in SamplePattern::ALL.into_iter().enumerate() {
            let depth = DEPTH_MODES[k % 3];
            let opts = ABufferOptions::default()
                .with_pattern(pattern)
                .with_depth(depth);
            let f = render(&mut ABuffer::new(opts), &s).0;
            let agreement = reference.compare(&f.ids, DEFAULT_TIE_TOLERANCE);
            assert!(agreement.is_exact(), "{pattern:?} {depth:?}: {agreement:?}");
            let centre_cover = f.ids.iter().filter(|&&id| id != hider_scene::NO_ID).count();
            assert_eq!(centre_cover, reference.covered_count());
        }
    }
}

/// Reduced to the pixel-centre sample, the A-buffer is a pixel-centre
/// z-buffer: one sample, coverage 0 or 1 exactly where the centre is
/// covered, the sample's primitive is the reported id.
#[test]
fn centre_pattern_is_the_pixel_centre_zbuffer() {
    let s = screen(&procedural::random_soup(120, 11), 40, 40);
    let mut a = ABuffer::new(
        ABufferOptions::default()
            .with_pattern(SamplePattern::Centre)
            .with_merge(MergePolicy::Off),
    );
    let f = render(&mut a, &s).0;
    assert_eq!(a.sample_ids(), f.ids);
    for (c, id) in f.coverage.iter().zip(&f.ids) {
        assert_eq!(*c, if *id == hider_scene::NO_ID { 0.0 } else { 1.0 });
    }
    let reference = reference::ray_cast(&s);
    assert!(reference.compare(&f.ids, DEFAULT_TIE_TOLERANCE).is_exact());
}
