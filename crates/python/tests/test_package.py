"""The package as installed: its version, its public names, the typing
files it ships, and what its docstrings say of the algorithms."""

import importlib
import pathlib
import re
import sys

import numpy as np
import pytest

import hider

ROOT = pathlib.Path(__file__).resolve().parents[3]
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from conftest import uv_sphere  # noqa: E402


def workspace_version():
    text = (ROOT / "Cargo.toml").read_text()
    section = text.split("[workspace.package]", 1)[1]
    return re.search(r'^version = "([^"]+)"', section, flags=re.M).group(1)


def test_version_is_the_workspaces():
    assert hider.__version__ == workspace_version()


def test_dir_shows_the_public_names_only():
    names = dir(hider)
    assert sorted(names) == sorted([*hider.__all__, "__version__", "mpl"])
    for private in ("np", "NamedTuple", "_as_vertices", "_hider"):
        assert private not in names
    for name in hider.__all__:
        assert hasattr(hider, name)


def test_dir_of_mpl_shows_the_public_names_only():
    mpl = pytest.importorskip("hider.mpl")
    assert dir(mpl) == sorted(mpl.__all__)


def test_the_typing_files_ship_with_the_package():
    folder = pathlib.Path(hider.__file__).parent
    for name in ("py.typed", "__init__.pyi", "mpl.pyi", "_hider.pyi"):
        assert (folder / name).is_file(), name


def stub_names(path):
    """The top-level names a stub defines (def, class, annotated or
    assigned)."""
    found = set()
    for line in path.read_text().splitlines():
        m = re.match(r"(?:def|class) (\w+)|(\w+)\s*[:=]", line)
        if m:
            found.add(m.group(1) or m.group(2))
    return found


@pytest.mark.parametrize("module", ["hider", "hider.mpl"])
def test_stubs_name_every_public_name(module):
    pytest.importorskip("matplotlib")
    mod = importlib.import_module(module)
    stub = pathlib.Path(mod.__file__).with_suffix(".pyi")
    names = stub_names(stub)
    assert set(mod.__all__) <= names, set(mod.__all__) - names


def test_kinds_come_from_the_registry():
    every = hider.algorithms()
    by_kind = {k: hider.algorithms(kind=k) for k in hider.KINDS}
    assert sorted(sum(by_kind.values(), [])) == sorted(every)
    assert "zbuffer-tiled" in by_kind["exact"] and hider.DEFAULT_ALGO in by_kind["exact"]
    assert by_kind["reference"] == ["oracle"]
    assert {"painter-naive", "zbuffer-linear-z"} <= set(by_kind["approximate"])
    assert "warnock-4x4" in by_kind["multisample"]
    with pytest.raises(ValueError):
        hider.algorithms(kind="fast")


def test_render_docstring_names_every_hider_that_may_disagree():
    doc = hider.render.__doc__
    for name in hider.algorithms(kind="approximate") + ["warnock-4x4"]:
        assert f'"{name}"' in doc, name
    assert "all of them agree" not in doc


def test_exact_hiders_agree_and_approximate_ones_need_not():
    """A sphere pierced by random triangles: every exact hider equals the
    reference but on depth ties (a few pixels); painter-naive,
    zbuffer-linear-z and warnock-4x4 differ on a few percent or more,
    as their docstring says."""
    v, f = uv_sphere(24, 12)
    rng = np.random.default_rng(0)
    tv = rng.uniform(-1.2, 1.2, (180, 3))
    V = np.concatenate([v, tv])
    F = np.concatenate([f, np.arange(180).reshape(60, 3) + len(v)])
    kw = dict(width=128, height=128, eye=(0.3, 0.5, 3.0), fovy=50, near=0.5, far=20)
    ref, _ = hider.render(V, F, algo="oracle", **kw)
    for name in hider.algorithms(kind="exact"):
        ids, _ = hider.render(V, F, algo=name, **kw)
        assert (ids != ref).mean() < 0.001, name
    for name in ("painter-naive", "zbuffer-linear-z", "warnock-4x4"):
        ids, _ = hider.render(V, F, algo=name, **kw)
        assert (ids != ref).mean() > 0.01, name
