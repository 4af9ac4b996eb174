//! Timing done right: warm-up runs that are not measured, repeated
//! measured runs, the median (robust to a neighbour's build stealing the
//! CPU) with the min-max spread, and a description of the machine.

use std::time::{Duration, Instant};

use serde::{Deserialize, Serialize};

/// How often to run each job. `Default` is the default matrix's choice.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimingOptions {
    /// Unmeasured runs first: they fault in pages, fill caches and let the
    /// hider size its scratch buffers (render takes `&mut self` and keeps
    /// them), so measured runs see the steady state.
    pub warmup: u32,
    /// Measured runs (at least 1).
    pub repeats: u32,
    /// Stop repeating once the measured runs of one job have taken this
    /// long (at least one run is always measured), so slow hiders on large
    /// scaling cases do not dominate the sweep.
    pub max_seconds_per_job: f64,
}

impl Default for TimingOptions {
    fn default() -> Self {
        Self {
            warmup: 1,
            repeats: 5,
            max_seconds_per_job: 2.0,
        }
    }
}

/// Summary of repeated measurements, in milliseconds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
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
    /// Summarises `samples` (empty gives all zeros).
    pub fn of(samples: &[Duration]) -> Self {
        if samples.is_empty() {
            return Self::default();
        }
        // Rounded to 0.1 microsecond: finer digits are clock noise and only
        // clutter the CSV.
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

/// Runs `f` `warmup` times unmeasured, then measured up to `repeats` times
/// within the time budget; stops at the first error. `stop` is polled
/// between runs (Ctrl-C).
pub fn measure<E>(
    options: &TimingOptions,
    stop: &dyn Fn() -> bool,
    mut f: impl FnMut() -> Result<(), E>,
) -> Result<Summary, E> {
    for _ in 0..options.warmup {
        if stop() {
            break;
        }
        f()?;
    }
    let mut samples = Vec::with_capacity(options.repeats as usize);
    let started = Instant::now();
    for k in 0..options.repeats.max(1) {
        if k > 0 && (stop() || started.elapsed().as_secs_f64() > options.max_seconds_per_job) {
            break;
        }
        let t = Instant::now();
        f()?;
        samples.push(t.elapsed());
    }
    Ok(Summary::of(&samples))
}

/// The machine a run was made on.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Machine {
    /// CPU model from `/proc/cpuinfo` (or "unknown").
    pub cpu: String,
    /// Logical cores the process may use.
    pub cores: u32,
    /// Operating system: `PRETTY_NAME` of `/etc/os-release` and the kernel
    /// release where available, else the target OS.
    pub os: String,
    /// Threads a hider may use: `RAYON_NUM_THREADS` if set, else the cores.
    /// Every hider in the registry today renders on one thread; the value
    /// is recorded so runs with parallel hiders stay comparable.
    pub threads: u32,
}

impl Machine {
    /// Describes the machine this process runs on.
    pub fn detect() -> Self {
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|s| {
                s.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split_once(':'))
                    .map(|(_, v)| v.trim().to_owned())
            })
            .unwrap_or_else(|| "unknown".into());
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get() as u32);
        let pretty = std::fs::read_to_string("/etc/os-release")
            .ok()
            .and_then(|s| {
                s.lines()
                    .find_map(|l| l.strip_prefix("PRETTY_NAME="))
                    .map(|v| v.trim_matches('"').to_owned())
            });
        let kernel = std::fs::read_to_string("/proc/sys/kernel/osrelease")
            .ok()
            .map(|s| s.trim().to_owned());
        let os = match (pretty, kernel) {
            (Some(p), Some(k)) => format!("{p}, kernel {k}"),
            (Some(p), None) => p,
            (None, Some(k)) => format!("{} {k}", std::env::consts::OS),
            (None, None) => std::env::consts::OS.to_owned(),
        };
        let threads = std::env::var("RAYON_NUM_THREADS")
            .ok()
            .and_then(|v| v.parse().ok())
            .filter(|&t: &u32| t > 0)
            .unwrap_or(cores);
        Self {
            cpu,
            cores,
            os,
            threads,
        }
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
    }

    #[test]
    fn measure_warms_up_repeats_and_stops_on_errors() {
        let mut calls = 0;
        let o = TimingOptions {
            warmup: 2,
            repeats: 3,
            max_seconds_per_job: 100.0,
        };
        let s = measure::<()>(&o, &|| false, || {
            calls += 1;
            Ok(())
        })
        .unwrap();
        assert_eq!((calls, s.runs), (5, 3));
        let mut calls = 0;
        let r = measure(&o, &|| false, || {
            calls += 1;
            if calls == 3 { Err("boom") } else { Ok(()) }
        });
        assert_eq!(r, Err("boom"));
        // A stop request still leaves one measured run.
        let s = measure::<()>(&o, &|| true, || Ok(())).unwrap();
        assert_eq!(s.runs, 1);
    }

    #[test]
    fn machine_is_described() {
        let m = Machine::detect();
        assert!(m.cores >= 1 && m.threads >= 1);
        assert!(!m.cpu.is_empty() && !m.os.is_empty());
    }
}
