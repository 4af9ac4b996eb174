//! The families of differential cases, in model units (radius about 6
//! around the origin, symmetric about the z axis where the family is).

use glam::DVec3;
use hider_geom::Camera;
use hider_scene::{Mesh, Scene};

use super::Bytes;
use crate::hard_cases::symmetric::turn;
use crate::{cameras, hard_cases};

/// A family's label, scene and, for the families that need their own,
/// camera and image size.
pub(super) type Family = (String, Scene, Option<(Camera, (u32, u32))>);

/// Decodes one family.
pub(super) fn family(b: &mut Bytes<'_>) -> Family {
    // Eight families by the first byte modulo 8; the upper half of the
    // last one's bytes chooses the parallel layers (added later, so that
    // stored cases decode as before).
    let first = b.byte();
    match first % 8 {
        7 if first >= 128 => layers(b),
        0 => {
            let (order, mirrored, bits) = (2 + b.pick(5), b.pick(2) == 1, b.pick(9));
            (
                format!("pinwheel order {order} mirrored {mirrored} bits {bits}"),
                hard_cases::pinwheel(order, mirrored, bits),
                None,
            )
        }
        1 => symmetric_lattice(b),
        2 => coplanar_stack(b),
        3 => {
            let repeats = 1 + b.pick(40);
            let mut s = hard_cases::repeated_polygon(repeats);
            for p in s.meshes.iter_mut().flat_map(|m| &mut m.positions) {
                *p *= 3.0;
            }
            (format!("repeated_polygon {repeats}"), s, None)
        }
        4 => slivers(b),
        5 => {
            let (n, seed) = (2 + b.pick(200), u64::from(b.byte()));
            (
                format!("one_pixel_pile {n} seed {seed}"),
                hard_cases::one_pixel_pile(n, seed),
                Some((cameras::one_pixel_camera(), (64, 64))),
            )
        }
        6 => {
            let mut s = hard_cases::far_plane_triangle();
            // A second triangle in front of part of it, or on it.
            let z = [-16.0, -15.0, -8.0][b.pick(3) as usize];
            let p = b.lattice_point(2, 0.5);
            push(
                &mut s,
                vec![
                    DVec3::new(p.x, p.y, z),
                    DVec3::new(p.x + 1.0, p.y, z),
                    DVec3::new(p.x, p.y + 1.0, z),
                ],
            );
            let size = 8 + 4 * b.pick(16);
            (
                format!("far_plane_triangle with one at z {z}"),
                s,
                Some((cameras::far_plane_camera(), (size, size))),
            )
        }
        _ => {
            let (n, seed) = (1 + b.pick(24), u64::from(b.byte()));
            let mut s = hard_cases::heavy_overdraw(n, seed);
            for p in s.meshes.iter_mut().flat_map(|m| &mut m.positions) {
                *p *= 4.0;
            }
            (format!("heavy_overdraw {n} seed {seed}"), s, None)
        }
    }
}

/// Parallel layers `10^-4` to `10^-9` apart (relative), 2 to 5 of them,
/// under a telephoto camera (distance 1e4, near and far 10 away, fovy 30),
/// an ordinary one (near 6.35, far 31.8, fovy 45) or a tight depth range
/// (distance 100, near and far 0.1 away, fovy 20): surfaces whose window
/// depths every `f64` hider resolves although they are relatively close.
fn layers(b: &mut Bytes<'_>) -> Family {
    let exponent = b.int(4, 9);
    let count = 2 + b.pick(4);
    let seed = u64::from(b.byte());
    let (name, distance, range, fovy) = [
        ("telephoto", 1e4, (9990.0, 10010.0), 30.0),
        ("ordinary", 12.7, (6.35, 31.8), 45.0),
        ("tight", 100.0, (99.9, 100.1), 20.0),
    ][b.pick(3) as usize];
    let gap = 10f64.powi(-exponent);
    let s = hard_cases::parallel_layers(count, distance, gap, range, fovy, seed);
    let camera = s.camera.expect("the layers come with their camera");
    let size = 8 + b.pick(57);
    (
        format!("parallel_layers {count} gap 1e-{exponent} {name} seed {seed}"),
        s,
        Some((camera, (size, size))),
    )
}

/// Adds one mesh of triangles `(3k, 3k+1, 3k+2)`.
fn push(scene: &mut Scene, positions: Vec<DVec3>) {
    let n = positions.len() as u32 / 3;
    scene.push_mesh(
        Mesh {
            name: format!("mesh_{}", scene.meshes.len()),
            positions,
            indices: (0..n).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect(),
            ..Mesh::default()
        },
        None,
    );
}

/// One to three triangles with corners on the lattice of step `2^-bits`,
/// repeated by a turn of order 1 to 6 about the z axis (snapped back to
/// the lattice: exact for orders 1, 2 and 4) and, optionally, mirrored
/// about the plane `x = 0`.
fn symmetric_lattice(b: &mut Bytes<'_>) -> Family {
    let bits = b.pick(5);
    let step = 2f64.powi(-(bits as i32));
    let reach = (4 << bits).min(64);
    let seeds = 1 + b.pick(3);
    let order = 1 + b.pick(6);
    let mirrored = b.pick(2) == 1;
    let mut tris: Vec<DVec3> = (0..3 * seeds)
        .map(|_| b.lattice_point(reach, step))
        .collect();
    let base = tris.clone();
    for k in 1..order {
        let angle = std::f64::consts::TAU * f64::from(k) / f64::from(order);
        tris.extend(base.iter().map(|&p| turn(p, angle, bits)));
    }
    if mirrored {
        let copy: Vec<DVec3> = tris.iter().map(|p| DVec3::new(-p.x, p.y, p.z)).collect();
        tris.extend(copy);
    }
    let mut s = Scene::default();
    push(&mut s, tris);
    (
        format!("symmetric_lattice seeds {seeds} order {order} mirrored {mirrored} bits {bits}"),
        s,
        None,
    )
}

/// A lattice triangle and up to five copies shifted sideways on the
/// lattice and along a common (possibly tilted) normal by 0 (coincident)
/// or a relative `2^-52`, `1e-12`, `1e-9`, `1e-6` or `1e-3`: exactly and
/// nearly coincident planes overlapping partly.
fn coplanar_stack(b: &mut Bytes<'_>) -> Family {
    let seed = [0; 3].map(|_| {
        let p = b.lattice_point(6, 0.5);
        DVec3::new(p.x, p.y, 0.0)
    });
    let tilt = DVec3::new(f64::from(b.int(-2, 2)), f64::from(b.int(-2, 2)), 4.0) / 4.0;
    let gap = [0.0, f64::EPSILON, 1e-12, 1e-9, 1e-6, 1e-3][b.pick(6) as usize];
    let copies = 1 + b.pick(6);
    let mut tris = Vec::new();
    for k in 0..copies {
        let shift = DVec3::new(
            f64::from(b.int(-2, 2)) * 0.5,
            f64::from(b.int(-2, 2)) * 0.5,
            0.0,
        );
        for p in seed {
            let q = p + shift;
            // The plane z = tilt.x * x + tilt.y * y (lattice slopes), moved
            // along z by k gaps relative to the scene size (about 4).
            let z = tilt.x * q.x + tilt.y * q.y + f64::from(k) * gap * 4.0;
            tris.push(DVec3::new(q.x, q.y, z));
        }
    }
    let mut s = Scene::default();
    push(&mut s, tris);
    (
        format!("coplanar_stack copies {copies} gap {gap:e} tilt {tilt}"),
        s,
        None,
    )
}

/// Triangles with two lattice corners and the third on the segment
/// between them (zero area), on it moved by `2^-k` of the lattice step
/// (slivers), or equal to a corner; one ordinary lattice triangle behind
/// them so that the slivers have something to hide.
fn slivers(b: &mut Bytes<'_>) -> Family {
    let count = 1 + b.pick(8);
    let mut tris = vec![
        DVec3::new(-5.0, -5.0, -2.0),
        DVec3::new(5.0, -5.0, -2.0),
        DVec3::new(0.0, 5.0, -2.0),
    ];
    for _ in 0..count {
        let p = b.lattice_point(4, 1.0);
        let q = b.lattice_point(4, 1.0);
        let t = f64::from(b.int(1, 7)) / 8.0;
        let off = match b.pick(3) {
            0 => 0.0,
            _ => 2f64.powi(-(b.int(1, 40))),
        };
        let side = DVec3::new(-(q - p).y, (q - p).x, 0.5);
        let c = match b.pick(4) {
            0 => p,
            _ => p + (q - p) * t + side * off,
        };
        tris.extend([p, q, c]);
    }
    let mut s = Scene::default();
    push(&mut s, tris);
    (format!("slivers {count}"), s, None)
}
