//! Stopping a render from outside: a cancel token every hider polls.
//!
//! A [`Cancel`] is handed to a hider through its options (every hider's
//! options have a `cancel` field; `hider_plan::HiderConfig::cancel` passes
//! one to any registered hider). Whoever holds a copy can stop the work
//! with [`Cancel::cancel`], or give it a deadline
//! ([`Cancel::with_timeout`]); the hider polls [`Cancel::poll`] at the
//! heads of its long loops (per tile, bin, band of rows, batch of pairs,
//! a few hundred polygons) and returns [`Error::Cancelled`] soon after,
//! leaving the frame half drawn.
//!
//! The default token is never cancelled and costs one branch to poll, so
//! code that does not stop renders pays nothing.
//!
//! ```
//! use std::time::Duration;
//! use hider_scene::{Cancel, Cancelled};
//!
//! let token = Cancel::new();
//! let hider_side = token;
//! assert!(hider_side.check().is_ok());
//! token.cancel();
//! assert_eq!(hider_side.check(), Err(Cancelled::Requested));
//!
//! let late = Cancel::default().with_timeout(Duration::ZERO);
//! assert!(matches!(late.check(), Err(Cancelled::TimedOut { .. })));
//! assert!(Cancel::default().check().is_ok());
//! ```
//!

use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use crate::Error;

/// How many iterations of a cheap loop (a triangle's set-up, a pair's
/// bounding-box test) a hider runs between two polls: a poll with a
/// deadline reads the clock (some 25 ns), which 1024 iterations of
/// anything make invisible, and 1024 iterations of the costliest such
/// loop take well under the 10 ms a cancel may wait.
pub const POLL_EVERY: usize = 1024;

/// Why a render stopped early: the error [`Cancel::check`] returns.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Cancelled {
    /// [`Cancel::cancel`] was called (Ctrl-C in Python, a caller giving
    /// up).
    #[error("render cancelled")]
    Requested,
    /// The token's deadline passed.
    #[error("render timed out after {timeout:?}")]
    TimedOut {
        /// The time the token was given ([`Cancel::with_timeout`]; for
        /// [`Cancel::with_deadline`], from then to the deadline).
        timeout: Duration,
    },
}

/// A cheap stop signal with an optional deadline; copies share it. See
/// the [module documentation](self).
///
/// A token is `Copy` (a pointer), so that the hiders' options, plain
/// `Copy` structs, can hold one. The state a live token points to is
/// never freed: [`Cancel::new`] keeps some 32 bytes for the rest of the
/// program. Tokens are made to be kept (one per worker or per window,
/// re-armed with [`Cancel::reset`] between renders, as the Python package
/// does), not one per frame.
///
/// Equality is identity: two tokens are equal when they are copies of one
/// (or both the never-cancelled default).
#[derive(Clone, Copy, Debug, Default)]
pub struct Cancel(Option<&'static Shared>);

/// The state copies share.
#[derive(Debug)]
struct Shared {
    /// Set by [`Cancel::cancel`].
    cancelled: AtomicBool,
    /// The deadline in nanoseconds after [`epoch`], [`NO_DEADLINE`] for
    /// none: an integer, so that a deadline can be set on a shared token.
    deadline: AtomicU64,
    /// The timeout the deadline came from, in nanoseconds, for the error.
    timeout: AtomicU64,
}

/// [`Shared::deadline`] of a token without one.
const NO_DEADLINE: u64 = u64::MAX;

/// The instant deadlines count from, taken the first time a deadline is
/// set: a program that sets none never reads the clock (WebAssembly
/// without a clock runs every hider).
fn epoch() -> Instant {
    static EPOCH: OnceLock<Instant> = OnceLock::new();
    *EPOCH.get_or_init(Instant::now)
}

/// Nanoseconds after [`epoch`], saturating (an instant before it is 0).
fn since_epoch(t: Instant) -> u64 {
    let nanos = t.saturating_duration_since(epoch()).as_nanos();
    u64::try_from(nanos).unwrap_or(NO_DEADLINE - 1)
}

impl Cancel {
    /// A token that can be cancelled, not yet cancelled, without a
    /// deadline.
    pub fn new() -> Self {
        // Leaked so that the token can be `Copy`: see the type's
        // documentation.
        Self(Some(Box::leak(Box::new(Shared {
            cancelled: AtomicBool::new(false),
            deadline: AtomicU64::new(NO_DEADLINE),
            timeout: AtomicU64::new(0),
        }))))
    }

    /// This token with a deadline (a new live token if it was the
    /// default): [`Cancel::check`] fails with [`Cancelled::TimedOut`] from
    /// then on. An instant already past times out at the first poll.
    pub fn with_deadline(self, deadline: Instant) -> Self {
        let token = if self.0.is_some() { self } else { Self::new() };
        token.set_deadline(Some(deadline));
        token
    }

    /// This token with a deadline `timeout` from now
    /// ([`Cancel::with_deadline`]).
    pub fn with_timeout(self, timeout: Duration) -> Self {
        let token = if self.0.is_some() { self } else { Self::new() };
        token.set_timeout(Some(timeout));
        token
    }

    /// Sets or clears the deadline of this token and every copy (no
    /// effect on the default token, which nothing can stop).
    pub fn set_deadline(&self, deadline: Option<Instant>) {
        if let Some(shared) = &self.0 {
            let (at, timeout) = match deadline {
                Some(t) => {
                    let now = Instant::now();
                    (since_epoch(t), t.saturating_duration_since(now))
                }
                None => (NO_DEADLINE, Duration::ZERO),
            };
            let timeout = u64::try_from(timeout.as_nanos()).unwrap_or(u64::MAX);
            shared.timeout.store(timeout, Ordering::Relaxed);
            shared.deadline.store(at, Ordering::Relaxed);
        }
    }

    /// Sets (a deadline `timeout` from now) or clears the deadline of this
    /// token and every copy, as [`Cancel::set_deadline`].
    pub fn set_timeout(&self, timeout: Option<Duration>) {
        if let Some(shared) = &self.0 {
            let Some(timeout) = timeout else {
                return self.set_deadline(None);
            };
            let at = Instant::now()
                .checked_add(timeout)
                .map_or(NO_DEADLINE - 1, since_epoch);
            let nanos = u64::try_from(timeout.as_nanos()).unwrap_or(u64::MAX);
            shared.timeout.store(nanos, Ordering::Relaxed);
            shared.deadline.store(at, Ordering::Relaxed);
        }
    }

    /// Stops every render polling this token or a copy (no effect on the
    /// default token).
    pub fn cancel(&self) {
        if let Some(shared) = &self.0 {
            shared.cancelled.store(true, Ordering::Relaxed);
        }
    }

    /// Clears the cancel and the deadline, so that the token (and the
    /// hiders holding copies) can run the next render: for a caller that
    /// keeps one token per worker and renders one frame at a time.
    pub fn reset(&self) {
        if let Some(shared) = &self.0 {
            shared.cancelled.store(false, Ordering::Relaxed);
            shared.deadline.store(NO_DEADLINE, Ordering::Relaxed);
        }
    }

    /// Whether this token can be cancelled at all (the default cannot).
    pub fn is_live(&self) -> bool {
        self.0.is_some()
    }

    /// `Ok` while the work may go on; the reason to stop otherwise. One
    /// branch on the default token; a relaxed load, and the clock when a
    /// deadline is set, on the others.
    #[inline]
    pub fn check(&self) -> Result<(), Cancelled> {
        match &self.0 {
            None => Ok(()),
            Some(shared) => shared.check(),
        }
    }

    /// [`Cancel::check`] as the crate's error ([`Error::Cancelled`]), for
    /// `?` in a hider's loop.
    #[inline]
    pub fn poll(&self) -> crate::Result<()> {
        self.check().map_err(Error::Cancelled)
    }

    /// [`Cancel::poll`] every [`POLL_EVERY`] iterations of a loop: `Ok`
    /// without looking when `iteration` is not a multiple of it.
    #[inline]
    pub fn poll_every(&self, iteration: usize) -> crate::Result<()> {
        if iteration.is_multiple_of(POLL_EVERY) {
            self.poll()
        } else {
            Ok(())
        }
    }
}

impl Shared {
    /// [`Cancel::check`] of a live token.
    #[cold]
    #[inline(never)]
    fn check(&self) -> Result<(), Cancelled> {
        if self.cancelled.load(Ordering::Relaxed) {
            return Err(Cancelled::Requested);
        }
        let deadline = self.deadline.load(Ordering::Relaxed);
        if deadline != NO_DEADLINE && since_epoch(Instant::now()) >= deadline {
            let timeout = Duration::from_nanos(self.timeout.load(Ordering::Relaxed));
            return Err(Cancelled::TimedOut { timeout });
        }
        Ok(())
    }
}

impl PartialEq for Cancel {
    fn eq(&self, other: &Self) -> bool {
        match (&self.0, &other.0) {
            (None, None) => true,
            (Some(a), Some(b)) => std::ptr::eq(*a, *b),
            _ => false,
        }
    }
}

impl Eq for Cancel {}

impl std::hash::Hash for Cancel {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.0.map(|s| s as *const Shared).hash(state);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_never_stops_and_cannot_be_cancelled() {
        let never = Cancel::default();
        never.cancel();
        assert_eq!(never.check(), Ok(()));
        assert!(!never.is_live());
        assert_eq!(never, Cancel::default());
    }

    #[test]
    fn copies_share_the_cancel_and_reset_rearms_them() {
        let a = Cancel::new();
        let b = a;
        assert_eq!(a, b);
        assert_ne!(a, Cancel::new());
        b.cancel();
        assert_eq!(a.check(), Err(Cancelled::Requested));
        a.reset();
        assert_eq!(b.check(), Ok(()));
    }

    #[test]
    fn a_past_deadline_times_out_and_names_the_timeout() {
        let t = Cancel::default().with_timeout(Duration::from_millis(0));
        let e = t.check().unwrap_err();
        assert_eq!(
            e,
            Cancelled::TimedOut {
                timeout: Duration::ZERO
            }
        );
        assert_eq!(e.to_string(), "render timed out after 0ns");
        let past = Instant::now() - Duration::from_millis(5);
        let d = Cancel::new().with_deadline(past);
        assert!(matches!(d.check(), Err(Cancelled::TimedOut { .. })));
        d.set_deadline(None);
        assert_eq!(d.check(), Ok(()));
        let far = Cancel::new().with_timeout(Duration::from_secs(3600));
        assert_eq!(far.check(), Ok(()));
        // A cancel wins over a deadline not yet reached.
        far.cancel();
        assert_eq!(far.check(), Err(Cancelled::Requested));
    }

    #[test]
    fn poll_every_looks_once_per_period() {
        let t = Cancel::new();
        t.cancel();
        assert!(matches!(
            t.poll_every(0),
            Err(Error::Cancelled(Cancelled::Requested))
        ));
        assert!(t.poll_every(1).is_ok());
        assert!(t.poll_every(POLL_EVERY).is_err());
    }
}
