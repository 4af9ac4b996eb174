//! Timing a frame loop: unmeasured warm-up runs, repeated measured runs,
//! and their median and minimum, the numbers the examples, the command
//! line's `--repeat` and the benchmark report.
//!
//! ```
//! use hider_scene::timing::Timer;
//!
//! let mut n = 0u64;
//! let summary = Timer::new(3).with_warmup(1).time(|| n += 1);
//! assert_eq!((n, summary.runs), (4, 3));
//! assert!(summary.min_ms <= summary.median_ms && summary.median_ms <= summary.max_ms);
//! ```

use std::time::{Duration, Instant};

/// How often to run what is timed. `Default`: one warm-up run, five
/// measured runs, no time limit.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct Timer {
    /// Unmeasured runs first: they fault in pages, fill caches and let a
    /// hider size its scratch buffers (`render` takes `&mut self` and keeps
    /// them), so measured runs see the steady state.
    pub warmup: u32,
    /// Measured runs (at least one is always made).
    pub runs: u32,
    /// Stop measuring once the measured runs have taken this many seconds
    /// (after at least one run), so a slow case does not dominate a sweep.
    pub max_seconds: f64,
}

impl Default for Timer {
    fn default() -> Self {
        Self {
            warmup: 1,
            runs: 5,
            max_seconds: f64::INFINITY,
        }
    }
}

impl Timer {
    /// A timer of `runs` measured runs after one warm-up run.
    pub fn new(runs: u32) -> Self {
        Self {
            runs,
            ..Self::default()
        }
    }

    /// Sets [`Self::warmup`].
    pub fn with_warmup(mut self, warmup: u32) -> Self {
        self.warmup = warmup;
        self
    }

    /// Sets [`Self::runs`].
    pub fn with_runs(mut self, runs: u32) -> Self {
        self.runs = runs;
        self
    }

    /// Sets [`Self::max_seconds`].
    pub fn with_max_seconds(mut self, seconds: f64) -> Self {
        self.max_seconds = seconds;
        self
    }

    /// Times `f`, which cannot fail.
    pub fn time(&self, mut f: impl FnMut()) -> Summary {
        let never = || false;
        match self.try_time::<std::convert::Infallible>(&never, || {
            f();
            Ok(())
        }) {
            Ok(summary) => summary,
            Err(never) => match never {},
        }
    }

    /// Times `f`: the warm-up runs unmeasured, then the measured runs
    /// within [`Self::max_seconds`]; stops at the first error. `stop` is
    /// asked between runs (a Ctrl-C flag); a stop request still leaves one
    /// measured run.
    pub fn try_time<E>(
        &self,
        stop: &dyn Fn() -> bool,
        mut f: impl FnMut() -> Result<(), E>,
    ) -> Result<Summary, E> {
        for _ in 0..self.warmup {
            if stop() {
                break;
            }
            f()?;
        }
        let mut samples = Vec::with_capacity(self.runs.max(1) as usize);
        let started = Instant::now();
        for k in 0..self.runs.max(1) {
            if k > 0 && (stop() || started.elapsed().as_secs_f64() > self.max_seconds) {
                break;
            }
            let t = Instant::now();
            f()?;
            samples.push(t.elapsed());
        }
        Ok(Summary::of(&samples))
    }
}

/// Repeated measurements summarised, in milliseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Summary {
    /// Median of the runs (mean of the two middle ones for an even count).
    pub median_ms: f64,
    /// Fastest run.
    pub min_ms: f64,
    /// Slowest run.
    pub max_ms: f64,
    /// Number of runs.
    pub runs: u32,
}

impl Summary {
    /// Summarises `samples` (empty gives all zeros). Times are rounded to
    /// 0.1 microsecond: finer digits are clock noise.
    pub fn of(samples: &[Duration]) -> Self {
        if samples.is_empty() {
            return Self::default();
        }
        let mut ms: Vec<f64> = samples
            .iter()
            .map(|d| (d.as_secs_f64() * 1e7).round() / 1e4)
            .collect();
        ms.sort_by(f64::total_cmp);
        let n = ms.len();
        let median = if n % 2 == 1 {
            ms[n / 2]
        } else {
            0.5 * (ms[n / 2 - 1] + ms[n / 2])
        };
        Self {
            median_ms: median,
            min_ms: ms[0],
            max_ms: ms[n - 1],
            runs: n as u32,
        }
    }
}

impl std::fmt::Display for Summary {
    /// `median X ms, min Y ms over N runs`, three decimals.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "median {:.3} ms, min {:.3} ms over {} runs",
            self.median_ms, self.min_ms, self.runs
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summary_takes_median_and_range() {
        let d = |ms: u64| Duration::from_millis(ms);
        let s = Summary::of(&[d(5), d(1), d(3)]);
        assert_eq!(
            (s.median_ms, s.min_ms, s.max_ms, s.runs),
            (3.0, 1.0, 5.0, 3)
        );
        assert_eq!(Summary::of(&[d(4), d(2)]).median_ms, 3.0);
        assert_eq!(Summary::of(&[]).runs, 0);
        assert_eq!(s.to_string(), "median 3.000 ms, min 1.000 ms over 3 runs");
    }

    #[test]
    fn timer_warms_up_repeats_and_stops_on_errors() {
        let timer = Timer::new(3).with_warmup(2).with_max_seconds(100.0);
        let mut calls = 0;
        let s = timer
            .try_time::<()>(&|| false, || {
                calls += 1;
                Ok(())
            })
            .unwrap();
        assert_eq!((calls, s.runs), (5, 3));
        let mut calls = 0;
        let r = timer.try_time(&|| false, || {
            calls += 1;
            if calls == 3 { Err("boom") } else { Ok(()) }
        });
        assert_eq!(r, Err("boom"));
        // A stop request still leaves one measured run.
        let s = timer.try_time::<()>(&|| true, || Ok(())).unwrap();
        assert_eq!(s.runs, 1);
        let mut calls = 0;
        assert_eq!(Timer::new(0).with_warmup(0).time(|| calls += 1).runs, 1);
        assert_eq!(calls, 1);
    }
}
