//! Many tiny triangles over one pixel: `N` triangles, each a third of a
//! pixel across, all covering the centre of one pixel of a 64 x 64 image,
//! each tilted at random and at a random depth. Every one of them overlaps
//! every other on screen, so anything quadratic in the depth complexity of
//! one pixel shows here. Times the painter (release build, one run per
//! size), prints its counters, checks the pixel against the window-depth
//! z-buffer, and gives the growth exponent between successive sizes.
//!
//! `cargo run --release -p hider-painter --example pile [sizes...]`
//! (default sizes: 100000 300000 1000000).

use glam::DVec3;
use hider_geom::Camera;
use hider_painter::{Painter, PainterOptions};
use hider_scene::procedural::SplitMix64;
use hider_scene::{Frame, Hider, Material, Mesh, PrepareOptions, Scene, View, prepare};
use hider_testkit::reference;

/// The world point that the camera below maps to the centre of pixel
/// (32, 31) at 64 x 64.
const CENTRE: DVec3 = DVec3::new(1.0 / 64.0, 1.0 / 64.0, 0.0);

/// `n` tiny triangles around [`CENTRE`], at depths in `[-1, 1]`, normals
/// within about 35 degrees of the view axis, corners 0.15 to 0.4 pixel
/// from the centre at angles about a third of a turn apart (so the centre
/// stays inside).
fn pile(n: u32, seed: u64) -> Scene {
    let mut rng = SplitMix64::new(seed);
    let pixel = 1.0 / 32.0;
    let mut positions = Vec::with_capacity(3 * n as usize);
    for _ in 0..n {
        let tilt = DVec3::new(rng.range(-0.7, 0.7), rng.range(-0.7, 0.7), 1.0).normalize();
        let u = tilt.any_orthonormal_vector();
        let v = tilt.cross(u);
        let centre = CENTRE + DVec3::Z * rng.range(-1.0, 1.0);
        let a0 = rng.range(0.0, std::f64::consts::TAU);
        for k in 0..3 {
            let a = a0 + std::f64::consts::TAU * f64::from(k) / 3.0 + rng.range(-0.4, 0.4);
            let r = pixel * rng.range(0.15, 0.4) / tilt.z;
            positions.push(centre + (u * a.cos() + v * a.sin()) * r);
        }
    }
    let mut scene = Scene::default();
    scene.push_mesh(
        Mesh {
            positions,
            indices: (0..n).map(|t| [3 * t, 3 * t + 1, 3 * t + 2]).collect(),
            ..Mesh::default()
        },
        Some(Material::default()),
    );
    // Orthographic down -z: a pixel is 1/32 wide at 64 x 64.
    scene.camera = Some(Camera::orthographic(
        DVec3::new(0.0, 0.0, 10.0),
        DVec3::ZERO,
        1.0,
        1.0,
        20.0,
    ));
    scene
}

fn main() -> Result<(), hider_scene::Error> {
    let sizes: Vec<u32> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let sizes = if sizes.is_empty() {
        vec![100_000, 300_000, 1_000_000]
    } else {
        sizes
    };
    println!(
        "| triangles | painter s | comparisons | blocked | moves | splits | pieces out | wrong px | exponent |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    let mut last: Option<(f64, f64)> = None;
    for &n in &sizes {
        let scene = pile(n, 1);
        let view = View::for_scene(&scene, 64, 64)?;
        let s = prepare(&scene, &view, &PrepareOptions::default())?;
        let mut frame = Frame::new(64, 64)?;
        let mut painter = Painter::new(PainterOptions::default());
        let start = std::time::Instant::now();
        let stats = painter.render(&s, &mut frame)?;
        let seconds = start.elapsed().as_secs_f64();
        let r = reference::pixel_centre(&s);
        let wrong = r.ids.iter().zip(&frame.ids).filter(|(a, b)| a != b).count();
        let exponent = last.map_or(String::from("-"), |(n0, t0)| {
            format!("{:.2}", (seconds / t0).ln() / (f64::from(n) / n0).ln())
        });
        println!(
            "| {} | {seconds:.2} | {} | {} | {} | {} | {} | {wrong} | {exponent} |",
            s.tris.len(),
            stats.comparisons,
            stats.blocked,
            stats.moves,
            stats.splits,
            stats.pieces_out,
        );
        last = Some((f64::from(n), seconds));
    }
    Ok(())
}
