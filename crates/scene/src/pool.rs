//! Which threads draw a frame: the one policy of the parallel hiders (the
//! A-buffer, the tiled z-buffer).
//!
//! A hider asked for `threads` threads ([`thread_count`]: 0 means every
//! core) runs a frame
//! - on the calling thread alone for one thread ([`Workers::Here`]);
//! - in the caller's rayon pool (the one `par_iter` would use here: the
//!   pool the current thread works for, or the global one) when it has
//!   exactly `threads` workers ([`Workers::Ambient`]): two pools on the
//!   same cores only take turns, and the CLI builds a global pool for the
//!   parallel front end, and a caller may run the front end and the hider
//!   inside one `install`;
//! - in a pool of the hider's own otherwise ([`Workers::Own`]), started on
//!   first use and kept from frame to frame ([`OwnPool`]): starting
//!   threads costs more than a small frame, and it is started again only
//!   when the number of threads asked for changes.
//!
//! The choice changes no pixel: the hiders split their work the same way
//! whichever threads run it.
//!
//! Without the crate's `parallel` feature (no rayon) every frame runs on
//! the calling thread: [`OwnPool::workers`] is always [`Workers::Here`],
//! [`OwnPool::start`] starts nothing, and [`current_threads`] is 1.

use crate::error::Result;

/// The number of threads a hider's `threads` option asks for: the number
/// itself, or the machine's core count for 0 (1 when it cannot tell).
pub fn thread_count(threads: usize) -> usize {
    match threads {
        0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
        n => n,
    }
}

/// The number of threads of the caller's pool (the one `par_iter` would
/// use here); 1 without the `parallel` feature.
pub fn current_threads() -> usize {
    #[cfg(feature = "parallel")]
    return rayon::current_num_threads();
    #[cfg(not(feature = "parallel"))]
    return 1;
}

/// A rayon thread pool: [`rayon::ThreadPool`].
#[cfg(feature = "parallel")]
pub type ThreadPool = rayon::ThreadPool;

/// No thread pool can exist without the `parallel` feature: a type without
/// values, so that [`Workers::Own`] is never made.
#[cfg(not(feature = "parallel"))]
#[derive(Debug)]
pub enum ThreadPool {}

/// The threads that run a frame's parallel work (see the module
/// documentation).
#[derive(Clone, Copy, Debug)]
pub enum Workers<'a> {
    /// The calling thread alone.
    Here,
    /// The caller's rayon pool, which has the threads asked for.
    Ambient,
    /// The hider's own pool.
    Own(&'a ThreadPool),
}

impl Workers<'_> {
    /// Whether more than one thread works (any but [`Workers::Here`]).
    pub fn is_parallel(self) -> bool {
        !matches!(self, Self::Here)
    }

    /// Runs `f` in the hider's own pool ([`Workers::Own`]), or right here
    /// otherwise: on the calling thread, where `par_iter` uses the
    /// caller's pool.
    pub fn install<R: Send>(self, f: impl FnOnce() -> R + Send) -> R {
        match self {
            #[cfg(feature = "parallel")]
            Self::Own(pool) => pool.install(f),
            #[cfg(not(feature = "parallel"))]
            Self::Own(pool) => match *pool {},
            Self::Here | Self::Ambient => f(),
        }
    }

    /// Wakes the pool's threads now, while the calling one does serial
    /// work (binning): an idle rayon worker sleeps, and on a virtual
    /// machine waking one takes tens of microseconds, a tenth of a small
    /// scene's frame. After the empty job it searches for work for a while
    /// before sleeping again, and the parallel work arrives within that
    /// while. Nothing to do for [`Workers::Here`].
    pub fn wake(self) {
        match self {
            #[cfg(feature = "parallel")]
            Self::Own(pool) => pool.spawn(|| {}),
            #[cfg(feature = "parallel")]
            Self::Ambient => rayon::spawn(|| {}),
            #[cfg(not(feature = "parallel"))]
            Self::Own(pool) => match *pool {},
            #[cfg(not(feature = "parallel"))]
            Self::Ambient => {}
            Self::Here => {}
        }
    }
}

/// A hider's own rayon pool, started when a frame needs it and kept
/// between frames (see the module documentation).
#[derive(Debug, Default)]
pub struct OwnPool {
    #[cfg(feature = "parallel")]
    pool: Option<rayon::ThreadPool>,
}

impl OwnPool {
    /// Makes ready the threads of a frame on `threads` threads: starts the
    /// hider's own pool when neither the calling thread alone nor the
    /// caller's pool will do and the pool kept has another size (or there
    /// is none). [`Self::workers`] then names them.
    ///
    /// # Errors
    ///
    /// [`Error::Render`](crate::Error::Render) naming `hider` when the
    /// threads cannot be started.
    pub fn start(&mut self, threads: usize, hider: &str) -> Result<()> {
        #[cfg(not(feature = "parallel"))]
        {
            let _ = (threads, hider);
            Ok(())
        }
        #[cfg(feature = "parallel")]
        self.start_pool(threads, hider)
    }

    #[cfg(feature = "parallel")]
    fn start_pool(&mut self, threads: usize, hider: &str) -> Result<()> {
        if threads <= 1 || rayon::current_num_threads() == threads {
            return Ok(());
        }
        if self
            .pool
            .as_ref()
            .is_none_or(|p| p.current_num_threads() != threads)
        {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .map_err(|e| crate::error::Error::Render {
                    hider: hider.to_owned(),
                    message: format!("cannot start {threads} threads: {e}"),
                })?;
            self.pool = Some(pool);
        }
        Ok(())
    }

    /// The threads for `threads`: [`Workers::Here`] for one,
    /// [`Workers::Ambient`] when the caller's pool has that many, the
    /// hider's own pool otherwise ([`Workers::Here`] when none was
    /// started: [`Self::start`] comes first).
    pub fn workers(&self, threads: usize) -> Workers<'_> {
        #[cfg(not(feature = "parallel"))]
        {
            let _ = threads;
            Workers::Here
        }
        #[cfg(feature = "parallel")]
        if threads <= 1 {
            Workers::Here
        } else if rayon::current_num_threads() == threads {
            Workers::Ambient
        } else {
            self.pool.as_ref().map_or(Workers::Here, Workers::Own)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_thread_stays_here_and_starts_nothing() {
        let mut own = OwnPool::default();
        own.start(1, "test").unwrap();
        assert!(matches!(own.workers(1), Workers::Here));
        #[cfg(feature = "parallel")]
        assert!(own.pool.is_none());
    }

    #[cfg(feature = "parallel")]
    #[test]
    fn the_callers_pool_of_the_right_size_is_used() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .unwrap();
        pool.install(|| {
            let mut own = OwnPool::default();
            own.start(3, "test").unwrap();
            assert!(matches!(own.workers(3), Workers::Ambient));
            assert!(own.pool.is_none());
        });
    }

    #[cfg(feature = "parallel")]
    #[test]
    fn an_own_pool_is_started_again_when_the_size_changes() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        pool.install(|| {
            let mut own = OwnPool::default();
            own.start(2, "test").unwrap();
            own.start(2, "test").unwrap();
            match own.workers(2) {
                Workers::Own(p) => assert_eq!(p.current_num_threads(), 2),
                other => panic!("{other:?}"),
            }
            own.start(3, "test").unwrap();
            assert_eq!(own.pool.as_ref().unwrap().current_num_threads(), 3);
        });
    }

    #[test]
    fn zero_threads_is_every_core() {
        assert!(thread_count(0) >= 1);
        assert_eq!(thread_count(5), 5);
    }
}
