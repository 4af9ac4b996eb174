//! Coincident coplanar fragments: a face whose vertex list repeats itself
//! (`f 1 2 3 4 1 2 3 4 ...`) is fan-split into many exactly overlapping
//! triangles. Their fragments tie in depth everywhere, so no strict depth
//! test culls them; they must cost bounded time and lose nothing without
//! saying so.

use std::path::Path;

use hider_abuffer::{ABuffer, ABufferOptions};
use hider_scene::obj::{ObjOptions, load_obj_bytes};
use hider_scene::{Hider, Material, Scene};
use hider_testkit::{render, screen};

/// A quad (slightly tilted, so depth varies over it) whose one face lists
/// its 4 vertices `repeats` times.
fn repeated_quad(repeats: usize) -> Scene {
    let mut obj = String::from("v -1 -1 0\nv 1 -1 0.3\nv 1 1 0.1\nv -1 1 -0.2\nf");
    for _ in 0..repeats {
        obj.push_str(" 1 2 3 4");
    }
    obj.push('\n');
    load_obj_bytes(
        obj.as_bytes(),
        Path::new("repeated.obj"),
        Path::new(""),
        &ObjOptions::default(),
    )
    .unwrap()
}

/// More exact copies per pixel than a list may hold: before coincident
/// opaque triangles were culled, every pixel overflowed, pruning found
/// nothing hidden (equal depths are not strictly behind) and hundreds of
/// fragments per pixel were dropped.
#[test]
fn repeated_vertex_list_renders_as_the_face_once() {
    let (repeats, size) = (150, 24);
    let once = screen(&repeated_quad(1), size, size);
    let many = screen(&repeated_quad(repeats), size, size);
    assert!(many.tris.len() >= 2 * repeats, "{}", many.tris.len());
    for options in [ABufferOptions::default(), ABufferOptions::carpenter()] {
        let (a, sa) = render(&mut ABuffer::new(options), &once);
        let (b, sb) = render(&mut ABuffer::new(options), &many);
        assert_eq!(sb.dropped, 0, "{sb:?}");
        assert!(sb.warnings().is_empty(), "{:?}", sb.warnings());
        assert_eq!(sb.max_list_len, sa.max_list_len, "{sb:?}");
        assert!(sb.coincident > 0, "{sb:?}");
        // The copies tie with the first and lose every tie (higher ids):
        // the image is the face's, bit for bit.
        assert_eq!(a, b, "{options:?}");
    }
}

/// Translucent copies do not hide one another: every layer counts, so a
/// pixel needs more fragments than a list holds. What is dropped is
/// counted and named in a warning, in bounded time.
#[test]
fn dropped_translucent_layers_are_reported() {
    let mut glass = repeated_quad(150);
    glass.materials.push(Material {
        opacity: 0.5,
        ..Material::default()
    });
    for mesh in &mut glass.meshes {
        mesh.material = Some(0);
    }
    let many = screen(&glass, 24, 24);
    let mut a = ABuffer::new(ABufferOptions::default());
    let (_, st) = render(&mut a, &many);
    assert!(st.dropped > 0, "{st:?}");
    let warnings = st.warnings();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(
        warnings[0].contains(&st.dropped.to_string()) && warnings[0].contains("max_list_len"),
        "{warnings:?}"
    );
}
