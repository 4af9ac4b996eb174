"""hider.mpl on the matplotlib installed (CI runs this file on the oldest
matplotlib the package claims, 3.7, and on the newest): the compatibility
layer reads back exactly what was given to matplotlib, the documented
examples draw correctly, and what hider cannot resolve is drawn by
matplotlib as before, with a warning, instead of failing ``savefig``."""

import io
import pathlib
import re
import warnings

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from mpl_toolkits.mplot3d import art3d  # noqa: E402

import hider.mpl  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[3]


def pixels(fig, **kwargs):
    buf = io.BytesIO()
    fig.savefig(buf, format="png", **kwargs)
    buf.seek(0)
    return plt.imread(buf)[..., :3]


def axes3d(dpi=100):
    fig = plt.figure(figsize=(4, 4), dpi=dpi)
    return fig, fig.add_subplot(projection="3d")


def test_matplotlib_version_is_claimed():
    """The package claims matplotlib >= 3.7 (pyproject.toml's [mpl] extra)."""
    text = (ROOT / "crates/python/pyproject.toml").read_text()
    assert re.search(r'mpl = \["matplotlib>=3\.7"\]', text)
    major, minor = (int(x) for x in matplotlib.__version__.split(".")[:2])
    assert (major, minor) >= (3, 7)


def test_polygons_read_back_as_given():
    rng = np.random.default_rng(3)
    tris = rng.uniform(-1, 1, (5, 3, 3))
    quads = rng.uniform(-1, 1, (4, 4, 3))
    fig, ax = axes3d()
    mixed = art3d.Poly3DCollection(list(tris[:2]) + list(quads[:2]))
    ax.add_collection3d(mixed)
    surf = ax.plot_surface(*np.meshgrid([0.0, 1.0, 2.0], [0.0, 1.0]),
                           np.array([[0.0, 1.0, 2.0], [3.0, 4.0, 5.0]]))
    fig.canvas.draw()
    faces, invalid = hider.mpl._polygons3d(mixed)
    assert faces.shape == (4, 4, 3)
    assert invalid.tolist() == [[False, False, False, True]] * 2 + [[False] * 4] * 2
    for k, want in enumerate(list(tris[:2]) + list(quads[:2])):
        np.testing.assert_array_equal(faces[k][~invalid[k]], want)
    faces, invalid = hider.mpl._polygons3d(surf)
    assert faces.shape[0] == 2 and not invalid.any()
    # Every corner of the 2 x 3 grid appears, z = the height given.
    corners = {tuple(c) for c in faces.reshape(-1, 3).tolist()}
    assert (2.0, 1.0, 5.0) in corners and (0.0, 0.0, 0.0) in corners
    plt.close(fig)


def test_projection_is_matplotlibs():
    """_project gives the 2D points matplotlib's own Line3D draw computes."""
    fig, ax = axes3d()
    t = np.linspace(0, 4, 30)
    line, = ax.plot(np.cos(t), np.sin(t), t / 4)
    ax.view_init(elev=20, azim=40)
    fig.canvas.draw()
    mine = hider.mpl._project(ax, np.column_stack(line.get_data_3d()))[:, :2]
    np.testing.assert_allclose(mine, line.get_xydata(), rtol=1e-12, atol=1e-12)
    plt.close(fig)


def test_segments_and_scatter_read_back():
    fig, ax = axes3d()
    x = np.linspace(0, 1, 4)
    X, Y = np.meshgrid(x, x)
    wire = ax.plot_wireframe(X, Y, X + Y)
    # The depth order (middle, last, first) is not the user's order, and
    # two draws sort them (matplotlib keeps sorted copies for its own
    # draw).
    pts = np.array([[0.9, 0.1, 0.3], [0.1, 0.9, 0.6], [0.5, 0.5, 0.9]])
    sc = ax.scatter(*pts.T, s=[10, 20, 30], c=[1.0, 2.0, 3.0], cmap="viridis")
    fig.canvas.draw()
    ax.view_init(elev=10, azim=30)
    fig.canvas.draw()
    depth = hider.mpl._project(ax, pts)[:, 2]
    assert list(np.argsort(depth)) not in ([0, 1, 2], [2, 1, 0])
    segs = hider.mpl._segments3d(wire)
    assert len(segs) == 8 and all(s.shape == (4, 3) for s in segs)
    np.testing.assert_array_equal(np.concatenate(segs)[:, 2],
                                  np.concatenate(segs)[:, 0] + np.concatenate(segs)[:, 1])
    xyz, sizes, _ = hider.mpl._scatter3d(sc)
    np.testing.assert_array_equal(xyz, pts)
    assert sizes.tolist() == [10, 20, 30]
    # Colours in the user's order: the colour map's ends at the ends (as
    # given, with matplotlib's depth shading applied on top).
    face, _ = hider.mpl._scatter_colours(sc, 3, np.zeros((3, 3)))
    cmap = matplotlib.colormaps["viridis"]
    np.testing.assert_allclose(face[0], cmap(0.0), atol=1e-6)
    np.testing.assert_allclose(face[2], cmap(1.0), atol=1e-6)
    plt.close(fig)


def example_block():
    """The hider.mpl example of docs/python.md, as written."""
    text = (ROOT / "docs/python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    return next(b for b in blocks if "hider.mpl.resolve(ax)" in b)


def test_the_documented_example_draws_the_nearer_plane(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code = example_block()
    namespace = {}
    with warnings.catch_warnings():
        warnings.simplefilter("error", hider.mpl.ResolveWarning)
        exec(compile(code, "docs/python.md", "exec"), namespace)
    saved = [p for p in tmp_path.iterdir() if p.suffix == ".png"]
    assert len(saved) == 1
    image = plt.imread(saved[0])[..., :3]
    ax = namespace["ax"]
    plt.close(ax.figure)
    # Both planes show: blue (z = 0) and orange (z = y), each over a large
    # area, and neither covers the other where they cross (matplotlib's
    # own drawing paints one over the whole crossing).
    blue = np.array(matplotlib.colors.to_rgb("tab:blue"))
    orange = np.array(matplotlib.colors.to_rgb("tab:orange"))
    near_blue = np.linalg.norm(image - blue, axis=2) < 0.25
    near_orange = np.linalg.norm(image - orange, axis=2) < 0.25
    assert near_blue.sum() > 5000 and near_orange.sum() > 5000


def test_the_readme_pictures_draw(tmp_path):
    """examples/pictures.py (the README's before/after pictures) runs
    without a warning; the line shows in both pictures, and the surfaces
    differ where they cross."""
    import importlib.util
    spec = importlib.util.spec_from_file_location(
        "pictures", ROOT / "crates/python/examples/pictures.py")
    pictures = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(pictures)
    with warnings.catch_warnings():
        warnings.simplefilter("error", hider.mpl.ResolveWarning)
        pictures.main(tmp_path)
    red = np.array(matplotlib.colors.to_rgb("tab:red"))
    images = [plt.imread(tmp_path / name)[..., :3]
              for name in ("python-before.png", "python-after.png")]
    counts = [int((np.linalg.norm(im - red, axis=2) < 0.1).sum()) for im in images]
    assert min(counts) > 50, counts
    changed = np.abs(images[0] - images[1]).max(axis=2) > 0.1
    assert changed.mean() > 0.03, changed.mean()


def crossing_soup(ax, n=400, seed=0):
    rng = np.random.default_rng(seed)
    tris = rng.uniform(-1, 1, (n, 3, 3))
    ax.add_collection3d(art3d.Poly3DCollection(tris, facecolors=rng.uniform(0, 1, (n, 3))))
    ax.set_xlim(-1, 1), ax.set_ylim(-1, 1), ax.set_zlim(-1, 1)


def test_an_unresolvable_soup_is_drawn_by_matplotlib_with_a_warning():
    """400 random crossing triangles need far more splits than the budget:
    savefig succeeds, warns once that the split budget (4,096 + 2 per
    triangle: the work is bounded by it, not by the 160,000 splits the soup
    would need) ran out, and shows exactly matplotlib's own picture."""
    fig, ax = axes3d()
    crossing_soup(ax)
    plain = pixels(fig)
    resolved = hider.mpl.resolve(ax)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        image = pixels(fig)
        again = pixels(fig)
    plt.close(fig)
    ours = [w for w in caught if issubclass(w.category, hider.mpl.ResolveWarning)]
    assert len(ours) == 1, [str(w.message) for w in caught]
    assert "split budget" in str(ours[0].message)
    assert resolved.fallback is not None and resolved.pieces == 0
    np.testing.assert_array_equal(image, plain)
    np.testing.assert_array_equal(again, plain)


def test_max_splits_is_a_keyword():
    fig, ax = axes3d()
    crossing_soup(ax, n=60, seed=1)
    with pytest.raises(ValueError):
        hider.mpl.resolve(ax, max_splits=-1)
    resolved = hider.mpl.resolve(ax, max_splits=10**6)
    with warnings.catch_warnings():
        warnings.simplefilter("error", hider.mpl.ResolveWarning)
        pixels(fig)
    assert resolved.fallback is None and resolved.pieces > 60
    resolved = hider.mpl.resolve(ax, max_splits=0)
    with pytest.warns(hider.mpl.ResolveWarning, match="split budget"):
        pixels(fig)
    plt.close(fig)


def test_a_painter_past_its_timeout_is_drawn_by_matplotlib_with_a_warning():
    """resolve(ax, timeout=0) stops the painter at once: savefig succeeds,
    warns once naming the timeout, and shows matplotlib's own picture."""
    fig, ax = axes3d()
    crossing_soup(ax, n=60, seed=1)
    plain = pixels(fig)
    with pytest.raises(ValueError, match="timeout"):
        hider.mpl.resolve(ax, timeout=-1)
    resolved = hider.mpl.resolve(ax, timeout=0)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        image = pixels(fig)
    plt.close(fig)
    ours = [w for w in caught if issubclass(w.category, hider.mpl.ResolveWarning)]
    assert len(ours) == 1, [str(w.message) for w in caught]
    assert "timed out" in str(ours[0].message) and "timeout=" in str(ours[0].message)
    assert resolved.fallback is not None and resolved.pieces == 0
    np.testing.assert_array_equal(image, plain)


def test_an_unreadable_collection_is_left_to_matplotlib(monkeypatch):
    """A Poly3DCollection whose 3D data this matplotlib hides from hider
    stays matplotlib's, with a warning; savefig draws it."""
    fig, ax = axes3d()
    X, Y = np.meshgrid([-1, 1], [-1, 1])
    surf = ax.plot_surface(X, Y, np.zeros((2, 2)), color="tab:blue")

    def unreadable(col):
        raise hider.mpl._Unsupported("cannot read the 3D polygons")

    monkeypatch.setattr(hider.mpl, "_polygons3d", unreadable)
    with pytest.warns(hider.mpl.ResolveWarning, match="cannot read"):
        resolved = hider.mpl.resolve(ax)
    assert surf not in resolved.sources and "draw" not in surf.__dict__
    image = pixels(fig)
    plt.close(fig)
    blue = np.array(matplotlib.colors.to_rgb("tab:blue"))
    assert (np.linalg.norm(image - blue, axis=2) < 0.3).sum() > 5000


def test_a_scatter_nothing_hides_is_matplotlibs_picture():
    """Colours, sizes, marker and depth shading (on by default, computed
    differently before and from matplotlib 3.11) as matplotlib draws
    them: with no surface, the resolved scatter is matplotlib's picture."""
    images = []
    for resolved in (False, True):
        fig, ax = axes3d()
        rng = np.random.default_rng(0)
        ax.scatter(*rng.uniform(-1, 1, (3, 60)), s=rng.uniform(20, 80, 60),
                   c=rng.uniform(0, 1, 60), cmap="plasma", marker="s")
        ax.set_axis_off()
        if resolved:
            hider.mpl.resolve(ax)
        images.append(pixels(fig))
        plt.close(fig)
    diff = np.abs(images[0] - images[1]).max(axis=2)
    assert (diff > 0.02).sum() == 0, (diff > 0.02).sum()
