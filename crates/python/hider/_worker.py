"""Where the package's long calls run, so that Ctrl-C and ``timeout=``
stop them: in place, with SIGINT cancelling the main thread's token, or on
one worker thread for the main thread's calls where that cannot be done;
a cancel token per thread that renders (see ``_interruptible``)."""

import os
import queue
import signal
import threading
from concurrent.futures import Future

import numpy as np

from . import _hider

_worker = None
_worker_lock = threading.Lock()
_tokens = threading.local()


def _forget_worker():
    """In a forked child, the parent's worker thread does not exist, nor
    do the thread pools of the thread that forked (with ``threads`` above
    1, a render on the main thread uses one)."""
    global _worker, _worker_lock
    _worker = None
    _worker_lock = threading.Lock()
    _hider.forget_threads_after_fork()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forget_worker)


def _worker_loop(jobs, token):
    """The main thread's render worker: runs each job it is given with its
    cancel token re-armed for the job's timeout."""
    while True:
        future, fn, args, timeout = jobs.get()
        # Re-armed before the job counts as running: a Ctrl-C from then on
        # cancels this job, never the one before.
        token.reset()
        token.set_timeout(timeout)
        if not future.set_running_or_notify_cancel():
            continue
        try:
            future.set_result(fn(*args, cancel=token))
        except BaseException as e:  # noqa: BLE001 - handed to the caller
            future.set_exception(e)


def _as_timeout(timeout):
    """``timeout=`` as seconds (a float), or None for none."""
    if timeout is None:
        return None
    if isinstance(timeout, (bool, np.bool_)) or not isinstance(
            timeout, (int, float, np.integer, np.floating)):
        raise TypeError(f"timeout must be a number of seconds, got {timeout!r}")
    timeout = float(timeout)
    if not (timeout >= 0 and np.isfinite(timeout)):
        raise ValueError(f"timeout must be a finite number of seconds >= 0, got {timeout}")
    return timeout


def _interruptible(fn, *args, timeout=None):
    """``fn(*args, cancel=token)``, stopped by Ctrl-C and after ``timeout``
    seconds.

    Every hider polls a cancel token (``hider_scene::Cancel``) at the
    heads of its long loops; each thread that renders keeps one,
    re-armed at every call with the call's ``timeout`` (a hider past it
    raises ``TimeoutError``). Python delivers SIGINT to the main thread
    only, between bytecodes, while a hider runs in Rust with the GIL
    released, so a call from the main thread is made stoppable in one of
    two ways:

    - In place, when Python's SIGINT handler is
      ``signal.default_int_handler`` (the usual case): while the call runs,
      the C-level SIGINT handler is one that cancels the main thread's
      token before passing the signal on to CPython's
      (``_hider.SigintCancels``), so the render stops within milliseconds
      and the call raises KeyboardInterrupt, once.
    - On a worker thread, under any other handler (a program's own, which
      may not raise, or none) or where the extension cannot catch SIGINT:
      one daemon worker thread (the same each time, which keeps the
      per-thread hider and frame cache) runs the call while the main
      thread waits on its result. The handler runs in the waiting main
      thread as for any wait; if it raises, the wait ends at once, the
      worker's token is cancelled so the render stops too, and the next
      call finds the worker free. This costs two thread hand-offs a call
      (some 0.1 ms).

    Calls from other threads run directly, with their own token (no
    signal reaches them; the timeout does)."""
    global _worker
    timeout = _as_timeout(timeout)
    if threading.current_thread() is not threading.main_thread():
        token = getattr(_tokens, "token", None)
        if token is None:
            token = _tokens.token = _hider.Cancel()
        token.reset()
        token.set_timeout(timeout)
        return fn(*args, cancel=token)
    if _hider.CATCHES_SIGINT and signal.getsignal(signal.SIGINT) is signal.default_int_handler:
        with _hider.SigintCancels(timeout) as token:
            return fn(*args, cancel=token)
    with _worker_lock:
        if _worker is None:
            jobs, token = queue.SimpleQueue(), _hider.Cancel()
            threading.Thread(target=_worker_loop, args=(jobs, token), daemon=True,
                             name="hider-render").start()
            _worker = (jobs, token)
    jobs, token = _worker
    future = Future()
    jobs.put((future, fn, args, timeout))
    try:
        return future.result()
    except KeyboardInterrupt:
        # Not started: it never will be; running: its hider stops at its
        # next poll.
        if not future.cancel():
            token.cancel()
        raise
