//! Watertightness: closed meshes under arbitrary cameras, counted with the
//! shared edge functions.
//!
//! Along any ray a closed, consistently wound mesh is entered as often as
//! it is left, so at every pixel centre the front-facing hits equal the
//! back-facing hits; for a convex mesh both are exactly 1 inside the
//! silhouette. A crack shows as a pixel with unequal counts, a double hit
//! (an edge or vertex owned by two triangles) as a count of 2 on a convex
//! mesh. The fill rule must make this hold *exactly*, including for
//! samples on shared edges and vertices, at every sub-pixel offset.

mod common;

use common::config;
use hider::scene::procedural::SplitMix64;
use hider::scene::{Scene, ScreenScene};
use hider_testkit::cameras::random_camera;
use hider_testkit::score::Tally;
use hider_testkit::{hard_cases, screen};
use proptest::prelude::*;
use proptest::test_runner::TestRunner;

/// Front- and back-facing hits per pixel centre.
fn hits(s: &ScreenScene) -> (Vec<u32>, Vec<u32>) {
    let (w, h) = (s.viewport.width as usize, s.viewport.height as usize);
    let mut front = vec![0; w * h];
    let mut back = vec![0; w * h];
    for t in &s.tris {
        let hits = if t.front_facing {
            &mut front
        } else {
            &mut back
        };
        t.for_each_centre(s.viewport, |i, j, covered| {
            if covered {
                hits[j as usize * w + i as usize] += 1;
            }
        });
    }
    (front, back)
}

fn check(
    name: &str,
    scene: &Scene,
    convex: bool,
    size: u32,
    tally: &Tally,
) -> Result<(), TestCaseError> {
    let s = screen(scene, size, size);
    prop_assert_eq!(s.stats.clipped, 0, "{}: the mesh must not be clipped", name);
    let (front, back) = hits(&s);
    let mut inside = 0;
    for (k, (&f, &b)) in front.iter().zip(&back).enumerate() {
        let (x, y) = (k as u32 % size, k as u32 / size);
        prop_assert_eq!(
            f,
            b,
            "{}: pixel ({}, {}) has {} front and {} back hits",
            name,
            x,
            y,
            f,
            b
        );
        if convex {
            prop_assert!(f <= 1, "{}: pixel ({}, {}) hit {} times", name, x, y, f);
        }
        inside += u64::from(f > 0);
    }
    Tally::add(&tally.pixels, front.len() as u64);
    Tally::add(&tally.covered, inside);
    Ok(())
}

#[test]
fn closed_meshes_are_watertight_from_every_side() {
    let tally = Tally::default();
    let meshes = hard_cases::closed_meshes(5);
    let mut runner = TestRunner::new(config("proptest-regressions/watertight.txt", 128));
    let strategy = (0..meshes.len(), any::<u64>(), 8u32..64);
    runner
        .run(&strategy, |(m, seed, size)| {
            Tally::add(&tally.cases, 1);
            let (name, mesh, convex) = &meshes[m];
            let mut scene = mesh.clone();
            let mut rng = SplitMix64::new(seed);
            let mut camera = random_camera(&scene, &mut rng);
            // Keep the whole mesh well inside near and far (no clipping).
            if let hider::geom::Projection::Perspective { near, far, .. } = &mut camera.projection {
                *near = near.min(0.1);
                *far = far.max(100.0);
            }
            scene.camera = Some(camera);
            check(name, &scene, *convex, size, &tally)
        })
        .unwrap();
    tally.report("watertightness");
}

/// An open, planar fan: seen nearly edge-on, snapping can fold triangles
/// thinner than the 1/256-pixel grid over each other (a centre may then be
/// hit by a front and a back face), but the winding number, front hits
/// minus back hits, is what a crack or a double hit would change: it must
/// be 0 or the same ±1 at every centre.
#[test]
fn an_open_fan_has_winding_zero_or_one_everywhere() {
    let tally = Tally::default();
    let mut runner = TestRunner::new(config("proptest-regressions/watertight-fan.txt", 64));
    runner
        .run(
            &(3u32..64, any::<u64>(), 8u32..64),
            |(segments, seed, size)| {
                let mut scene = hard_cases::fan(segments, seed);
                scene.camera = Some(random_camera(&scene, &mut SplitMix64::new(seed)));
                let s = screen(&scene, size, size);
                let (front, back) = hits(&s);
                let windings: Vec<i64> = front
                    .iter()
                    .zip(&back)
                    .map(|(&f, &b)| i64::from(f) - i64::from(b))
                    .collect();
                let sign = windings
                    .iter()
                    .copied()
                    .find(|&w| w != 0)
                    .unwrap_or(1)
                    .signum();
                for (k, &w) in windings.iter().enumerate() {
                    prop_assert!(
                        w == 0 || w == sign,
                        "pixel {}: winding {} ({} front, {} back)",
                        k,
                        w,
                        front[k],
                        back[k]
                    );
                }
                Tally::add(&tally.cases, 1);
                Tally::add(
                    &tally.covered,
                    windings.iter().filter(|&&w| w != 0).count() as u64,
                );
                Ok(())
            },
        )
        .unwrap();
    tally.report("fan");
}
