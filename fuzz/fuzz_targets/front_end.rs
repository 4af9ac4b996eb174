//! Arbitrary f32 triangles and cameras -> prepare -> every hider. The
//! decoder and the invariants live in `hider::hostile`, so inputs found
//! here replay as the workspace test `tests/hostile.rs`.
#![no_main]

use hider::hostile::{check_all_hiders, front_end_case};
use hider::scene::prepare;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some(case) = front_end_case(data) else {
        return;
    };
    if let Ok(screen) = prepare(&case.scene, &case.view, &case.options)
        && let Err(violation) = check_all_hiders(&screen)
    {
        panic!("{violation}");
    }
});
