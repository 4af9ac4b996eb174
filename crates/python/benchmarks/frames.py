"""hider.render's frame against llvmpipe's frame read back, same run (a
benchmark, not a test).

What it measures: the wall time of ``hider.render(vertices, faces,
width=1024, height=1024, algo="zbuffer-tiled", threads=T)`` returning the
numpy id and depth arrays (what a Python user receives), on the four scenes
of the llvmpipe comparison (the spider, the UV spheres of 200 and 500
segments, the soup of 100k triangles), at 1 and 2 threads, against Mesa's
llvmpipe drawing the same scene and reading its colour and depth back with
``glReadPixels`` (the ``peers`` package's ``llvmpipe+read`` rows, wall
time, the frame in client memory on both sides).

Each round first runs ``peers --peers llvmpipe --threads 1,2 --runs 5
--rounds 1 --sizes 1024``, then times ``hider.render`` on every scene and
thread count (warm-up renders for 40 ms, then the median of ``--frames``
timed calls, ``time.perf_counter``), then, when the ``hider`` command line
is given, its ``render --repeat 100`` median on the same OBJ file. The table
of each round gives the ratio llvmpipe+read / hider.render; a second table
gives every scene's median over the rounds.

The scenes come from ``export_scenes`` (crates/bench/src/bin), which writes
them from the same ``llvmpipe_scenes()`` the Rust benchmark
``frame_readback`` renders, and checks that each file reads back triangle
for triangle. They are read here with the tests' ``read_obj``
(``crates/python/tests/conftest.py``: ``v`` and ``f`` lines); the ``f``
lines are in primitive-id order, so the ids are the Rust ones.

The camera is the fit camera on both sides (``View::for_scene`` in Rust,
the fit camera of ``hider.render`` without camera keywords; none of the
scenes has a camera of its own, and export_scenes refuses one that
has). Checked with ``--check-cli``: for every scene, ``hider render
MODEL --size 1024 --algo zbuffer-tiled --ids-out FILE --depth-out
FILE`` is run once and its dumps compared with
``hider.render``'s arrays, which must be equal (ids exactly, depth
exactly), so that Python and the command line draw the same frame; the
command line's file reproduces the Rust benchmark's scene triangle for
triangle (export_scenes checks it), so the fit camera is the same there
too. Results and the check's outcome: docs/notes/2026-11-28-python-frames.md.

Run from the repository root with the package installed (a release build:
``maturin develop --release --manifest-path crates/python/Cargo.toml``)::

    cargo run --release -p hider-bench --bin export_scenes -- "$SCENES"
    cargo build --release --manifest-path peers/Cargo.toml
    cargo build --release --bin hider
    python crates/python/benchmarks/frames.py "$SCENES" \\
        --peers peers/target/release/peers [--cli target/release/hider] \\
        [--check-cli] [--rounds 3] [--frames 10]
"""

import argparse
import json
import os
import pathlib
import re
import subprocess
import sys
import tempfile
import time

# numpy's OpenBLAS threads spin after a matrix product and take a core
# from whatever runs next (see bench.py); one BLAS thread for both sides.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

import hider  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests"))
from conftest import read_obj  # noqa: E402

SIZE = 1024
ALGO = "zbuffer-tiled"
THREADS = (1, 2)
# The order and names of the peers package (and of llvmpipe_scenes()).
SCENES = ("spider", "sphere 200", "sphere 500", "soup 100k")
WARM_UP_S = 0.04


def median_ms(f, frames):
    """Median wall ms of ``frames`` calls of f, after calls for the warm-up
    (an idle vCPU takes tens of milliseconds to run at full speed)."""
    start = time.perf_counter()
    count = 0
    while count < 2 or time.perf_counter() - start < WARM_UP_S:
        f()
        count += 1
    times = []
    for _ in range(frames):
        t = time.perf_counter()
        f()
        times.append((time.perf_counter() - t) * 1e3)
    return float(np.median(times))


def run_peers(peers):
    """One run of llvmpipe (render only and with read-back) on every scene
    at 1 and 2 threads: {(scene, peer, threads): median ms}."""
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp) / "peers.json"
        subprocess.run([str(peers), "--peers", "llvmpipe", "--threads", "1,2", "--runs", "5",
                        "--rounds", "1", "--sizes", str(SIZE), "--json", str(out)],
                       check=True, stdout=subprocess.DEVNULL)
        rows = json.loads(out.read_text())
    return {(r["scene"], r["peer"], r["threads"]): r["median_ms"]
            for r in rows if r["size"] == SIZE}


def cli_ms(cli, model, threads, repeat=100):
    """``hider render --repeat``'s median ms."""
    with tempfile.TemporaryDirectory() as tmp:
        p = subprocess.run([str(cli), "render", str(model), "--size", str(SIZE), "--algo", ALGO,
                            "--threads", str(threads), "--repeat", str(repeat),
                            "-o", str(pathlib.Path(tmp) / "o.png")],
                           check=True, capture_output=True, text=True)
    m = re.search(r"median ([0-9.]+) ms", p.stdout + p.stderr)
    if m is None:
        sys.exit(f"no 'median X ms' in the output of {cli} render --repeat")
    return float(m.group(1))


def check_cli(cli, models, meshes):
    """hider.render's ids and depth equal the command line's dumps."""
    for name in SCENES:
        with tempfile.TemporaryDirectory() as tmp:
            ids_path, depth_path = pathlib.Path(tmp) / "ids", pathlib.Path(tmp) / "depth"
            subprocess.run([str(cli), "render", str(models[name]), "--size", str(SIZE),
                            "--algo", ALGO, "--ids-out", str(ids_path),
                            "--depth-out", str(depth_path),
                            "-o", str(pathlib.Path(tmp) / "o.png")],
                           check=True, capture_output=True)
            cli_ids = np.fromfile(ids_path, dtype="<i4").reshape(SIZE, SIZE)
            cli_depth = np.fromfile(depth_path, dtype="<f4").reshape(SIZE, SIZE)
        ids, depth = hider.render(*meshes[name], width=SIZE, height=SIZE, algo=ALGO)
        same_ids = np.array_equal(ids, cli_ids)
        same_depth = np.array_equal(depth, cli_depth)
        print(f"camera check, {name}: {int((ids >= 0).sum())} pixels covered; ids "
              f"{'equal' if same_ids else 'DIFFER'}, depth "
              f"{'equal' if same_depth else 'DIFFER'} to the command line's dumps")
        if not (same_ids and same_depth):
            sys.exit("hider.render and the command line disagree")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scenes", type=pathlib.Path, help="the folder export_scenes wrote")
    ap.add_argument("--peers", required=True, help="the peers package's binary")
    ap.add_argument("--cli", help="the hider command line, for its --repeat figure")
    ap.add_argument("--check-cli", action="store_true",
                    help="compare hider.render's arrays with the command line's dumps first")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--frames", type=int, default=10)
    args = ap.parse_args()

    models = {name: args.scenes / f"{name.replace(' ', '_')}.obj" for name in SCENES}
    meshes = {name: read_obj(path) for name, path in models.items()}
    if args.check_cli:
        if args.cli is None:
            sys.exit("--check-cli needs --cli")
        check_cli(args.cli, models, meshes)

    cols = "| scene | threads | hider.render ms | llvmpipe+read ms | ratio |"
    rule = "|---|---|---|---|---|"
    if args.cli:
        cols += " hider render --repeat ms | ratio |"
        rule += "---|---|"
    summary = {}
    for r in range(args.rounds):
        peers = run_peers(args.peers)
        print(f"\nround {r + 1} of {args.rounds}: {SIZE}x{SIZE}, {ALGO}, wall time, "
              f"median of {args.frames} frames; ratio = llvmpipe+read / hider\n")
        print(cols)
        print(rule)
        for name in SCENES:
            v, f = meshes[name]
            for t in THREADS:
                py = median_ms(lambda: hider.render(v, f, width=SIZE, height=SIZE, algo=ALGO,
                                                    threads=t), args.frames)
                gl = peers[(name, "llvmpipe+read", t)]
                row = f"| {name} | {t} | {py:.2f} | {gl:.2f} | {gl / py:.2f}x |"
                s = summary.setdefault((name, t), {"py": [], "gl": [], "cli": []})
                s["py"].append(py)
                s["gl"].append(gl)
                if args.cli:
                    c = cli_ms(args.cli, models[name], t)
                    s["cli"].append(c)
                    row += f" {c:.2f} | {gl / c:.2f}x |"
                print(row)
    print(f"\nmedians over the {args.rounds} rounds (ratios of the per-round ratios' median)\n")
    print(cols)
    print(rule)
    for (name, t), s in summary.items():
        py, gl = np.median(s["py"]), np.median(s["gl"])
        ratio = np.median(np.array(s["gl"]) / np.array(s["py"]))
        row = f"| {name} | {t} | {py:.2f} | {gl:.2f} | {ratio:.2f}x |"
        if s["cli"]:
            c = np.median(s["cli"])
            row += f" {c:.2f} | {np.median(np.array(s['gl']) / np.array(s['cli'])):.2f}x |"
        print(row)


if __name__ == "__main__":
    main()
