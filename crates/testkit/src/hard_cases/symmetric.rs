//! Exactly symmetric cycles: bars in a pinwheel about the view axis with
//! their vertices on a small dyadic lattice, so that cut lines of
//! different planes coincide on screen and pixel centres fall exactly on
//! them.

use glam::DVec3;
use hider_scene::Scene;

use super::support::{colour, push};
use crate::cameras::pinwheel_camera;

/// Rounds `v` to the nearest multiple of `2^-bits` (halves away from zero,
/// so rounding commutes with the sign changes of a quarter or half turn).
fn snap(v: f64, bits: u32) -> f64 {
    let scale = f64::from(1u32 << bits.min(30));
    (v * scale).round() / scale
}

/// `p` turned by `angle` about the z axis (the view axis of the pinwheel
/// cameras) and snapped to the lattice. A lattice point turned by a
/// multiple of a quarter turn lands exactly on the lattice point the exact
/// turn gives: the trigonometric rounding (about `1e-16`) is far below half
/// a lattice step.
pub(crate) fn turn(p: DVec3, angle: f64, bits: u32) -> DVec3 {
    let (s, c) = angle.sin_cos();
    DVec3::new(
        snap(p.x * c - p.y * s, bits),
        snap(p.x * s + p.y * c, bits),
        p.z,
    )
}

/// `order` (2 to 6) long bars in a pinwheel about the view axis (the z
/// axis), each lying over the next: bar `k` runs along the side
/// `P_k -> P_{k+1}` of a regular `order`-gon of radius 4, high (`z = +1`)
/// at its base before `P_k` and low (`z = -1`) at its tip beyond
/// `P_{k+1}`, so it passes under bar `k + 1` and over bar `k - 1`: no depth
/// order of the bars exists. Bars are 2 wide; two triangles per bar (four
/// bars: 8 triangles).
///
/// Every vertex lies on the lattice of step `2^-bits` (`bits = 0`: small
/// integers). Bar 0 is snapped first and the others are bar 0 turned by
/// `k / order` of a full turn and snapped again, so orders 2 and 4 are
/// *exactly* symmetric (a quarter turn maps the lattice onto itself);
/// orders 3, 5 and 6 are symmetric to within the lattice step. For order 2
/// the two bars share their footprint with opposite slopes and cross along
/// the symmetry axis.
///
/// With `mirrored`, the mirror image of the pinwheel about the plane
/// `x = 0` (which contains the view axis) is added: the scene is then
/// symmetric under the dihedral group and the bars of the two hands pierce
/// each other along cut lines that coincide on screen.
///
/// The camera ([`pinwheel_camera`](crate::cameras::pinwheel_camera)) looks down the z axis, so the
/// symmetry axis passes through the image centre: at an even image size a
/// pixel corner, and the cut lines through it run along pixel-centre
/// diagonals.
pub fn pinwheel(order: u32, mirrored: bool, bits: u32) -> Scene {
    let n = order.clamp(2, 6);
    let corner = |k: u32| {
        let a = std::f64::consts::TAU * f64::from(k) / f64::from(n) + std::f64::consts::FRAC_PI_2;
        DVec3::new(4.0 * a.cos(), 4.0 * a.sin(), 0.0)
    };
    let (p, q) = (corner(0), corner(1));
    let along = q - p;
    // Half-width 1: at least one lattice step whatever the lattice, so no
    // bar snaps to a segment.
    let across = DVec3::new(-along.y, along.x, 0.0).normalize();
    let lattice = |v: DVec3| DVec3::new(snap(v.x, bits), snap(v.y, bits), v.z);
    // A parallelogram of lattice points: base and tip centres and the
    // half-width snapped separately, so the bar stays exactly planar (its
    // height depends on the position along it alone).
    let base = lattice(p - along * 0.3 + DVec3::Z);
    let tip = lattice(q + along * 0.3 - DVec3::Z);
    let across = lattice(across);
    let bar = [base + across, base - across, tip - across, tip + across];
    let mut s = Scene::default();
    let hands: &[bool] = if mirrored { &[false, true] } else { &[false] };
    for &mirror in hands {
        for k in 0..n {
            let angle = std::f64::consts::TAU * f64::from(k) / f64::from(n);
            let positions: Vec<DVec3> = bar
                .iter()
                .map(|&v| {
                    let v = turn(v, angle, bits);
                    if mirror {
                        DVec3::new(-v.x, v.y, v.z)
                    } else {
                        v
                    }
                })
                .collect();
            // Counter-clockwise seen from +z for either hand.
            let indices = if mirror {
                vec![[0, 2, 1], [0, 3, 2]]
            } else {
                vec![[0, 1, 2], [0, 2, 3]]
            };
            let name = format!("{}bar_{k}", if mirror { "mirror_" } else { "" });
            push(&mut s, name, positions, indices, colour(k));
        }
    }
    s.camera = Some(pinwheel_camera(1e-1));
    s
}

/// A cycle of three bars ([`pinwheel`] of order 3 on the lattice of step
/// `1/256`) seen through
/// [`pinwheel_camera`](crate::cameras::pinwheel_camera) with near plane `near`: the
/// scene where a window-depth tolerance that does not scale with the near
/// plane (about `1e-10` at `near = 1e-8`) starts deciding plane sides
/// wrongly.
pub fn bar_cycle(near: f64) -> Scene {
    let mut s = pinwheel(3, false, 8);
    s.camera = Some(pinwheel_camera(near));
    s
}
