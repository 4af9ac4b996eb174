//! Runs the differential check (`hider_testkit::differential`) on random
//! inputs outside the fuzzer, in release, and sums up the findings by
//! hider and message (the first few inputs of each printed as bytes); or
//! replays one input given as comma-separated bytes.
//!
//! ```text
//! cargo run --release -p hider-testkit --features hostile --example differential_probe -- [CASES] [SEED]
//! cargo run --release -p hider-testkit --features hostile --example differential_probe -- --bytes 0,3,1,8
//! ```
//!
//! `PROBE_VERBOSE=1` prints every case's label and outcome;
//! `PROBE_FILTER=TEXT` checks only the cases whose label contains `TEXT`
//! (to hunt one family). A progress line goes to stderr every 1,000
//! cases, and every case slower than half a second is named there with its
//! bytes, so it can be replayed.

use std::collections::BTreeMap;
use std::time::Instant;

use hider_scene::procedural::SplitMix64;
use hider_testkit::differential::{check_case, differential_case};

/// Replays one input and prints what it is and what the check says.
fn replay(bytes: &str) {
    let data: Vec<u8> = bytes
        .split(',')
        .map(|b| b.trim().parse().expect("bytes 0 to 255"))
        .collect();
    match differential_case(&data) {
        None => println!("{data:?}: the camera is refused"),
        Some(case) => {
            let t = Instant::now();
            let result = check_case(&case);
            let dt = t.elapsed().as_secs_f64();
            println!("{}\n  {result:?}\n  {dt:.3} s", case.label);
        }
    }
}

/// The class of a finding or a refusal: its hider and its message without
/// the case's label and numbers.
fn class(finding: &str) -> String {
    let hider = finding.split([' ', ':']).next().unwrap_or("");
    let message = finding.rsplit(": ").next().unwrap_or("");
    let words: String = message
        .chars()
        .map(|c| if c.is_ascii_digit() { '#' } else { c })
        .collect();
    format!("{hider}: {words}")
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().is_some_and(|a| a == "--bytes") {
        replay(args.get(1).map_or("", String::as_str));
        return;
    }
    let cases: u64 = args.first().and_then(|s| s.parse().ok()).unwrap_or(20);
    let seed: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(1);
    let verbose = std::env::var_os("PROBE_VERBOSE").is_some();
    let filter = std::env::var("PROBE_FILTER").unwrap_or_default();
    let mut rng = SplitMix64::new(seed);
    let (mut rendered, mut slowest) = (0u64, (0.0f64, String::new()));
    let mut findings: BTreeMap<String, u64> = BTreeMap::new();
    let mut budgets: BTreeMap<String, u64> = BTreeMap::new();
    let start = Instant::now();
    for k in 0..cases {
        if k > 0 && k % 1_000 == 0 {
            eprintln!(
                "{k} cases, {rendered} rendered, {} findings, {:.0} s",
                findings.values().sum::<u64>(),
                start.elapsed().as_secs_f64()
            );
        }
        let len = (rng.next_u64() % 64) as usize;
        let data: Vec<u8> = (0..len).map(|_| rng.next_u64() as u8).collect();
        let Some(case) = differential_case(&data) else {
            continue;
        };
        if !case.label.contains(&filter) {
            continue;
        }
        let t = Instant::now();
        let result = check_case(&case);
        let dt = t.elapsed().as_secs_f64();
        if dt > slowest.0 {
            slowest = (dt, case.label.clone());
        }
        if dt > 0.5 {
            let bytes: Vec<String> = data.iter().map(u8::to_string).collect();
            eprintln!(
                "slow: {dt:.2} s: {} --bytes {}",
                case.label,
                bytes.join(",")
            );
        }
        match result {
            Ok(o) => {
                rendered += u64::from(o.refused.is_none());
                for refusal in &o.budget_refusals {
                    let seen = budgets.entry(class(refusal)).or_default();
                    *seen += 1;
                    if *seen <= 3 {
                        let bytes: Vec<String> = data.iter().map(u8::to_string).collect();
                        println!(
                            "BUDGET {k} --bytes {}\n  {refusal} [{}]",
                            bytes.join(","),
                            case.label
                        );
                    }
                }
                if verbose {
                    println!("{k}: {} -> {o:?}", case.label);
                }
            }
            Err(finding) => {
                let seen = findings.entry(class(&finding)).or_default();
                *seen += 1;
                if *seen <= 3 {
                    let bytes: Vec<String> = data.iter().map(u8::to_string).collect();
                    println!("FINDING {k} --bytes {}\n  {finding}", bytes.join(","));
                }
            }
        }
    }
    println!(
        "{cases} cases, {rendered} rendered and compared, {} findings, {:.1} s; slowest {:.3} s: {}",
        findings.values().sum::<u64>(),
        start.elapsed().as_secs_f64(),
        slowest.0,
        slowest.1
    );
    for (class, n) in &findings {
        println!("{n:>8}  {class}");
    }
    println!("refusals under a documented budget:");
    for (class, n) in &budgets {
        println!("{n:>8}  {class}");
    }
}
