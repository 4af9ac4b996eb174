"""Correct occlusion for matplotlib's 3D axes.

mplot3d sorts whole polygons by one depth each (their mean, or min or max
``zsort``) and whole collections by another, then paints them in that
order. Where two surfaces intersect, or a long polygon overlaps a short
one, no order of whole polygons is right, and one surface is drawn
entirely over the other.

``resolve(ax)`` replaces that sort for every ``Poly3DCollection`` of an
``Axes3D`` (``plot_surface``, ``plot_trisurf``, ``bar3d``, ``voxels``,
``add_collection3d``): at each draw it projects all their polygons with the
axes' own projection (``ax.M``), keeps matplotlib's colours, and orders
and splits them jointly with the painter's algorithm of Newell, Newell &
Sancha (splitting a polygon by another's plane where no order exists). The
pieces are painted in that order, so ``savefig`` to PNG, PDF or SVG shows
each surface exactly where it is the nearest, and rotating the view
re-resolves. Lines (``plot``, ``plot_wireframe``) and the coloured edges of
polygons are cut where they pass behind a surface, against a depth buffer
of the same projection; markers (``scatter``, ``plot(..., "o")``) are
hidden one by one where a surface is in front of their centre.

Whatever ``resolve`` cannot handle (a scene that needs more polygon splits
than its budget, an artist it does not know) is drawn by matplotlib as
before, with one ``ResolveWarning``: ``savefig`` never fails because of
hider. Works with matplotlib 3.7 and later (the few private attributes
mplot3d offers no public getter for are read in one tested place,
``_polygons3d`` and its neighbours, per version).
"""

import warnings
from typing import NamedTuple

import numpy as np
from matplotlib import collections as mcoll
from matplotlib import colors as mcolors
from matplotlib import lines as mlines
from matplotlib import path as mpath
from matplotlib.transforms import IdentityTransform
from mpl_toolkits.mplot3d import art3d, proj3d

from . import _hider
from ._worker import _as_timeout, _interruptible

__all__ = ["resolve", "unresolve", "Resolved", "ResolveWarning", "Projected",
           "project", "zbuffer"]


def __dir__():
    """The public names only."""
    return sorted(__all__)


# Window depth of the orthographic screen camera for depth t in [0, 1]:
# the eye is one unit before t = 0, the near plane at 0.5 and the far at
# 2.5 (the constants of the extension's screen-space scenes).
_NEAR, _EYE_TO_FRONT, _FAR = 0.5, 1.0, 2.5

# A line sample or marker centre is hidden when a surface is nearer than it
# by more than this much window depth (of a scene spanning 0.5): edges lie
# on their own polygons, whose f32 depth differs from the line's in the
# last bits.
_LINE_DEPTH_TOLERANCE = 2e-4

# Alpha from which a face counts as opaque (hides lines, gets a stroke).
_OPAQUE = 0.999

# Samples per pixel of line length for the visibility test.
_LINE_SAMPLES_PER_PIXEL = 2.0

# The painter's split budget per draw: this many, plus this many per
# triangle. Surfaces need well under one split per triangle (two crossing
# 100 x 100 grids: about 400 for 39,204 triangles); 400 random crossing
# triangles would need over 160,000 and take many seconds, and fail
# within about a quarter of a second with this budget instead.
_SPLITS_BASE, _SPLITS_PER_TRIANGLE = 4096, 2


class ResolveWarning(UserWarning):
    """``resolve`` left something to matplotlib's own drawing: a scene over
    the painter's split budget (raise it with ``resolve(ax,
    max_splits=...)``), an artist it cannot read. Issued once per
    ``Resolved`` artist and cause."""


class _Unsupported(Exception):
    """An artist whose 3D data this matplotlib does not expose."""


# ---------------------------------------------------------------------------
# The compatibility layer: what each matplotlib version offers.
#
# mplot3d has no public getter for a Poly3DCollection's 3D vertices, a
# Line3DCollection's 3D segments or a scatter's 3D offsets and sizes; the
# private attributes holding them differ between versions. Each reader
# below tries the public API first, then the attributes of each version,
# and raises _Unsupported when none is there (resolve then leaves that
# artist to matplotlib, with a warning). tests/test_mpl_compat.py checks
# each against the data given to matplotlib, on the oldest and newest
# matplotlib CI installs.
# ---------------------------------------------------------------------------


def _project(ax, xyz):
    """Points (..., 3) in data coordinates to (..., 3) projected points:
    x, y in the 2D axes' data coordinates and matplotlib's view depth, as
    ``proj3d.proj_transform`` (public in every version) computes them with
    the axes' projection ``ax.M``, after the axes' scale transforms (the
    identity for linear axes; 3.11's log axes)."""
    xyz = np.asarray(xyz, dtype=float)
    shape = xyz.shape[:-1]
    flat = xyz.reshape(-1, 3)
    coords = []
    for k, axis in enumerate((ax.xaxis, ax.yaxis, ax.zaxis)):
        c = flat[:, k]
        transform = axis.get_transform()
        if not isinstance(transform, IdentityTransform):
            c = transform.transform(c)
        coords.append(c)
    if len(flat) == 0:
        return np.zeros((*shape, 3))
    x, y, z = proj3d.proj_transform(*coords, ax.M)
    return np.stack([np.asarray(x, float), np.asarray(y, float), np.asarray(z, float)],
                    axis=-1).reshape(*shape, 3)


def _polygons3d(col):
    """The 3D corners of a Poly3DCollection's polygons in the user's order:
    ``(faces, invalid)``, faces (n, v, 3) float padded to the most corners,
    invalid (n, v) True on padding and masked corners.

    matplotlib 3.7 to 3.10 keep the corners as one 4 x N array ``_vec``
    sliced by ``_segslices``; 3.11 and later keep the padded (n, v, 3)
    array ``_faces`` with the mask ``_invalid_vertices``."""
    vec, slices = getattr(col, "_vec", None), getattr(col, "_segslices", None)
    if vec is not None and slices is not None:
        xyz = np.ma.getdata(np.asarray(vec)[:3]).T.astype(float)
        starts = np.array([s.start for s in slices], dtype=np.int64)
        counts = np.array([s.stop - s.start for s in slices], dtype=np.int64)
        n = len(counts)
        v = int(counts.max()) if n else 0
        invalid = np.arange(v)[None, :] >= counts[:, None]
        index = np.where(invalid, 0, starts[:, None] + np.arange(v)[None, :])
        faces = xyz[index] if n and len(xyz) else np.zeros((n, v, 3))
        return faces, invalid
    faces = getattr(col, "_faces", None)
    if faces is not None:
        faces = np.asarray(np.ma.getdata(faces), dtype=float)
        if faces.ndim != 3:
            return np.zeros((0, 0, 3)), np.zeros((0, 0), bool)
        n, v = faces.shape[:2]
        invalid = np.broadcast_to(np.asarray(getattr(col, "_invalid_vertices", False),
                                             dtype=bool), (n, v))
        return faces, invalid
    raise _Unsupported(f"cannot read the 3D polygons of {type(col).__name__} "
                       "on this matplotlib")


def _polygon_colours(col, n):
    """Face and edge RGBA per polygon in the user's order, colour maps
    applied as the collection's ``do_3d_projection`` applies them (3D
    colours in ``_facecolor3d``/``_edgecolor3d`` in every version; the
    public getters return them sorted by depth)."""
    if col.get_array() is not None:
        col.update_scalarmappable()
        if getattr(col, "_face_is_mapped", False):
            col._facecolor3d = col._facecolors
        if getattr(col, "_edge_is_mapped", False):
            col._edgecolor3d = col._edgecolors
    face = getattr(col, "_facecolor3d", None)
    edge = getattr(col, "_edgecolor3d", None)
    if face is None:
        face = mcoll.PolyCollection.get_facecolor(col)
    if edge is None:
        edge = mcoll.PolyCollection.get_edgecolor(col)
    face = _rgba(face, n)
    edge = face.copy() if len(edge) == 0 else _rgba(edge, n)
    return face, edge


def _antialiased(col):
    """A collection's antialiasing flags (``get_antialiased`` from 3.8)."""
    getter = getattr(col, "get_antialiased", None)
    flags = getter() if getter is not None else getattr(col, "_antialiaseds", True)
    return np.atleast_1d(np.asarray(flags, dtype=bool))


def _segments3d(col):
    """The 3D polylines of a Line3DCollection (``_segments3d`` in every
    version, a list or an (n, k, 3) possibly masked array) as float arrays
    with masked points as NaN."""
    segs = getattr(col, "_segments3d", None)
    if segs is None:
        raise _Unsupported(f"cannot read the 3D segments of {type(col).__name__} "
                           "on this matplotlib")
    out = []
    for s in segs:
        a = np.ma.asarray(s, dtype=float)
        out.append(np.ma.filled(a, np.nan).reshape(-1, 3))
    return out


def _scatter3d(col):
    """A scatter's 3D points, sizes and linewidths in the user's order
    (``_offsets3d``, ``_sizes3d``, ``_linewidths3d`` in every version; the
    public getters return them sorted by depth after a draw)."""
    offsets = getattr(col, "_offsets3d", None)
    if offsets is None:
        raise _Unsupported(f"cannot read the 3D points of {type(col).__name__} "
                           "on this matplotlib")
    xyz = np.column_stack([np.ma.filled(np.ma.asarray(c, dtype=float).ravel(), np.nan)
                           for c in offsets]) if len(offsets) == 3 else np.zeros((0, 3))
    sizes = getattr(col, "_sizes3d", None)
    sizes = np.asarray(col.get_sizes() if sizes is None else sizes, dtype=float)
    widths = getattr(col, "_linewidths3d", None)
    widths = np.asarray(col.get_linewidth() if widths is None else widths, dtype=float)
    return xyz, sizes, widths


def _scatter_colours(col, n, xyz_view):
    """A scatter's face and edge RGBA per point in the user's order, with
    matplotlib's depth shading (``depthshade``, on by default), as the
    version installed computes it: up to 3.10, alpha falls linearly from 1
    for the nearest point to 0.3 for the farthest; from 3.11, by the depth
    behind the nearest point over the data's projected extent (the
    ``_data_scale`` its last draw computed), down to
    ``depthshade_minalpha``. ``xyz_view`` holds the projected points
    (x, y and view depth)."""
    col.update_scalarmappable()
    face = _rgba(mcoll.Collection.get_facecolor(col), n)
    raw_edge = getattr(col, "_edgecolors", None)
    if isinstance(raw_edge, str) and raw_edge == "face":
        edge = face.copy()
    else:
        edge = _rgba(mcoll.Collection.get_edgecolor(col), n)
    z = xyz_view[:, 2]
    if getattr(col, "_depthshade", False) and n > 0 and np.isfinite(z).any():
        lo, hi = np.nanmin(z), np.nanmax(z)
        floor = float(getattr(col, "_depthshade_minalpha", 0.3))
        if hasattr(col, "_data_scale"):
            finite = np.isfinite(xyz_view).all(axis=1)
            ptp = np.ptp(xyz_view[finite], axis=0) if finite.any() else np.zeros(3)
            scale = float(np.sqrt((ptp ** 2).sum()))
            alpha = (np.clip(1 - (z - lo) / scale, floor, 1) if scale > 0
                     else np.ones(n))
        else:
            alpha = 1 - (z - lo) / (hi - lo) * 0.7 if hi > lo else np.ones(n)
        face[:, 3] *= alpha
        edge[:, 3] *= alpha
    return face, edge


def _rgba(colors, count):
    """Colours as an (count, 4) array, one per item (matplotlib stores one
    colour for all items as a single row)."""
    if isinstance(colors, str):
        c = mcolors.to_rgba_array(colors) if colors != "none" else np.zeros((1, 4))
    else:
        c = mcolors.to_rgba_array(colors) if len(colors) else np.zeros((0, 4))
    if len(c) == count:
        return c.copy()
    if len(c) == 0:
        return np.zeros((count, 4))
    return np.repeat(c[:1], count, axis=0)


def _polygon_source(col):
    """The polygons of a Poly3DCollection with their colours and edge
    widths in the user's order."""
    faces, invalid = _polygons3d(col)
    n = len(faces)
    face, edge = _polygon_colours(col, n)
    lw = np.asarray(col.get_linewidth(), dtype=float)
    lw = np.broadcast_to(lw if lw.size in (1, n) else lw[:1], (n,)) if n else np.zeros(0)
    return faces, invalid, face, edge, lw


def _fan(depth, bad, base):
    """Fans each polygon (rows of ``depth``, the view depth of its corners)
    into triangles from its farthest valid corner: ``(triangles as point
    indices from base, polygon of each)``, each polygon's triangles one
    after another. A triangle with a bad corner is left out.

    All the triangles of a polygon then share its farthest depth, which is
    the painter's sort key, so they sort together and are mostly painted
    one after another: the pieces of one polygon painted in a row are
    drawn as one path, and a quad becomes one path rather than two (a fan
    from a fixed corner would give the two triangles of a surface's quads
    different keys, with unrelated polygons sorted between them). Any
    corner gives the same outline for a polygon that is convex on screen,
    as the polygons of surfaces, bars and voxels are."""
    n, v = depth.shape
    if v < 3:
        return np.zeros((0, 3), np.int64), np.zeros(0, np.int64)
    apex = np.argmax(np.where(bad, -np.inf, depth), axis=1)
    k = np.arange(1, v - 1)
    corners = np.stack([np.broadcast_to(apex[:, None], (n, v - 2)),
                        (apex[:, None] + k) % v, (apex[:, None] + k + 1) % v], axis=2)
    ok = ~np.take_along_axis(bad, corners.reshape(n, -1), axis=1).reshape(n, v - 2, 3).any(axis=2)
    idx = corners + (np.arange(n) * v + base)[:, None, None]
    poly = np.broadcast_to(np.arange(n)[:, None], (n, v - 2))
    return idx[ok], poly[ok]


def _convex(xy):
    """Whether each polygon of ``xy`` (n, v, 2) is convex (turns one way
    only; straight and degenerate corners allowed)."""
    e = np.roll(xy, -1, axis=1) - xy
    turn = e[..., 0] * np.roll(e[..., 1], -1, axis=1) - e[..., 1] * np.roll(e[..., 0], -1, axis=1)
    return (turn >= 0).all(axis=1) | (turn <= 0).all(axis=1)


class _Gathered:
    """Every polygon of the sources fanned into triangles in window pixels
    (y down) with depth t in [0, 1], plus each triangle's polygon."""

    def __init__(self, ax, sources, width, height):
        pts, tris, tri_poly = [], [], []
        face_rgba, edge_rgba, widths, outlines, which, convex = [], [], [], [], [], []
        base, poly_base = 0, 0
        for c, col in enumerate(sources):
            faces, invalid, face, edge, lw = _polygon_source(col)
            n = len(faces)
            if n == 0:
                continue
            proj = _project(ax, faces)
            disp = ax.transData.transform(proj[..., :2].reshape(-1, 2)).reshape(n, -1, 2)
            p = np.concatenate([disp, proj[..., 2:3]], axis=-1)
            bad = invalid | ~np.isfinite(p).all(axis=-1)
            v = faces.shape[1]
            t, poly = _fan(p[..., 2], bad, base)
            tris.append(t)
            tri_poly.append(poly + poly_base)
            pts.append(p.reshape(-1, 3))
            face_rgba.append(face)
            edge_rgba.append(edge)
            widths.append(lw)
            outlines.append((p, bad))
            convex.append(_convex(disp) & ~bad.any(axis=1))
            which.append(np.full(n, c))
            base += n * v
            poly_base += n
        self.width, self.height = width, height
        self.points = np.concatenate(pts) if pts else np.zeros((0, 3))
        self.faces = np.concatenate(tris).astype(np.int64) if tris else np.zeros((0, 3), np.int64)
        self.tri_poly = np.concatenate(tri_poly) if tri_poly else np.zeros(0, np.int64)
        self.face_rgba = np.concatenate(face_rgba) if face_rgba else np.zeros((0, 4))
        self.edge_rgba = np.concatenate(edge_rgba) if edge_rgba else np.zeros((0, 4))
        self.linewidths = np.concatenate(widths) if widths else np.zeros(0)
        self.outlines = outlines
        self.collection = np.concatenate(which) if which else np.zeros(0, np.int64)
        #: Per polygon: convex on screen with every corner valid, so that
        #: its fan's triangles fill exactly its outline.
        self.convex = np.concatenate(convex) if convex else np.zeros(0, bool)
        #: Per polygon, the number of triangles of its fan.
        self.tri_count = np.bincount(self.tri_poly, minlength=len(self.collection))
        # Depth over the points in use, mapped onto [0, 1].
        used = np.zeros(len(self.points), dtype=bool)
        used[self.faces.ravel()] = True
        z = self.points[used, 2] if used.any() else np.zeros(1)
        self.zlo, zhi = float(z.min()), float(z.max())
        self.zspan = zhi - self.zlo if zhi > self.zlo else 1.0
        self.points[:, 1] = height - self.points[:, 1]
        self.points[:, 2] = (self.points[:, 2] - self.zlo) / self.zspan
        # Unused padding vertices (masked) must still be finite.
        self.points[~np.isfinite(self.points)] = 0.0

    def window_depth(self, z):
        """matplotlib view depths as the screen camera's window depths."""
        t = (np.asarray(z, dtype=float) - self.zlo) / self.zspan
        return (t + _EYE_TO_FRONT - _NEAR) / (_FAR - _NEAR)


class Projected(NamedTuple):
    """What ``project`` returns: the screen-space triangles of an axes."""

    #: (P, 3) window pixels (x right, y down from the top of the figure)
    #: and a depth in [0, 1] growing away from the viewer.
    points: np.ndarray
    #: (T, 3) indices into ``points``; triangle ``k`` is id ``k`` of
    #: ``zbuffer``.
    faces: np.ndarray
    #: (T,) the polygon each triangle comes from, numbered across the
    #: collections in ``ax.collections`` order.
    polygon: np.ndarray
    #: (polygons,) the index in ``collections`` of each polygon's
    #: collection.
    collection: np.ndarray
    #: (polygons, 4) the RGBA face colour matplotlib computed for each
    #: polygon (shading, colour map, alpha).
    facecolors: np.ndarray
    #: The Poly3DCollections gathered.
    collections: list
    #: The window size in pixels, (width, height).
    size: tuple


def project(ax, width=None, height=None):
    """The screen-space triangles of every Poly3DCollection of ``ax`` as
    ``resolve`` sees them (a ``Projected``), by default at the figure's
    size in pixels. The axes must have been drawn once
    (``fig.canvas.draw()``) so that its projection is current.
    """
    width, height = _size(ax, width, height)
    sources = _sources(ax)
    g = _Gathered(ax, sources, width, height)
    return Projected(g.points, g.faces, g.tri_poly, g.collection, g.face_rgba,
                     sources, (width, height))


def zbuffer(ax, algo="zbuffer"):
    """Renders ``project(ax)`` at the figure's pixel size with the
    registered hider ``algo``: ``(ids, depth)`` as from ``hider.render``,
    the ids numbering the triangles of ``project``."""
    p = project(ax)
    return _hider.screen_render(p.points, p.faces, p.size[0], p.size[1], algo)


def _size(ax, width=None, height=None):
    """The figure's size in display pixels, rounded up."""
    fig = ax.figure
    w = width if width is not None else int(np.ceil(fig.bbox.width))
    h = height if height is not None else int(np.ceil(fig.bbox.height))
    return max(w, 1), max(h, 1)


def _sources(ax):
    """The visible Poly3DCollections of ``ax`` (those a ``Resolved`` draws
    included)."""
    return [c for c in ax.collections
            if isinstance(c, art3d.Poly3DCollection) and c.get_visible()]


def _skip_draw(renderer):
    """The draw of an artist a ``Resolved`` draws instead."""


def _far_key():
    """The depth key of a polygon collection a ``Resolved`` draws: it stays
    visible (so that ``ax.legend()`` shows it) but matplotlib need not sort
    its polygons; any constant keeps the sort of the others well defined."""
    return -np.inf


def _take(artist, project):
    """Takes an artist over: it stays visible (legends keep their handles)
    but its own draw does nothing, and for a polygon collection without a
    legend entry (``project`` false) matplotlib's sort of its polygons is
    skipped too."""
    artist._hider_source = True
    artist.draw = _skip_draw
    if not project:
        artist.do_3d_projection = _far_key


def _give_back(artist):
    """Undoes ``_take``."""
    for name in ("draw", "do_3d_projection", "_hider_source"):
        artist.__dict__.pop(name, None)
    artist.stale = True


def _labelled(artist):
    label = artist.get_label()
    return bool(label) and not str(label).startswith("_")


def _matplotlib_draw(artists, renderer):
    """Draws artists with matplotlib's own methods, ordered as ``Axes3D``
    orders collections (farthest first by their ``do_3d_projection``)."""
    keyed = []
    for a in artists:
        key = type(a).do_3d_projection(a) if hasattr(type(a), "do_3d_projection") else 0.0
        key = float(key) if key is not None and np.isfinite(key) else -np.inf
        keyed.append((key, a))
    keyed.sort(key=lambda ka: ka[0], reverse=True)
    for _, a in keyed:
        type(a).draw(a, renderer)


def _has_marker(line):
    return line.get_marker() not in (None, "", "None", " ", "none")


def _has_line(line):
    return line.get_linestyle() not in (None, "", "None", " ", "none") and line.get_linewidth() > 0


def _polylines(ax, parts):
    """3D polylines (each (k, 3)) projected to display x, y and view depth,
    split at non-finite points: ``(polylines, index of their part)``."""
    out, which = [], []
    for i, part in enumerate(parts):
        if len(part) < 2:
            continue
        p = _project(ax, part)
        d = ax.transData.transform(p[:, :2])
        q = np.column_stack([d, p[:, 2]])
        good = np.isfinite(q).all(axis=1)
        if good.all():
            out.append(q)
            which.append(i)
            continue
        edges = np.diff(np.r_[0, good.astype(np.int8), 0])
        for a, b in zip(np.nonzero(edges == 1)[0], np.nonzero(edges == -1)[0]):
            if b - a >= 2:
                out.append(q[a:b])
                which.append(i)
    return out, np.asarray(which, dtype=np.int64)


def _visible_runs(polylines, window_depth, far, height):
    """Cuts display-space polylines (each (k, 3): x, y, view depth) to their
    runs in front of the depth map ``far``: ``(runs, polyline of each)``,
    each run a (m, 2) array of display points, one path per visible run:
    its original corners inside, its ends where it leaves or meets a
    surface (within half a pixel). ``far=None`` keeps every polyline
    whole."""
    if far is None:
        return [p[:, :2] for p in polylines], np.arange(len(polylines))
    if not polylines:
        return [], np.zeros(0, np.int64)
    h, w = far.shape
    lengths = np.array([len(p) for p in polylines])
    pts = np.concatenate(polylines)
    line_of_pt = np.repeat(np.arange(len(polylines)), lengths)
    last = np.cumsum(lengths) - 1
    seg_ok = np.ones(len(pts), dtype=bool)
    seg_ok[last] = False
    a_idx = np.nonzero(seg_ok)[0]
    a, b = pts[a_idx], pts[a_idx + 1]
    seg_len = np.hypot(b[:, 0] - a[:, 0], b[:, 1] - a[:, 1])
    # Samples on [a, b): the corner itself first; the polyline's last
    # corner is added on its own.
    counts = np.maximum(1, np.ceil(seg_len * _LINE_SAMPLES_PER_PIXEL).astype(np.int64))
    seg_of = np.repeat(np.arange(len(a_idx)), counts)
    starts = np.cumsum(counts) - counts
    u = (np.arange(counts.sum()) - starts[seg_of]) / counts[seg_of]
    samples = a[seg_of] + (b[seg_of] - a[seg_of]) * u[:, None]
    line_of = line_of_pt[a_idx][seg_of]
    corner = u == 0
    # Append each polyline's last corner after its samples.
    order = np.argsort(np.r_[line_of, line_of_pt[last]], kind="stable")
    samples = np.concatenate([samples, pts[last]])[order]
    line_of = np.r_[line_of, line_of_pt[last]][order]
    corner = np.r_[corner, np.ones(len(last), dtype=bool)][order]
    x, y = samples[:, 0], height - samples[:, 1]
    inside = (x >= 0) & (x < w) & (y >= 0) & (y < h)
    xi = np.clip(np.floor(x).astype(np.int64), 0, w - 1)
    yi = np.clip(np.floor(y).astype(np.int64), 0, h - 1)
    visible = ~inside | (window_depth(samples[:, 2]) <= far[yi, xi] + _LINE_DEPTH_TOLERANCE)
    same = np.r_[False, line_of[1:] == line_of[:-1]]
    run_start = visible & ~(same & np.r_[False, visible[:-1]])
    run_end = visible & ~(np.r_[same[1:], False] & np.r_[visible[1:], False])
    run_id = np.cumsum(run_start) - 1
    keep = visible & (corner | run_start | run_end)
    idx = np.nonzero(keep)[0]
    if len(idx) == 0:
        return [], np.zeros(0, np.int64)
    rid = run_id[idx]
    bounds = np.nonzero(np.r_[True, rid[1:] != rid[:-1], True])[0]
    runs, which = [], []
    for s, e in zip(bounds[:-1].tolist(), bounds[1:].tolist()):
        if e - s >= 2:
            runs.append(samples[idx[s:e], :2])
            which.append(line_of[idx[s]])
    return runs, np.asarray(which, dtype=np.int64)


def _far_depth(depth):
    """The farthest depth around each pixel: a line on a silhouette, or on
    its own polygon's edge, is not hidden by the neighbour it borders."""
    h, w = depth.shape
    pad = np.pad(depth, 1, mode="edge")
    return np.max([pad[dy:dy + h, dx:dx + w] for dy in range(3) for dx in range(3)], axis=0)


def _points_visible(xyz_display, window_depth, far, height):
    """Whether each display point (x, y, view depth) is in front of the
    depth map (points outside the window count as visible)."""
    if far is None or len(xyz_display) == 0:
        return np.isfinite(xyz_display).all(axis=1)
    h, w = far.shape
    x, y = xyz_display[:, 0], height - xyz_display[:, 1]
    finite = np.isfinite(xyz_display).all(axis=1)
    inside = finite & (x >= 0) & (x < w) & (y >= 0) & (y < h)
    xi = np.clip(np.floor(np.where(finite, x, 0)).astype(np.int64), 0, w - 1)
    yi = np.clip(np.floor(np.where(finite, y, 0)).astype(np.int64), 0, h - 1)
    wd = window_depth(np.where(finite, xyz_display[:, 2], 0.0))
    return finite & (~inside | (wd <= far[yi, xi] + _LINE_DEPTH_TOLERANCE))


def _outline_polylines(g):
    """The closed outlines of the polygons whose edges have their own
    colour (not their face's), as display polylines with colour and
    width."""
    polys, rgba, widths = [], [], []
    poly = 0
    for p, bad in g.outlines:
        n = p.shape[0]
        edge = g.edge_rgba[poly:poly + n]
        face = g.face_rgba[poly:poly + n]
        lw = g.linewidths[poly:poly + n]
        own = (np.abs(edge - face).max(axis=1) > 1e-6) & (edge[:, 3] > 0) & (lw > 0)
        for i in np.nonzero(own)[0]:
            q = p[i][~bad[i]]
            if len(q) < 2:
                continue
            polys.append(np.concatenate([q, q[:1]]))
            rgba.append(edge[i])
            widths.append(lw[i])
        poly += n
    return polys, np.array(rgba).reshape(-1, 4), np.array(widths, dtype=float)


def _path(verts, codes, like):
    """A Path of these vertices and codes with the simplification settings
    of ``like``, made without the checks of the constructor (tens of
    thousands are made per draw)."""
    fast = getattr(mpath.Path, "_fast_from_codes_and_verts", None)
    if fast is None:
        return mpath.Path(verts, codes)
    return fast(verts, codes, internals_from=like)


def _whole_paths(paths, runs, run_poly, g, like):
    """Fills ``paths[r]`` for each run ``r`` of ``runs`` with the outline of
    its polygon ``run_poly[r]``: its corners in display pixels and the
    first again to close it, one code array shared by the polygons of a
    collection (they have the same corner count)."""
    if len(runs) == 0:
        return
    polys = run_poly[runs]
    base = 0
    for p, _ in g.outlines:
        n, v = p.shape[:2]
        mine = (polys >= base) & (polys < base + n)
        if mine.any():
            local = polys[mine] - base
            verts = np.concatenate([p[local, :, :2], p[local, :1, :2]], axis=1)
            codes = np.full(v + 1, mpath.Path.LINETO, dtype=mpath.Path.code_type)
            codes[0], codes[-1] = mpath.Path.MOVETO, mpath.Path.CLOSEPOLY
            for r, vv in zip(runs[mine].tolist(), verts):
                paths[r] = _path(vv, codes, like)
        base += n


class Resolved(mcoll.PolyCollection):
    """The artist ``resolve`` adds: at each draw it gathers the source
    collections, orders and splits their polygons with hider's painter and
    paints the pieces, then draws the source lines cut where surfaces hide
    them and the source markers whose centre no surface hides.

    Attributes: ``sources`` (the Poly3DCollections), ``line_sources``
    (Line3Ds and Line3DCollections), ``marker_sources`` (scatters), as
    lists; ``pieces``, the painter's piece count at the last draw;
    ``fallback``, the reason the polygons were last left to matplotlib's
    own sort (``None`` when they were resolved)."""

    def __init__(self, ax, sources, lines, markers, max_splits=None, timeout=None):
        super().__init__([], transform=IdentityTransform())
        self._ax = ax
        self.sources = list(sources)
        self.line_sources = list(lines)
        self.marker_sources = list(markers)
        self.max_splits = max_splits
        self.timeout = timeout
        self.pieces = 0
        self.fallback = None
        self._painter_failed = None
        self._warned = set()
        self._overlay = []
        self._stroke = np.zeros(0, bool)
        self._fallback_polygons = []
        self._fallback_overlay = []
        flags = [_antialiased(c) for c in self.sources]
        self.set_antialiased(bool(np.all(np.concatenate(flags))) if flags else True)

    def _warn(self, key, message):
        """Warns once per artist and cause."""
        if key not in self._warned:
            self._warned.add(key)
            warnings.warn(f"hider.mpl.resolve: {message}", ResolveWarning, stacklevel=3)

    def do_3d_projection(self):
        """Orders and splits the polygons for the current projection and cuts
        the lines and markers; the return value places this artist among
        unresolved ones as matplotlib's own collections do (by their
        nearest point). Nothing here raises: what fails is left to
        matplotlib's own drawing, with a ``ResolveWarning``."""
        try:
            return self._prepare()
        except Exception as e:  # noqa: BLE001 - savefig must not fail because of hider
            self._warn(("error", type(e).__name__),
                       f"{type(e).__name__}: {e}; drawn by matplotlib as before")
            self._paths = []
            self._overlay = []
            self._fallback_polygons = [c for c in self.sources if c.get_visible()]
            self._fallback_overlay = [a for a in self.line_sources + self.marker_sources
                                      if a.get_visible()]
            self.fallback = f"{type(e).__name__}: {e}"
            return -np.inf

    def _prepare(self):
        ax = self._ax
        self._fallback_overlay = []
        width, height = _size(ax)
        polys = [c for c in self.sources if c.get_visible()]
        g = _Gathered(ax, polys, width, height)
        self._fallback_polygons = []
        self.fallback = None
        resolved_faces = False
        if len(g.faces) and self._painter_failed is None:
            budget = self.max_splits
            if budget is None:
                budget = _SPLITS_BASE + _SPLITS_PER_TRIANGLE * len(g.faces)
            try:
                # Faces drawn see-through hide nothing: the painter must
                # keep what lies behind them.
                translucent = g.face_rgba[g.tri_poly, 3] < _OPAQUE
                prims, offsets, xy, uncut = _interruptible(
                    _hider.screen_pieces, g.points, g.faces, width, height, int(budget),
                    translucent, timeout=self.timeout)
            except (ValueError, MemoryError) as e:
                self._painter_failed = str(e)
            except TimeoutError as e:
                self._painter_failed = f"{e}; resolve(ax, timeout=...) allows more time"
            else:
                resolved_faces = True
                self.pieces = len(prims)
                xy = xy.copy()
                xy[:, 1] = height - xy[:, 1]
                poly = g.tri_poly[prims]
                poly = poly[self._set_pieces(xy, offsets, poly, uncut, g)]
                self._colour_pieces(poly, g)
        if not resolved_faces:
            self.pieces = 0
            self._paths = []
            self._stroke = np.zeros(0, bool)
            self.stale = True
            if len(g.faces):
                self.fallback = self._painter_failed
                self._fallback_polygons = polys
                self._warn(("painter",),
                           f"{self._painter_failed}; these {len(g.faces)} triangles are "
                           "drawn in matplotlib's own order (resolve(ax, max_splits=...) "
                           "allows more splits; lines and markers are still cut)")
        self._prepare_overlay(g)
        return g.zlo if len(g.faces) else -np.inf

    def _colour_pieces(self, poly, g):
        """Each path in its polygon's face colour. A path is filled and,
        where its polygon's edges take the face's colour (matplotlib's
        default, which hides the seams between polygons), stroked one device
        pixel wide in that colour (set in ``draw``): the stroke covers the
        antialiasing seams between neighbours and reaches half a pixel past
        the piece, at any dpi. Edges of their own colour are drawn as lines
        (cut where hidden), never around each piece; a polygon collection
        with ``linewidth=0`` is not stroked; translucent pieces are not
        stroked (the stroke would darken every edge where it overlaps its
        own fill and its neighbours')."""
        face = g.face_rgba[poly]
        self.set_facecolor(face)
        self.set_edgecolor(face)
        self._stroke = (face[:, 3] >= _OPAQUE) & (g.linewidths[poly] > 0)

    def _set_pieces(self, xy, offsets, poly, uncut, g):
        """The pieces as this collection's paths, in paint order; returns
        the first piece of each path. Consecutive pieces of one polygon
        become one path, filled in one pass, so no seam shows between them
        (the two triangles of a quad, most often), and there are fewer
        paths to make: tens of thousands of path objects dominate the draw
        otherwise. When the run is the whole polygon (all its triangles,
        none cut) and the polygon is convex on screen, the path is the
        polygon's own outline, as matplotlib would draw it; otherwise it
        has one closed part per piece."""
        k = len(offsets) - 1
        if k == 0:
            self._paths = []
            self.stale = True
            return np.zeros(0, np.int64)
        counts = np.diff(offsets)
        first = np.nonzero(np.r_[True, poly[1:] != poly[:-1]])[0]
        run_length = np.diff(np.r_[first, k])
        run_poly = poly[first]
        cut_in_run = np.add.reduceat((~uncut).astype(np.int64), first) > 0
        whole = (~cut_in_run & (run_length == g.tri_count[run_poly])
                 & g.convex[run_poly])
        paths = [None] * len(first)
        like = mpath.Path(np.zeros((1, 2)))
        _whole_paths(paths, np.nonzero(whole)[0], run_poly, g, like)
        # The other runs: each piece's corners, then its first corner
        # again to close it.
        total = int(offsets[-1])
        piece_of = np.repeat(np.arange(k), counts)
        verts = np.empty((total + k, 2))
        codes = np.full(total + k, mpath.Path.LINETO, dtype=mpath.Path.code_type)
        verts[np.arange(total) + piece_of] = xy
        close = offsets[1:] + np.arange(k)
        verts[close] = xy[offsets[:-1]]
        codes[offsets[:-1] + np.arange(k)] = mpath.Path.MOVETO
        codes[close] = mpath.Path.CLOSEPOLY
        starts = offsets[first] + first
        ends = np.r_[starts[1:], total + k]
        for r, a, b in zip(np.nonzero(~whole)[0].tolist(), starts[~whole].tolist(),
                           ends[~whole].tolist()):
            paths[r] = _path(verts[a:b], codes[a:b], like)
        self._paths = paths
        self.stale = True
        return first

    def _prepare_overlay(self, g):
        """The lines cut where surfaces hide them, and the markers whose
        centre no surface hides, as 2D artists in display pixels."""
        polys, rgba, widths = _outline_polylines(g)
        lines = [a for a in self.line_sources if a.get_visible()]
        markers = [a for a in self.marker_sources if a.get_visible()]
        self._overlay = []
        if not (polys or lines or markers):
            return
        opaque = g.faces[g.face_rgba[g.tri_poly, 3] >= _OPAQUE] if len(g.faces) else g.faces
        far = None
        if len(opaque):
            _, depth = _hider.screen_render(g.points, opaque, g.width, g.height, "zbuffer")
            far = _far_depth(depth)
        overlay = []
        for src in lines:
            try:
                overlay.extend(self._cut_line(src, g, far))
            except _Unsupported as e:
                self._warn(("unsupported", id(src)), f"{e}; drawn by matplotlib as before")
                self._fallback_overlay.append(src)
        if polys:
            runs, which = _visible_runs(polys, g.window_depth, far, g.height)
            if runs:
                overlay.append(mcoll.LineCollection(
                    runs, colors=rgba[which], linewidths=widths[which],
                    transform=IdentityTransform()))
        for src in markers:
            try:
                overlay.extend(self._cut_scatter(src, g, far))
            except _Unsupported as e:
                self._warn(("unsupported", id(src)), f"{e}; drawn by matplotlib as before")
                self._fallback_overlay.append(src)
        self._overlay = overlay

    def _cut_line(self, src, g, far):
        """A Line3D or Line3DCollection as 2D artists: its visible runs, one
        path each, in its style; a Line3D's markers where their centre is
        visible."""
        ax = self._ax
        out = []
        if isinstance(src, art3d.Line3DCollection):
            parts = _segments3d(src)
            colours = _rgba(src.get_color(), len(parts))
            widths = np.resize(np.atleast_1d(src.get_linewidth()), len(parts))
            styles = src.get_linestyle()
            polylines, part_of = _polylines(ax, parts)
            runs, which = _visible_runs(polylines, g.window_depth, far, g.height)
            if runs:
                src_of = part_of[which]
                lc = mcoll.LineCollection(
                    runs, colors=colours[src_of], linewidths=widths[src_of],
                    linestyles=styles[0] if len(styles) else "solid",
                    antialiaseds=_antialiased(src)[:1], transform=IdentityTransform())
                out.append(lc)
            return out
        xyz = np.column_stack([np.asarray(a, dtype=float).ravel() for a in src.get_data_3d()])
        if _has_line(src):
            polylines, _ = _polylines(ax, [xyz])
            runs, _ = _visible_runs(polylines, g.window_depth, far, g.height)
            if runs:
                lc = mcoll.LineCollection(
                    runs, colors=[mcolors.to_rgba(src.get_color(), src.get_alpha())],
                    linewidths=[src.get_linewidth()], linestyles=src.get_linestyle(),
                    capstyle=src.get_solid_capstyle(), joinstyle=src.get_solid_joinstyle(),
                    antialiaseds=[src.get_antialiased()], transform=IdentityTransform())
                out.append(lc)
        if _has_marker(src) and len(xyz):
            p = _project(ax, xyz)
            d = np.column_stack([ax.transData.transform(p[:, :2]), p[:, 2]])
            keep = _markevery(src.get_markevery(), len(d))
            vis = keep & _points_visible(d, g.window_depth, far, g.height)
            marks = mlines.Line2D(d[vis, 0], d[vis, 1])
            marks.update_from(src)
            marks.set_linestyle("None")
            marks.set_markevery(None)
            marks.set_transform(IdentityTransform())
            marks.set_label("_nolegend_")
            out.append(marks)
        return out

    def _cut_scatter(self, src, g, far):
        """A scatter's markers whose centre no surface hides, farthest
        first, in its colours (depth shading included), sizes and marker."""
        ax = self._ax
        xyz, sizes, widths = _scatter3d(src)
        n = len(xyz)
        if n == 0:
            return []
        p = _project(ax, xyz)
        d = np.column_stack([ax.transData.transform(p[:, :2]), p[:, 2]])
        face, edge = _scatter_colours(src, n, p)
        vis = _points_visible(d, g.window_depth, far, g.height)
        order = np.nonzero(vis)[0]
        order = order[np.argsort(-d[order, 2], kind="stable")]
        sizes = np.resize(sizes, n) if sizes.size else np.full(n, 20.0)
        widths = np.resize(widths, n) if widths.size else np.ones(n)
        pc = mcoll.PathCollection(
            src.get_paths(), sizes=sizes[order], offsets=d[order, :2],
            offset_transform=IdentityTransform(), transform=IdentityTransform(),
            facecolors=face[order], edgecolors=edge[order], linewidths=widths[order],
            linestyles=src.get_linestyle()[0] if len(src.get_linestyle()) else "solid")
        return [pc]

    def draw(self, renderer):
        """Paints the pieces in order (or, where the painter gave up, the
        polygon collections as matplotlib would), then the visible parts of
        lines and the visible markers."""
        if self._fallback_polygons:
            _matplotlib_draw(self._fallback_polygons, renderer)
        else:
            px = renderer.points_to_pixels(1.0)
            hairline = 1.0 / px if px > 0 else 1.0
            if len(self._stroke) and self._stroke.all():
                self.set_linewidth(hairline)
            elif len(self._stroke):
                self.set_linewidth(np.where(self._stroke, hairline, 0.0))
            super().draw(renderer)
        if self._fallback_overlay:
            _matplotlib_draw([a for a in self._fallback_overlay
                              if not isinstance(a, mlines.Line2D)], renderer)
            for a in self._fallback_overlay:
                if isinstance(a, mlines.Line2D):
                    type(a).draw(a, renderer)
        for a in self._overlay:
            a.set_figure(self.figure)
            a.set_clip_box(self.get_clip_box())
            clip = self.get_clip_path()
            if clip is not None:
                a.set_clip_path(clip)
            a.draw(renderer)


def _markevery(every, n):
    """Which of ``n`` points a line's ``markevery`` marks: None, an int, a
    (start, step) pair, a slice or a list of indices or booleans; the
    distance-based float forms mark every point."""
    keep = np.zeros(n, dtype=bool)
    if every is None:
        keep[:] = True
    elif isinstance(every, (int, np.integer)) and not isinstance(every, bool):
        keep[::max(int(every), 1)] = True
    elif (isinstance(every, tuple) and len(every) == 2
          and all(isinstance(v, (int, np.integer)) for v in every)):
        keep[int(every[0])::max(int(every[1]), 1)] = True
    elif isinstance(every, slice):
        keep[every] = True
    else:
        a = np.asarray(every)
        if a.dtype == bool and a.shape == (n,):
            keep[:] = a
        elif a.dtype.kind in "iu":
            keep[a[(a >= -n) & (a < n)]] = True
        else:
            keep[:] = True
    return keep


def resolve(ax, *, max_splits=None, timeout=None):
    """Draw the polygons, lines and markers of a 3D axes with correct
    occlusion.

    Takes over every ``Poly3DCollection`` of ``ax``, every 3D line
    (``plot``, with or without markers; ``plot_wireframe``) and every 3D
    scatter, and adds one ``Resolved`` artist that draws them instead: at
    each draw (``savefig``, ``plt.show``, an interactive rotation) their
    polygons are projected with the axes' projection, ordered and split
    jointly by hider's painter and painted in that order, in matplotlib's
    colours; lines are cut where surfaces hide them (one path per visible
    run) and each marker is drawn when no surface is in front of its
    centre. The artists taken over stay visible to ``ax.legend()``. Call it
    after plotting; calling it again takes in what was plotted since (and
    retries a painter that gave up). Returns the ``Resolved`` artist.
    ``unresolve(ax)`` undoes it.

    ``max_splits`` bounds the painter's polygon splits per draw (default
    4096 plus 2 per triangle; surfaces need far fewer). A scene that needs
    more is drawn in matplotlib's own order, with one ``ResolveWarning``,
    instead of taking many seconds; lines and markers are still cut.
    ``timeout`` (seconds, default none) bounds the painter's time per draw
    the same way: past it the painter stops and the polygons are drawn in
    matplotlib's own order, with one ``ResolveWarning``; ``savefig`` never
    fails because of hider. Ctrl-C stops the painter
    (``KeyboardInterrupt``). Artists this matplotlib does not let hider read are left to matplotlib,
    with a ``ResolveWarning``.
    """
    if max_splits is not None and (isinstance(max_splits, bool) or int(max_splits) < 0):
        raise ValueError(f"max_splits must be a count of splits, got {max_splits!r}")
    timeout = _as_timeout(timeout)
    for r in [c for c in ax.collections if isinstance(c, Resolved)]:
        _release(r)
        r.remove()
    sources, lines, markers, skipped = [], [], [], []
    for c in ax.collections:
        if isinstance(c, Resolved) or not c.get_visible():
            continue
        if isinstance(c, art3d.Poly3DCollection):
            try:
                _polygons3d(c)
            except _Unsupported as e:
                skipped.append(str(e))
                continue
            sources.append(c)
        elif isinstance(c, art3d.Line3DCollection):
            lines.append(c)
        elif isinstance(c, art3d.Path3DCollection):
            markers.append(c)
    for line in ax.lines:
        if isinstance(line, art3d.Line3D) and line.get_visible():
            lines.append(line)
    resolved = Resolved(ax, sources, lines, markers,
                        None if max_splits is None else int(max_splits), timeout)
    for s in skipped:
        resolved._warn(("unsupported", s), f"{s}; drawn by matplotlib as before")
    for artist in sources:
        _take(artist, project=_labelled(artist))
    for artist in lines + markers:
        _take(artist, project=True)
    ax.add_collection(resolved, autolim=False)
    return resolved


def _release(resolved):
    for artist in resolved.sources + resolved.line_sources + resolved.marker_sources:
        _give_back(artist)


def unresolve(ax):
    """Removes what ``resolve`` added and gives the artists back to
    matplotlib."""
    for r in [c for c in ax.collections if isinstance(c, Resolved)]:
        _release(r)
        r.remove()
