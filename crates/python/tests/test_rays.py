"""hider.render's ray-caster outputs (distance, z, barycentrics, normals,
vertex normals) and cameras (pose + intrinsics in both conventions,
orthographic), against a ray cast written here in numpy.

The reference intersects every pixel-centre ray with every triangle
(Möller-Trumbore, vectorised over all triangles: fine for meshes of a
few hundred triangles) and keeps the nearest hit in front. Its rays are
built from the camera's definition (K, the pose, the orthographic box),
not from hider's matrices.

Tolerances, where the reference and hider see the same triangle:
- distance and z: 2e-6 relative. hider solves in float64 and rounds to
  float32 (3e-8 relative); its rays come through the projection matrix,
  whose field of view went through atan and tan (1e-15 relative).
- barycentrics: 2e-6 absolute, the same float32 rounding of values in
  [-0.01, 1.01] with the same margin.
- normals: 1e-6 absolute: unit vectors rounded to float32.
Ids agree except where the reference itself changes its answer within
1/128 pixel of the centre: hider snaps vertices to 1/256 pixel, so a
centre that close to a shared edge (or to a crossing) may go either way.
"""

import numpy as np
import pytest

import hider
from conftest import uv_sphere

W, H = 64, 48


def scene():
    """A sphere with two crossing planes through it: occlusion, intersection
    lines, and faces seen at every angle."""
    v, f = uv_sphere(20, 10)
    plane = np.array([[-1.6, -1.0, -0.4], [1.6, -1.0, 0.5], [1.6, 0.9, -0.3],
                      [-1.6, 0.9, 0.6]])
    plane2 = np.array([[-0.2, -1.4, -1.5], [0.3, 1.4, -1.5], [0.1, 1.4, 1.5],
                       [-0.4, -1.4, 1.5]])
    quads = np.array([[0, 1, 2], [0, 2, 3]])
    V = np.concatenate([v, plane, plane2])
    F = np.concatenate([f, quads + len(v), quads + len(v) + 4])
    return V.astype(np.float64), F.astype(np.int64)


def cast(origins, dirs, V, F):
    """The nearest hit of each ray (P, 3) among the triangles: (id, t, u,
    v), id -1 and t inf where none. Möller-Trumbore over all triangles at
    once, in float64."""
    p0, p1, p2 = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    e1, e2 = p1 - p0, p2 - p0
    d = dirs[:, None, :]
    p = np.cross(d, e2[None])
    det = np.einsum("mk,pmk->pm", e1, p)
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / det
        s = origins[:, None, :] - p0[None]
        u = np.einsum("pmk,pmk->pm", s, p) * inv
        q = np.cross(s, e1[None])
        v = np.einsum("pmk,pmk->pm", d, q) * inv
        t = np.einsum("mk,pmk->pm", e2, q) * inv
    hit = (det != 0) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0)
    t = np.where(hit, t, np.inf)
    ids = np.argmin(t, axis=1)
    rows = np.arange(len(origins))
    best = t[rows, ids]
    ids = np.where(np.isfinite(best), ids, -1)
    return ids, best, u[rows, ids], v[rows, ids]


def pinhole_rays(K, pose_cv, dx=0.0, dy=0.0):
    """Rays of pixel centres (shifted by dx, dy pixels) of an OpenCV
    camera: origin the camera centre, direction R K^-1 (i + 0.5, j + 0.5, 1)
    with camera z 1, so that t is the view depth."""
    j, i = np.mgrid[0:H, 0:W]
    px = np.stack([i + 0.5 + dx, j + 0.5 + dy, np.ones_like(i, dtype=float)], -1).reshape(-1, 3)
    cam = px @ np.linalg.inv(K).T
    dirs = cam @ pose_cv[:3, :3].T
    origins = np.broadcast_to(pose_cv[:3, 3], dirs.shape)
    return origins, dirs


def ortho_rays(eye, right, up, forward, half_height, dx=0.0, dy=0.0):
    """Rays of pixel centres of an orthographic camera: parallel to
    `forward`, from the plane through the eye, unit direction."""
    j, i = np.mgrid[0:H, 0:W]
    x = (2 * (i + 0.5 + dx) / W - 1) * half_height * W / H
    y = (1 - 2 * (j + 0.5 + dy) / H) * half_height
    origins = eye + x.reshape(-1, 1) * right + y.reshape(-1, 1) * up
    dirs = np.broadcast_to(forward, origins.shape)
    return origins, dirs


def look_pose_cv(eye, target, up_hint):
    """An OpenCV camera-to-world pose at eye looking at target."""
    z = np.asarray(target, float) - eye
    z /= np.linalg.norm(z)
    x = np.cross(z, -np.asarray(up_hint, float))
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    pose = np.eye(4)
    pose[:3, 0], pose[:3, 1], pose[:3, 2], pose[:3, 3] = x, y, z, eye
    return pose


ALL = ("ids", "distance", "z", "barycentrics", "normals")


def check_against_reference(out, ref, ref_distance, ref_z, jittered, V, F):
    """hider's outputs equal the reference wherever both see the same
    triangle; the other pixels are ties the jittered reference shows."""
    ids, dist, z, bary, normals = (a.reshape(H * W, *a.shape[2:]) for a in out)
    ref_ids, _, ref_u, ref_v = ref
    same = ids == ref_ids
    hits = same & (ids >= 0)
    assert hits.sum() > 0.4 * H * W
    # Ties: the reference gives hider's answer within 1/128 pixel.
    for k in np.flatnonzero(~same):
        assert any(j[k] == ids[k] for j in jittered), (k, ids[k], ref_ids[k])
    assert (~same).sum() < 0.01 * H * W
    np.testing.assert_allclose(dist[hits], ref_distance[hits], rtol=2e-6)
    np.testing.assert_allclose(z[hits], ref_z[hits], rtol=2e-6)
    np.testing.assert_allclose(bary[hits, 0], ref_u[hits], atol=2e-6)
    np.testing.assert_allclose(bary[hits, 1], ref_v[hits], atol=2e-6)
    p0, p1, p2 = V[F[:, 0]], V[F[:, 1]], V[F[:, 2]]
    n = np.cross(p1 - p0, p2 - p0)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    np.testing.assert_allclose(normals[hits], n[ids[hits]], atol=1e-6)
    background = ids < 0
    assert np.isinf(dist[background]).all() and np.isinf(z[background]).all()
    assert (bary[background] == 0).all() and (normals[background] == 0).all()


K_CASES = [
    np.array([[60.0, 0, 32.0], [0, 60.0, 24.0], [0, 0, 1]]),
    # Off-centre principal point and non-square pixels.
    np.array([[55.0, 0, 20.5], [0, 70.0, 31.25], [0, 0, 1]]),
]


@pytest.mark.parametrize("K", K_CASES)
def test_pose_and_intrinsics_equal_a_numpy_ray_cast(K):
    V, F = scene()
    pose_cv = look_pose_cv(np.array([1.2, 2.0, 3.5]), [0.1, -0.1, 0.0], [0, 1, 0])
    out = hider.render(V, F, width=W, height=H, pose=pose_cv, convention="opencv",
                       intrinsics=K, outputs=ALL)
    origins, dirs = pinhole_rays(K, pose_cv)
    ref = cast(origins, dirs, V, F)
    jittered = [cast(*pinhole_rays(K, pose_cv, dx, dy), V, F)[0]
                for dx, dy in ((1 / 128, 0), (-1 / 128, 0), (0, 1 / 128), (0, -1 / 128))]
    # The reference's t is the view depth (camera z of its rays is 1), and
    # t times the direction's length the distance.
    t = ref[1]
    check_against_reference(out, ref, t * np.linalg.norm(dirs, axis=1), t, jittered, V, F)
    # The same camera as an OpenGL pose gives the same arrays.
    pose_gl = pose_cv @ np.diag([1.0, -1.0, -1.0, 1.0])
    out_gl = hider.render(V, F, width=W, height=H, pose=pose_gl, convention="opengl",
                          intrinsics=(K[0, 0], K[1, 1], K[0, 2], K[1, 2]), outputs=ALL)
    for a, b in zip(out, out_gl):
        np.testing.assert_array_equal(a, b)


def test_orthographic_equals_a_numpy_ray_cast():
    V, F = scene()
    eye = np.array([0.4, 0.8, 4.0])
    pose_cv = look_pose_cv(eye, [0.0, 0.0, 0.0], [0, 1, 0])
    right, up, forward = pose_cv[:3, 0], -pose_cv[:3, 1], pose_cv[:3, 2]
    out = hider.render(V, F, width=W, height=H, pose=pose_cv, convention="opencv",
                       orthographic=1.3, outputs=ALL)
    ref = cast(*ortho_rays(eye, right, up, forward, 1.3), V, F)
    jittered = [cast(*ortho_rays(eye, right, up, forward, 1.3, dx, dy), V, F)[0]
                for dx, dy in ((1 / 128, 0), (-1 / 128, 0), (0, 1 / 128), (0, -1 / 128))]
    # Unit directions from the eye's plane: t is both distance and z.
    check_against_reference(out, ref, ref[1], ref[1], jittered, V, F)
    # Orthographic distance is measured from the eye's plane: it is z.
    np.testing.assert_array_equal(out[1], out[2])


def test_a_known_point_lands_on_its_pixel_in_both_conventions():
    """A triangle facing the camera around a world point shows at the pixel
    K puts the point at, whichever convention the pose is given in, and
    its pixels centre where K puts its corners."""
    K = np.array([[40.0, 0, 13.3], [0, 45.0, 30.9], [0, 0, 1]])
    pose_cv = look_pose_cv(np.array([0.5, -1.0, 2.0]), [0.0, 0.2, -1.0], [0, 0, 1])
    local = np.array([0.3, -0.2, 2.5])  # OpenCV camera coordinates
    s = 0.3
    corners = local + np.array([[-s, -s, 0], [s, -s, 0], [0, s, 0]])
    tri = corners @ pose_cv[:3, :3].T + pose_cv[:3, 3]
    u = K[0, 0] * local[0] / local[2] + K[0, 2]
    v = K[1, 1] * local[1] / local[2] + K[1, 2]
    # All corners share one depth: the projected triangle is similar, and
    # its pixel centres' mean is near its centroid.
    centroid = corners.mean(0)
    cu = K[0, 0] * centroid[0] / centroid[2] + K[0, 2]
    cv = K[1, 1] * centroid[1] / centroid[2] + K[1, 2]
    for pose, convention in ((pose_cv, "opencv"),
                             (pose_cv @ np.diag([1.0, -1.0, -1.0, 1.0]), "opengl")):
        ids, z = hider.render(tri, [[0, 1, 2]], width=W, height=H, pose=pose,
                              convention=convention, intrinsics=K, near=0.1, far=10,
                              outputs=("ids", "z"))
        assert ids[int(v), int(u)] == 0, convention
        rows, cols = np.nonzero(ids == 0)
        assert abs(cols.mean() + 0.5 - cu) < 0.3 and abs(rows.mean() + 0.5 - cv) < 0.3
        assert abs(z[int(v), int(u)] - 2.5) < 1e-6


def test_every_exact_hider_renders_an_off_axis_camera():
    """The lens reaches every hider: each exact one equals the oracle on
    an off-centre, non-square-pixel camera but on ties."""
    V, F = scene()
    kw = dict(width=W, height=H, pose=look_pose_cv(np.array([1.0, 1.5, 3.0]), [0, 0, 0],
                                                   [0, 1, 0]),
              convention="opencv", intrinsics=K_CASES[1])
    ref, _ = hider.render(V, F, algo="oracle", **kw)
    assert (ref >= 0).mean() > 0.4
    for name in hider.algorithms(kind="exact"):
        ids, _ = hider.render(V, F, algo=name, **kw)
        assert (ids != ref).mean() < 0.002, name
    # The others are wrong by design in places, but see the same picture:
    # a lens they ignored would move it by tens of pixels.
    for name in set(hider.algorithms()) - set(hider.algorithms(kind="exact")):
        ids, _ = hider.render(V, F, algo=name, **kw)
        assert (ids != ref).mean() < 0.1, name


def test_vertex_normals_are_interpolated_with_the_barycentrics():
    v, f = uv_sphere(16, 8)
    n = v / np.linalg.norm(v, axis=1, keepdims=True)
    ids, bary, vn = hider.render(v, f, width=W, height=H, normals=n.astype(np.float32),
                                 outputs=("ids", "barycentrics", "vertex_normals"))
    hit = ids >= 0
    u, w = bary[hit, 0].astype(float), bary[hit, 1].astype(float)
    corners = f[ids[hit]]
    want = ((1 - u - w)[:, None] * n[corners[:, 0]] + u[:, None] * n[corners[:, 1]]
            + w[:, None] * n[corners[:, 2]])
    want /= np.linalg.norm(want, axis=1, keepdims=True)
    np.testing.assert_allclose(vn[hit], want, atol=2e-6)
    assert (vn[~hit] == 0).all()


def test_outputs_come_in_the_order_asked_and_the_default_is_unchanged():
    v, f = uv_sphere(12, 6)
    ids, depth = hider.render(v, f, width=32, height=24)
    z, i2, d2 = hider.render(v, f, width=32, height=24, outputs=["z", "ids", "depth"])
    np.testing.assert_array_equal(ids, i2)
    np.testing.assert_array_equal(depth, d2)
    assert z.dtype == np.float32 and z.shape == (24, 32)
    b, nrm = hider.render(v, f, width=32, height=24, outputs=("barycentrics", "normals"))
    assert b.shape == (24, 32, 2) and nrm.shape == (24, 32, 3)
    # A pool of threads renders on another thread: the same outputs.
    many = hider.render(v, f, width=32, height=24, outputs=ALL, threads=2)
    for a, b in zip(hider.render(v, f, width=32, height=24, outputs=ALL), many):
        np.testing.assert_array_equal(a, b)


def test_plan_and_auto_take_the_new_cameras():
    V, F = scene()
    kw = dict(width=W, height=H, pose=look_pose_cv(np.array([1.0, 1.5, 3.0]), [0, 0, 0],
                                                   [0, 1, 0]),
              convention="opencv", intrinsics=K_CASES[1])
    chosen = hider.plan(V, F, **kw)
    assert chosen.algo in hider.algorithms(kind="exact")
    auto = hider.render(V, F, algo="auto", outputs=ALL, **kw)
    named = hider.render(V, F, algo=chosen.algo, outputs=ALL, **kw)
    for a, b in zip(auto, named):
        np.testing.assert_array_equal(a, b)
    ortho = hider.plan(V, F, width=W, height=H, orthographic=2.0)
    assert ortho.algo in hider.algorithms()


def test_window_depth_converts_to_z_and_distance_by_the_documented_formulas():
    """docs/python.md's formulas: z from window depth and near/far, and
    distance from z and the pixel's ray. The wall faces the camera, so its
    window depth is the same at every pixel and the vertices' snapping to
    1/256 pixel does not move it (on a slanted face it does, by the depth
    gradient times up to 1/512 pixel: the z output has no such error)."""
    wall = np.array([[-9, -9, -3.0], [9, -9, -3.0], [9, 9, -3.0], [-9, 9, -3.0]])
    near, far, fovy = 0.5, 20.0, 50.0
    ids, depth, z, dist = hider.render(wall, [[0, 1, 2], [0, 2, 3]], width=W, height=H,
                                       eye=(0, 0, 0), target=(0, 0, -1), fovy=fovy,
                                       near=near, far=far,
                                       outputs=("ids", "depth", "z", "distance"))
    assert (ids >= 0).all()
    d = depth.astype(np.float64)
    z_from_depth = near * far / (far - d * (far - near))
    # float32 window depth near 0.9: 6e-8 apart, 4e-7 of z here.
    np.testing.assert_allclose(z_from_depth, 3.0, rtol=1e-6)
    np.testing.assert_allclose(z, 3.0, rtol=1e-7)
    j, i = np.mgrid[0:H, 0:W]
    t = np.tan(np.radians(fovy) / 2)
    x = (2 * (i + 0.5) / W - 1) * t * W / H
    y = (1 - 2 * (j + 0.5) / H) * t
    np.testing.assert_allclose(dist, z * np.sqrt(1 + x * x + y * y), rtol=2e-7)


@pytest.mark.parametrize("kwargs, error, message", [
    ({"pose": np.eye(4)}, ValueError, "pose needs convention="),
    ({"convention": "opencv"}, ValueError, "convention applies to pose"),
    ({"pose": np.eye(4), "convention": "vulkan"}, ValueError, "got 'vulkan'"),
    ({"pose": np.eye(3), "convention": "opengl"}, ValueError,
     "pose must be a 4x4 camera-to-world matrix, got shape (3, 3)"),
    ({"pose": "eye", "convention": "opengl"}, TypeError, "pose must be a 4x4 array"),
    ({"pose": np.diag([2.0, 2.0, 2.0, 1.0]), "convention": "opengl"}, ValueError,
     "pose's upper 3x3 must be a rotation"),
    ({"pose": np.diag([1.0, 1.0, -1.0, 1.0]), "convention": "opengl"}, ValueError,
     "pose's upper 3x3 must be a rotation"),
    ({"pose": np.full((4, 4), np.nan), "convention": "opengl"}, ValueError, "pose has a non-finite"),
    ({"pose": np.eye(4), "convention": "opengl", "eye": (0, 0, 3)}, ValueError,
     "pose places the camera; leave eye unset"),
    ({"intrinsics": (1, 2, 3)}, ValueError, "intrinsics must be a 3x3 camera matrix or 4"),
    ({"intrinsics": [[10, 1, 8], [0, 10, 8], [0, 0, 1]]}, ValueError, "(no skew)"),
    ({"intrinsics": ("a", 1, 2, 3)}, TypeError, "intrinsics must be"),
    ({"intrinsics": (-10, 10, 8, 8)}, ValueError, "intrinsics fx -10 must be"),
    ({"intrinsics": (10, 10, 8, 8), "fovy": 40}, ValueError, "fovy and intrinsics"),
    ({"intrinsics": (10, 10, 8, 8), "orthographic": 1.0}, ValueError,
     "orthographic cannot take them"),
    ({"orthographic": -1.0}, ValueError, "orthographic half height must be > 0"),
    ({"orthographic": "wide"}, TypeError, "orthographic must be a number"),
    ({"outputs": "distance"}, TypeError, "outputs must be a sequence of names"),
    ({"outputs": ("ids", "t_hit")}, ValueError, "unknown output 't_hit'"),
    ({"outputs": ()}, ValueError, "outputs must name at least one"),
    ({"outputs": ("ids", "ids")}, ValueError, "outputs names one twice"),
    ({"outputs": ("vertex_normals",)}, ValueError, "needs the normals= keyword"),
    ({"outputs": ("vertex_normals",), "normals": np.zeros((2, 3))}, ValueError,
     "normals must have one row per vertex: 2 rows for 3 vertices"),
    ({"outputs": ("vertex_normals",), "normals": np.full((3, 3), np.inf)}, ValueError,
     "normals row 0 is not finite"),
])
def test_bad_camera_and_output_arguments_are_named(kwargs, error, message):
    v = np.array([[-1, -1, 0], [1, -1, 0], [0, 1, 0]], dtype=float)
    with pytest.raises(error) as info:
        hider.render(v, [[0, 1, 2]], width=16, height=16, **kwargs)
    assert message in str(info.value)
    assert "\n" not in str(info.value)


@pytest.mark.parametrize("K", K_CASES)
def test_ids_and_distance_equal_open3d_raycasting(K):
    """Where open3d is installed: ``ids`` and ``distance`` equal
    ``open3d.t.geometry.RaycastingScene.cast_rays`` on the rays of
    ``create_rays_pinhole`` (normalised, so that ``t_hit`` is the
    distance) with the same intrinsics and pose. open3d takes float32
    vertices: distances agree within 1e-5 relative where both see the same
    triangle, and the ids differ only at ties (pixel centres within 1/128
    pixel of a shared edge or a crossing, where the numpy reference itself
    changes its answer)."""
    o3d = pytest.importorskip("open3d")
    V, F = scene()
    pose_cv = look_pose_cv(np.array([1.2, 2.0, 3.5]), [0.1, -0.1, 0.0], [0, 1, 0])
    ids, dist = hider.render(V, F, width=W, height=H, pose=pose_cv, convention="opencv",
                             intrinsics=K, outputs=("ids", "distance"))
    rc = o3d.t.geometry.RaycastingScene()
    rc.add_triangles(o3d.core.Tensor(V.astype(np.float32)),
                     o3d.core.Tensor(F.astype(np.uint32)))
    rays = o3d.t.geometry.RaycastingScene.create_rays_pinhole(
        intrinsic_matrix=o3d.core.Tensor(K), extrinsic_matrix=o3d.core.Tensor(
            np.linalg.inv(pose_cv)), width_px=W, height_px=H).numpy()
    rays[..., 3:] /= np.linalg.norm(rays[..., 3:], axis=-1, keepdims=True)
    hit = rc.cast_rays(o3d.core.Tensor(rays.astype(np.float32)))
    o3d_ids = hit["primitive_ids"].numpy().astype(np.int64)
    o3d_ids[o3d_ids == o3d.t.geometry.RaycastingScene.INVALID_ID] = -1
    t_hit = hit["t_hit"].numpy()
    same = ids == o3d_ids
    jittered = [cast(*pinhole_rays(K, pose_cv, dx, dy), V, F)[0].reshape(H, W)
                for dx, dy in ((1 / 128, 0), (-1 / 128, 0), (0, 1 / 128), (0, -1 / 128))]
    for j, i in zip(*np.nonzero(~same)):
        assert any(r[j, i] == ids[j, i] for r in jittered), (j, i, ids[j, i], o3d_ids[j, i])
    assert (~same).sum() < 0.01 * H * W
    hits = same & (ids >= 0)
    assert hits.sum() > 0.4 * H * W
    np.testing.assert_allclose(dist[hits], t_hit[hits], rtol=1e-5)
    background = same & (ids < 0)
    assert np.isinf(dist[background]).all() and np.isinf(t_hit[background]).all()
