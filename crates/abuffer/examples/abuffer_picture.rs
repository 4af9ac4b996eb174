//! Writes the pictures of `docs/abuffer.md`.
//!
//! `cargo run --release -p hider-abuffer --example abuffer_picture [-- OUT_DIR]`
//! (default `docs/images`):
//! - `abuffer-transparency.png`: three translucent triangles, the first two
//!   piercing each other, rendered by the A-buffer (left) and by the
//!   sorted-transparency z-buffer (right);
//! - `abuffer-edge.png`: a close-up (8x) of the edges of the intersecting
//!   pair, one sample per pixel (left) and the A-buffer's 8 x 4 masks
//!   (right).

use std::path::PathBuf;

use glam::DVec3;
use hider_abuffer::{
    ABuffer, ABufferOptions, SamplePattern, SortedTransparencyZBuffer, SsaaOptions,
};
use hider_scene::{Frame, Hider, Material, Mesh, Scene, procedural};
use hider_testkit::{render, screen};

fn glass_scene() -> Scene {
    let tris = [
        (
            [
                DVec3::new(-1.0, -0.8, -0.3),
                DVec3::new(0.9, -0.6, 0.3),
                DVec3::new(-0.2, 0.9, 0.0),
            ],
            [0.9, 0.15, 0.1],
            0.5,
        ),
        (
            [
                DVec3::new(-0.9, 0.7, 0.35),
                DVec3::new(-0.1, -1.0, -0.35),
                DVec3::new(1.0, 0.5, 0.0),
            ],
            [0.1, 0.85, 0.2],
            0.6,
        ),
        (
            [
                DVec3::new(-0.5, -0.2, 0.5),
                DVec3::new(0.6, -0.9, 0.5),
                DVec3::new(0.4, 0.8, 0.5),
            ],
            [0.15, 0.3, 0.95],
            0.4,
        ),
    ];
    let mut s = Scene::default();
    for (k, (p, c, a)) in tris.into_iter().enumerate() {
        s.push_mesh(
            Mesh {
                name: format!("glass {k}"),
                positions: p.to_vec(),
                indices: vec![[0, 1, 2]],
                ..Mesh::default()
            },
            Some(Material {
                name: format!("glass {k}"),
                diffuse: c,
                opacity: a,
                ..Material::default()
            }),
        );
    }
    s
}

/// `scene` rendered by `hider` at `width x height`.
fn picture<H: Hider>(hider: &mut H, scene: &Scene, width: u32, height: u32) -> Frame {
    render(hider, &screen(scene, width, height)).0
}

/// Copies `src` (or its `crop` region, enlarged `zoom` times) into `dst`
/// at `(x, y)`.
fn blit(dst: &mut Frame, src: &Frame, crop: (u32, u32, u32, u32), zoom: u32, at: (u32, u32)) {
    let (cx, cy, cw, ch) = crop;
    for j in 0..ch * zoom {
        for i in 0..cw * zoom {
            let s = src.index(cx + i / zoom, cy + j / zoom);
            let d = dst.index(at.0 + i, at.1 + j);
            dst.color[d] = src.color[s];
        }
    }
}

fn main() -> hider_scene::Result<()> {
    let out = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "docs/images".into()),
    );
    std::fs::create_dir_all(&out).map_err(|source| hider_scene::Error::Io {
        path: out.clone(),
        source,
    })?;

    // Transparency: A-buffer vs sorted z-buffer, 256 x 256 each.
    let glass = glass_scene();
    let a = picture(
        &mut ABuffer::new(ABufferOptions::default()),
        &glass,
        256,
        256,
    );
    let z = picture(
        &mut SortedTransparencyZBuffer::new(SsaaOptions::default()),
        &glass,
        256,
        256,
    );
    let mut sheet = Frame::new(516, 256)?;
    sheet.color.fill([255, 255, 255, 255]);
    blit(&mut sheet, &a, (0, 0, 256, 256), 1, (0, 0));
    blit(&mut sheet, &z, (0, 0, 256, 256), 1, (260, 0));
    sheet.write_png(&out.join("abuffer-transparency.png"))?;

    // Anti-aliased edge close-up: 32 x 32 crop of a 127 x 127 render (odd, so the
    // intersection line crosses pixels instead of following a pixel border), 8x.
    let pair = procedural::intersecting_pair();
    let one = picture(
        &mut ABuffer::new(ABufferOptions::default().with_pattern(SamplePattern::Centre)),
        &pair,
        127,
        127,
    );
    let aa = picture(
        &mut ABuffer::new(ABufferOptions::default()),
        &pair,
        127,
        127,
    );
    let crop = (52, 36, 32, 32);
    let mut sheet = Frame::new(516, 256)?;
    sheet.color.fill([255, 255, 255, 255]);
    blit(&mut sheet, &one, crop, 8, (0, 0));
    blit(&mut sheet, &aa, crop, 8, (260, 0));
    sheet.write_png(&out.join("abuffer-edge.png"))?;
    println!(
        "wrote {}/abuffer-transparency.png and abuffer-edge.png",
        out.display()
    );
    Ok(())
}
