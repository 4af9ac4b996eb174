//! The thread pools of `threads` above 1: one per calling thread and size,
//! the main thread working in its first one.

use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rayon::ThreadPool;

thread_local! {
    /// This thread's pool for `threads` above 1, with its size.
    static POOL: RefCell<Option<(usize, Arc<ThreadPool>)>> = const { RefCell::new(None) };
}

/// Set in a forked child ([`forget_after_fork`]).
static FORKED: AtomicBool = AtomicBool::new(false);

/// In a forked child, on the thread that forked: forgets this thread's
/// pool, whose threads were not copied into the child, without dropping it
/// (dropping a pool signals threads that are not there), and keeps the
/// child off the main thread's pool.
pub fn forget_after_fork() {
    FORKED.store(true, Ordering::Relaxed);
    if let Some(pool) = POOL.with_borrow_mut(Option::take) {
        std::mem::forget(pool);
    }
}

/// This thread's pool of `threads` workers, made when the size differs.
///
/// The main thread's first pool takes the main thread in as its worker 0
/// (rayon's `use_current_thread`), for the rest of the process: a call on
/// the main thread then runs the frame right there, its parallel steps
/// joins inside the pool, where a pool of other threads would take the
/// frame over and put the main thread to sleep until it is done, two
/// thread wake-ups a call that cost the spider at 1024 on 2 threads a
/// third of its time here. Other sizes on the main thread, and every
/// other thread, get pools of their own threads.
pub fn pool(threads: usize) -> PyResult<Arc<ThreadPool>> {
    if let Some(pool) = main_pool(threads)? {
        return Ok(pool);
    }
    POOL.with_borrow_mut(|slot| {
        if let Some((n, pool)) = slot.as_ref()
            && *n == threads
        {
            return Ok(Arc::clone(pool));
        }
        // A pool of the caller's size: the command line sizes rayon's
        // global pool, which a library must leave alone.
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map(Arc::new)
            .map_err(pool_error)?;
        *slot = Some((threads, Arc::clone(&pool)));
        Ok(pool)
    })
}

/// The pool the main thread is worker 0 of, when this call is on the main
/// thread and asks for its size (made on the first such call); none
/// otherwise. Never dropped: rayon keeps the main thread registered with
/// it, and a forked child, where its other threads do not exist, does not
/// use it.
fn main_pool(threads: usize) -> PyResult<Option<Arc<ThreadPool>>> {
    static MAIN_POOL: OnceLock<(usize, Arc<ThreadPool>)> = OnceLock::new();
    if !on_main_thread() || FORKED.load(Ordering::Relaxed) {
        return Ok(None);
    }
    if let Some((n, pool)) = MAIN_POOL.get() {
        return Ok((*n == threads).then(|| Arc::clone(pool)));
    }
    if rayon::current_thread_index().is_some() {
        return Ok(None);
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .use_current_thread()
        .build()
        .map(Arc::new)
        .map_err(pool_error)?;
    // Only the main thread gets here: no other call can have set it.
    let _ = MAIN_POOL.set((threads, Arc::clone(&pool)));
    Ok(Some(pool))
}

/// Whether this is the process's first thread (Linux: its thread id is
/// the process id); false where that cannot be told.
#[allow(
    unsafe_code,
    reason = "getpid and the gettid system call, libc calls without arguments"
)]
fn on_main_thread() -> bool {
    // The system call rather than glibc's `gettid`, which glibc only has
    // from 2.30 (a manylinux wheel may not link against it).
    #[cfg(target_os = "linux")]
    // SAFETY: both calls only return an id.
    return unsafe { libc::c_long::from(libc::getpid()) == libc::syscall(libc::SYS_gettid) };
    #[cfg(not(target_os = "linux"))]
    return false;
}

/// A pool that could not be started, as a Python exception.
fn pool_error(e: rayon::ThreadPoolBuildError) -> PyErr {
    PyValueError::new_err(format!("cannot start the thread pool: {e}"))
}
