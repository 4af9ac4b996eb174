//! The texture memory budget: the decoded texture bytes alive in the
//! process are bounded, checked before a texture is decoded.
//!
//! A texture's decoded size is known from its file's header (width x
//! height x bytes per texel, summed over the mip levels kept, see
//! [`super::mip`]), so a texture that would exceed the budget is refused
//! before a byte of it is decoded: its material's colour is drawn, and the
//! refusal (file, size, limit) is what [`super::TextureRef::problem`]
//! reports, which `hider render` prints as a warning.
//!
//! The budget is one per process, not per scene: it bounds memory, which
//! is the process's, and it reaches every decode (the colour pass, the
//! A-buffer, supersampling, a library user's sampler) without options
//! threaded through each hider. [`set_texture_budget`] changes it;
//! [`DEFAULT_TEXTURE_BUDGET`] is the default.

use std::sync::atomic::{AtomicU64, Ordering};

/// The default texture budget: 1 GiB of decoded texels, enough for four
/// 8192 x 8192 RGBA textures at full resolution with their mip levels
/// (each 8192^2 x 4 x 4/3 bytes = 358 MB), or any number at the levels a
/// small image needs.
pub const DEFAULT_TEXTURE_BUDGET: u64 = 1 << 30;

static LIMIT: AtomicU64 = AtomicU64::new(DEFAULT_TEXTURE_BUDGET);
static USED: AtomicU64 = AtomicU64::new(0);

/// Sets the budget: the most decoded texture bytes alive at once in this
/// process. Textures decoded already are kept; later decodes that would
/// exceed it are refused with a warning. The command line's texture budget
/// flag sets it.
pub fn set_texture_budget(bytes: u64) {
    LIMIT.store(bytes, Ordering::Relaxed);
}

/// The budget ([`set_texture_budget`]).
pub fn texture_budget() -> u64 {
    LIMIT.load(Ordering::Relaxed)
}

/// Decoded texture bytes alive now, counted against the budget.
pub fn texture_bytes_in_use() -> u64 {
    USED.load(Ordering::Relaxed)
}

/// Bytes counted against the budget while this is alive (a decoded
/// texture holds one).
#[derive(Debug, PartialEq, Eq)]
pub(crate) struct Reservation {
    bytes: u64,
}

/// Why a reservation was refused: the bytes in use and the limit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct OverBudget {
    pub(crate) used: u64,
    pub(crate) limit: u64,
}

impl Reservation {
    /// Counts `bytes` if they fit the budget with what is in use.
    pub(crate) fn try_new(bytes: u64) -> Result<Self, OverBudget> {
        let limit = texture_budget();
        USED.fetch_update(Ordering::AcqRel, Ordering::Acquire, |used| {
            used.checked_add(bytes).filter(|&total| total <= limit)
        })
        .map(|_| Self { bytes })
        .map_err(|used| OverBudget { used, limit })
    }

    /// Counts `bytes` whatever the budget: for textures the caller built
    /// in memory (their bytes are allocated already).
    pub(crate) fn force(bytes: u64) -> Self {
        USED.fetch_add(bytes, Ordering::AcqRel);
        Self { bytes }
    }
}

impl Clone for Reservation {
    fn clone(&self) -> Self {
        Self::force(self.bytes)
    }
}

impl Drop for Reservation {
    fn drop(&mut self) {
        USED.fetch_sub(self.bytes, Ordering::AcqRel);
    }
}

/// `bytes` in the largest binary unit that keeps it at or above 1 (for
/// messages: "358.0 MB", "1.0 GiB").
pub(crate) fn human_bytes(bytes: u64) -> String {
    const UNITS: [&str; 4] = ["bytes", "KiB", "MiB", "GiB"];
    let mut value = bytes as f64;
    let mut unit = 0;
    while value >= 1024.0 && unit + 1 < UNITS.len() {
        value /= 1024.0;
        unit += 1;
    }
    if unit == 0 {
        format!("{bytes} bytes")
    } else {
        format!("{value:.1} {}", UNITS[unit])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bytes_read_as_people_write_them() {
        assert_eq!(human_bytes(12), "12 bytes");
        assert_eq!(human_bytes(1 << 30), "1.0 GiB");
        assert_eq!(human_bytes(3 << 19), "1.5 MiB");
    }
}
