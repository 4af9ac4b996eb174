//! Shared helpers of the cross-validation suite: scene choice and proptest
//! configuration. Screens, cameras, references and tallies come from
//! `hider-testkit`.

#![allow(dead_code, reason = "each test binary uses a different subset")]

use hider::scene::Scene;
use hider::scene::procedural::{self, SplitMix64};
use hider_testkit::cameras::random_camera;
use hider_testkit::hard_cases;
use proptest::test_runner::{Config, FileFailurePersistence};

/// Cases per property: `PROPTEST_CASES` if set, else `default`.
pub fn cases(default: u32) -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// A proptest configuration whose shrunk failures are written to
/// `proptest-regressions/NAME.txt` (committed) and replayed first.
pub fn config(name: &'static str, default_cases: u32) -> Config {
    Config {
        cases: cases(default_cases),
        failure_persistence: Some(Box::new(FileFailurePersistence::Direct(name))),
        ..Config::default()
    }
}

/// Number of scene kinds [`scene`] can build: every hard case plus random
/// soups under random cameras.
pub fn scene_kinds() -> usize {
    hard_cases::all(0).len() + 1
}

/// The scene of kind `kind` (see [`scene_kinds`]) for `seed`, with its name.
/// The last kind is a random soup of 1 to 120 triangles seen from a random
/// perspective or orthographic camera.
pub fn scene(kind: usize, seed: u64) -> (String, Scene) {
    let cases = hard_cases::all(seed);
    if kind < cases.len() {
        let (name, scene) = cases.into_iter().nth(kind).unwrap();
        return (name.to_owned(), scene);
    }
    let mut rng = SplitMix64::new(seed ^ 0x5eed);
    let count = 1 + (rng.next_u64() % 120) as u32;
    let mut scene = procedural::random_soup(count, seed);
    scene.camera = Some(random_camera(&scene, &mut rng));
    (format!("random_soup({count}, {seed})"), scene)
}
