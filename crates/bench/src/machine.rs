//! The machine a run was made on: CPU model, cores, operating system and
//! the threads a hider may use, recorded with every results file so that
//! timings from different machines are never compared unawares.

use serde::{Deserialize, Serialize};

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
    /// Recorded so that the times of parallel hiders (the tiled z-buffer)
    /// are read against the threads they had.
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

/// This process's peak resident memory in bytes (Linux's `VmHWM` in
/// `/proc/self/status`), `None` where the platform reports none. The bench
/// programs that measure memory run each case in a child process, or
/// start a new peak with [`reset_peak_resident`], so that the figure is
/// that case's.
pub fn peak_resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// Starts a new peak of resident memory for [`peak_resident_bytes`]
/// (Linux: `5` written to `/proc/self/clear_refs` sets `VmHWM` to the
/// current resident size; elsewhere nothing happens).
pub fn reset_peak_resident() {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn machine_is_described() {
        let m = Machine::detect();
        assert!(m.cores >= 1 && m.threads >= 1);
        assert!(!m.cpu.is_empty() && !m.os.is_empty());
    }
}
