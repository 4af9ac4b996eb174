//! Scenes that test numeric precision: exact depth ties, layers too close
//! for a far depth buffer, near-plane crossings, huge depth ranges and
//! huge world coordinates.

use glam::{DQuat, DVec3};
use hider_scene::Scene;
use hider_scene::procedural::SplitMix64;

use super::support::{colour, push, random_unit, triangle_around};
use crate::cameras::look_at;

/// `count` triangles lying in one plane (`z = 0`), overlapping: every
/// overlap is an exact depth tie (z-fighting), decided by the tie rule
/// alone. The camera looks at the plane obliquely so depth varies across
/// it.
pub fn coplanar_overlaps(count: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let mut s = Scene::default();
    for k in 0..count {
        let c = DVec3::new(rng.range(-0.6, 0.6), rng.range(-0.6, 0.6), 0.0);
        let size = rng.range(0.3, 0.7);
        let t = triangle_around(&mut rng, c, DVec3::Z, size);
        // Exactly in the plane, whatever the rounding above did.
        let t = t.map(|p| DVec3::new(p.x, p.y, 0.0));
        push(
            &mut s,
            format!("coplanar_{k}"),
            t.to_vec(),
            vec![[0, 1, 2]],
            colour(k),
        );
    }
    s.camera = Some(look_at(DVec3::new(1.0, -1.5, 2.5), DVec3::ZERO, 0.1, 20.0));
    s
}

/// `layers` parallel, slightly tilted quads stacked at `distance` in front
/// of the camera, `relative_gap * distance` apart and shifted sideways so
/// they overlap partly. They are listed far to near, so a depth buffer that
/// cannot separate them (and keeps the earlier of equal depths) shows the
/// farthest layer: the wrong one. The camera has
/// `near = 1`, `far = 10 * distance`: far from the camera, window depth has
/// little resolution left.
pub fn near_coplanar_far(layers: u32, distance: f64, relative_gap: f64, seed: u64) -> Scene {
    let tilt = DQuat::from_axis_angle(DVec3::new(1.0, 0.3, 0.0).normalize(), 0.3);
    let mut s = tilted_layers(layers, distance, relative_gap, 0.35 * distance, tilt, seed);
    s.camera = Some(look_at(DVec3::ZERO, DVec3::NEG_Z, 1.0, 10.0 * distance));
    s
}

/// `layers` parallel quads, slightly tilted, stacked `relative_gap *
/// distance` apart along the view axis at `distance` in front of a camera
/// at the origin looking down -Z with `fovy_degrees` and the depth range
/// `near..far`, shifted sideways so they overlap partly and listed far to
/// near (so a tie rule of "lower id wins" shows the farthest layer where
/// a hider calls them tied). The tilt keeps every layer within the depth
/// range over the visible part of it.
///
/// The families that exposed the oracle's old tolerance-based ties:
/// telephoto views (`fovy` 30 at `distance` 1e4, near and far 10 away),
/// ordinary cameras with layers `1e-4` to `1e-9` apart, and tight depth
/// ranges. Window depth separates such layers by far more than `f64`
/// rounding, so every `f64` hider must order them as the oracle does.
///
/// ```
/// use hider_testkit::hard_cases::parallel_layers;
///
/// let s = parallel_layers(3, 1e4, 5e-6, (9990.0, 10010.0), 30.0, 1);
/// assert_eq!(s.triangle_count(), 6);
/// ```
pub fn parallel_layers(
    layers: u32,
    distance: f64,
    relative_gap: f64,
    (near, far): (f64, f64),
    fovy_degrees: f64,
    seed: u64,
) -> Scene {
    let half = distance * (0.5 * fovy_degrees).to_radians().tan();
    let size = 1.2 * half;
    // Depth varies by about `2 size tan(tilt)` across a layer: keep that
    // within a quarter of the room between the layers and near or far.
    let room = (distance - near).min(far - distance * (1.0 + relative_gap * f64::from(layers)));
    let tilt_angle = (0.25 * room / (2.0 * size)).atan().min(0.3);
    let tilt = DQuat::from_axis_angle(DVec3::new(1.0, 0.3, 0.0).normalize(), tilt_angle);
    let mut s = tilted_layers(layers, distance, relative_gap, size, tilt, seed);
    s.camera = Some(look_at(DVec3::ZERO, DVec3::NEG_Z, near, far).with_fovy_degrees(fovy_degrees));
    s
}

/// `count` triangles around a camera at the origin looking down -Z (near
/// 0.1): corners anywhere in `z ∈ [-5, 2]`, so many cross the near plane,
/// some lie partly or wholly behind the eye, and some straddle the eye
/// plane `z = 0` itself.
pub fn near_plane_crossing(count: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let mut s = Scene::default();
    for k in 0..count {
        let p = [0; 3].map(|_| {
            DVec3::new(
                rng.range(-2.0, 2.0),
                rng.range(-2.0, 2.0),
                rng.range(-5.0, 2.0),
            )
        });
        push(
            &mut s,
            format!("crossing_{k}"),
            p.to_vec(),
            vec![[0, 1, 2]],
            colour(k),
        );
    }
    s.camera = Some(look_at(DVec3::ZERO, DVec3::NEG_Z, 0.1, 100.0));
    s
}

/// `count` triangles at view distances spread log-uniformly from `1e-2` to
/// `max_distance`, each sized to its distance so all stay visible, every
/// other one paired with a twin 1% further away; the camera has
/// `near = 1e-3`, `far = 1e6`.
///
/// Window depth is `about 1 - near / d`, so its `f32` resolution (`2^-24`
/// near 1) separates the 1% twins only up to `d` of about 40, and rounds to
/// exactly 1 (the cleared depth) beyond about `3e4`. With `max_distance`
/// up to 30 every exact hider must still be exact; larger values show
/// where `f32` window depth breaks (and where reversed or `f64` depth do
/// not).
pub fn huge_depth_range(count: u32, max_distance: f64, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let mut s = Scene::default();
    let top = max_distance.max(0.02).log10();
    for k in 0..count {
        let d = 10f64.powf(rng.range(-2.0, top));
        let c = DVec3::new(rng.range(-0.3, 0.3) * d, rng.range(-0.3, 0.3) * d, -d);
        let n = (DVec3::Z + random_unit(&mut rng) * 0.5).normalize();
        let t = triangle_around(&mut rng, c, n, 0.3 * d);
        let mut positions = t.to_vec();
        let mut indices = vec![[0, 1, 2]];
        if k % 2 == 0 {
            // A twin 1% further along the view axis, shifted a little.
            let shift = DVec3::new(0.05 * d, 0.03 * d, -0.01 * d);
            positions.extend(t.map(|p| p + shift));
            indices.push([3, 4, 5]);
        }
        push(&mut s, format!("depth_{k}"), positions, indices, colour(k));
    }
    s.camera = Some(look_at(DVec3::ZERO, DVec3::NEG_Z, 1e-3, 1e6));
    s
}

/// `count` small triangles (about unit size) scattered in a box of side 4
/// around `(offset, offset, offset)` with `offset = 1e7`: world
/// coordinates whose `f32` spacing is 1, so only an `f64` transform keeps
/// them apart. The fit camera frames them.
pub fn huge_coordinates(count: u32, seed: u64, offset: f64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let mut s = Scene::default();
    let o = DVec3::splat(offset);
    for k in 0..count {
        let c = o + DVec3::new(
            rng.range(-2.0, 2.0),
            rng.range(-2.0, 2.0),
            rng.range(-2.0, 2.0),
        );
        let n = random_unit(&mut rng);
        let size = rng.range(0.3, 0.8);
        let t = triangle_around(&mut rng, c, n, size);
        push(
            &mut s,
            format!("far_{k}"),
            t.to_vec(),
            vec![[0, 1, 2]],
            colour(k),
        );
    }
    s
}

/// `layers` quads of half side `size`, turned by `tilt`, stacked
/// `relative_gap * distance` apart along -Z from `distance`, far to near,
/// each shifted within its (tilted) plane by a random fraction of `size`
/// (from `seed`), so they stay exactly that far apart along the view axis
/// and overlap partly.
fn tilted_layers(
    layers: u32,
    distance: f64,
    relative_gap: f64,
    size: f64,
    tilt: DQuat,
    seed: u64,
) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let mut s = Scene::default();
    for k in 0..layers {
        let z = -distance * (1.0 + relative_gap * f64::from(layers - 1 - k));
        let shift = tilt * DVec3::new(rng.range(-0.3, 0.3), rng.range(-0.3, 0.3), 0.0) * size;
        let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        let positions = corners
            .iter()
            .map(|&(x, y)| {
                tilt * DVec3::new(x * size, y * size, 0.0) + shift + DVec3::new(0.0, 0.0, z)
            })
            .collect();
        push(
            &mut s,
            format!("layer_{k}"),
            positions,
            vec![[0, 1, 2], [0, 2, 3]],
            colour(k),
        );
    }
    s
}
