//! Hostile inputs through the whole pipeline: arbitrary bytes decoded as
//! triangles and cameras (the fuzz targets' decoder), and every input the
//! fuzzer ever found a problem with, replayed as a regression test.

use std::path::PathBuf;

use hider::scene::prepare;
use hider_testkit::hostile::{
    all_violations, check_all_hiders, check_lean_pipeline, front_end_case,
};
use proptest::prelude::*;

fn replay(data: &[u8]) -> Result<(), String> {
    let Some(case) = front_end_case(data) else {
        return Ok(());
    };
    match prepare(&case.scene, &case.view, &case.options) {
        Ok(screen) => check_all_hiders(&screen).and_then(|()| check_lean_pipeline(&case, &screen)),
        Err(_) => Ok(()),
    }
}

#[test]
fn fuzz_regressions_replay_cleanly() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz-regressions");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        // Subfolders hold other targets' inputs (differential/).
        if path.is_dir() {
            continue;
        }
        let data = std::fs::read(&path).unwrap();
        if replay(&data).is_err() {
            let case = front_end_case(&data).unwrap();
            let screen = prepare(&case.scene, &case.view, &case.options).unwrap();
            panic!(
                "{}: {:?} {:?}\n{:?}",
                path.display(),
                all_violations(&screen),
                check_lean_pipeline(&case, &screen),
                screen.tris
            );
        }
        count += 1;
    }
    assert!(count > 0, "no regression inputs found in {}", dir.display());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn arbitrary_bytes_never_break_a_hider(data in prop::collection::vec(any::<u8>(), 52..240)) {
        prop_assert_eq!(replay(&data), Ok(()));
    }

    #[test]
    fn arbitrary_finite_geometry_never_breaks_a_hider(
        camera in prop::collection::vec(-20.0f32..20.0, 13),
        corners in prop::collection::vec(prop_oneof![-1e7f32..1e7, -2.0f32..2.0], 9..45),
        size in any::<[u8; 3]>(),
    ) {
        let mut data = size.to_vec();
        data.push(0);
        data.truncate(0);
        let mut floats = camera;
        floats.extend(corners);
        for f in floats {
            data.extend(f.to_le_bytes());
        }
        data[0] = size[0];
        data[1] = size[1];
        data[2] = size[2];
        prop_assert_eq!(replay(&data), Ok(()));
    }
}
