"""Stopping a render: Ctrl-C (SIGINT) on the main thread, in place or through
the worker thread, and the ``timeout=`` keyword of every call."""

import ctypes
import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

import hider


def soup(n, seed=0):
    """`n` random crossing triangles in [-1, 1]^3."""
    rng = np.random.default_rng(seed)
    return rng.uniform(-1, 1, (3 * n, 3)), np.arange(3 * n).reshape(n, 3)


def run_child(tmp_path, body):
    """Runs ``body`` (Python source) in a fresh interpreter with ``hider``,
    ``soup``, ``np`` and ``signal`` imported; returns its stdout lines
    and return code."""
    script = tmp_path / "child.py"
    script.write_text("import os, signal, sys, threading, time\n"
                      "import numpy as np, hider\n"
                      "def soup(n, seed=0):\n"
                      "    rng = np.random.default_rng(seed)\n"
                      "    return rng.uniform(-1, 1, (3 * n, 3)), np.arange(3 * n).reshape(n, 3)\n"
                      + textwrap.dedent(body))
    proc = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                          timeout=120)
    return proc.stdout.split("\n"), proc.returncode, proc.stderr


def test_ctrl_c_stops_a_long_render_within_a_second(tmp_path):
    """SIGINT from another process during a painter run of seconds (64,000
    random crossing triangles at 256 px: 5.7 s in a release build on the
    2-core machine, more in CI's dev build) raises KeyboardInterrupt in the
    caller within a second, and stops the render itself: the next small
    render returns at once (before the cancel token it waited for the
    abandoned painter)."""
    script = tmp_path / "long.py"
    script.write_text(textwrap.dedent("""
        import sys, numpy as np, hider
        rng = np.random.default_rng(0)
        v = rng.uniform(-1, 1, (192000, 3))
        f = np.arange(192000).reshape(64000, 3)
        print("start", flush=True)
        try:
            hider.render(v, f, width=256, height=256, algo="painter")
        except KeyboardInterrupt:
            print("interrupted", flush=True)
            import time
            start = time.perf_counter()
            small = hider.render(v[:3], f[:1], width=16, height=16)
            print(f"next {time.perf_counter() - start:.3f}", flush=True)
            sys.exit(3)
        print("finished", flush=True)
    """))
    proc = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True)
    try:
        assert proc.stdout.readline().strip() == "start"
        time.sleep(1.0)
        assert proc.poll() is None, "the render ended before the signal"
        sent = time.perf_counter()
        proc.send_signal(signal.SIGINT)
        line = proc.stdout.readline().strip()
        waited = time.perf_counter() - sent
        next_line = proc.stdout.readline().strip()
        proc.wait(timeout=30)
    finally:
        proc.kill()
    assert line == "interrupted", (line, proc.stderr.read())
    assert proc.returncode == 3
    assert waited < 1.0, waited
    assert next_line.startswith("next "), (next_line, proc.stderr.read())
    # The painter polls its token at every ordering step: it stops within
    # milliseconds, so the next call waits for nothing.
    assert float(next_line.split()[1]) < 1.0, next_line


def test_ctrl_c_in_place_raises_once_and_puts_the_handler_back(tmp_path):
    """Under Python's own SIGINT handler the main thread renders in place
    (no worker thread is started): a SIGINT from a timer thread during a
    painter of many seconds stops it within a second with one
    KeyboardInterrupt, none raised a second time in the ``except`` block,
    and the process's handler is CPython's again afterwards (a SIGINT
    outside a render raises as usual)."""
    lines, code, err = run_child(tmp_path, """
        v, f = soup(64000)
        threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT)).start()
        start = time.perf_counter()
        try:
            hider.render(v, f, width=256, height=256, algo="painter")
            print("finished")
        except KeyboardInterrupt as e:
            # Bytecodes enough for a pending signal to be handled.
            for _ in range(100000):
                pass
            time.sleep(0.1)
            print(f"interrupted {time.perf_counter() - start:.3f} {e.__context__ is None} {e}")
        print("worker", "hider-render" in [t.name for t in threading.enumerate()])
        print("handler", signal.getsignal(signal.SIGINT) is signal.default_int_handler)
        try:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(1)
            print("no KeyboardInterrupt")
        except KeyboardInterrupt:
            print("plain")
        ids, _ = hider.render(v[:3], f[:1], width=16, height=16)
        print("next", int((ids == 0).sum()))
    """)
    assert code == 0, err
    assert lines[0].startswith("interrupted "), (lines, err)
    # One exception, the hider's, not the signal's raised over it.
    _, seconds, alone, message = lines[0].split(" ", 3)
    assert float(seconds) < 1.5, lines
    assert alone == "True" and message == "render cancelled", lines
    assert lines[1:4] == ["worker False", "handler True", "plain"], lines
    assert lines[4].startswith("next ") and int(lines[4].split()[1]) > 0, lines


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads glibc's sigaction")
def test_the_c_level_handler_is_the_same_after_a_render():
    """The C-level SIGINT action (handler address and flags) after a render
    on the main thread, whole or cancelled by its timeout, is the one
    before it: the in-place handler is removed."""
    libc = ctypes.CDLL(None, use_errno=True)

    def action():
        # x86-64 and aarch64 glibc: handler, 128-byte mask, int flags,
        # restorer; the handler and the flags are what is compared.
        buf = ctypes.create_string_buffer(256)
        assert libc.sigaction(signal.SIGINT, None, buf) == 0
        raw = buf.raw
        return raw[:8], raw[136:140]

    before = action()
    v, f = soup(200)
    hider.render(v, f, width=32, height=32)
    assert action() == before
    with pytest.raises(TimeoutError):
        hider.render(v, f, width=32, height=32, algo="painter", timeout=0)
    assert action() == before


def test_a_handler_of_the_programs_own_keeps_its_meaning(tmp_path):
    """A program whose SIGINT handler does not raise gets its handler
    called and the render finished (the call runs on the worker thread and
    the handler interrupts only the wait); with SIGINT ignored the render
    finishes too and nothing is raised."""
    # The painter on 12,000 random crossing triangles at 128 px takes
    # about 0.65 s in a release build (longer in CI's dev build); the
    # signal comes 0.1 s in.
    lines, code, err = run_child(tmp_path, """
        v, f = soup(12000)
        calls = []
        signal.signal(signal.SIGINT, lambda *_: calls.append(time.perf_counter()))
        threading.Timer(0.1, os.kill, (os.getpid(), signal.SIGINT)).start()
        start = time.perf_counter()
        own, _ = hider.render(v, f, width=128, height=128, algo="painter")
        end = time.perf_counter()
        # The handler ran during the render (in the main thread's wait).
        print("own", len(calls), start < calls[0] < end)
        print("worker", "hider-render" in [t.name for t in threading.enumerate()])
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        threading.Timer(0.1, os.kill, (os.getpid(), signal.SIGINT)).start()
        ignored, _ = hider.render(v, f, width=128, height=128, algo="painter")
        print("ignored", bool((own == ignored).all()), int((own >= 0).sum()))
    """)
    assert code == 0, err
    assert lines[:2] == ["own 1 True", "worker True"], (lines, err)
    # Both renders ran to the end: the same, whole image.
    assert lines[2].startswith("ignored True ") and int(lines[2].split()[2]) > 1000, lines


def test_timeout_raises_timeout_error_naming_the_keyword():
    """A render past its ``timeout=`` stops with ``TimeoutError``; a
    timeout of 0 stops every hider at its first poll (the same for every
    call, no clock involved), and the next call without one renders."""
    v, f = soup(200)
    for algo in ("zbuffer-tiled", "zbuffer", "abuffer", "painter", "warnock", "scanline",
                 "oracle", "auto"):
        with pytest.raises(TimeoutError, match=r"timed out after 0ns \(the timeout= keyword"):
            hider.render(v, f, width=32, height=32, algo=algo, timeout=0)
    ids, _ = hider.render(v, f, width=32, height=32, algo="painter", timeout=60)
    want, _ = hider.render(v, f, width=32, height=32, algo="painter")
    np.testing.assert_array_equal(ids, want)


def test_timeout_stops_a_long_painter():
    """The painter on 64,000 random crossing triangles runs for many
    seconds; with ``timeout=0.2`` it stops with TimeoutError."""
    v, f = soup(64000)
    with pytest.raises(TimeoutError, match="timed out after 200ms"):
        hider.render(v, f, width=256, height=256, algo="painter", timeout=0.2)


def test_timeout_is_checked():
    v, f = soup(2)
    for bad, error in ((-1, ValueError), (float("nan"), ValueError), ("1", TypeError),
                       (True, TypeError)):
        with pytest.raises(error, match="timeout"):
            hider.render(v, f, width=8, height=8, timeout=bad)


def test_svg_timeout(tmp_path):
    v, f = soup(50)
    out = tmp_path / "t.svg"
    with pytest.raises(TimeoutError):
        hider.svg(v, f, out, width=32, height=32, timeout=0)
    assert not out.exists()
    hider.svg(v, f, out, width=32, height=32, mode="lines", timeout=60)
    assert out.exists()


def test_render_in_a_forked_child_after_one_in_the_parent():
    """The main thread's worker (in use under a SIGINT handler of the
    program's own) is started again in a forked child, where the parent's
    does not exist; in place, the child renders too."""
    import multiprocessing

    v = np.array([[-1, -1, 0], [1, -1, 0], [0, 1, 0]], dtype=float)
    ctx = multiprocessing.get_context("fork")
    previous = signal.signal(signal.SIGINT, lambda *_: None)
    try:
        want, _ = hider.render(v, [[0, 1, 2]], width=16, height=16)
        with ctx.Pool(1) as pool:
            got = pool.apply_async(_render_small).get(timeout=30)
    finally:
        signal.signal(signal.SIGINT, previous)
    assert (got == want).all()
    # In place, the main thread keeps its pool of 2 and its workspace: the
    # child, where the pool's threads do not exist, starts its own.
    two, _ = hider.render(v, [[0, 1, 2]], width=16, height=16, threads=2)
    with ctx.Pool(1) as pool:
        got = pool.apply_async(_render_small).get(timeout=30)
        got_two = pool.apply_async(_render_small, (2,)).get(timeout=30)
    assert (got == want).all() and (got_two == two).all() and (two == want).all()


def _render_small(threads=1):
    v = np.array([[-1, -1, 0], [1, -1, 0], [0, 1, 0]], dtype=float)
    return hider.render(v, [[0, 1, 2]], width=16, height=16, threads=threads)[0]
