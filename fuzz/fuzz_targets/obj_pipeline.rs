//! OBJ bytes -> load -> prepare -> render with every hider. Nothing may
//! panic, hang or allocate without bound.
#![no_main]

use std::path::Path;

use hider_scene::obj::{ObjOptions, load_obj_bytes};
use hider_scene::{PrepareOptions, View, prepare};
use hider_testkit::hostile::check_all_hiders;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // Small limits keep each execution fast: the fuzzer looks for panics,
    // not for slow large scenes.
    let options = ObjOptions {
        max_triangles: 2_000,
        ..ObjOptions::default()
    };
    let Ok(scene) = load_obj_bytes(
        data,
        Path::new("fuzz.obj"),
        Path::new("/nonexistent"),
        &options,
    ) else {
        return;
    };
    let Ok(view) = View::for_scene(&scene, 24, 16) else {
        return;
    };
    if let Ok(screen) = prepare(&scene, &view, &PrepareOptions::default())
        && let Err(violation) = check_all_hiders(&screen)
    {
        panic!("{violation}");
    }
});
