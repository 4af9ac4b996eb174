"""Timings of the Python bindings (a benchmark, not a test).

1. ``hider.mpl.resolve`` on two intersecting 100 x 100 ``plot_surface``
   grids (39,204 triangles): the time spent ordering and splitting at
   draw time, against matplotlib's own ``savefig`` of the same figure to
   PNG without it.
2. ``hider.render`` at 1024 x 1024 against the ``hider`` command line's
   ``--repeat`` median on the same scene (a UV sphere of about 130,000
   triangles written to OBJ), the same hider and thread count.

Run from the repository root with the package installed:
``python crates/python/benchmarks/bench.py [path/to/hider]``.
"""

import io
import pathlib
import re
import subprocess
import sys
import tempfile
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

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


def bench_resolve(repeat=5):
    fig, ax, _ = surfaces_figure(False)
    fig.canvas.draw()
    tris = len(hider.mpl.project(ax).faces)
    save = median_ms(lambda: fig.savefig(io.BytesIO(), format="png"), repeat)
    plt.close(fig)
    fig, ax, r = surfaces_figure(True)
    fig.canvas.draw()
    order = median_ms(r.do_3d_projection, repeat)
    save_resolved = median_ms(lambda: fig.savefig(io.BytesIO(), format="png"), repeat)
    print(f"resolve: {tris} triangles, {r.pieces} pieces after splitting")
    print(f"  matplotlib savefig PNG (its own sort): median {save[0]:.0f} ms (min {save[1]:.0f})")
    print(f"  resolve at draw time (gather, order, split): median {order[0]:.0f} ms "
          f"(min {order[1]:.0f}); ratio {order[0] / save[0]:.2f}")
    print(f"  savefig PNG with resolve: median {save_resolved[0]:.0f} ms (min {save_resolved[1]:.0f})")
    plt.close(fig)


def bench_render(cli, repeat=10, algo="zbuffer-tiled"):
    vertices, faces = uv_sphere(512, 128)
    with tempfile.TemporaryDirectory() as tmp:
        model = pathlib.Path(tmp) / "sphere.obj"
        write_obj(model, vertices, faces)
        out = subprocess.run(
            [str(cli), "render", str(model), "-o", str(pathlib.Path(tmp) / "o.png"),
             "--size", "1024", "--algo", algo, "--repeat", str(repeat)],
            check=True, capture_output=True, text=True).stdout
    m = re.search(r"median ([0-9.]+)", out)
    py = median_ms(lambda: hider.render(vertices, faces, width=1024, height=1024, algo=algo),
                   repeat)
    print(f"render: {len(faces)} triangles at 1024x1024, {algo}, 1 thread")
    print(f"  hider CLI --repeat {repeat}: {out.strip()}")
    if m:
        cli_ms = float(m.group(1))
        print(f"  hider.render: median {py[0]:.1f} ms (min {py[1]:.1f}); "
              f"ratio to the CLI {py[0] / cli_ms:.2f}")


if __name__ == "__main__":
    cli = sys.argv[1] if len(sys.argv) > 1 else "target/debug/hider"
    bench_resolve()
    bench_render(cli)
