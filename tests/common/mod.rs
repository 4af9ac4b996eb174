//! Shared helpers of the cross-validation suite: scene choice, random
//! cameras, proptest configuration and the tallies the suite prints.

#![allow(dead_code)] // each test binary uses a different subset

use std::sync::atomic::{AtomicU64, Ordering};

use hider::geom::glam::DVec3;
use hider::geom::{Camera, Projection};
use hider::scene::hard_cases;
use hider::scene::procedural::{self, SplitMix64};
use hider::scene::{PrepareOptions, Scene, ScreenScene, View, prepare};
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

/// A camera looking at the scene's bounding-box centre from a random
/// direction at 2.5 to 6 radii, with a random up vector and a target
/// jittered by a few per cent (sub-pixel to pixel-sized shifts); one time
/// in four orthographic. The whole scene stays between near and far.
pub fn random_camera(scene: &Scene, rng: &mut SplitMix64) -> Camera {
    let (lo, hi) = scene.bounds().unwrap_or((DVec3::ZERO, DVec3::ZERO));
    let centre = (lo + hi) * 0.5;
    let r = ((hi - lo).length() * 0.5).max(1e-3);
    let dir = unit(rng);
    let mut up = unit(rng);
    if dir.cross(up).length() < 0.1 {
        up = dir.any_orthonormal_vector();
    }
    let dist = r * rng.range(2.5, 6.0);
    let target = centre + unit(rng) * (r * rng.range(0.0, 0.05));
    let projection = if rng.next_u64() % 4 == 0 {
        Projection::Orthographic {
            half_height: r * rng.range(0.8, 1.5),
            near: 0.1 * r,
            far: dist + 2.0 * r,
        }
    } else {
        Projection::Perspective {
            fovy_degrees: rng.range(30.0, 75.0),
            near: r * rng.range(0.05, 0.5),
            far: dist + r * rng.range(2.0, 50.0),
        }
    };
    Camera {
        eye: target + dir * dist,
        target,
        up,
        projection,
    }
}

fn unit(rng: &mut SplitMix64) -> DVec3 {
    loop {
        let v = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        if (1e-4..=1.0).contains(&v.length_squared()) {
            return v.normalize();
        }
    }
}

/// Prepares `scene` at `size x size` with the default (accurate) options.
pub fn screen(scene: &Scene, size: u32) -> ScreenScene {
    let view = View::for_scene(scene, size, size).expect("generated scenes have valid cameras");
    prepare(scene, &view, &PrepareOptions::default()).expect("generated scenes prepare")
}

/// Counters accumulated over a property's cases and printed at its end.
#[derive(Default)]
pub struct Tally {
    pub cases: AtomicU64,
    pub frames: AtomicU64,
    pub pixels: AtomicU64,
    pub covered: AtomicU64,
    pub ties: AtomicU64,
    pub tie_differences: AtomicU64,
}

impl Tally {
    pub fn add(counter: &AtomicU64, v: u64) {
        counter.fetch_add(v, Ordering::Relaxed);
    }

    pub fn report(&self, property: &str) {
        let g = |c: &AtomicU64| c.load(Ordering::Relaxed);
        eprintln!(
            "{property}: {} cases, {} frames, {} pixels ({} covered), {} tie pixels ({} where a hider chose another id), 0 failures",
            g(&self.cases),
            g(&self.frames),
            g(&self.pixels),
            g(&self.covered),
            g(&self.ties),
            g(&self.tie_differences)
        );
    }
}
