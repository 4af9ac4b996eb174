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
    # The distances of each distinct colour (far fewer than pixels).
    rgb, inverse = np.unique(image[interior], axis=0, return_inverse=True)
    dist = np.stack([np.min(np.linalg.norm(rgb[:, None, :] - pal[None, :, :], axis=2), axis=1)
                     for pal in palettes], axis=1)
    seen = np.argmin(dist, axis=1)[inverse.ravel()]
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


def test_intersections_have_no_fringe_at_high_dpi():
    """Pieces are stroked one device pixel wide, not one point: at 300 dpi
    a point is over 4 pixels, and a piece's stroke would reach 2 pixels
    over the surface in front of it along every intersection curve."""
    fig = plt.figure(figsize=(4, 4), dpi=300)
    ax = fig.add_subplot(projection="3d")
    crossing_planes(ax)
    ax.view_init(elev=30, azim=-60)
    ax.set_axis_off()
    hider.mpl.resolve(ax)
    fig.canvas.draw()
    owner, palettes = nearer_surface(ax)
    image = pixels(fig)
    plt.close(fig)
    assert image.shape[:2] == owner.shape == (1200, 1200)
    # Pixels one away from a boundary: 1.0 with the hairline; 0.9967 with
    # the one-point stroke hider drew before.
    share, _, _ = agreement(image, owner, palettes, margin=1)
    assert share >= 0.999, share


def plane_with_points(ax, resolved, scatter=True, line=True, plane=True):
    """A grey plane at z = 0.3; a red scatter point above it (z = 0.6) and
    a blue one below (z = -0.2, seen through the plane); a green line with
    markers from above the plane to below it."""
    if plane:
        X, Y = np.meshgrid(np.linspace(-1, 1, 5), np.linspace(-1, 1, 5))
        ax.plot_surface(X, Y, np.full_like(X, 0.3), color="0.75", shade=False)
    if scatter:
        ax.scatter([0.3], [0.3], [0.6], color="red", s=300, depthshade=False)
        ax.scatter([-0.3], [0.6], [-0.2], color="blue", s=300, depthshade=False)
    if line:
        ax.plot([-0.4, -0.2], [0.4, 0.7], [0.7, -0.1], "g-o", markersize=14, label="g-o")
    ax.set_xlim(-1, 1), ax.set_ylim(-1, 1), ax.set_zlim(-1, 1)
    ax.view_init(elev=30, azim=-60)
    ax.set_axis_off()
    if resolved:
        hider.mpl.resolve(ax)


def colour_mask(image, name, tol=0.2):
    rgb = np.array(matplotlib.colors.to_rgb(name))
    return np.linalg.norm(image - rgb, axis=2) < tol


def disc(ax, fig, xyz, radius):
    """The image pixels within radius of a 3D point's projection."""
    x, y = ax.transData.transform(hider.mpl._project(ax, np.array([xyz]))[:, :2])[0]
    h = int(fig.bbox.height)
    yy, xx = np.mgrid[0:h, 0:int(fig.bbox.width)]
    return np.hypot(xx + 0.5 - x, yy + 0.5 - (h - y)) < radius


def test_markers_are_depth_tested_per_marker():
    # The markers alone, for the reference counts.
    fig = plt.figure(figsize=(4, 4), dpi=100)
    ax = fig.add_subplot(projection="3d")
    plane_with_points(ax, resolved=False, plane=False)
    alone = pixels(fig)
    plt.close(fig)
    # matplotlib alone paints the plane over the point above it (its
    # nearest corner is nearer than the point).
    fig = plt.figure(figsize=(4, 4), dpi=100)
    ax = fig.add_subplot(projection="3d")
    plane_with_points(ax, resolved=False)
    assert colour_mask(pixels(fig), "red").sum() < 0.5 * colour_mask(alone, "red").sum()
    plt.close(fig)
    fig = plt.figure(figsize=(4, 4), dpi=100)
    ax = fig.add_subplot(projection="3d")
    plane_with_points(ax, resolved=True)
    image = pixels(fig)
    above_g = disc(ax, fig, (-0.4, 0.4, 0.7), 5)
    below_g = disc(ax, fig, (-0.2, 0.7, -0.1), 5)
    plt.close(fig)
    red, blue = colour_mask(image, "red"), colour_mask(image, "blue")
    # The scatter point above the plane is whole, the one below is gone.
    assert colour_mask(alone, "red").sum() > 200
    assert red.sum() >= 0.97 * colour_mask(alone, "red").sum(), (red.sum(),)
    assert colour_mask(alone, "blue").sum() > 200 and blue.sum() == 0
    # The line's marker above the plane shows, the one below does not.
    green = colour_mask(image, "green", tol=0.3)
    assert green[above_g].mean() > 0.9
    assert colour_mask(alone, "green", tol=0.3)[below_g].mean() > 0.6
    assert green[below_g].sum() == 0


def test_a_cut_line_is_one_path_per_visible_run():
    fig = plt.figure(figsize=(4, 4), dpi=100)
    ax = fig.add_subplot(projection="3d")
    plane_with_points(ax, resolved=False, scatter=False, line=False)
    x = np.linspace(-0.9, 0.9, 181)
    # Above the plane for x in (-0.9, -0.5) and (0, 0.5), below (and seen
    # through the plane) elsewhere.
    line, = ax.plot(x, np.zeros_like(x), 0.3 + 0.2 * np.sin(2 * np.pi * x), color="red")
    resolved = hider.mpl.resolve(ax)
    pixels(fig)
    plt.close(fig)
    runs = [s for a in resolved._overlay if isinstance(a, LineCollection)
            for s in a.get_segments()]
    assert len(runs) == 2, [len(r) for r in runs]
    # Each run keeps the data points it passes (about 40 and 50), not two
    # ends per segment.
    assert sorted(len(r) for r in runs)[0] >= 38, [len(r) for r in runs]


def test_an_uncut_line_draws_as_matplotlib_draws_it():
    """No ticks at data points: a translucent polyline that nothing hides
    is drawn as matplotlib draws it, one path (separate segments would
    overlap at every data point and darken it); so is a dashed line with
    markers at every fifth point."""
    images = []
    for resolved in (False, True):
        fig = plt.figure(figsize=(4, 4), dpi=100)
        ax = fig.add_subplot(projection="3d")
        t = np.linspace(0, 1, 60)
        ax.plot(t, t, 0.5 * t, color="purple", alpha=0.4, linewidth=4)
        ax.plot(t, 1 - t, 0.5 * t, "g--o", markevery=5, markersize=6)
        ax.set_axis_off()
        if resolved:
            hider.mpl.resolve(ax)
        images.append(pixels(fig))
        plt.close(fig)
    diff = np.abs(images[0] - images[1]).max(axis=2)
    assert (diff > 0.02).sum() < 20, (diff > 0.02).sum()


def test_legend_keeps_resolved_handles():
    counts = []
    for resolved in (False, True):
        fig = plt.figure(figsize=(4, 4), dpi=100)
        ax = fig.add_subplot(projection="3d")
        plane_with_points(ax, resolved=False, scatter=False)
        ax.plot([0.5, 0.6], [0.5, 0.6], [0.5, 0.6], color="red", linewidth=3, label="red line")
        if resolved:
            hider.mpl.resolve(ax)
        legend = ax.legend(loc="upper left")
        image = pixels(fig)
        box = legend.get_window_extent()
        h = image.shape[0]
        region = image[int(h - box.y1):int(h - box.y0), int(box.x0):int(box.x1)]
        counts.append((colour_mask(region, "red").sum(),
                       colour_mask(region, "green", tol=0.3).sum()))
        plt.close(fig)
    (red0, green0), (red1, green1) = counts
    assert red0 > 30 and green0 > 30
    assert red1 >= 0.9 * red0 and green1 >= 0.9 * green0, counts


def test_unresolve_gives_the_artists_back():
    fig = plt.figure(figsize=(4, 4), dpi=100)
    ax = fig.add_subplot(projection="3d")
    plane_with_points(ax, resolved=False)
    plain = pixels(fig)
    hider.mpl.resolve(ax)
    pixels(fig)
    hider.mpl.unresolve(ax)
    for a in list(ax.collections) + list(ax.lines):
        assert "draw" not in a.__dict__ and "do_3d_projection" not in a.__dict__
    again = pixels(fig)
    plt.close(fig)
    np.testing.assert_array_equal(plain, again)


def test_faces_behind_translucent_faces_are_kept():
    """The painter drops pieces hidden behind opaque faces; a face drawn
    see-through hides nothing, so what is behind it must still be painted
    (it shows through). Without the translucent flags the back face, fully
    covered, is culled."""
    from hider import _hider

    # Window pixels, y down, depth t in [0, 1] growing away: a small
    # triangle at t = 0.8 wholly behind a large one at t = 0.2.
    points = np.array([
        [10, 10, 0.8], [30, 10, 0.8], [20, 30, 0.8],
        [0, 0, 0.2], [40, 0, 0.2], [20, 40, 0.2],
    ], dtype=float)
    faces = np.array([[0, 1, 2], [3, 4, 5]], dtype=np.int64)
    opaque, *_ = _hider.screen_pieces(points, faces, 40, 40)
    assert list(opaque) == [1]
    seen, *_ = _hider.screen_pieces(points, faces, 40, 40, None,
                                    np.array([False, True]))
    assert list(seen) == [0, 1]
    with pytest.raises(ValueError, match="translucent: 1 flags for 2 faces"):
        _hider.screen_pieces(points, faces, 40, 40, None, np.array([True]))
