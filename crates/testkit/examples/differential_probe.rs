//! Decodes inputs with the differential decoder and prints each case's
//! label and outcome: for looking at what the generator makes and for
//! running it outside the fuzzer.
//!
//! ```text
//! cargo run --release -p hider-testkit --features hostile --example differential_probe -- [CASES] [SEED]
//! ```

use std::time::Instant;

use hider_scene::procedural::SplitMix64;
use hider_testkit::differential::{check_case, differential_case};

fn main() {
    let mut args = std::env::args().skip(1);
    let cases: u64 = args.next().and_then(|s| s.parse().ok()).unwrap_or(20);
    let seed: u64 = args.next().and_then(|s| s.parse().ok()).unwrap_or(1);
    let verbose = std::env::var_os("PROBE_VERBOSE").is_some();
    let mut rng = SplitMix64::new(seed);
    let (mut rendered, mut findings, mut slowest) = (0u64, 0u64, (0.0f64, String::new()));
    let start = Instant::now();
    for k in 0..cases {
        let len = (rng.next_u64() % 64) as usize;
        let data: Vec<u8> = (0..len).map(|_| rng.next_u64() as u8).collect();
        let Some(case) = differential_case(&data) else {
            continue;
        };
        let t = Instant::now();
        let result = check_case(&case);
        let dt = t.elapsed().as_secs_f64();
        if dt > slowest.0 {
            slowest = (dt, case.label.clone());
        }
        match result {
            Ok(o) => {
                rendered += u64::from(o.refused.is_none());
                if verbose {
                    println!("{k}: {} -> {o:?}", case.label);
                }
            }
            Err(finding) => {
                findings += 1;
                println!("FINDING {k} {data:?}\n  {finding}");
            }
        }
    }
    println!(
        "{cases} cases, {rendered} rendered and compared, {findings} findings, {:.1} s; slowest {:.3} s: {}",
        start.elapsed().as_secs_f64(),
        slowest.0,
        slowest.1
    );
}
