"""Hidden-surface removal for numpy and matplotlib.

``hider`` renders triangle meshes given as numpy arrays into a face-id
buffer and a depth buffer on the CPU, with any of the classic
hidden-surface algorithms of the hider workspace (z-buffer, A-buffer,
painter's algorithm, Warnock, scanline, an exact ray-cast oracle): no
OpenGL context, no display, bit for bit the ``hider`` command line's
``--ids-out`` and ``--depth-out`` dumps.

``hider.mpl`` fixes occlusion in matplotlib's 3D axes: it orders and
splits every polygon of an ``Axes3D`` jointly, so intersecting surfaces
and lines behind surfaces are drawn as they are seen.

Example::

    import numpy as np
    import hider

    vertices = np.array([[-1, -1, 0], [1, -1, 0], [0, 1, 0]], dtype=float)
    faces = np.array([[0, 1, 2]])
    ids, depth = hider.render(vertices, faces, width=64, height=64)
    assert ids[32, 32] == 0 and ids[0, 0] == -1
"""

import os
from typing import NamedTuple

import numpy as np

from . import _hider
from ._worker import _interruptible

__all__ = ["render", "visible_faces", "plan", "Plan", "algorithms", "svg", "AUTO",
           "DEFAULT_ALGO", "KINDS", "OUTPUTS", "CONVENTIONS"]

#: The package's version (the Rust workspace's, as built into the
#: extension).
__version__ = _hider.__version__


def __dir__():
    """The public names only (``np``, ``NamedTuple`` and the private
    helpers stay out of ``dir(hider)``)."""
    return sorted([*__all__, "__version__", "mpl"])

#: The hider ``render`` uses unless told: the binned, tiled z-buffer, the
#: fastest exact one.
DEFAULT_ALGO = "zbuffer-tiled"


#: The ``algo`` that lets hider's planner choose, as the command line's
#: ``--algo auto``: the cheapest registered hider that is exact for the
#: scene and view (``plan`` says which, and why).
AUTO = "auto"


#: The kinds of hider the registry knows, as ``algorithms(kind=...)``
#: takes them: ``"exact"`` (decides at pixel centres and equals the exact
#: reference on every pixel that is not a depth tie), ``"approximate"``
#: (decides at pixel centres but is wrong by design in documented cases:
#: a plain sort, coarse or linearly interpolated depth), ``"multisample"``
#: (resolves several samples per pixel: anti-aliasing, transparency) and
#: ``"reference"`` (the exact ray-cast oracle, slow).
KINDS = ("exact", "approximate", "multisample", "reference")


#: The names ``render(..., outputs=...)`` takes, in the order ``render``
#: computes them: ``"ids"`` (int32 face id, -1 for none), ``"depth"``
#: (float32 window depth, 1.0 for none), ``"distance"`` (float32 distance
#: from the eye along the pixel-centre ray, open3d's ``t_hit`` for unit
#: rays, inf for none), ``"z"`` (float32 view depth along the view axis,
#: positive in front, inf for none), ``"barycentrics"`` (float32
#: ``(..., 2)``: open3d's ``primitive_uvs``), ``"normals"`` (float32
#: ``(..., 3)`` unit geometric normals, open3d's ``primitive_normals``) and
#: ``"vertex_normals"`` (float32 ``(..., 3)``, the ``normals=`` keyword's
#: vertex normals interpolated).
OUTPUTS = ("ids", "depth", "distance", "z", "barycentrics", "normals", "vertex_normals")

#: The axis conventions a ``pose`` can be given in: ``"opengl"`` (the
#: camera looks down its -z axis with +y up: OpenGL, pyrender, Blender)
#: and ``"opencv"`` (it looks down +z with +y down: OpenCV, open3d,
#: COLMAP).
CONVENTIONS = ("opengl", "opencv")


def algorithms(kind=None):
    """The names of the registered hiders, for ``algo=`` (besides
    ``"auto"``), in the registry's order: all of them, or those of one
    ``kind`` of ``KINDS``.

    Example::

        >>> import hider
        >>> hider.algorithms(kind="approximate")
        ['zbuffer-fixed24', 'zbuffer-fixed16', 'painter-naive', 'zbuffer-linear-z']
    """
    if kind is None:
        return list(_hider.algorithms())
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {', '.join(KINDS)}, got {kind!r}")
    return [name for name, k, _ in _hider.algorithm_kinds() if k == kind]


class Plan(NamedTuple):
    """The planner's choice, as ``plan`` returns it."""

    #: The registry name of the chosen hider (one of ``algorithms()``):
    #: what ``algo="auto"`` renders with.
    algo: str
    #: Why, in one sentence.
    reason: str
    #: The command line's line for ``--algo auto``: what was asked for,
    #: the choice, why, and the stages that would run.
    summary: str


def _as_vertices(vertices, name="vertices"):
    """Any real (N, 3) array-like as a C-contiguous array the extension
    reads in place: float64 or float32 kept (no copy when already
    contiguous), any other real dtype converted to float64."""
    a = np.asarray(vertices)
    if a.dtype.kind not in "biuf":
        raise ValueError(f"{name} must be a real numeric array, got dtype {a.dtype}")
    if a.ndim != 2 or a.shape[1] != 3:
        raise ValueError(f"{name} must have shape (N, 3), got {a.shape}")
    if a.dtype == np.float64 or a.dtype == np.float32:
        return np.ascontiguousarray(a)
    return np.ascontiguousarray(a, dtype=np.float64)


def _as_faces(faces, name="faces"):
    """Any integer (M, 3) array-like as a C-contiguous array the extension
    reads in place: int64, int32 and uint32 kept (no copy when already
    contiguous), any other integer dtype converted to int64 (unsigned
    values beyond int64 become -1, which the range check refuses)."""
    a = np.asarray(faces)
    if a.dtype.kind not in "iu":
        raise ValueError(f"{name} must be an integer array, got dtype {a.dtype}")
    if a.ndim != 2 or a.shape[1] != 3:
        raise ValueError(f"{name} must have shape (M, 3), got {a.shape}")
    if a.dtype == np.int64 or a.dtype == np.int32 or a.dtype == np.uint32:
        return np.ascontiguousarray(a)
    if a.dtype.kind == "u" and a.size and a.max() > np.iinfo(np.int64).max:
        a = np.where(a > np.iinfo(np.int64).max, -1, a.astype(np.int64, copy=False))
    return np.ascontiguousarray(a, dtype=np.int64)


def _as_point(value, name):
    """An optional 3-vector as a tuple of floats."""
    if value is None:
        return None
    a = np.asarray(value, dtype=np.float64)
    if a.shape != (3,):
        raise ValueError(f"{name} must be 3 numbers x, y, z, got shape {a.shape}")
    return tuple(float(x) for x in a)


def _as_size(value, name):
    """A positive image side; the Rust side checks the upper limit."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise ValueError(f"{name} must be an integer, got {value!r}")
    if value < 1:
        raise ValueError(f"image {name} must be at least 1 pixel, got {value}")
    if value > 2**32 - 1:
        raise ValueError(f"image {name} {value} is over the limit of 16384")
    return int(value)


def _as_pose(pose, convention):
    """A 4x4 camera-to-world pose as OpenGL-convention rows of floats, its
    rotation checked."""
    if pose is None:
        if convention is not None:
            raise ValueError("convention applies to pose; it was given without one")
        return None
    if convention not in CONVENTIONS:
        raise ValueError("pose needs convention='opengl' (the camera looks down -z, +y up: "
                         "pyrender) or convention='opencv' (down +z, +y down: open3d), "
                         f"got {convention!r}")
    try:
        a = np.array(pose, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError(f"pose must be a 4x4 array of numbers, got {type(pose).__name__}") from None
    if a.shape != (4, 4):
        raise ValueError(f"pose must be a 4x4 camera-to-world matrix, got shape {a.shape}")
    if not np.isfinite(a).all():
        raise ValueError("pose has a non-finite value")
    if not np.allclose(a[3], [0, 0, 0, 1], rtol=0, atol=1e-9):
        raise ValueError(f"pose's last row must be 0, 0, 0, 1, got {a[3].tolist()}")
    r = a[:3, :3]
    if np.abs(r.T @ r - np.eye(3)).max() > 1e-6 or np.linalg.det(r) <= 0:
        raise ValueError("pose's upper 3x3 must be a rotation (orthonormal, determinant +1; "
                         "no scale or mirror)")
    if convention == "opencv":
        a = a @ np.diag([1.0, -1.0, -1.0, 1.0])
    return tuple(tuple(float(x) for x in row) for row in a)


def _as_intrinsics(intrinsics):
    """Pinhole intrinsics, a 3x3 camera matrix or (fx, fy, cx, cy), as
    four floats."""
    if intrinsics is None:
        return None
    try:
        a = np.array(intrinsics, dtype=np.float64)
    except (TypeError, ValueError):
        raise TypeError("intrinsics must be a 3x3 camera matrix or 4 numbers fx, fy, cx, cy, "
                        f"got {type(intrinsics).__name__}") from None
    if a.shape == (3, 3):
        if a[0, 1] != 0 or a[1, 0] != 0 or a[2, 0] != 0 or a[2, 1] != 0 or a[2, 2] != 1:
            raise ValueError("intrinsics must be [[fx, 0, cx], [0, fy, cy], [0, 0, 1]] "
                             f"(no skew), got {a.tolist()}")
        a = np.array([a[0, 0], a[1, 1], a[0, 2], a[1, 2]])
    if a.shape != (4,):
        raise ValueError("intrinsics must be a 3x3 camera matrix or 4 numbers fx, fy, cx, cy, "
                         f"got shape {a.shape}")
    return tuple(float(x) for x in a)


def _camera_args(eye, target, up, fovy, near, far, pose, convention, intrinsics, orthographic):
    """The camera keywords, checked against each other, as the extension
    takes them: (eye, target, up, fovy, near, far) and
    (pose, intrinsics, orthographic)."""
    pose = _as_pose(pose, convention)
    if pose is not None:
        given = [n for n, v in (("eye", eye), ("target", target), ("up", up)) if v is not None]
        if given:
            raise ValueError(f"pose places the camera; leave {', '.join(given)} unset")
    k = _as_intrinsics(intrinsics)
    if orthographic is not None:
        if isinstance(orthographic, (bool, np.bool_)) or not isinstance(
                orthographic, (int, float, np.integer, np.floating)):
            raise TypeError(f"orthographic must be a number (the view's half height), "
                            f"got {orthographic!r}")
        orthographic = float(orthographic)
        if not (orthographic > 0 and np.isfinite(orthographic)):
            raise ValueError(f"orthographic half height must be > 0, got {orthographic}")
    for name, value in (("intrinsics", k), ("orthographic", orthographic)):
        if value is not None and fovy is not None:
            raise ValueError(f"fovy and {name} both set the field of view; give one")
    if k is not None and orthographic is not None:
        raise ValueError("intrinsics are a perspective camera's; orthographic cannot take them")
    look = (_as_point(eye, "eye"), _as_point(target, "target"), _as_point(up, "up"),
            None if fovy is None else float(fovy),
            None if near is None else float(near),
            None if far is None else float(far))
    return look, (pose, k, orthographic)


def _as_outputs(outputs, normals):
    """The names of ``outputs`` checked, and the extension's flags for the
    surface attributes."""
    if outputs is None:
        return ("ids", "depth"), (False,) * 5
    if isinstance(outputs, str):
        raise TypeError(f"outputs must be a sequence of names such as ('ids', 'distance'), "
                        f"got the string {outputs!r}")
    names = tuple(outputs)
    if not names:
        raise ValueError(f"outputs must name at least one of {', '.join(OUTPUTS)}")
    for name in names:
        if name not in OUTPUTS:
            raise ValueError(f"unknown output {name!r} (one of {', '.join(OUTPUTS)})")
    if len(set(names)) != len(names):
        raise ValueError(f"outputs names one twice: {names}")
    if "vertex_normals" in names and normals is None:
        raise ValueError("the vertex_normals output needs the normals= keyword "
                         "(one normal per vertex)")
    return names, tuple(n in names for n in OUTPUTS[2:])


def render(vertices, faces, *, width, height, eye=None, target=None, up=None,
           fovy=None, near=None, far=None, pose=None, convention=None, intrinsics=None,
           orthographic=None, normals=None, outputs=None, algo=DEFAULT_ALGO, threads=1,
           timeout=None):
    """Render a triangle mesh into a face-id buffer and a depth buffer, and
    on request what a ray caster reports per pixel.

    Parameters
    ----------
    vertices : (N, 3) array-like of any real dtype, C or Fortran order
        World-space positions (right-handed). float64 and float32 arrays
        are read in place, without a converted copy.
    faces : (M, 3) array-like of any integer dtype
        Vertex indices of each triangle; triangle ``k`` has id ``k``.
        int64, int32 and uint32 arrays are read in place.
    width, height : int
        Image size in pixels (1 to 16384 each).
    eye, target, up : 3 numbers, optional
        A look-at camera. Unset values come from the *fit camera* of the
        ``hider`` command line: centred on the bounding box, at 2.5 times
        its half diagonal along +Z, looking down -Z with +Y up.
    fovy : float, optional
        Vertical field of view in degrees (60 when unset).
    near, far : float, optional
        Clip distances along the view axis (default 0.1 and 10 times the
        half diagonal; with ``pose``, the view depths of the bounding box's
        corners widened by 1%).
    pose : (4, 4) array-like, optional
        Camera-to-world matrix (the camera's axes and position as columns),
        in place of ``eye``/``target``/``up``; needs ``convention``.
    convention : {"opengl", "opencv"}
        The axes of ``pose``: ``"opengl"`` (the camera looks down its -z
        axis, +y up: OpenGL, pyrender) or ``"opencv"`` (down +z, +y down:
        OpenCV, open3d). open3d's ``extrinsic`` is world-to-camera: pass
        its inverse.
    intrinsics : (3, 3) or 4 numbers, optional
        Pinhole intrinsics in pixels, the camera matrix
        ``[[fx, 0, cx], [0, fy, cy], [0, 0, 1]]`` or ``(fx, fy, cx, cy)``,
        in place of ``fovy``; the principal point may lie anywhere (an
        off-axis frustum). Pixel ``(i, j)`` is the ray through
        ``(i + 0.5, j + 0.5)``, as in open3d's ``create_rays_pinhole``
        (OpenCV puts pixel centres at integers: add 0.5 to its cx, cy).
    orthographic : float, optional
        An orthographic camera showing this half height in world units
        (pyrender's ``ymag``); the half width follows the image's aspect.
    normals : (N, 3) array-like, optional
        Vertex normals, for the ``"vertex_normals"`` output.
    outputs : sequence of str, optional
        What to return, in this order, from ``OUTPUTS``: ``"ids"``,
        ``"depth"``, ``"distance"``, ``"z"``, ``"barycentrics"``,
        ``"normals"``, ``"vertex_normals"``. Unset: ``("ids", "depth")``.
        The surface attributes are computed after the render from the id
        buffer, by intersecting each pixel-centre ray with its face in
        float64, and cost nothing when not asked for.
    algo : str
        Any name of ``algorithms()``. The exact ones
        (``algorithms(kind="exact")``, the default among them) and the
        reference ``"oracle"`` agree on every pixel that is not a depth
        tie. The others are not bound to: the approximate ones are wrong by
        design in documented cases (``"painter-naive"`` sorts whole
        triangles and is wrong where they intersect or overlap in a cycle,
        ``"zbuffer-linear-z"`` interpolates depth linearly on the screen
        and is wrong under perspective, ``"zbuffer-fixed16"`` and
        ``"zbuffer-fixed24"`` round depth to 16 or 24 bits and are wrong
        where surfaces come closer than that), and the multi-sample ones
        resolve several samples per pixel, so that the id they report for
        a pixel may be another than the one at its centre (``"warnock-4x4"``
        along edges). ``"auto"`` lets the planner choose the cheapest
        exact one for this mesh and view, as ``hider render --algo auto``
        does (``plan`` with the same arguments says which, and why); the
        buffers are then those of the hider chosen. The analysis runs the
        front end once more than a named hider: to render one mesh many
        times, call ``plan`` once and pass its ``algo``.
    threads : int
        Worker threads for the hiders that render in parallel (1 to 1024).
    timeout : float, optional
        Seconds the call may take: past them the hider stops (within
        milliseconds; every hider polls its cancel token at the heads of
        its long loops) and ``TimeoutError`` is raised. Unset: no limit.

    Returns
    -------
    ids, depth : (height, width) int32, (height, width) float32
        Without ``outputs``: the visible triangle at each pixel centre
        (``-1`` for background; row 0 is the top of the image) and its
        window depth ``z/w`` in [0, 1] (``1.0`` for background).
    tuple of arrays
        With ``outputs``: one array per name, in its order. ``distance``
        and ``z`` are (height, width) float32, ``inf`` for background;
        ``barycentrics`` (height, width, 2) float32 ``(u, v)`` with the hit
        at ``(1 - u - v) p0 + u p1 + v p2`` (open3d's ``primitive_uvs``),
        ``normals`` and ``vertex_normals`` (height, width, 3) float32 unit
        vectors in world space, the geometric one
        ``(p1 - p0) x (p2 - p0)`` not turned toward the camera; all 0 for
        background. For an orthographic camera ``distance`` is measured
        from the plane through the eye, and equals ``z``.

    Raises
    ------
    ValueError
        Bad arrays (wrong shape or dtype, a NaN or infinite coordinate, an
        index out of range), a bad camera or size, an unknown ``algo`` or
        output, camera keywords that contradict each other; the message
        names the argument.
    TypeError
        An argument of the wrong type (a pose or intrinsics that are not
        numbers, outputs given as one string).
    MemoryError
        The hider's memory budget ran out.
    TimeoutError
        The render took longer than ``timeout`` seconds.

    The GIL is released while rendering. Ctrl-C (``KeyboardInterrupt``)
    ends the call at once and stops the render (it stops within
    milliseconds, so the next call does not wait for it).

    Example::

        >>> import numpy as np, hider
        >>> v = np.array([[-1, -1, 0], [1, -1, 0], [0, 1, 0]], dtype=float)
        >>> ids, z = hider.render(v, [[0, 1, 2]], width=64, height=64,
        ...                       outputs=("ids", "z"))
        >>> # The fit camera's eye is 2.5 half diagonals (sqrt 2) away.
        >>> round(float(z[32, 32]), 4), round(2.5 * 2 ** 0.5, 4)
        (3.5355, 3.5355)
    """
    v = _as_vertices(vertices)
    f = _as_faces(faces)
    names, want = _as_outputs(outputs, normals)
    n = None if normals is None else _as_vertices(normals, "normals")
    look, extra = _camera_args(eye, target, up, fovy, near, far, pose, convention, intrinsics,
                               orthographic)
    (ids, depth), surface = _interruptible(
        _hider.render, v, f, _as_size(width, "width"), _as_size(height, "height"),
        *look, str(algo), int(threads), *extra, n, want, timeout=timeout,
    )
    if outputs is None:
        return ids, depth
    arrays = dict(zip(OUTPUTS, (ids, depth, *surface)))
    return tuple(arrays[name] for name in names)


def plan(vertices, faces, *, width, height, eye=None, target=None, up=None,
         fovy=None, near=None, far=None, pose=None, convention=None, intrinsics=None,
         orthographic=None, threads=1):
    """The hider ``render(..., algo="auto")`` chooses for these arguments.

    The scene is analysed as the command line's ``--algo auto`` analyses it
    for an id and depth image (no shading, anti-aliasing or vector
    output): depth range against the near plane, back faces, effects the
    mesh calls for. Returns a ``Plan``; the arguments and errors are
    ``render``'s.

    Example::

        >>> import numpy as np, hider
        >>> v = np.array([[-1, -1, 0], [1, -1, 0], [0, 1, 0]], dtype=float)
        >>> hider.plan(v, [[0, 1, 2]], width=64, height=64).algo
        'zbuffer-tiled'
    """
    v = _as_vertices(vertices)
    f = _as_faces(faces)
    look, extra = _camera_args(eye, target, up, fovy, near, far, pose, convention, intrinsics,
                               orthographic)
    algo, reason, summary = _interruptible(
        _hider.plan, v, f, _as_size(width, "width"), _as_size(height, "height"),
        *look, int(threads), *extra,
    )
    return Plan(algo, reason, summary)


def visible_faces(vertices, faces, **kwargs):
    """Which faces are seen: a boolean mask of shape ``(M,)``.

    Face ``k`` is visible when it is the nearest surface at one pixel centre
    or more of the image ``render(vertices, faces, **kwargs)`` makes; the
    keyword arguments are ``render``'s.
    """
    f = _as_faces(faces)
    ids, _ = render(vertices, f, **kwargs)
    mask = np.zeros(len(f), dtype=bool)
    seen = ids[ids >= 0]
    mask[seen] = True
    return mask


def svg(vertices, faces, path, *, width, height, eye=None, target=None, up=None,
        fovy=None, near=None, far=None, pose=None, convention=None, intrinsics=None,
        orthographic=None, mode="regions", crease_angle=30.0,
        stroke_width=1.0, stroke_mm=None, page_mm=None, hidden="none", background=None,
        seams=True, timeout=None):
    """Write an exact vector drawing of a triangle mesh as SVG.

    ``mode="regions"`` writes every surface's exact visible region (one
    path per flat face group, seamless in anti-aliasing viewers with
    ``seams=True``); ``mode="lines"`` the visible silhouettes, creases,
    boundaries and intersection lines as polylines ordered for a pen
    plotter. The keywords are the ``hider render`` command line's vector
    flags: ``crease_angle`` (degrees between two faces' normals that make
    an edge a crease), ``stroke_width`` (pixels) or ``stroke_mm``
    (millimetres on the ``page_mm=(width, height)`` page, else at 96 dots
    per inch), ``hidden`` (``"none"`` or ``"dashed"``: hidden lines drawn
    dashed), ``background`` (an SVG colour, or ``None`` for none), and
    ``seams``. The camera and size arguments are ``render``'s, and so is
    ``timeout`` (seconds; past them ``TimeoutError``, no file written);
    the file is written atomically. Ctrl-C stops the drawing.

    Example::

        >>> import numpy as np, hider, tempfile, os
        >>> v = np.array([[-1, -1, 0], [1, -1, 0], [0, 1, 0]], dtype=float)
        >>> out = os.path.join(tempfile.mkdtemp(), "t.svg")
        >>> hider.svg(v, [[0, 1, 2]], out, width=64, height=64, mode="lines")
        >>> "<polyline" in open(out).read() or "<path" in open(out).read()
        True
    """
    v = _as_vertices(vertices)
    f = _as_faces(faces)
    page = None if page_mm is None else (float(page_mm[0]), float(page_mm[1]))
    look, extra = _camera_args(eye, target, up, fovy, near, far, pose, convention, intrinsics,
                               orthographic)
    _interruptible(
        _hider.svg, v, f, os.fspath(path), _as_size(width, "width"),
        _as_size(height, "height"), *look,
        str(mode), float(crease_angle), float(stroke_width),
        None if stroke_mm is None else float(stroke_mm), page, str(hidden),
        None if background is None else str(background), bool(seams), *extra,
        timeout=timeout,
    )
