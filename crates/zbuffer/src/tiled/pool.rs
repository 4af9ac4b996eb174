//! Which threads draw: the caller's rayon pool when it has the wanted
//! number of workers, the hider's own pool otherwise, or just the calling
//! thread.

/// Whether the caller's rayon pool (the one `par_iter` would use here:
/// the pool the current thread works for, or the global one) has exactly
/// `threads` workers. Then the hider uses it rather than a pool of its own:
/// two pools on the same cores only take turns (the CLI builds a global
/// pool for the parallel front end, and a caller may run the front end and
/// the hider inside one `install`).
pub(super) fn ambient_pool(threads: usize) -> bool {
    rayon::current_num_threads() == threads
}

/// The workers of a frame: `None` to stay on the calling thread,
/// `Some(None)` for the ambient pool, `Some(Some(pool))` for the hider's.
pub(super) type Workers<'a> = Option<Option<&'a rayon::ThreadPool>>;

/// The workers for `threads` (see [`Workers`]).
pub(super) fn workers(own: Option<&rayon::ThreadPool>, threads: usize) -> Workers<'_> {
    if threads <= 1 {
        None
    } else if ambient_pool(threads) {
        Some(None)
    } else {
        own.map(Some)
    }
}

/// Wakes the other threads now, while this one bins: an idle rayon worker
/// sleeps, and on these virtual machines waking one takes tens of
/// microseconds, a tenth of a small scene's frame. After the empty job it
/// searches for work for a while before sleeping again, and the tiles
/// arrive within that while.
pub(super) fn wake(workers: Workers<'_>) {
    match workers {
        Some(Some(pool)) => pool.spawn(|| {}),
        Some(None) => rayon::spawn(|| {}),
        None => {}
    }
}

/// Runs `f` in `pool`, or right here in the ambient pool.
pub(super) fn install<R: Send>(
    pool: Option<&rayon::ThreadPool>,
    f: impl FnOnce() -> R + Send,
) -> R {
    match pool {
        Some(pool) => pool.install(f),
        None => f(),
    }
}
