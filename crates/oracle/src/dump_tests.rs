//! The oracle's id and depth dumps agree: at every covered pixel centre
//! the depth dump is the window depth of the reported primitive, and no
//! other covering primitive is nearer (nor equally near with a lower id).

use std::cmp::Ordering;

use hider_geom::fixed::pixel_center;
use hider_scene::procedural::{self, SplitMix64};
use hider_scene::{NO_ID, Scene, ScreenScene};
use hider_testkit::cameras::random_camera;
use hider_testkit::{hard_cases, screen};
use proptest::prelude::*;

use crate::exact::{DepthAt, compare};
use crate::{RayCastOracle, Reference};

/// Checks the dumps of `r` against `s` pixel by pixel.
fn dumps_agree(s: &ScreenScene, r: &Reference) -> Result<(), TestCaseError> {
    let w = s.viewport.width as usize;
    for (k, &id) in r.ids.iter().enumerate() {
        let (i, j) = ((k % w) as i32, (k / w) as i32);
        let (x, y) = (i64::from(pixel_center(i)), i64::from(pixel_center(j)));
        let covering: Vec<_> = s
            .tris
            .iter()
            .filter(|t| t.edges().iter().all(|e| e.contains(x, y)))
            .map(|t| (t.prim, DepthAt::new(t, x, y)))
            .collect();
        if id == NO_ID {
            prop_assert!(covering.is_empty(), "pixel {k}: background over a triangle");
            prop_assert_eq!(r.depth[k], 1.0);
            continue;
        }
        // The reported primitive's nearest piece.
        let winner = covering
            .iter()
            .filter(|(p, _)| *p == id)
            .min_by(|a, b| compare(&a.1, &b.1))
            .map(|(_, d)| *d);
        prop_assert!(winner.is_some(), "pixel {k}: id {id} does not cover it");
        let winner = winner.unwrap();
        prop_assert_eq!(
            r.depth[k],
            winner.estimate.clamp(0.0, 1.0) as f32,
            "pixel {}: the depth dump is not the reported surface's",
            k
        );
        let mut tied = false;
        for (p, d) in covering.iter().filter(|(p, _)| *p != id) {
            match compare(d, &winner) {
                Ordering::Less => {
                    return Err(TestCaseError::fail(format!(
                        "pixel {k}: primitive {p} is nearer than the reported {id}"
                    )));
                }
                Ordering::Equal => {
                    prop_assert!(id < *p, "pixel {}: tie not won by the lower id", k);
                    tied = true;
                }
                Ordering::Greater => {}
            }
            // Nothing nearer in the dump either.
            prop_assert!(d.estimate.clamp(0.0, 1.0) as f32 >= r.depth[k] || tied);
        }
        prop_assert_eq!(tied, r.is_exact_tie(k), "pixel {}: tie flag", k);
        if tied {
            prop_assert!(r.is_tie(k));
        }
        prop_assert!(r.gap[k] >= 0.0 && r.window_gap[k] >= 0.0);
    }
    Ok(())
}

fn scene_of(kind: u8, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    match kind % 4 {
        0 => {
            let mut s = procedural::random_soup(1 + (seed % 80) as u32, seed);
            s.camera = Some(random_camera(&s, &mut rng));
            s
        }
        1 => {
            let exponent = 4 + (seed % 6) as i32;
            hard_cases::parallel_layers(
                2 + (seed % 3) as u32,
                12.7,
                10f64.powi(-exponent),
                (6.35, 31.8),
                45.0,
                seed,
            )
        }
        2 => hard_cases::parallel_layers(3, 1e4, 5e-6, (9990.0, 10010.0), 30.0, seed),
        _ => hard_cases::coplanar_overlaps(2 + (seed % 6) as u32, seed),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]
    #[test]
    fn id_and_depth_dumps_agree(kind in any::<u8>(), seed in any::<u64>(), size in 4u32..40) {
        let s = screen(&scene_of(kind, seed), size, size);
        let r = RayCastOracle::default().evaluate(&s);
        dumps_agree(&s, &r)?;
    }
}

#[test]
fn dumps_agree_on_every_hard_case() {
    for (name, scene) in hard_cases::all(3) {
        let s = screen(&scene, 40, 40);
        let r = RayCastOracle::default().evaluate(&s);
        dumps_agree(&s, &r).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}
