//! Ctrl-C that stops a render running on the main thread itself.
//!
//! CPython runs a Python signal handler on the main thread only, between
//! bytecodes; while a hider runs in Rust with the GIL released, a SIGINT
//! only sets CPython's "tripped" flag, and `KeyboardInterrupt` would wait
//! for the render to end. The package used to move every main-thread call
//! to a worker thread and wait on it, so that the main thread stayed free
//! to take the signal: two thread hand-offs a call, some 0.1 ms, which is a
//! sixth of a 1024 px frame of a small mesh.
//!
//! [`SigintCancels`] does it in place instead: while it is entered, the
//! C-level SIGINT handler is one that cancels the package's main-thread
//! token (an atomic store, which a signal handler may do) and then calls
//! the handler it replaced, CPython's own, so that Python still sees the
//! signal. The hider stops at its next poll, returns `KeyboardInterrupt`,
//! and on exit the old handler is put back and the signal CPython recorded
//! is handled at once (`PyErr_CheckSignals`), so that it is raised once,
//! in the call, and not a second time in the caller's `except` block.
//!
//! The package enters it only on the main thread and only while Python's
//! SIGINT handler is `signal.default_int_handler` (the one that raises
//! `KeyboardInterrupt`): a program with a handler of its own, or that
//! ignores SIGINT, keeps the worker thread, whose wait that handler
//! interrupts as it would any other wait.

use std::ffi::{c_int, c_void};
use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use pyo3::exceptions::PyKeyboardInterrupt;
use pyo3::prelude::*;
use pyo3::types::PyType;

use crate::cancel::PyCancel;

/// The token SIGINT cancels while a [`SigintCancels`] is entered: one for
/// the process, since there is one main thread. Read by the signal
/// handler, so it lives in a `OnceLock` (a plain atomic load once set).
static TOKEN: OnceLock<hider_scene::Cancel> = OnceLock::new();

/// The handler [`on_sigint`] replaced, as the address `sigaction` gave
/// (`SIG_DFL`, `SIG_IGN` or a function): what it passes the signal on to.
static REPLACED: AtomicUsize = AtomicUsize::new(0);

/// Whether [`REPLACED`] takes `siginfo` (was installed with `SA_SIGINFO`).
static REPLACED_TAKES_INFO: AtomicBool = AtomicBool::new(false);

/// The main thread's token.
fn token() -> hider_scene::Cancel {
    *TOKEN.get_or_init(hider_scene::Cancel::new)
}

/// The SIGINT handler while a [`SigintCancels`] is entered: only
/// async-signal-safe work (a relaxed atomic store and loads) before the
/// handler it replaced, which for CPython's sets the tripped flag and
/// writes the wakeup fd.
#[cfg(unix)]
#[allow(
    unsafe_code,
    reason = "calls the replaced handler through the address sigaction gave"
)]
extern "C" fn on_sigint(signal: c_int, info: *mut libc::siginfo_t, context: *mut c_void) {
    if let Some(token) = TOKEN.get() {
        token.cancel();
    }
    let replaced = REPLACED.load(Ordering::Relaxed);
    if replaced == libc::SIG_DFL || replaced == libc::SIG_IGN || replaced == libc::SIG_ERR {
        // SIG_DFL cannot be in place: install only replaces a function.
        return;
    }
    if REPLACED_TAKES_INFO.load(Ordering::Relaxed) {
        // SAFETY: `replaced` is the address of a handler installed with
        // SA_SIGINFO, so it takes these three arguments, and is called
        // with the ones the kernel gave.
        let handler: extern "C" fn(c_int, *mut libc::siginfo_t, *mut c_void) =
            unsafe { std::mem::transmute(replaced) };
        handler(signal, info, context);
    } else {
        // SAFETY: the address of a handler installed without SA_SIGINFO,
        // which takes the signal number only.
        let handler: extern "C" fn(c_int) = unsafe { std::mem::transmute(replaced) };
        handler(signal);
    }
}

/// Whether this build can catch SIGINT in place (`hider._worker` keeps its
/// worker thread where it cannot).
pub const CATCHES_SIGINT: bool = cfg!(unix);

/// `with SigintCancels(timeout) as token:` arms the main thread's token
/// (not cancelled, the call's deadline), makes SIGINT cancel it while the
/// block runs, and on exit puts the replaced handler back and raises a
/// Ctrl-C that came meanwhile as one `KeyboardInterrupt`. See the [module
/// documentation](self). The package's private machinery, not API.
#[pyclass(module = "hider._hider")]
pub struct SigintCancels {
    /// The call's timeout in seconds, or none.
    timeout: Option<f64>,
    /// The action `__enter__` replaced, to put back on exit; none when it
    /// installed nothing (a nested block, a handler it must not wrap, a
    /// build without signals).
    replaced: Option<Action>,
}

#[pymethods]
impl SigintCancels {
    #[new]
    #[pyo3(signature = (timeout))]
    fn new(timeout: Option<f64>) -> Self {
        Self {
            timeout,
            replaced: None,
        }
    }

    fn __enter__(&mut self) -> PyResult<PyCancel> {
        let cancel = PyCancel(token());
        // Inside an outer block (the package never nests them) the token
        // is the outer call's: a Ctrl-C it already took must not be
        // forgotten, nor its deadline moved.
        if !installed() {
            cancel.0.reset();
            cancel.arm(self.timeout)?;
            self.replaced = install();
        }
        Ok(cancel)
    }

    #[pyo3(signature = (exc_type, exc, traceback))]
    fn __exit__(
        &mut self,
        py: Python<'_>,
        exc_type: Option<Bound<'_, PyType>>,
        exc: Option<Bound<'_, PyAny>>,
        traceback: Option<Bound<'_, PyAny>>,
    ) -> PyResult<bool> {
        // The type alone decides; Python passes all three.
        drop((exc, traceback));
        let Some(action) = self.replaced.take() else {
            return Ok(false);
        };
        restore(&action);
        // A Ctrl-C during the block is pending in CPython: handle it now,
        // inside the call. If the block already ends with the
        // KeyboardInterrupt of the cancelled hider, that one goes on and
        // the signal's own is dropped, so the caller sees one.
        match py.check_signals() {
            Ok(()) => Ok(false),
            Err(e) => {
                let interrupted = exc_type
                    .is_some_and(|t| t.is_subclass_of::<PyKeyboardInterrupt>().unwrap_or(false));
                if interrupted && e.is_instance_of::<PyKeyboardInterrupt>(py) {
                    Ok(false)
                } else {
                    Err(e)
                }
            }
        }
    }
}

/// A signal action as `sigaction` reads and sets it.
#[cfg(unix)]
type Action = libc::sigaction;
#[cfg(not(unix))]
type Action = ();

/// The present SIGINT action.
#[cfg(unix)]
#[allow(unsafe_code, reason = "sigaction, a libc call")]
fn present() -> libc::sigaction {
    // SAFETY: a zeroed sigaction is a valid value to be overwritten, and
    // sigaction with a null new action only reads the present one.
    unsafe {
        let mut action: libc::sigaction = std::mem::zeroed();
        libc::sigaction(libc::SIGINT, std::ptr::null(), &mut action);
        action
    }
}

/// Whether [`on_sigint`] is the SIGINT handler now (an outer block's).
#[cfg(unix)]
fn installed() -> bool {
    present().sa_sigaction == on_sigint as *const () as usize
}

/// Installs [`on_sigint`] in front of the present SIGINT handler and
/// returns the action it replaced; installs nothing when that is not a
/// function (SIG_DFL ends the process and SIG_IGN drops the signal, as
/// they should while a hider runs too).
#[cfg(unix)]
#[allow(unsafe_code, reason = "sigaction, a libc call")]
fn install() -> Option<Action> {
    let before = present();
    let handler = before.sa_sigaction;
    if handler == libc::SIG_DFL || handler == libc::SIG_IGN || handler == libc::SIG_ERR {
        return None;
    }
    REPLACED.store(handler, Ordering::Relaxed);
    REPLACED_TAKES_INFO.store(before.sa_flags & libc::SA_SIGINFO != 0, Ordering::Relaxed);
    let mut ours = before;
    ours.sa_sigaction = on_sigint as *const () as usize;
    // The replaced handler's mask and flags (CPython's: SA_ONSTACK, no
    // SA_RESTART), with the three-argument form so that a replaced
    // SA_SIGINFO handler gets its arguments.
    ours.sa_flags = (before.sa_flags | libc::SA_SIGINFO) & !libc::SA_RESETHAND;
    // SAFETY: a complete action whose handler takes the SA_SIGINFO
    // arguments and does only async-signal-safe work.
    let ok = unsafe { libc::sigaction(libc::SIGINT, &ours, std::ptr::null_mut()) } == 0;
    ok.then_some(before)
}

/// Puts back the action [`install`] replaced.
#[cfg(unix)]
#[allow(unsafe_code, reason = "sigaction, a libc call")]
fn restore(action: &libc::sigaction) {
    // SAFETY: an action sigaction itself reported.
    unsafe { libc::sigaction(libc::SIGINT, action, std::ptr::null_mut()) };
}

#[cfg(not(unix))]
fn installed() -> bool {
    false
}

#[cfg(not(unix))]
fn install() -> Option<Action> {
    None
}

#[cfg(not(unix))]
fn restore(_: &Action) {}
