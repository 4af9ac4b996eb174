"""Shared fixtures: the repository root, the ``hider`` command line built by
cargo, and a temporary folder for its dumps."""

import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[3]


@pytest.fixture(scope="session")
def hider_cli():
    """The path of the ``hider`` binary (``HIDER_CLI``, or built with cargo
    in the workspace's target folder; a no-op when it is up to date)."""
    given = os.environ.get("HIDER_CLI")
    if given:
        return pathlib.Path(given)
    subprocess.run(["cargo", "build", "--quiet", "--bin", "hider"], cwd=ROOT, check=True)
    meta = subprocess.run(
        ["cargo", "metadata", "--format-version", "1", "--no-deps"],
        cwd=ROOT, check=True, capture_output=True, text=True,
    )
    return pathlib.Path(json.loads(meta.stdout)["target_directory"]) / "debug" / "hider"


def read_obj(path):
    """Vertices and triangles of an OBJ file in the order of its ``f``
    lines, polygons fanned from their first corner (the primitive order of
    the scene crate's loader)."""
    vertices, faces = [], []
    for line in pathlib.Path(path).read_text().splitlines():
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            vertices.append([float(x) for x in parts[1:4]])
        elif parts[0] == "f":
            idx = []
            for corner in parts[1:]:
                i = int(corner.split("/")[0])
                idx.append(i - 1 if i > 0 else len(vertices) + i)
            for k in range(1, len(idx) - 1):
                faces.append([idx[0], idx[k], idx[k + 1]])
    return np.array(vertices, dtype=np.float64), np.array(faces, dtype=np.int64)


def write_obj(path, vertices, faces):
    """An OBJ file whose numbers read back exactly (shortest round-trip
    text of each float64)."""
    lines = [f"v {x!r} {y!r} {z!r}" for x, y, z in np.asarray(vertices, dtype=float).tolist()]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in np.asarray(faces).tolist()]
    pathlib.Path(path).write_text("\n".join(lines) + "\n")


def uv_sphere(segments=24, rings=12):
    """A UV sphere of radius 1: (vertices, faces) with poles shared."""
    verts = [[0.0, 1.0, 0.0]]
    for r in range(1, rings):
        phi = np.pi * r / rings
        for s in range(segments):
            theta = 2 * np.pi * s / segments
            verts.append([np.sin(phi) * np.cos(theta), np.cos(phi), np.sin(phi) * np.sin(theta)])
    verts.append([0.0, -1.0, 0.0])
    faces = []
    ring = lambda r, s: 1 + (r - 1) * segments + s % segments  # noqa: E731
    for s in range(segments):
        faces.append([0, ring(1, s + 1), ring(1, s)])
    for r in range(1, rings - 1):
        for s in range(segments):
            a, b, c, d = ring(r, s), ring(r, s + 1), ring(r + 1, s + 1), ring(r + 1, s)
            faces += [[a, b, c], [a, c, d]]
    south = len(verts) - 1
    for s in range(segments):
        faces.append([south, ring(rings - 1, s), ring(rings - 1, s + 1)])
    return np.array(verts), np.array(faces)


def cli_render(cli, model, tmp_path, size, *args):
    """The command line's id and depth dumps of ``model`` as arrays."""
    ids, depth = tmp_path / "ids.i32", tmp_path / "depth.f32"
    subprocess.run(
        [str(cli), "render", str(model), "-o", str(tmp_path / "out.png"),
         "--width", str(size[0]), "--height", str(size[1]),
         "--ids-out", str(ids), "--depth-out", str(depth), *args],
        check=True, capture_output=True,
    )
    shape = (size[1], size[0])
    return (np.fromfile(ids, dtype="<i4").reshape(shape),
            np.fromfile(depth, dtype="<f4").reshape(shape))
