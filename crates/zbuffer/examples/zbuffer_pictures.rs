//! Makes the pictures of `docs/zbuffer.md`: the spider of the GL reference
//! shaded, and the error of linear camera depth on two intersecting
//! triangles (wrong pixels in white).
//!
//! `cargo run --release -p hider-zbuffer --example zbuffer_pictures`

use std::path::PathBuf;

use hider_scene::{
    Frame, Hider, PrepareOptions, ShadeMode, View, load_obj, prepare, procedural, shade_frame,
};
use hider_zbuffer::{DepthFormat, DepthSource, ZBuffer, ZBufferOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let images = root.join("docs/images");
    std::fs::create_dir_all(&images)?;

    let spider = root.join("../shared/gl-reference/models/spider.obj");
    if spider.exists() {
        let scene = load_obj(&spider)?;
        let view = View::for_scene(&scene, 384, 384)?;
        let screen = prepare(&scene, &view, &PrepareOptions::default())?;
        let mut frame = Frame::new(384, 384)?;
        ZBuffer::default().render(&screen, &mut frame)?;
        shade_frame(&screen, &mut frame, ShadeMode::Lambert)?;
        frame.write_png(&images.join("zbuffer-spider.png"))?;
    } else {
        eprintln!("skipped the spider: {} not found", spider.display());
    }

    let scene = procedural::intersecting_pair();
    let view = View::for_scene(&scene, 256, 256)?;
    let screen = prepare(&scene, &view, &PrepareOptions::default())?;
    let mut good = Frame::new(256, 256)?;
    let mut bad = Frame::new(256, 256)?;
    ZBuffer::new(ZBufferOptions::default().with_depth_format(DepthFormat::F64))
        .render(&screen, &mut good)?;
    ZBuffer::new(ZBufferOptions::default().with_depth_source(DepthSource::LinearViewZ))
        .render(&screen, &mut bad)?;
    shade_frame(&screen, &mut bad, ShadeMode::Lambert)?;
    let mut wrong = 0;
    for i in 0..bad.len() {
        if good.ids[i] != bad.ids[i] {
            bad.color[i] = [255, 255, 255, 255];
            wrong += 1;
        }
    }
    bad.write_png(&images.join("zbuffer-linear-z-error.png"))?;
    println!(
        "linear view z: {wrong} of {} covered pixels wrong on the intersecting pair",
        good.covered_count()
    );
    Ok(())
}
