"""hider.mpl.resolve on the scenes matplotlib's own sort gets wrong: the
colour at each pixel is the nearer surface's, as hider's z-buffer finds it
on the same projection."""

import io

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pytest  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402

import hider.mpl  # noqa: E402


def crossing_planes(ax):
    """matplotlib's two crossing planes: z = 0 and z = y."""
    X, Y = np.meshgrid([-1, 1], [-1, 1])
    ax.plot_surface(X, Y, np.zeros_like(X, dtype=float), color="tab:blue")
    ax.plot_surface(X, Y, np.array([[-1.0, -1.0], [1.0, 1.0]]), color="tab:orange")


def crossing_grids(ax, n=50):
    """Two intersecting n x n surfaces: a saddle and a tilted wave."""
    x = np.linspace(-1, 1, n)
    X, Y = np.meshgrid(x, x)
    ax.plot_surface(X, Y, X * Y, color="tab:blue")
    ax.plot_surface(X, Y, 0.5 * np.sin(3 * X) + 0.3 * Y, color="tab:orange")


def bar_stack(ax):
    """Boxes stacked on a ground slab, one bar3d call each: the slab's
    nearest corner is nearer than any box's, so matplotlib paints the whole
    slab last, over the boxes standing on it."""
    ax.bar3d(-2, -2, 0, 4, 4, 0.2, color="tab:gray")
    ax.bar3d([0.5, -1.0], [1.0, 0.8], [0.2, 0.2], 0.6, 0.6, [1.5, 0.8], color="tab:blue")
    ax.bar3d([0.5], [1.0], [1.7], 0.6, 0.6, 0.5, color="tab:orange")


def voxels_and_trisurf(ax):
    """Three voxels of their own colours pierced by a tilted
    plot_trisurf plane."""
    filled = np.zeros((2, 2, 2), dtype=bool)
    filled[0, 0, 0] = filled[1, 0, 0] = filled[1, 1, 1] = True
    colors = np.empty(filled.shape, dtype=object)
    colors[0, 0, 0], colors[1, 0, 0], colors[1, 1, 1] = "tab:blue", "tab:green", "tab:red"
    ax.voxels(filled, facecolors=colors)
    rng = np.random.default_rng(1)
    x, y = rng.uniform(-0.2, 2.2, 60), rng.uniform(-0.2, 2.2, 60)
    ax.plot_trisurf(x, y, 0.4 + 0.5 * x, color="tab:purple")


def figure(scene, resolved, elev=30, azim=-60):
    fig = plt.figure(figsize=(4, 4), dpi=100)
    ax = fig.add_subplot(projection="3d")
    scene(ax)
    ax.view_init(elev=elev, azim=azim)
    ax.set_axis_off()
    if resolved:
        hider.mpl.resolve(ax)
    fig.canvas.draw()
    return fig, ax


def pixels(fig):
    """The figure as saved to PNG by Agg: (height, width, 3) floats."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    buf.seek(0)
    return plt.imread(buf)[..., :3]


def nearer_surface(ax):
    """Per pixel, the index of the nearest collection per hider's
    z-buffer on the axes' own projection (-1 for background), and each
    collection's palette of face colours."""
    p = hider.mpl.project(ax)
    ids, _ = hider.mpl.zbuffer(ax)
    owner = np.where(ids >= 0, p.collection[p.polygon[np.maximum(ids, 0)]], -1)
    palettes = [np.unique(p.facecolors[p.collection == c, :3], axis=0)
                for c in range(len(p.collections))]
    return owner, palettes


def agreement(image, owner, palettes, margin=2):
    """The share of covered pixels away from surface boundaries whose
    colour is nearest the palette of the surface the z-buffer found."""
    h, w = owner.shape
    pad = np.pad(owner, margin, mode="edge")
    interior = np.ones_like(owner, dtype=bool)
    for dy in range(2 * margin + 1):
        for dx in range(2 * margin + 1):
            interior &= pad[dy:dy + h, dx:dx + w] == owner
    interior &= owner >= 0
    assert interior.sum() > 1000
    rgb = image[interior]
    dist = np.stack([np.min(np.linalg.norm(rgb[:, None, :] - pal[None, :, :], axis=2), axis=1)
                     for pal in palettes], axis=1)
    seen = np.argmin(dist, axis=1)
    return float(np.mean(seen == owner[interior])), seen, owner[interior]


@pytest.mark.parametrize("scene", [crossing_planes, crossing_grids, bar_stack,
                                   voxels_and_trisurf])
def test_resolve_shows_the_nearer_surface(scene):
    fig, ax = figure(scene, resolved=True)
    owner, palettes = nearer_surface(ax)
    share, _, _ = agreement(pixels(fig), owner, palettes)
    plt.close(fig)
    assert share >= 0.99, share


@pytest.mark.parametrize("scene", [crossing_planes, crossing_grids, bar_stack])
def test_without_resolve_matplotlib_gets_it_wrong(scene):
    fig, ax = figure(scene, resolved=False)
    owner, palettes = nearer_surface(ax)
    share, seen, want = agreement(pixels(fig), owner, palettes)
    plt.close(fig)
    assert share < 0.97, share
    if scene is crossing_planes:
        # One plane is painted wholly over the other: where the two
        # overlap, one colour covers the whole crossing.
        both = want != seen
        assert both.sum() > 1000
        assert len(np.unique(seen[np.isin(want, [0, 1])])) == 2
        assert len(np.unique(seen[both])) == 1


def test_resolve_follows_a_rotation():
    fig, ax = figure(crossing_grids, resolved=True)
    for azim in (-60, 30, 120):
        ax.view_init(elev=20, azim=azim)
        fig.canvas.draw()
        owner, palettes = nearer_surface(ax)
        share, _, _ = agreement(pixels(fig), owner, palettes)
        assert share >= 0.99, (azim, share)
    plt.close(fig)


@pytest.mark.parametrize("fmt", ["pdf", "svg"])
def test_vector_formats_save(fmt):
    fig, ax = figure(crossing_planes, resolved=True)
    buf = io.BytesIO()
    fig.savefig(buf, format=fmt)
    plt.close(fig)
    assert len(buf.getvalue()) > 1000


def test_a_line_behind_a_surface_is_cut():
    fig = plt.figure(figsize=(4, 4), dpi=100)
    ax = fig.add_subplot(projection="3d")
    X, Y = np.meshgrid([-1, 1], [-1, 1])
    ax.plot_surface(X, Y, np.zeros((2, 2)), color="tab:blue")
    # A vertical line through the plane: its lower part is behind it.
    ax.plot([0, 0], [0, 0], [-0.3, 1], color="red", linewidth=2)
    ax.view_init(elev=30, azim=-60)
    ax.set_axis_off()
    resolved = hider.mpl.resolve(ax)
    img = pixels(fig)
    segments = [s for a in resolved._overlay if isinstance(a, LineCollection)
                for s in a.get_segments()]
    plt.close(fig)
    red = (img[..., 0] > 0.8) & (img[..., 1] < 0.3) & (img[..., 2] < 0.3)
    assert red.sum() > 20
    assert len(segments) >= 1
    # The visible part starts at the plane: the lower end is cut off.
    lowest = min(s[:, 1].min() for s in segments)
    end, crossing = ax.transData.transform(
        hider.mpl._project(ax, np.array([[0.0, 0.0, -0.3], [0.0, 0.0, 0.0]]))[:, :2])[:, 1]
    assert crossing > end + 10
    assert abs(lowest - crossing) < 2


def test_unresolve_restores_matplotlib():
    fig, ax = figure(crossing_planes, resolved=True)
    hider.mpl.unresolve(ax)
    assert not any(isinstance(c, hider.mpl.Resolved) for c in ax.collections)
    assert all(c.get_visible() for c in ax.collections)
    plt.close(fig)


def test_savefig_at_another_dpi_re_resolves():
    fig, ax = figure(crossing_grids, resolved=True)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=150)
    buf.seek(0)
    image = plt.imread(buf)[..., :3]
    # The reference at the saved size: the figure drawn at that dpi.
    fig.set_dpi(150)
    fig.canvas.draw()
    owner, palettes = nearer_surface(ax)
    plt.close(fig)
    assert image.shape[:2] == owner.shape == (600, 600)
    share, _, _ = agreement(image, owner, palettes)
    assert share >= 0.99, share


def test_a_quads_triangles_are_drawn_as_one_path():
    # Each quad is fanned from its farthest corner, so its two triangles
    # share the painter's sort key and are painted one after the other:
    # one path per quad, but for the few cut along the crossing.
    fig, ax = figure(crossing_grids, resolved=True)
    resolved = next(c for c in ax.collections if isinstance(c, hider.mpl.Resolved))
    quads = 2 * 49 * 49
    paths = resolved.get_paths()
    p = hider.mpl.project(ax)
    plt.close(fig)
    assert len(p.faces) == 2 * quads
    assert quads <= len(paths) < 1.1 * quads, len(paths)
    # A quad painted whole is drawn by its own outline, as matplotlib
    # draws it: four corners and the close, not two triangles.
    outlines = [q for q in paths if len(q.vertices) == 5]
    assert len(outlines) > 0.9 * quads, len(outlines)
    assert all(list(q.codes) == [1, 2, 2, 2, 79] for q in outlines)
    # The fan's apex is each polygon's farthest corner.
    far = p.points[p.faces, 2].max(axis=1)
    assert np.all(p.points[p.faces[:, 0], 2] == far)
