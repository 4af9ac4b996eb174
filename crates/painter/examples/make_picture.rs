//! Draws the picture of `docs/painter.md`: the naive painter (top) and the
//! Newell-Newell-Sancha painter (bottom) on the intersecting pair (left)
//! and the cyclic triple (right), 512 x 512 in all; and the split cyclic
//! triple as SVG.
//!
//! `cargo run --release -p hider-painter --example make_picture [out_dir]`
//! (default `docs/images`).

use std::path::PathBuf;

use hider_painter::{NaivePainter, Painter};
use hider_scene::{
    DynHider, Frame, PrepareOptions, ShadeMode, View, prepare, procedural, shade_frame,
};

fn main() -> Result<(), hider_scene::Error> {
    let dir = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "docs/images".into()),
    );
    const TILE: u32 = 256;
    let mut sheet = Frame::new(2 * TILE, 2 * TILE)?;
    let scenes = [procedural::intersecting_pair(), procedural::cyclic_triple()];
    for (col, scene) in scenes.iter().enumerate() {
        let view = View::for_scene(scene, TILE, TILE)?;
        let s = prepare(scene, &view, &PrepareOptions::default())?;
        let hiders: [Box<dyn DynHider>; 2] = [
            Box::new(NaivePainter::default()),
            Box::new(Painter::default()),
        ];
        for (row, mut h) in hiders.into_iter().enumerate() {
            let mut f = Frame::new(TILE, TILE)?;
            let stats = h.render(&s, &mut f)?;
            println!("{} on scene {col}: {stats}", h.name());
            shade_frame(&s, &mut f, ShadeMode::Lambert)?;
            for j in 0..TILE {
                for i in 0..TILE {
                    let to = sheet.index(col as u32 * TILE + i, row as u32 * TILE + j);
                    sheet.color[to] = f.color[f.index(i, j)];
                }
            }
            // The split cyclic triple, from the frame just painted.
            if col == 1 && row == 1 {
                let svg = dir.join("painter-cycle.svg");
                let vector = h.ordered_polygons().expect("the painter writes SVG");
                vector.write_svg(&s, &svg, ShadeMode::Lambert)?;
                println!("wrote {}", svg.display());
            }
        }
    }
    let png = dir.join("painter-naive-vs-nns.png");
    sheet.write_png(&png)?;
    println!("wrote {}", png.display());
    Ok(())
}
