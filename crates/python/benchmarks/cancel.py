"""How soon a render stops past its ``timeout=`` (a benchmark, not a
test): each hider family on a large scene, its full time, and how long
past a 20 ms and a 100 ms timeout the ``TimeoutError`` arrived (the
unpolled front end and set-up, then at most one unit of work between two
polls). UV sphere of 249,000 triangles at 1024 x 1024; 20,000 random
crossing triangles at 256 x 256 for the oracle and the painter.

Run from the repository root with the package installed:
``python crates/python/benchmarks/cancel.py``.
"""

import pathlib
import sys
import time

import numpy as np

import hider

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests"))
from conftest import uv_sphere  # noqa: E402


def main():
    sphere = uv_sphere(500, 250)
    rng = np.random.default_rng(0)
    soup = rng.uniform(-1, 1, (60000, 3)), np.arange(60000).reshape(20000, 3)
    cases = [("zbuffer", sphere, 1024), ("zbuffer-tiled", sphere, 1024),
             ("abuffer", sphere, 1024), ("ssaa-8", sphere, 1024), ("scanline", sphere, 1024),
             ("warnock", sphere, 1024), ("oracle", soup, 256), ("painter", soup, 256)]
    print("| hider | triangles | size | full render | past a 20 ms timeout | past 100 ms |")
    print("|---|---|---|---|---|---|")
    for algo, (v, f), size in cases:
        start = time.perf_counter()
        hider.render(v, f, width=size, height=size, algo=algo)
        full = time.perf_counter() - start
        late = []
        for timeout in (0.02, 0.1):
            start = time.perf_counter()
            try:
                hider.render(v, f, width=size, height=size, algo=algo, timeout=timeout)
                late.append("finished")
            except TimeoutError:
                late.append(f"{(time.perf_counter() - start - timeout) * 1000:.0f} ms")
        print(f"| {algo} | {len(f):,} | {size} | {full * 1000:.0f} ms | {late[0]} | {late[1]} |")


if __name__ == "__main__":
    main()
