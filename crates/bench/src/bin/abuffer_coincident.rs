//! Times the A-buffer on a face whose vertex list repeats itself
//! (`f 1 2 3 4 1 2 3 4 ...`, 1900 entries): about 950 triangles, in two
//! sets of exactly coincident copies, at 512 x 512, opaque and translucent.
//!
//! `cargo run --release -p hider-bench --bin abuffer_coincident [-- "1 2 3 4 2 3 4 1"]`
//! (the vertex list that repeats, default `1 2 3 4`)

use std::path::Path;
use std::time::Instant;

use hider_abuffer::{ABuffer, ABufferOptions};
use hider_scene::obj::{ObjOptions, load_obj_bytes};
use hider_scene::{Frame, Hider, Material};
use hider_testkit::screen;

fn main() {
    let face = std::env::args().nth(1).unwrap_or_else(|| "1 2 3 4".into());
    let mut obj = String::from("v -1 -1 0\nv 1 -1 0.3\nv 1 1 0.1\nv -1 1 -0.2\nf");
    for _ in 0..1900 / face.split_whitespace().count().max(1) {
        obj.push(' ');
        obj.push_str(&face);
    }
    obj.push('\n');
    let options = ObjOptions::default();
    let opaque = load_obj_bytes(
        obj.as_bytes(),
        Path::new("repeated.obj"),
        Path::new(""),
        &options,
    )
    .expect("the OBJ loads");
    let mut glass = opaque.clone();
    glass.materials.push(Material {
        opacity: 0.5,
        ..Material::default()
    });
    for mesh in &mut glass.meshes {
        mesh.material = Some(0);
    }
    for (name, scene) in [("opaque", &opaque), ("translucent", &glass)] {
        let s = screen(scene, 512, 512);
        for (hider, o) in [
            ("abuffer", ABufferOptions::default()),
            ("abuffer-carpenter", ABufferOptions::carpenter()),
        ] {
            let mut a = ABuffer::new(o);
            let mut frame = Frame::new(512, 512).expect("frame");
            let t = Instant::now();
            let st = a.render(&s, &mut frame).expect("render");
            println!(
                "{name} {hider}: {} triangles, {:.1} ms, fragments {}, coincident {}, dropped {}, max list {}",
                s.tris.len(),
                t.elapsed().as_secs_f64() * 1e3,
                st.fragments,
                st.coincident,
                st.dropped,
                st.max_list_len
            );
            for w in st.warnings() {
                println!("  warning: {w}");
            }
        }
    }
}
