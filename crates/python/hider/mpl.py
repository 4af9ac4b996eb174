"""Correct occlusion for matplotlib's 3D axes.

mplot3d sorts whole polygons by one depth each (their mean, or min or max
``zsort``) and whole collections by another, then paints them in that
order. Where two surfaces intersect, or a long polygon overlaps a short
one, no order of whole polygons is right, and one surface is drawn
entirely over the other.

``resolve(ax)`` replaces that sort for every ``Poly3DCollection`` of an
``Axes3D`` (``plot_surface``, ``plot_trisurf``, ``bar3d``, ``voxels``,
``add_collection3d``): at each draw it projects all their polygons with the
axes' own projection (``ax.get_proj()``), keeps matplotlib's colours,
and orders and splits them jointly with the painter's algorithm of
Newell, Newell & Sancha (splitting a polygon by another's plane where no
order exists). The pieces are painted in that order, so ``savefig`` to
PNG, PDF or SVG shows each surface exactly where it is the nearest, and
rotating the view re-resolves. Lines (``plot``, ``plot_wireframe``) and the
coloured edges of polygons are cut where they pass behind a surface,
against a depth buffer of the same projection.
"""

from typing import NamedTuple

import numpy as np
from matplotlib import collections as mcoll
from matplotlib import colors as mcolors
from matplotlib import path as mpath
from matplotlib.transforms import IdentityTransform
from mpl_toolkits.mplot3d import art3d, proj3d

from . import _hider

__all__ = ["resolve", "unresolve", "Resolved", "Projected", "project", "zbuffer"]

# Window depth of the orthographic screen camera for depth t in [0, 1]:
# the eye is one unit before t = 0, the near plane at 0.5 and the far at
# 2.5 (the constants of the extension's screen-space scenes).
_NEAR, _EYE_TO_FRONT, _FAR = 0.5, 1.0, 2.5

# A line sample is hidden when a surface is nearer than it by more than
# this much window depth (of a scene spanning 0.5): edges lie on their own
# polygons, whose f32 depth differs from the line's in the last bits.
_LINE_DEPTH_TOLERANCE = 2e-4

# Alpha from which a face counts as opaque (hides lines, gets a stroke).
_OPAQUE = 0.999

# Samples per pixel of line length for the visibility test.
_LINE_SAMPLES_PER_PIXEL = 2.0


def _project(ax, xyz):
    """Points (..., 3) in data coordinates to (..., 3) projected points:
    x, y in the 2D axes' data coordinates and matplotlib's view depth."""
    if hasattr(proj3d, "_scale_proj_transform_vectors"):
        return proj3d._scale_proj_transform_vectors(xyz, ax)
    return proj3d._proj_transform_vectors(xyz, ax.M)


def _rgba(colors, count):
    """Colours as an (count, 4) array, one per item (matplotlib stores one
    colour for all items as a single row)."""
    c = mcolors.to_rgba_array(colors) if len(colors) else np.zeros((0, 4))
    if len(c) == count:
        return c
    if len(c) == 0:
        return np.zeros((count, 4))
    return np.repeat(c[:1], count, axis=0)


def _polygon_source(col):
    """The polygons of a Poly3DCollection with their colours in the user's
    order, colour maps applied as its do_3d_projection applies them (that
    method also sorts and sets its own 2D polygons, which is not needed
    here)."""
    if col._A is not None:
        col.update_scalarmappable()
        if col._face_is_mapped:
            col._facecolor3d = col._facecolors
        if col._edge_is_mapped:
            col._edgecolor3d = col._edgecolors
    faces = np.asarray(col._faces, dtype=float)
    n, v = faces.shape[:2] if faces.ndim == 3 else (0, 0)
    invalid = np.broadcast_to(np.asarray(col._invalid_vertices, dtype=bool), (n, v)) \
        if n else np.zeros((0, 0), bool)
    face = _rgba(col._facecolor3d, n)
    edge = col._edgecolor3d
    edge = face.copy() if len(edge) == 0 else _rgba(edge, n)
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
    """The polygon collections of ``ax`` that a resolver draws: every
    Poly3DCollection that is visible or that a resolver hid."""
    return [c for c in ax.collections
            if isinstance(c, art3d.Poly3DCollection) and not isinstance(c, Resolved)
            and (c.get_visible() or getattr(c, "_hider_hidden", False))]


def _line_sources(ax):
    """The 3D lines of ``ax`` (``plot_wireframe``'s Line3DCollections and
    ``plot``'s markerless Line3Ds) that a resolver clips."""
    out = []
    for c in ax.collections:
        if isinstance(c, art3d.Line3DCollection) and (
                c.get_visible() or getattr(c, "_hider_hidden", False)):
            out.append(c)
    for line in ax.lines:
        plain = line.get_marker() in (None, "", "None", " ", "none")
        if isinstance(line, art3d.Line3D) and plain and (
                line.get_visible() or getattr(line, "_hider_hidden", False)):
            out.append(line)
    return out


def _segments(ax, lines):
    """The 3D segments of the line sources, projected: an (S, 2, 3) array
    of display x, y and view depth, with colours and widths per segment."""
    segs, rgba, widths = [], [], []
    for src in lines:
        if isinstance(src, art3d.Line3DCollection):
            parts = [np.asarray(s, dtype=float) for s in src._segments3d]
            colors = src.get_color()
            lws = np.atleast_1d(src.get_linewidth())
        else:
            parts = [np.column_stack([np.asarray(a, dtype=float).ravel()
                                      for a in src.get_data_3d()])]
            colors = [src.get_color()]
            lws = np.atleast_1d(src.get_linewidth())
        colors = _rgba(colors, len(parts))
        lws = np.resize(lws, len(parts))
        for k, part in enumerate(parts):
            if len(part) < 2:
                continue
            p = _project(ax, part)
            d = ax.transData.transform(p[:, :2])
            q = np.column_stack([d, p[:, 2]])
            s = np.stack([q[:-1], q[1:]], axis=1)
            s = s[np.isfinite(s).all(axis=(1, 2))]
            segs.append(s)
            rgba.append(np.repeat(colors[k:k + 1], len(s), axis=0))
            widths.append(np.full(len(s), lws[k]))
    if not segs:
        return np.zeros((0, 2, 3)), np.zeros((0, 4)), np.zeros(0)
    return np.concatenate(segs), np.concatenate(rgba), np.concatenate(widths)


def _visible_parts(segs, window_depth, depth, height):
    """Cuts display-space segments (S, 2, 3) to the parts in front of the
    depth buffer: (display segments, index of their source segment)."""
    if len(segs) == 0:
        return np.zeros((0, 2, 2)), np.zeros(0, np.int64)
    h, w = depth.shape
    # The farthest depth around each pixel: a line on a silhouette, or on
    # its own polygon's edge, is not hidden by the neighbour it borders.
    pad = np.pad(depth, 1, mode="edge")
    far = np.max([pad[dy:dy + h, dx:dx + w] for dy in range(3) for dx in range(3)], axis=0)
    a, b = segs[:, 0, :], segs[:, 1, :]
    length = np.hypot(b[:, 0] - a[:, 0], b[:, 1] - a[:, 1])
    counts = np.maximum(2, np.ceil(length * _LINE_SAMPLES_PER_PIXEL).astype(np.int64) + 1)
    seg_of = np.repeat(np.arange(len(segs)), counts)
    starts = np.cumsum(counts) - counts
    u = (np.arange(counts.sum()) - starts[seg_of]) / (counts[seg_of] - 1)
    pts = a[seg_of] + (b[seg_of] - a[seg_of]) * u[:, None]
    x = np.clip(np.floor(pts[:, 0]).astype(np.int64), 0, w - 1)
    y = np.clip(np.floor(height - pts[:, 1]).astype(np.int64), 0, h - 1)
    inside = (pts[:, 0] >= 0) & (pts[:, 0] < w) & (height - pts[:, 1] >= 0) & (height - pts[:, 1] < h)
    visible = ~inside | (window_depth(pts[:, 2]) <= far[y, x] + _LINE_DEPTH_TOLERANCE)
    # Runs of visible samples within one segment become sub-segments.
    same = np.r_[False, seg_of[1:] == seg_of[:-1]]
    run_start = visible & ~(same & np.r_[False, visible[:-1]])
    run_id = np.cumsum(run_start) - 1
    keep = np.nonzero(visible)[0]
    if len(keep) == 0:
        return np.zeros((0, 2, 2)), np.zeros(0, np.int64)
    rid = run_id[keep]
    first = np.r_[True, rid[1:] != rid[:-1]]
    last = np.r_[rid[1:] != rid[:-1], True]
    p0, p1 = keep[first], keep[last]
    nonzero = p1 > p0
    p0, p1 = p0[nonzero], p1[nonzero]
    out = np.stack([pts[p0, :2], pts[p1, :2]], axis=1)
    return out, seg_of[p0]


def _outline_segments(g):
    """The outlines of the polygons whose edges have their own colour
    (not their face's), as projected segments with colour and width."""
    segs, rgba, widths = [], [], []
    poly = 0
    for p, bad in g.outlines:
        n, v = p.shape[:2]
        edge = g.edge_rgba[poly:poly + n]
        face = g.face_rgba[poly:poly + n]
        lw = g.linewidths[poly:poly + n]
        own = (np.abs(edge - face).max(axis=1) > 1e-6) & (edge[:, 3] > 0) & (lw > 0)
        for i in np.nonzero(own)[0]:
            q = p[i][~bad[i]]
            if len(q) < 2:
                continue
            s = np.stack([q, np.roll(q, -1, axis=0)], axis=1)
            segs.append(s)
            rgba.append(np.repeat(edge[i:i + 1], len(s), axis=0))
            widths.append(np.full(len(s), lw[i]))
        poly += n
    if not segs:
        return np.zeros((0, 2, 3)), np.zeros((0, 4)), np.zeros(0)
    return np.concatenate(segs), np.concatenate(rgba), np.concatenate(widths)


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
    """The artist ``resolve`` adds: at each draw it gathers the hidden
    source collections, orders and splits their polygons with hider's
    painter and paints the pieces, then draws the source lines cut where
    surfaces hide them."""

    def __init__(self, ax, sources, lines):
        super().__init__([], transform=IdentityTransform())
        self._ax = ax
        self.sources = list(sources)
        self.line_sources = list(lines)
        self._lines = mcoll.LineCollection([], transform=IdentityTransform())
        self.pieces = 0
        antialiased = [c.get_antialiased() for c in self.sources]
        self.set_antialiased(np.all(np.concatenate([np.atleast_1d(a) for a in antialiased]))
                             if antialiased else True)

    def do_3d_projection(self):
        """Orders and splits the polygons for the current projection; the
        return value places this artist among unresolved ones as
        matplotlib's own collections do (by their nearest point)."""
        ax = self._ax
        width, height = _size(ax)
        g = _Gathered(ax, self.sources, width, height)
        prims, offsets, xy, uncut = _hider.screen_pieces(g.points, g.faces, width, height)
        self.pieces = len(prims)
        xy = xy.copy()
        xy[:, 1] = height - xy[:, 1]
        poly = g.tri_poly[prims]
        poly = poly[self._set_pieces(xy, offsets, poly, uncut, g)]
        face = g.face_rgba[poly]
        edge = g.edge_rgba[poly]
        lw = g.linewidths[poly]
        # Pieces are stroked like their polygon when its edges take the
        # face's colour (matplotlib's default, which hides the seams); an
        # edge of its own colour would outline every piece, so those
        # pieces are stroked in their face colour and the true edges are
        # drawn as lines.
        own = np.abs(edge - face).max(axis=1) > 1e-6 if len(poly) else np.zeros(0, bool)
        edge[own] = face[own]
        # A translucent piece's stroke would darken every edge where it
        # overlaps its own fill and its neighbours' strokes.
        lw = np.where(face[:, 3] < _OPAQUE, 0.0, lw)
        self.set_facecolor(face)
        self.set_edgecolor(edge)
        # One width for all is the common case, and much cheaper for
        # matplotlib to set than one per piece.
        same = len(lw) == 0 or np.all(lw == lw[0])
        self.set_linewidth((lw[0] if len(lw) else 0.0) if same else lw)
        self._resolve_lines(g, len(prims) > 0)
        return g.zlo if len(g.faces) else np.nan

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

    def _resolve_lines(self, g, any_faces):
        """Cuts the source lines and the outlines of edge-coloured polygons
        against a depth buffer of the same screen-space triangles."""
        ax = self._ax
        ls, lc, lw = _segments(ax, self.line_sources)
        os_, oc, ow = _outline_segments(g)
        segs = np.concatenate([ls, os_]) if len(os_) else ls
        rgba = np.concatenate([lc, oc]) if len(os_) else lc
        widths = np.concatenate([lw, ow]) if len(os_) else lw
        if len(segs) == 0:
            self._lines.set_segments([])
            return
        # Only opaque surfaces hide lines: one seen through a translucent
        # surface stays, as matplotlib blends it.
        opaque = g.faces[g.face_rgba[g.tri_poly, 3] >= _OPAQUE]
        if any_faces and len(opaque):
            _, depth = _hider.screen_render(g.points, opaque, g.width, g.height, "zbuffer")
            parts, src = _visible_parts(segs, g.window_depth, depth, g.height)
        else:
            parts, src = segs[:, :, :2], np.arange(len(segs))
        self._lines.set_segments(list(parts))
        self._lines.set_color(rgba[src] if len(src) else "none")
        self._lines.set_linewidth(widths[src] if len(src) else 0.0)

    def draw(self, renderer):
        """Paints the pieces in order, then the visible parts of lines."""
        super().draw(renderer)
        self._lines.set_figure(self.figure)
        self._lines.draw(renderer)


def resolve(ax):
    """Draw the polygons and lines of a 3D axes with correct occlusion.

    Hides every ``Poly3DCollection`` (and every markerless 3D line) of
    ``ax`` and adds one ``Resolved`` artist that draws them instead: at
    each draw (``savefig``, ``plt.show``, an interactive rotation) their
    polygons are projected with ``ax.get_proj()``, ordered and split
    jointly by hider's painter and painted in that order, in matplotlib's
    colours, and the lines are cut where surfaces hide them. Call it after
    plotting; calling it again takes in what was plotted since. Returns the
    ``Resolved`` artist. ``unresolve(ax)`` undoes it.
    """
    old = [c for c in ax.collections if isinstance(c, Resolved)]
    for r in old:
        r.remove()
    sources = _sources(ax)
    lines = _line_sources(ax)
    for artist in sources + lines:
        artist._hider_hidden = True
        artist.set_visible(False)
    resolved = Resolved(ax, sources, lines)
    ax.add_collection(resolved, autolim=False)
    return resolved


def unresolve(ax):
    """Removes what ``resolve`` added and shows the original artists."""
    for r in [c for c in ax.collections if isinstance(c, Resolved)]:
        for artist in r.sources + r.line_sources:
            artist._hider_hidden = False
            artist.set_visible(True)
        r.remove()
