//! Draws the pictures of `docs/warnock.md`: the final regions of the
//! subdivision over the shaded image (coloured by the rule that decided
//! them), and the 4 x 4 anti-aliased mode.
//!
//! `cargo run --release -p hider-warnock --example warnock_picture [-- OUT_DIR]`
//!
//! Writes `warnock-regions.png` and `warnock-antialiased.png` to `OUT_DIR`
//! (default: the workspace's `docs/images`).

use std::path::PathBuf;

use hider_scene::{
    Frame, Hider, PrepareOptions, Scene, ShadeMode, View, prepare, procedural, shade_frame,
};
use hider_warnock::{Rule, Warnock, WarnockOptions, draw_region_outlines};

/// The cyclic triple (no depth order exists) in front of a coarse sphere:
/// silhouettes, crossings and large quiet areas in one picture.
fn scene() -> Scene {
    let mut scene = procedural::cyclic_triple();
    let sphere = procedural::uv_sphere(10);
    for mesh in &sphere.meshes {
        let mut mesh = mesh.clone();
        for p in &mut mesh.positions {
            *p = *p * 0.9 + glam::DVec3::new(0.35, 0.3, -1.2);
        }
        scene.push_mesh(mesh, sphere.materials.first().cloned());
    }
    // The fit camera, moved in so the scene fills the frame.
    let mut camera = hider_scene::fit_camera(&scene);
    camera.eye = camera.target + (camera.eye - camera.target) * 0.55;
    scene.camera = Some(camera);
    scene
}

fn main() -> Result<(), hider_scene::Error> {
    let out = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/images"));
    std::fs::create_dir_all(&out).map_err(|source| hider_scene::Error::Io {
        path: out.clone(),
        source,
    })?;
    let scene = scene();
    let size = 384;
    let view = View::for_scene(&scene, size, size)?;
    let screen = prepare(&scene, &view, &PrepareOptions::default())?;

    let mut frame = Frame::new(size, size)?;
    let mut warnock = Warnock::new(WarnockOptions::default().with_record_regions(true));
    let stats = warnock.render(&screen, &mut frame)?;
    shade_frame(&screen, &mut frame, ShadeMode::Lambert)?;
    draw_region_outlines(&mut frame, warnock.leaf_regions());
    let path = out.join("warnock-regions.png");
    frame.write_png(&path)?;
    println!(
        "{}: {} regions, {} leaves",
        path.display(),
        stats.regions,
        warnock.leaf_regions().len()
    );
    for rule in Rule::ALL {
        println!("  {:>20}: {}", rule.name(), stats.decided_by(rule));
    }
    println!("  regions per level: {:?}", stats.regions_per_level);

    let mut aa = Warnock::new(WarnockOptions::default().with_samples_per_side(4));
    let stats = aa.render(&screen, &mut frame)?;
    let path = out.join("warnock-antialiased.png");
    frame.write_png(&path)?;
    println!(
        "{}: {} regions, {} pixels subdivided to 4 x 4 samples",
        path.display(),
        stats.regions,
        stats.decided_by(Rule::PixelSubdivided)
    );
    Ok(())
}
