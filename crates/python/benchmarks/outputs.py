"""What ``hider.render``'s outputs and dtypes cost (a benchmark, not a
test): a UV sphere of 1,046,528 triangles at 1024 x 1024, ``zbuffer-tiled``
on one thread, medians of 5 calls each: float64/int64 against
float32/int32 arrays (read in place), the ids and depth alone, with
``distance``, with every output; and numpy's own float64/int64 copies of
the arrays, the conversion the extension no longer makes.

Run from the repository root with the package installed:
``python crates/python/benchmarks/outputs.py``.
"""

import pathlib
import sys
import time

import numpy as np

import hider

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests"))
from conftest import uv_sphere  # noqa: E402


def median_ms(fn, n=5):
    """The median wall time of ``n`` calls of ``fn``, milliseconds."""
    times = []
    for _ in range(n):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return 1000 * sorted(times)[n // 2]


def main():
    v, f = uv_sphere(1024, 512)
    v32, f32 = v.astype(np.float32), f.astype(np.int32)
    kw = dict(width=1024, height=1024)
    hider.render(v32, f32, **kw)
    print(f"{len(f):,} triangles, 1024 x 1024, zbuffer-tiled, 1 thread, medians of 5")
    for name, fn in [
        ("float64/int64, ids + depth", lambda: hider.render(v, f, **kw)),
        ("float32/int32, ids + depth", lambda: hider.render(v32, f32, **kw)),
        ("float32/int32, ids + depth + distance",
         lambda: hider.render(v32, f32, outputs=("ids", "depth", "distance"), **kw)),
        ("float32/int32, every output",
         lambda: hider.render(v32, f32, normals=v32, outputs=hider.OUTPUTS, **kw)),
        ("float32/int32, ids + depth, 2 threads", lambda: hider.render(v32, f32, threads=2, **kw)),
        ("float32/int32, every output, 2 threads",
         lambda: hider.render(v32, f32, normals=v32, outputs=hider.OUTPUTS, threads=2, **kw)),
        ("numpy's float64/int64 copies of the arrays",
         lambda: (np.ascontiguousarray(v32, dtype=np.float64),
                  np.ascontiguousarray(f32, dtype=np.int64))),
    ]:
        print(f"{name}: {median_ms(fn):.0f} ms")


if __name__ == "__main__":
    main()
