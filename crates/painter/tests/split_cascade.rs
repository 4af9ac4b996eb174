//! Mirrored pinwheels behind tiny near planes (the differential fuzzing's
//! split-budget finding). Behind a near plane of `1e-6` or less every
//! window depth is all but 1 and the scene's depth differences sit in its
//! last bits. The line along which two depth planes meet must then be set
//! up with its offset rounded relative to those differences, as the side
//! test rounds them: rounded at the scale of the depths it lands micro-
//! pixels to pixels away, a vertex the side test calls strictly in front
//! stays on the far side of the cut, each cut shaves off a sliver of no
//! area, and the same pair is cut again until the split budget runs out
//! (after seconds to minutes at the default budget). These cases must
//! finish with a few dozen splits and equal the oracle off ties.

use hider_geom::Camera;
use hider_oracle::DEFAULT_TIE_TOLERANCE;
use hider_painter::{Painter, PainterOptions};
use hider_scene::{Frame, Hider, PrepareOptions, Scene, View, prepare};
use hider_testkit::{cameras, hard_cases, reference};

/// A split budget well above what these cases need and far below the
/// default, so that a cascade fails at once instead of running for
/// seconds.
const BUDGET: u64 = 2_000;

/// The most splits any of these cases may use.
const MAX_SPLITS: u64 = 200;

/// Renders the scene with the Newell painter and returns its splits and
/// its wrong ids off ties against the oracle's ray cast, or its refusal.
fn splits_and_wrong(
    scene: &Scene,
    camera: Camera,
    (w, h): (u32, u32),
) -> Result<(u64, u64), String> {
    let view = View::new(camera, w, h).unwrap();
    let screen = prepare(scene, &view, &PrepareOptions::default()).unwrap();
    let mut frame = Frame::new(w, h).unwrap();
    let stats = Painter::new(PainterOptions::default().with_max_splits(BUDGET))
        .render(&screen, &mut frame)
        .map_err(|e| e.to_string())?;
    let cmp = reference::ray_cast(&screen).compare_strict(&frame.ids, DEFAULT_TIE_TOLERANCE);
    assert_eq!(cmp.coverage_mismatches, 0, "{cmp}");
    Ok((stats.splits, cmp.wrong_ids))
}

#[test]
fn mirrored_pinwheel_behind_a_near_plane_of_1e_7_needs_few_splits() {
    let scene = hard_cases::pinwheel(3, true, 0);
    let (splits, wrong) =
        splits_and_wrong(&scene, cameras::pinwheel_camera(1e-7), (64, 64)).unwrap();
    assert!(splits <= MAX_SPLITS, "{splits} splits");
    assert_eq!(wrong, 0);
}

#[test]
fn mirrored_pinwheels_behind_tiny_near_planes_need_few_splits() {
    let mut failures = Vec::new();
    for order in 2..=6 {
        for bits in [0, 1, 2, 3, 6, 8] {
            for near in [1e-6, 1e-7, 1e-9, 1e-12] {
                let scene = hard_cases::pinwheel(order, true, bits);
                match splits_and_wrong(&scene, cameras::pinwheel_camera(near), (64, 64)) {
                    Ok((splits, wrong)) if splits <= MAX_SPLITS && wrong == 0 => {}
                    Ok((splits, wrong)) => failures.push(format!(
                        "order {order} bits {bits} near {near:e}: {splits} splits, {wrong} wrong"
                    )),
                    Err(e) => {
                        failures.push(format!("order {order} bits {bits} near {near:e}: {e}"))
                    }
                }
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
