"""Timings of the Python bindings (a benchmark, not a test).

1. ``hider.mpl.resolve`` on two intersecting 100 x 100 ``plot_surface``
   grids (39,204 triangles): the time spent ordering and splitting at
   draw time, against matplotlib's own ``savefig`` of the same figure to
   PNG without it, the two interleaved round by round.
2. ``resolve`` on 400 random crossing triangles, which need far more
   polygon splits than the painter's budget: ``savefig`` with ``resolve``
   (the painter giving up, matplotlib drawing) against ``savefig``
   without it.
3. ``hider.render`` at 1024 x 1024 against the ``hider`` command line's
   ``--repeat`` median on the same scene (a UV sphere of about 130,000
   triangles written to OBJ), the same hider and thread count, alternated
   (left out with ``--no-cli``).

Run from the repository root with the package installed:
``python crates/python/benchmarks/bench.py [path/to/hider | --no-cli]``.
"""

import io
import os
import pathlib
import re
import subprocess
import sys
import tempfile
import time
import warnings

# numpy's OpenBLAS threads spin for a while after each matrix product
# (matplotlib's projection makes many) and take a core from whatever runs
# next: on a 2-core machine that made hider.render's times bimodal. Both
# sides of every comparison here run with one BLAS thread.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d import art3d  # noqa: E402

import hider  # noqa: E402
import hider.mpl  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests"))
from conftest import uv_sphere, write_obj  # noqa: E402


def median_ms(f, repeat):
    f()  # warm-up
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        f()
        times.append((time.perf_counter() - t) * 1e3)
    return float(np.median(times)), float(np.min(times))


def timed(f):
    """Wall milliseconds of one call of f. (Process CPU time is no better
    a measure here: numpy's OpenBLAS threads spin after each matrix
    product of matplotlib's projection and count as CPU time.)"""
    w = time.perf_counter()
    f()
    return (time.perf_counter() - w) * 1e3


def surfaces_figure(resolved):
    x = np.linspace(-1, 1, 100)
    X, Y = np.meshgrid(x, x)
    fig = plt.figure(figsize=(6, 6), dpi=100)
    ax = fig.add_subplot(projection="3d")
    ax.plot_surface(X, Y, X * Y, cmap="viridis", rstride=1, cstride=1)
    ax.plot_surface(X, Y, 0.5 * np.sin(3 * X) + 0.3 * Y, cmap="plasma", rstride=1,
                    cstride=1)
    r = hider.mpl.resolve(ax) if resolved else None
    return fig, ax, r


def bench_resolve(rounds=15):
    """The three timings interleaved round by round, so that load from
    other processes falls on all of them alike; the ratio is taken per
    round, then its median."""
    fig, ax, _ = surfaces_figure(False)
    fig.canvas.draw()
    tris = len(hider.mpl.project(ax).faces)
    rfig, rax, r = surfaces_figure(True)
    rfig.canvas.draw()

    def save_plain():
        fig.savefig(io.BytesIO(), format="png")

    def save_resolved():
        rfig.savefig(io.BytesIO(), format="png")

    rows = {"save": [], "resolve": [], "save_resolved": []}
    for _ in range(rounds):
        rows["save"].append(timed(save_plain))
        rows["resolve"].append(timed(r.do_3d_projection))
        rows["save_resolved"].append(timed(save_resolved))
    plt.close(fig)
    plt.close(rfig)
    a = {k: np.array(v) for k, v in rows.items()}

    def line(what, k):
        return f"  {what}: median {np.median(a[k]):.0f} ms (min {a[k].min():.0f})"

    print(f"resolve: {tris} triangles, {r.pieces} pieces after splitting, "
          f"{len(r.get_paths())} paths, {rounds} interleaved rounds")
    print(line("matplotlib savefig PNG (its own sort)", "save"))
    print(line("resolve at draw time (gather, order, split, paths)", "resolve"))
    print(line("savefig PNG with resolve (resolve included)", "save_resolved"))
    for k, what in (("resolve", "resolve"), ("save_resolved", "savefig with resolve")):
        ratio = np.median(a[k] / a["save"])
        print(f"  {what} / savefig, median of per-round ratios: {ratio:.2f}")


def bench_fallback(rounds=5):
    """A scene the painter gives up on: savefig with and without resolve,
    interleaved; each resolved figure is new, so that every round pays
    for the painter's attempt (a Resolved does not retry once it gave
    up)."""
    def soup(resolved):
        rng = np.random.default_rng(0)
        fig = plt.figure(figsize=(4, 4), dpi=100)
        ax = fig.add_subplot(projection="3d")
        ax.add_collection3d(art3d.Poly3DCollection(rng.uniform(-1, 1, (400, 3, 3)),
                                                   facecolors=rng.uniform(0, 1, (400, 3))))
        if resolved:
            hider.mpl.resolve(ax)
        return fig

    rows = {"plain": [], "resolved": []}
    for _ in range(rounds):
        for k in rows:
            fig = soup(k == "resolved")
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", hider.mpl.ResolveWarning)
                rows[k].append(timed(lambda: fig.savefig(io.BytesIO(), format="png")))
            plt.close(fig)
    print(f"fallback: 400 random crossing triangles, {rounds} interleaved rounds")
    for k, what in (("plain", "matplotlib savefig PNG"),
                    ("resolved", "savefig PNG with resolve (painter gives up at its budget)")):
        print(f"  {what}: median {np.median(rows[k]):.0f} ms (max {np.max(rows[k]):.0f})")


def bench_render(cli, repeat=10, algo="zbuffer-tiled", rounds=3):
    """The command line's ``--repeat`` median and ``hider.render``'s median
    over the same number of renders, alternated ``rounds`` times so that
    load from other processes falls on both alike; the ratio is taken per
    round, then its median."""
    vertices, faces = uv_sphere(512, 128)
    ratios = []
    with tempfile.TemporaryDirectory() as tmp:
        model = pathlib.Path(tmp) / "sphere.obj"
        write_obj(model, vertices, faces)
        print(f"render: {len(faces)} triangles at 1024x1024, {algo}, 1 thread")
        for _ in range(rounds):
            out = subprocess.run(
                [str(cli), "render", str(model), "-o", str(pathlib.Path(tmp) / "o.png"),
                 "--size", "1024", "--algo", algo, "--repeat", str(repeat)],
                check=True, capture_output=True, text=True).stdout
            cli_ms = float(re.search(r"median ([0-9.]+)", out).group(1))
            py = median_ms(lambda: hider.render(vertices, faces, width=1024, height=1024,
                                                algo=algo), repeat)
            ratios.append(py[0] / cli_ms)
            print(f"  hider CLI --repeat {repeat}: median {cli_ms:.2f} ms; hider.render: "
                  f"median {py[0]:.2f} ms (min {py[1]:.2f}); ratio {ratios[-1]:.2f}")
    print(f"  hider.render / CLI, median of per-round ratios: {np.median(ratios):.2f}")


if __name__ == "__main__":
    cli = sys.argv[1] if len(sys.argv) > 1 else "target/debug/hider"
    bench_resolve()
    bench_fallback()
    if cli != "--no-cli":
        bench_render(cli)
