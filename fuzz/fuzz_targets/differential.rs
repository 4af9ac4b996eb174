//! Bytes decoded into the hard-case families at extreme scales, offsets
//! and near planes; every exact hider must equal the oracle off ties,
//! coverage must be identical across the pixel-centre hiders, budgets
//! respected. The decoder and the check live in
//! `hider_testkit::differential`, so a finding replays as the workspace
//! test `tests/differential.rs` (save its bytes under
//! `tests/fuzz-regressions/differential/`).
#![no_main]

use hider_testkit::differential::{check_case, differential_case};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some(case) = differential_case(data) else {
        return;
    };
    if let Err(finding) = check_case(&case) {
        panic!("{finding}");
    }
});
