//! Arbitrary f32 triangles and cameras -> prepare -> every hider, and the
//! lean front end + fast z-buffer against prepare + ZBuffer. The
//! decoder and the invariants live in `hider_testkit::hostile`, so inputs
//! found here replay as the workspace test `tests/hostile.rs`.
#![no_main]

use hider_scene::prepare;
use hider_testkit::hostile::{check_all_hiders, check_lean_pipeline, front_end_case};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some(case) = front_end_case(data) else {
        return;
    };
    if let Ok(screen) = prepare(&case.scene, &case.view, &case.options)
        && let Err(violation) =
            check_all_hiders(&screen).and_then(|()| check_lean_pipeline(&case, &screen))
    {
        panic!("{violation}");
    }
});
