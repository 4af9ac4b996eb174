//! Hard cases: scenes built to break hidden-surface algorithms.
//!
//! Each generator is parameterised and deterministic (same arguments, same
//! scene, bit for bit) and returns a [`Scene`], with its own camera when the
//! fit camera would not show the difficulty. [`all`] lists one modest
//! instance of each by name, for the cross-validation suite and the
//! benchmark; [`closed_meshes`] lists the closed, consistently oriented
//! meshes the watertightness checks use.
//!
//! | case | what breaks |
//! |---|---|
//! | [`intersecting_pairs`], [`interpenetrating_boxes`] | any per-triangle depth order (painter's without splitting) |
//! | [`coplanar_overlaps`] | z-fighting: every overlap is a depth tie |
//! | [`near_coplanar_far`] | depth-buffer precision far from the camera |
//! | [`slivers`], [`near_degenerate_fan`] | area near zero, ill-conditioned planes |
//! | [`fan`], [`bipyramid`], [`torus`] (and `procedural::{cube, uv_sphere}`) | cracks and double hits on shared edges and vertices |
//! | [`near_plane_crossing`] | near-plane clipping, geometry behind the eye |
//! | [`huge_depth_range`] | `near = 1e-3`, `far = 1e6`: window-depth resolution |
//! | [`huge_coordinates`] | `1e7` world coordinates with unit-size triangles |
//! | [`cyclic_overlap`] | no depth order exists at all |
//! | [`heavy_overdraw`], `procedural::random_soup` | many layers per pixel, random interpenetration |

use glam::{DQuat, DVec3};
use hider_geom::Camera;

use crate::model::{Material, Mesh, Scene};
use crate::procedural::{self, SplitMix64};

fn push(
    scene: &mut Scene,
    name: String,
    positions: Vec<DVec3>,
    indices: Vec<[u32; 3]>,
    colour: [f32; 3],
) {
    let material = Material {
        name: name.clone(),
        diffuse: colour,
        ..Material::default()
    };
    scene.push_mesh(
        Mesh {
            name,
            positions,
            indices,
            ..Mesh::default()
        },
        Some(material),
    );
}

/// A colour from a hue-like index, so neighbouring meshes differ.
fn colour(k: u32) -> [f32; 3] {
    let t = k as f32 * 0.618_034;
    let f = |s: f32| 0.35 + 0.5 * (std::f32::consts::TAU * (t + s)).sin().abs();
    [f(0.0), f(0.33), f(0.67)]
}

/// A perspective camera (60 degree field of view) looking from `eye` at
/// `target` with +Y up.
pub fn look_at(eye: DVec3, target: DVec3, near: f64, far: f64) -> Camera {
    Camera::perspective(eye, target, near, far)
}

fn random_unit(rng: &mut SplitMix64) -> DVec3 {
    loop {
        let v = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let l = v.length_squared();
        if l > 1e-4 && l <= 1.0 {
            return v / l.sqrt();
        }
    }
}

/// A triangle with centroid `c`, in the plane with normal `n`, corners at
/// distance about `size` from the centroid.
fn triangle_around(rng: &mut SplitMix64, c: DVec3, n: DVec3, size: f64) -> [DVec3; 3] {
    let u = n.any_orthonormal_vector();
    let v = n.cross(u);
    let a0 = rng.range(0.0, std::f64::consts::TAU);
    let mut p = [DVec3::ZERO; 3];
    for (k, q) in p.iter_mut().enumerate() {
        let a = a0 + std::f64::consts::TAU * k as f64 / 3.0 + rng.range(-0.4, 0.4);
        let r = size * rng.range(0.7, 1.3);
        *q = u * (r * a.cos()) + v * (r * a.sin());
    }
    // Move the centroid onto c exactly (up to rounding).
    let g = (p[0] + p[1] + p[2]) / 3.0;
    p.map(|q| q - g + c)
}

/// `count` pairs of triangles that pierce each other: both triangles of a
/// pair have their centroid at the same point but different planes, so
/// they cross along a line through it. No per-triangle depth order is
/// right for both halves of either triangle.
pub fn intersecting_pairs(count: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let mut s = Scene::default();
    for k in 0..count {
        let c = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-0.5, 0.5),
        );
        let size = rng.range(0.3, 0.6);
        let na = random_unit(&mut rng);
        let nb = (random_unit(&mut rng) + na * -0.5).normalize();
        let a = triangle_around(&mut rng, c, na, size);
        let b = triangle_around(&mut rng, c, nb, size);
        let positions = [a, b].concat();
        push(
            &mut s,
            format!("pair_{k}"),
            positions,
            vec![[0, 1, 2], [3, 4, 5]],
            colour(k),
        );
    }
    s
}

/// The 12 triangles of `procedural::cube()` (outward, counter-clockwise),
/// scaled, rotated and moved.
fn box_mesh(half: DVec3, rotation: DQuat, centre: DVec3) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let cube = procedural::cube();
    let m = &cube.meshes[0];
    let positions = m
        .positions
        .iter()
        .map(|&p| rotation * (p * half) + centre)
        .collect();
    (positions, m.indices.clone())
}

/// `count` boxes with random sizes and rotations, centred close together so
/// they interpenetrate. Each box is a closed mesh.
pub fn interpenetrating_boxes(count: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let mut s = Scene::default();
    for k in 0..count {
        let half = DVec3::new(
            rng.range(0.2, 0.6),
            rng.range(0.2, 0.6),
            rng.range(0.2, 0.6),
        );
        let rotation =
            DQuat::from_axis_angle(random_unit(&mut rng), rng.range(0.0, std::f64::consts::TAU));
        let centre = DVec3::new(
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
        );
        let (p, i) = box_mesh(half, rotation, centre);
        push(&mut s, format!("box_{k}"), p, i, colour(k));
    }
    s
}

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
    let mut rng = SplitMix64::new(seed);
    let mut s = Scene::default();
    let size = 0.35 * distance;
    let tilt = DQuat::from_axis_angle(DVec3::new(1.0, 0.3, 0.0).normalize(), 0.3);
    for k in 0..layers {
        let z = -distance * (1.0 + relative_gap * f64::from(layers - 1 - k));
        // Shifted within the (tilted) layer plane, so the layers stay
        // exactly `relative_gap * distance` apart along the view axis.
        let shift = tilt * DVec3::new(rng.range(-0.3, 0.3), rng.range(-0.3, 0.3), 0.0) * size;
        let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
        let positions = corners
            .iter()
            .map(|&(x, y)| {
                tilt * DVec3::new(x * size, y * size, 0.0) + shift + DVec3::new(0.0, 0.0, z)
                // (the shift above keeps every layer parallel to the first)
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
    s.camera = Some(look_at(DVec3::ZERO, DVec3::NEG_Z, 1.0, 10.0 * distance));
    s
}

/// `count` needles: two corners far apart and the third within
/// `10^-6 .. 10^-2` of the segment between them (relative to its length),
/// some exactly on it (zero area). Planes of such triangles are
/// ill-conditioned; most cover no pixel centre at all after snapping.
pub fn slivers(count: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let mut s = Scene::default();
    let mut positions = Vec::new();
    let mut indices = Vec::new();
    for k in 0..count {
        let a = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let b = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        let t = rng.range(0.1, 0.9);
        let off = if k % 5 == 0 {
            0.0
        } else {
            10f64.powf(rng.range(-6.0, -2.0)) * (b - a).length()
        };
        let c = a + (b - a) * t + random_unit(&mut rng) * off;
        let base = positions.len() as u32;
        positions.extend([a, b, c]);
        indices.push([base, base + 1, base + 2]);
    }
    push(
        &mut s,
        "slivers".into(),
        positions,
        indices,
        [0.8, 0.75, 0.3],
    );
    s
}

/// A fan of `segments` triangles around a centre whose wedges have random,
/// mostly tiny angles (down to `1e-6` rad), a few repeated rim vertices
/// (zero-area wedges) and a tilted plane: near-degenerate triangles
/// sharing edges.
pub fn near_degenerate_fan(segments: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let segments = segments.max(3);
    let mut weights: Vec<f64> = (0..segments)
        .map(|k| match k % 4 {
            0 => 1.0,
            1 => 10f64.powf(rng.range(-6.0, -2.0)),
            2 => 0.0,
            _ => rng.range(0.05, 0.5),
        })
        .collect();
    let total: f64 = weights.iter().sum();
    weights
        .iter_mut()
        .for_each(|w| *w *= std::f64::consts::TAU / total);
    let tilt = DQuat::from_axis_angle(DVec3::new(1.0, 1.0, 0.0).normalize(), 0.6);
    let mut positions = vec![DVec3::ZERO];
    let mut angle: f64 = 0.0;
    for w in &weights {
        positions.push(tilt * DVec3::new(angle.cos(), angle.sin(), 0.0));
        angle += w;
    }
    let indices = (0..segments)
        .map(|k| [0, 1 + k, 1 + (k + 1) % segments])
        .collect();
    let mut s = Scene::default();
    push(
        &mut s,
        "near_degenerate_fan".into(),
        positions,
        indices,
        [0.4, 0.8, 0.5],
    );
    s
}

/// A star-shaped disc in the plane `z = 0`: `segments` triangles around a
/// centre, rim radii jittered, every interior edge shared by two triangles
/// and the centre by all. Each pixel centre inside it must be covered
/// exactly once.
pub fn fan(segments: u32, seed: u64) -> Scene {
    let (positions, indices) = fan_mesh(segments, seed, 0.0);
    let mut s = Scene::default();
    push(&mut s, "fan".into(), positions, indices, [0.5, 0.6, 0.9]);
    s
}

fn fan_mesh(segments: u32, seed: u64, apex: f64) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut rng = SplitMix64::new(seed);
    let n = segments.max(3);
    let mut positions = vec![DVec3::new(0.0, 0.0, apex)];
    for k in 0..n {
        let a = std::f64::consts::TAU * f64::from(k) / f64::from(n);
        let r = rng.range(0.6, 1.0);
        positions.push(DVec3::new(r * a.cos(), r * a.sin(), 0.0));
    }
    // Counter-clockwise seen from +z.
    let indices = (0..n).map(|k| [0, 1 + k, 1 + (k + 1) % n]).collect();
    (positions, indices)
}

/// A closed star-shaped double pyramid: two fans of `segments` triangles
/// sharing a jittered rim, apexes at `z = ±0.8`, wound outward. A closed
/// mesh whose pixel centres meet many shared vertices and edges.
pub fn bipyramid(segments: u32, seed: u64) -> Scene {
    let (mut positions, mut indices) = fan_mesh(segments, seed, 0.8);
    let n = positions.len() as u32 - 1;
    positions.push(DVec3::new(0.0, 0.0, -0.8));
    let bottom = n + 1;
    // The bottom fan is wound the other way, so it faces -z (outward).
    indices.extend((0..n).map(|k| [bottom, 1 + (k + 1) % n, 1 + k]));
    let rotation = DQuat::from_axis_angle(DVec3::new(1.0, 0.2, 0.0).normalize(), 0.9);
    let positions = positions.into_iter().map(|p| rotation * p).collect();
    let mut s = Scene::default();
    push(
        &mut s,
        "bipyramid".into(),
        positions,
        indices,
        [0.9, 0.6, 0.4],
    );
    s
}

/// A torus around the y axis: `major` segments around the ring (radius
/// `ring`), `minor` around the tube (radius `tube`), outward
/// counter-clockwise: a closed mesh that is not convex (two layers overlap
/// on screen). Segment counts are clamped to at least 3.
pub fn torus(major: u32, minor: u32, ring: f64, tube: f64) -> Scene {
    let (major, minor) = (major.max(3), minor.max(3));
    let mut positions = Vec::with_capacity((major * minor) as usize);
    for i in 0..major {
        let u = std::f64::consts::TAU * f64::from(i) / f64::from(major);
        for j in 0..minor {
            let v = std::f64::consts::TAU * f64::from(j) / f64::from(minor);
            let r = ring + tube * v.cos();
            positions.push(DVec3::new(r * u.cos(), tube * v.sin(), -r * u.sin()));
        }
    }
    let at = |i: u32, j: u32| (i % major) * minor + (j % minor);
    let mut indices = Vec::with_capacity((2 * major * minor) as usize);
    for i in 0..major {
        for j in 0..minor {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            indices.push([a, b, c]);
            indices.push([a, c, d]);
        }
    }
    let mut s = Scene::default();
    push(
        &mut s,
        format!("torus_{major}x{minor}"),
        positions,
        indices,
        [0.6, 0.8, 0.7],
    );
    // Tilted view so the hole and both layers show.
    s.camera = Some(look_at(
        DVec3::new(0.0, 1.6 * (ring + tube), 2.4 * (ring + tube)),
        DVec3::ZERO,
        0.1 * ring,
        20.0 * ring,
    ));
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

/// `n` (at least 3) long strips in cyclic overlap: strip `k` runs along
/// the side `P_k -> P_{k+1}` of a regular `n`-gon, high at its base before
/// `P_k` and low at its tip beyond `P_{k+1}`, so it passes under strip
/// `k + 1` near `P_{k+1}` and over strip `k - 1` near `P_k`. No depth
/// order of the strips exists.
pub fn cyclic_overlap(n: u32) -> Scene {
    let n = n.max(3);
    let corner = |k: u32| {
        let a =
            std::f64::consts::TAU * f64::from(k % n) / f64::from(n) + std::f64::consts::FRAC_PI_2;
        DVec3::new(a.cos(), a.sin(), 0.0)
    };
    let mut s = Scene::default();
    for k in 0..n {
        let (p, q) = (corner(k), corner(k + 1));
        let along = q - p;
        let side = DVec3::new(-along.y, along.x, 0.0).normalize() * (0.3 * along.length());
        let base = p - along * 0.3 + DVec3::Z * 0.3;
        let tip = q + along * 0.8 - DVec3::Z * 0.3;
        push(
            &mut s,
            format!("strip_{k}"),
            vec![base + side, base - side, tip],
            vec![[0, 1, 2]],
            colour(k),
        );
    }
    s
}

/// `count` large random triangles (corners up to 0.6 from centres uniform
/// in `[-0.5, 0.5]^3`) piled on the same screen area: every pixel is covered
/// by many layers (heavy overdraw), and many pairs interpenetrate.
pub fn heavy_overdraw(count: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let mut positions = Vec::with_capacity(3 * count as usize);
    for _ in 0..count {
        let c = DVec3::new(
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
            rng.range(-0.5, 0.5),
        );
        for _ in 0..3 {
            positions.push(
                c + DVec3::new(
                    rng.range(-0.6, 0.6),
                    rng.range(-0.6, 0.6),
                    rng.range(-0.6, 0.6),
                ),
            );
        }
    }
    let indices = (0..count).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    let mut s = Scene::default();
    push(
        &mut s,
        format!("overdraw_{count}"),
        positions,
        indices,
        [0.7, 0.6, 0.5],
    );
    s
}

/// One modest instance of every hard case, by name, derived from `seed`:
/// small enough that the exact oracle and every hider run on all of them in
/// well under a second at 64 x 64.
pub fn all(seed: u64) -> Vec<(&'static str, Scene)> {
    let s = |k: u64| seed.wrapping_mul(0x9e37_79b9_7f4a_7c15).wrapping_add(k);
    vec![
        ("intersecting_pairs", intersecting_pairs(6, s(1))),
        ("interpenetrating_boxes", interpenetrating_boxes(4, s(2))),
        ("coplanar_overlaps", coplanar_overlaps(6, s(3))),
        (
            "near_coplanar_far",
            near_coplanar_far(4, 1000.0, 1e-3, s(4)),
        ),
        ("slivers", slivers(40, s(5))),
        ("near_degenerate_fan", near_degenerate_fan(48, s(6))),
        ("fan", fan(24, s(7))),
        ("bipyramid", bipyramid(16, s(8))),
        ("cube", procedural::cube()),
        ("uv_sphere", procedural::uv_sphere(12)),
        ("torus", torus(16, 8, 1.0, 0.35)),
        ("near_plane_crossing", near_plane_crossing(30, s(9))),
        ("huge_depth_range", huge_depth_range(24, 30.0, s(10))),
        ("huge_coordinates", huge_coordinates(30, s(11), 1e7)),
        ("cyclic_overlap", cyclic_overlap(5)),
        ("cyclic_triple", procedural::cyclic_triple()),
        ("random_soup", procedural::random_soup(200, s(12))),
        ("heavy_overdraw", heavy_overdraw(100, s(13))),
    ]
}

/// The closed, consistently outward-wound meshes among the hard cases
/// (every edge shared by exactly two triangles with opposite directions),
/// by name: what watertightness checks need. Convex ones are marked `true`
/// (each pixel inside the silhouette meets exactly one front and one back
/// face).
pub fn closed_meshes(seed: u64) -> Vec<(&'static str, Scene, bool)> {
    vec![
        ("cube", procedural::cube(), true),
        ("uv_sphere", procedural::uv_sphere(16), true),
        ("bipyramid", bipyramid(20, seed), false),
        ("torus", torus(20, 10, 1.0, 0.4), false),
        ("box", interpenetrating_boxes(1, seed), true),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use hider_geom::Projection;
    use std::collections::HashMap;

    #[test]
    fn every_case_is_valid_deterministic_and_non_empty() {
        let a = all(7);
        let b = all(7);
        assert_eq!(a, b);
        assert_ne!(all(8)[0].1, a[0].1);
        for (name, scene) in &a {
            assert!(scene.validate().is_ok(), "{name}");
            assert!(scene.triangle_count() > 0, "{name}");
        }
    }

    /// Every directed edge appears once and its reverse once.
    fn is_closed(scene: &Scene) -> bool {
        let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
        for mesh in &scene.meshes {
            for t in &mesh.indices {
                for k in 0..3 {
                    *edges.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
                }
            }
        }
        edges
            .iter()
            .all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1))
    }

    #[test]
    fn closed_meshes_are_closed_and_outward() {
        for (name, scene, _) in closed_meshes(3) {
            assert!(is_closed(&scene), "{name}");
            // Outward: the signed volume is positive.
            let mut volume = 0.0;
            for (_, m, t) in scene.triangles() {
                let [a, b, c] = scene.triangle_positions(m, t);
                volume += a.dot(b.cross(c)) / 6.0;
            }
            assert!(volume > 0.0, "{name}: volume {volume}");
        }
        assert!(!is_closed(&fan(8, 1)));
    }

    #[test]
    fn intersecting_pairs_really_intersect() {
        // Both triangles of a pair share their centroid, which lies inside
        // both: the pair has points on either side of each other's plane.
        let s = intersecting_pairs(5, 11);
        for m in &s.meshes {
            let p = &m.positions;
            let n = (p[1] - p[0]).cross(p[2] - p[0]);
            let side: Vec<f64> = p[3..].iter().map(|q| n.dot(*q - p[0])).collect();
            assert!(
                side.iter().any(|&d| d > 0.0) && side.iter().any(|&d| d < 0.0),
                "{}",
                m.name
            );
        }
    }

    #[test]
    fn coplanar_triangles_are_exactly_coplanar() {
        let s = coplanar_overlaps(5, 1);
        assert!(
            s.meshes
                .iter()
                .flat_map(|m| &m.positions)
                .all(|p| p.z == 0.0)
        );
    }

    #[test]
    fn huge_cases_have_what_they_promise() {
        let b = huge_coordinates(10, 1, 1e7).bounds().unwrap();
        assert!(b.0.min_element() > 1e7 - 4.0 && b.1.max_element() < 1e7 + 4.0);
        let c = huge_depth_range(10, 1e5, 1).camera.unwrap();
        assert_eq!(
            c.projection,
            Projection::Perspective {
                fovy_degrees: 60.0,
                near: 1e-3,
                far: 1e6
            }
        );
        let s = near_plane_crossing(20, 1);
        let behind = s
            .meshes
            .iter()
            .flat_map(|m| &m.positions)
            .filter(|p| p.z > 0.0)
            .count();
        assert!(behind > 0);
    }
}
