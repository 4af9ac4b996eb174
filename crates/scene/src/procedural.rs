//! Procedural scenes: the stress scenes of the GL reference (UV sphere,
//! random soup), closed meshes, and the small hard cases bundled as assets.
//!
//! Every generator is deterministic: the same parameters (and seed) give the
//! same scene, bit for bit, on every machine.

use glam::DVec3;

use crate::model::{Material, Mesh, Scene};

/// A small, fast, deterministic random number generator (SplitMix64, Steele
/// et al. 2014), so generated scenes do not depend on a crate's stream
/// stability.
#[derive(Clone, Debug)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator from a seed.
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// A uniform `f64` in `[lo, hi)`.
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        let unit = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        lo + (hi - lo) * unit
    }

    /// A uniform index in `0..n` (`n` at least 1).
    pub fn below(&mut self, n: usize) -> usize {
        ((self.range(0.0, 1.0) * n as f64) as usize).min(n.max(1) - 1)
    }

    /// A random unit vector: a point of the cube `[-1, 1]^3` farther than
    /// 0.2 from the centre, normalised (not uniform on the sphere; enough
    /// for test scenes, and never near zero length).
    pub fn direction(&mut self) -> DVec3 {
        loop {
            let v = DVec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            if v.length() > 0.2 {
                return v.normalize();
            }
        }
    }
}

fn mesh(name: &str, positions: Vec<DVec3>, indices: Vec<[u32; 3]>) -> Mesh {
    Mesh {
        name: name.into(),
        positions,
        indices,
        ..Mesh::default()
    }
}

fn material(name: &str, diffuse: [f32; 3]) -> Material {
    Material {
        name: name.into(),
        diffuse,
        ..Material::default()
    }
}

/// The UV sphere of the GL reference, `n` x `n` segments, radius 1: vertex
/// 0 is the north pole (0, 1, 0); rings `i = 1..n-1` at polar angle
/// `pi i / n`, each with `n` vertices at azimuth `2 pi j / n`,
/// `(r cos phi, cos theta, r sin phi)`; then the south pole. Triangles: the
/// north cap fan, two triangles per segment for each ring pair, the south
/// cap fan: `2n + 2n(n-2)` triangles. `n` is clamped to at least 3.
pub fn uv_sphere(n: u32) -> Scene {
    let n = n.max(3);
    let mut positions = vec![DVec3::Y];
    for i in 1..n {
        let theta = std::f64::consts::PI * f64::from(i) / f64::from(n);
        let r = theta.sin();
        for j in 0..n {
            let phi = std::f64::consts::TAU * f64::from(j) / f64::from(n);
            positions.push(DVec3::new(r * phi.cos(), theta.cos(), r * phi.sin()));
        }
    }
    positions.push(-DVec3::Y);
    let south = positions.len() as u32 - 1;
    let ring = |i: u32, j: u32| 1 + (i - 1) * n + (j % n);
    let mut indices = Vec::with_capacity((2 * n + 2 * n * (n - 2)) as usize);
    for j in 0..n {
        indices.push([0, ring(1, j + 1), ring(1, j)]);
    }
    for i in 1..n - 1 {
        for j in 0..n {
            let (a, b) = (ring(i, j), ring(i, j + 1));
            let (c, d) = (ring(i + 1, j), ring(i + 1, j + 1));
            indices.push([a, b, d]);
            indices.push([a, d, c]);
        }
    }
    for j in 0..n {
        indices.push([south, ring(n - 1, j), ring(n - 1, j + 1)]);
    }
    let mut s = Scene::default();
    s.push_mesh(
        mesh(&format!("uv_sphere_{n}"), positions, indices),
        Some(material("sphere", [0.75, 0.75, 0.8])),
    );
    s
}

/// The random soup of the GL reference: `count` triangles, each with a
/// centre uniform in `[-1, 1]^3` and three corners at centre + uniform
/// `[-0.1, 0.1]^3` (heavy overdraw).
pub fn random_soup(count: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let mut positions = Vec::with_capacity(count as usize * 3);
    for _ in 0..count {
        let c = DVec3::new(
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        );
        for _ in 0..3 {
            positions.push(
                c + DVec3::new(
                    rng.range(-0.1, 0.1),
                    rng.range(-0.1, 0.1),
                    rng.range(-0.1, 0.1),
                ),
            );
        }
    }
    let indices = (0..count).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect();
    let mut s = Scene::default();
    s.push_mesh(
        mesh(&format!("soup_{count}_{seed}"), positions, indices),
        Some(material("soup", [0.7, 0.6, 0.5])),
    );
    s
}

/// An axis-aligned cube from -1 to 1, 12 triangles wound counter-clockwise
/// seen from outside: a closed mesh for watertightness tests.
pub fn cube() -> Scene {
    let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
    let positions = vec![
        p(-1.0, -1.0, -1.0),
        p(1.0, -1.0, -1.0),
        p(1.0, 1.0, -1.0),
        p(-1.0, 1.0, -1.0),
        p(-1.0, -1.0, 1.0),
        p(1.0, -1.0, 1.0),
        p(1.0, 1.0, 1.0),
        p(-1.0, 1.0, 1.0),
    ];
    let quads = [
        [4, 5, 6, 7], // +z
        [1, 0, 3, 2], // -z
        [5, 1, 2, 6], // +x
        [0, 4, 7, 3], // -x
        [7, 6, 2, 3], // +y
        [0, 1, 5, 4], // -y
    ];
    let indices = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    let mut s = Scene::default();
    s.push_mesh(
        mesh("cube", positions, indices),
        Some(material("cube", [0.8, 0.5, 0.3])),
    );
    s
}

/// Two triangles that pierce each other: a naive depth sort must get part
/// of one of them wrong.
pub fn intersecting_pair() -> Scene {
    let mut s = Scene::default();
    s.push_mesh(
        mesh(
            "tilted",
            vec![
                DVec3::new(-1.0, -0.6, -0.8),
                DVec3::new(1.0, -0.6, 0.8),
                DVec3::new(0.0, 0.9, 0.0),
            ],
            vec![[0, 1, 2]],
        ),
        Some(material("red", [0.85, 0.2, 0.15])),
    );
    s.push_mesh(
        mesh(
            "counter_tilted",
            vec![
                DVec3::new(-1.0, 0.6, 0.8),
                DVec3::new(0.0, -0.9, 0.0),
                DVec3::new(1.0, 0.6, -0.8),
            ],
            vec![[0, 1, 2]],
        ),
        Some(material("blue", [0.15, 0.35, 0.85])),
    );
    s
}

/// Three long triangles overlapping in a cycle (each above the next, the
/// last above the first): no depth order exists.
///
/// Strip `k` runs along the side `P_k -> P_{k+1}` of an equilateral
/// triangle, wide and high (z = +0.3) at its base before `P_k`, narrowing
/// and descending to z = -0.3 at its tip beyond `P_{k+1}`. Near `P_{k+1}` it
/// passes under the base of strip `k + 1`; near `P_k` over the tip of strip
/// `k - 1`.
pub fn cyclic_triple() -> Scene {
    let mut s = Scene::default();
    let colours = [[0.85, 0.25, 0.2], [0.25, 0.75, 0.3], [0.25, 0.35, 0.85]];
    let corner = |k: u32| {
        let a = std::f64::consts::TAU * f64::from(k % 3) / 3.0 + std::f64::consts::FRAC_PI_2;
        DVec3::new(0.8 * a.cos(), 0.8 * a.sin(), 0.0)
    };
    for k in 0..3 {
        let (p, q) = (corner(k), corner(k + 1));
        let along = q - p;
        let side = DVec3::new(-along.y, along.x, 0.0).normalize() * 0.25;
        let base = p - along * 0.3 + DVec3::Z * 0.3;
        let tip = q + along * 0.8 - DVec3::Z * 0.3;
        s.push_mesh(
            mesh(
                &format!("strip_{k}"),
                vec![base + side, base - side, tip],
                vec![[0, 1, 2]],
            ),
            Some(material(&format!("strip_{k}"), colours[k as usize])),
        );
    }
    s
}

/// Two triangles in the same plane, overlapping: every overlapped pixel is a
/// depth tie (z-fighting), decided only by the tie rule.
pub fn coplanar_pair() -> Scene {
    let mut s = Scene::default();
    s.push_mesh(
        mesh(
            "first",
            vec![
                DVec3::new(-1.0, -1.0, 0.0),
                DVec3::new(0.6, -1.0, 0.0),
                DVec3::new(-0.2, 0.8, 0.0),
            ],
            vec![[0, 1, 2]],
        ),
        Some(material("first", [0.9, 0.7, 0.2])),
    );
    s.push_mesh(
        mesh(
            "second",
            vec![
                DVec3::new(-0.6, -0.8, 0.0),
                DVec3::new(1.0, -0.8, 0.0),
                DVec3::new(0.2, 1.0, 0.0),
            ],
            vec![[0, 1, 2]],
        ),
        Some(material("second", [0.2, 0.7, 0.9])),
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_counts_match_the_gl_reference() {
        let s = uv_sphere(200);
        assert_eq!(s.triangle_count(), 79_600);
        assert_eq!(s.meshes[0].positions.len(), 39_802);
        assert!(s.validate().is_ok());
    }

    #[test]
    fn soup_is_deterministic() {
        assert_eq!(random_soup(50, 7), random_soup(50, 7));
        assert_ne!(random_soup(50, 7), random_soup(50, 8));
        assert_eq!(random_soup(50, 7).triangle_count(), 50);
    }

    #[test]
    fn small_scenes_are_valid() {
        for s in [
            cube(),
            intersecting_pair(),
            cyclic_triple(),
            coplanar_pair(),
        ] {
            assert!(s.validate().is_ok());
        }
        assert_eq!(cube().triangle_count(), 12);
    }
}
