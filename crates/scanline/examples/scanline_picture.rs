//! Renders the picture of `docs/scanline.md`: two interpenetrating spheres
//! cut by a tilted plate, shaded (left), and the runs the scanline resolved
//! (right): each run in its primitive's false colour, dimmed when one
//! decision covered the whole span, bright orange where a span was split at
//! a depth crossing (the intersection curves), magenta for the row-buffer
//! fallback; alternate runs on a row are shaded lighter and darker so the
//! spans show.
//!
//! `cargo run --release -p hider-scanline --example scanline_picture [OUT.png]`

use hider_scanline::{Resolution, Scanline, ScanlineOptions};
use hider_scene::geom::glam::DVec3;
use hider_scene::geom::{Camera, Projection};
use hider_scene::shade::{id_color, to_srgb8};
use hider_scene::{
    Frame, Hider, HiderStats, Mesh, PrepareOptions, Scene, ShadeMode, View, prepare, procedural,
    shade_frame,
};

fn scene() -> Scene {
    let mut s = Scene::default();
    let sphere = procedural::uv_sphere(14);
    let transforms = [
        (DVec3::new(-0.45, 0.0, 0.0), 1.0),
        (DVec3::new(0.6, 0.25, 0.2), 0.8),
    ];
    for (k, (offset, scale)) in transforms.into_iter().enumerate() {
        let mut mesh = sphere.meshes[0].clone();
        for p in &mut mesh.positions {
            *p = *p * scale + offset;
        }
        let mut material = sphere.materials[0].clone();
        material.diffuse = if k == 0 {
            [0.8, 0.45, 0.3]
        } else {
            [0.35, 0.55, 0.85]
        };
        s.push_mesh(mesh, Some(material));
    }
    let plate = Mesh {
        name: "plate".into(),
        positions: vec![
            DVec3::new(-1.6, 0.5, -1.3),
            DVec3::new(1.7, 0.5, -1.3),
            DVec3::new(1.7, -0.5, 1.3),
            DVec3::new(-1.6, -0.5, 1.3),
        ],
        indices: vec![[0, 1, 2], [0, 2, 3]],
        ..Mesh::default()
    };
    let mut material = s.materials[0].clone();
    material.diffuse = [0.6, 0.75, 0.4];
    s.push_mesh(plate, Some(material));
    s
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "docs/images/scanline-spans.png".into());
    let size = 256;
    let scene = scene();
    let camera = Camera {
        eye: DVec3::new(0.3, 2.4, 5.2),
        target: DVec3::new(0.1, 0.05, 0.0),
        up: DVec3::Y,
        projection: Projection::Perspective {
            fovy_degrees: 36.0,
            near: 0.5,
            far: 20.0,
        },
        lens: hider_scene::geom::Lens::CENTRED,
    };
    let view = View::new(camera, size, size)?;
    let screen = prepare(&scene, &view, &PrepareOptions::default())?;
    let mut frame = Frame::new(size, size)?;
    let mut hider = Scanline::new(ScanlineOptions::default().with_record_spans(true));
    let stats = hider.render(&screen, &mut frame)?;
    shade_frame(&screen, &mut frame, ShadeMode::Lambert)?;

    let mut sheet = Frame::new(2 * size, size)?;
    for y in 0..size {
        for x in 0..size {
            let k = sheet.index(x, y);
            sheet.color[k] = frame.color[frame.index(x, y)];
        }
    }
    for (n, r) in hider.spans().iter().enumerate() {
        let shade = if n % 2 == 0 { 0.2 } else { 0.4 };
        for x in r.x0..=r.x1 {
            let rgb = match r.how {
                Resolution::Whole => id_color(r.prim).map(|c| c * shade),
                Resolution::Split => [1.0, 0.45 + 0.3 * shade, 0.05],
                Resolution::Fallback => [1.0, 0.1, 0.9],
            };
            let k = sheet.index(size + x, r.row);
            sheet.color[k] = [to_srgb8(rgb[0]), to_srgb8(rgb[1]), to_srgb8(rgb[2]), 255];
        }
    }
    sheet.write_png(std::path::Path::new(&out))?;
    println!("wrote {out}");
    println!("{}", stats.table());
    Ok(())
}
