//! The median/min timer for examples: [`hider_scene::timing`], which the
//! command line's `--repeat` and the benchmark use too.
//!
//! ```
//! use hider_testkit::timer::Timer;
//!
//! let summary = Timer::new(5).time(|| {
//!     std::hint::black_box((0..1000u64).sum::<u64>());
//! });
//! println!("sum: {summary}"); // median X ms, min Y ms over 5 runs
//! assert_eq!(summary.runs, 5);
//! ```

pub use hider_scene::timing::{Summary, Timer};
