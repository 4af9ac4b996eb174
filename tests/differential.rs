//! Differential testing: cases decoded from bytes into the hard-case
//! families (exact rotational and mirror symmetry about the view axis,
//! integer and dyadic lattices, coincident and nearly coincident planes,
//! near planes down to `1e-12` of the scene size, far/near up to `1e13`,
//! scales `1e-20` to `1e20`, offsets up to `1e17`, a pile over one pixel,
//! repeated vertex lists, slivers and degenerate triangles), on which every
//! exact pixel-centre hider must give the oracle's id off ties, every
//! pixel-centre hider the oracle's coverage, and none hold more than its
//! budget (`hider_testkit::differential`).
//!
//! The same decoder drives the `differential` cargo-fuzz target, so an
//! input either finds replays in the other: put its bytes in
//! `tests/fuzz-regressions/differential/`.
//!
//! `PROPTEST_CASES=N` sets the case count (default 48, a few seconds);
//! shrunk failures are kept in `proptest-regressions/differential.txt`.
//! Run with `--nocapture` to see the tallies.

mod common;

use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};

use common::config;
use hider_testkit::differential::{check_case, differential_case};
use proptest::prelude::*;
use proptest::test_runner::TestRunner;

fn replay(data: &[u8]) -> Result<u64, String> {
    match differential_case(data) {
        Some(case) => check_case(&case).map(|o| u64::from(o.refused.is_none())),
        None => Ok(0),
    }
}

#[test]
fn differential_regressions_replay_cleanly() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz-regressions/differential");
    let entries = std::fs::read_dir(&dir).expect("the stored differential regressions");
    let mut replayed = 0;
    for entry in entries {
        let path = entry.unwrap().path();
        let data = std::fs::read(&path).unwrap();
        // Stored findings must now render: neither a wrong pixel nor a
        // refusal under a budget (the painter's split cascade behind tiny
        // near planes once ran out of its split budget on these).
        let case = differential_case(&data).expect("a stored case has a camera");
        match check_case(&case) {
            Ok(outcome) => assert!(
                outcome.budget_refusals.is_empty() && outcome.refused.is_none(),
                "{}: {:?} {:?}",
                path.display(),
                outcome.refused,
                outcome.budget_refusals
            ),
            Err(finding) => panic!("{}: {finding}", path.display()),
        }
        replayed += 1;
    }
    assert!(replayed >= 5, "only {replayed} stored cases");
}

#[test]
fn every_exact_hider_equals_the_oracle_off_ties() {
    let rendered = AtomicU64::new(0);
    let total = AtomicU64::new(0);
    let mut runner = TestRunner::new(config("proptest-regressions/differential.txt", 48));
    runner
        .run(&prop::collection::vec(any::<u8>(), 0..64), |data| {
            total.fetch_add(1, Ordering::Relaxed);
            match replay(&data) {
                Ok(n) => {
                    rendered.fetch_add(n, Ordering::Relaxed);
                    Ok(())
                }
                Err(finding) => Err(TestCaseError::fail(finding)),
            }
        })
        .unwrap();
    println!(
        "differential: {} cases, {} rendered and compared",
        total.load(Ordering::Relaxed),
        rendered.load(Ordering::Relaxed)
    );
}
