"""hider.render and hider.visible_faces: the command line's dumps bit for
bit, every dtype and memory order, and clear errors for bad input."""

import pathlib
import sys
import textwrap
import threading

import numpy as np
import pytest

import hider
from conftest import ROOT, cli_render, read_obj, uv_sphere, write_obj

SPIDER = ROOT.parent / "shared" / "gl-reference" / "models" / "spider.obj"


def test_sphere_equals_the_command_line_bit_for_bit(hider_cli, tmp_path):
    vertices, faces = uv_sphere(32, 16)
    model = tmp_path / "sphere.obj"
    write_obj(model, vertices, faces)
    for algo in ["zbuffer", "zbuffer-tiled", "scanline"]:
        want_ids, want_depth = cli_render(hider_cli, model, tmp_path, (96, 64), "--algo", algo)
        ids, depth = hider.render(vertices, faces, width=96, height=64, algo=algo)
        assert (want_ids >= 0).sum() > 300
        np.testing.assert_array_equal(ids, want_ids)
        assert depth.tobytes() == want_depth.tobytes(), algo


def test_asset_sphere_with_a_camera_equals_the_command_line(hider_cli, tmp_path):
    model = ROOT / "assets" / "sphere.obj"
    vertices, faces = read_obj(model)
    camera = ["--eye", "1.5,2,3", "--target", "0,0.1,0", "--up", "0,1,0.2",
              "--fovy", "40", "--near", "0.5", "--far", "20"]
    want_ids, want_depth = cli_render(hider_cli, model, tmp_path, (80, 80), *camera,
                                      "--algo", "zbuffer-tiled")
    ids, depth = hider.render(vertices, faces, width=80, height=80, eye=(1.5, 2, 3),
                              target=[0, 0.1, 0], up=np.array([0, 1, 0.2]), fovy=40,
                              near=0.5, far=20)
    np.testing.assert_array_equal(ids, want_ids)
    assert depth.tobytes() == want_depth.tobytes()


@pytest.mark.skipif(not SPIDER.exists(), reason=f"the GL reference models are absent ({SPIDER})")
def test_spider_equals_the_command_line_bit_for_bit(hider_cli, tmp_path):
    vertices, faces = read_obj(SPIDER)
    want_ids, want_depth = cli_render(hider_cli, SPIDER, tmp_path, (128, 128),
                                      "--algo", "zbuffer-tiled")
    ids, depth = hider.render(vertices, faces, width=128, height=128, threads=2)
    assert len(np.unique(want_ids)) > 200
    np.testing.assert_array_equal(ids, want_ids)
    assert depth.tobytes() == want_depth.tobytes()


def test_vertices_no_face_uses_do_not_move_the_camera():
    # The bounds of the fit camera and of a moved eye's clip planes are
    # those of the vertices the faces use, computed while the arrays are
    # read: a stray vertex far away changes nothing, for a mesh of shared
    # vertices and for a soup (three vertices a face), each with the fit
    # camera, a moved eye and a pose.
    vertices, faces = uv_sphere(12, 6)
    soup = vertices[faces].reshape(-1, 3)
    soup_faces = np.arange(len(soup)).reshape(-1, 3)
    pose = np.eye(4)
    pose[:3, 3] = [0.5, 0.2, 4.0]
    for v, f in [(vertices, faces), (soup, soup_faces)]:
        stray = np.vstack([[[50.0, -40.0, 30.0]], v, [[-60.0, 70.0, -80.0]]])
        for camera in [{}, dict(eye=(3.0, 1.0, 2.0)), dict(pose=pose, convention="opengl")]:
            want = hider.render(v, f, width=40, height=30, **camera)
            got = hider.render(stray, f + 1, width=40, height=30, **camera)
            assert (want[0] >= 0).sum() > 100
            np.testing.assert_array_equal(got[0], want[0])
            assert got[1].tobytes() == want[1].tobytes()


def test_every_dtype_and_order_gives_the_same_buffers():
    vertices, faces = uv_sphere(12, 6)
    vertices = np.round(vertices * 8)  # exact in every dtype below
    want = hider.render(vertices, faces, width=40, height=30)
    assert want[0].dtype == np.int32 and want[1].dtype == np.float32
    assert want[0].shape == want[1].shape == (30, 40)
    for vdtype in [np.float32, np.float64, np.int16, np.int64, np.longdouble]:
        for fdtype in [np.int32, np.uint32, np.uint16, np.int64, np.uint64]:
            for order in "CF":
                v = np.asarray(vertices, dtype=vdtype, order=order)
                f = np.asarray(faces, dtype=fdtype, order=order)
                ids, depth = hider.render(v, f, width=40, height=30)
                np.testing.assert_array_equal(ids, want[0])
                np.testing.assert_array_equal(depth, want[1])
    strided = hider.render(np.repeat(vertices, 2, axis=0)[::2], faces.tolist(), width=40, height=30)
    np.testing.assert_array_equal(strided[0], want[0])


def test_float32_and_int32_arrays_are_read_in_place():
    """float32 vertices and int32 or uint32 faces reach the extension as
    they are (no conversion copy): the same buffers as their float64 and
    int64 values, and the index checks hold for each type."""
    vertices, faces = uv_sphere(16, 8)
    v32 = (vertices * 1.1).astype(np.float32)  # not exact in float32
    want = hider.render(v32.astype(np.float64), faces, width=48, height=40)
    for f in (faces.astype(np.int32), faces.astype(np.uint32)):
        assert np.shares_memory(hider._as_vertices(v32), v32)
        assert np.shares_memory(hider._as_faces(f), f)
        got = hider.render(v32, f, width=48, height=40)
        np.testing.assert_array_equal(got[0], want[0])
        np.testing.assert_array_equal(got[1], want[1])
    with pytest.raises(ValueError, match="triangle 0 uses vertex -1"):
        hider.render(v32, np.array([[-1, 0, 1]], dtype=np.int32), width=8, height=8)
    with pytest.raises(ValueError, match="triangle 0 uses vertex 4294967295"):
        hider.render(v32, np.array([[2**32 - 1, 0, 1]], dtype=np.uint32), width=8, height=8)


def test_visible_faces_is_the_set_of_ids_seen():
    vertices, faces = uv_sphere(16, 8)
    mask = hider.visible_faces(vertices, faces, width=64, height=64, eye=(0, 0, 4))
    ids, _ = hider.render(vertices, faces, width=64, height=64, eye=(0, 0, 4))
    assert mask.dtype == bool and mask.shape == (len(faces),)
    assert set(np.nonzero(mask)[0]) == set(np.unique(ids[ids >= 0]))
    # From +Z the far hemisphere is hidden: about half the faces are seen.
    assert 0.3 * len(faces) < mask.sum() < 0.7 * len(faces)


def test_auto_renders_with_the_planners_choice(hider_cli, tmp_path):
    vertices, faces = uv_sphere(24, 12)
    model = tmp_path / "sphere.obj"
    write_obj(model, vertices, faces)
    size = {"width": 64, "height": 48}
    # An ordinary view: the tiled z-buffer. A near plane a million times
    # nearer than the sphere: f32 window depth runs out of bits, so the
    # planner takes the reversed-Z z-buffer.
    for camera, flags, want_algo in [
        ({}, [], "zbuffer-tiled"),
        ({"near": 1e-6}, ["--near", "1e-6"], "zbuffer-reversed"),
    ]:
        p = hider.plan(vertices, faces, **size, **camera)
        assert p.algo == want_algo, p
        assert p.algo in hider.algorithms()
        assert p.summary.startswith("auto, asked for an id-coloured 64 x 48 image: " + want_algo)
        assert p.reason in p.summary
        ids, depth = hider.render(vertices, faces, **size, **camera, algo="auto")
        named = hider.render(vertices, faces, **size, **camera, algo=p.algo)
        np.testing.assert_array_equal(ids, named[0])
        assert depth.tobytes() == named[1].tobytes()
        # The command line's --algo auto gives the same dumps.
        want_ids, want_depth = cli_render(hider_cli, model, tmp_path, (64, 48), *flags,
                                          "--algo", "auto")
        assert (want_ids >= 0).sum() > 250
        np.testing.assert_array_equal(ids, want_ids)
        assert depth.tobytes() == want_depth.tobytes(), want_algo
        mask = hider.visible_faces(vertices, faces, **size, **camera, algo=hider.AUTO)
        assert set(np.nonzero(mask)[0]) == set(np.unique(ids[ids >= 0]))
    with pytest.raises(ValueError, match="uses vertex 999"):
        hider.plan(vertices, np.array([[0, 1, 999]]), **size)


def test_every_registered_hider_renders_by_name():
    vertices, faces = uv_sphere(8, 4)
    want, _ = hider.render(vertices, faces, width=24, height=24, algo="oracle")
    assert (want >= 0).sum() > 40
    for algo in hider.algorithms():
        ids, depth = hider.render(vertices, faces, width=24, height=24, algo=algo)
        # Multi-sample hiders report a pixel's id by their own rule; the
        # pixel-centre ones cover exactly the oracle's pixels.
        assert (ids >= 0).sum() > 0 and ids.max() < len(faces), algo
        assert ((ids >= 0) == (depth < 1.0)).all(), algo


@pytest.mark.parametrize("vertices, faces, kwargs, error, message", [
    ([[np.nan, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], {}, ValueError,
     "invalid scene: mesh 0 ('array') vertex 0 has a non-finite position [NaN, 0, 0]"),
    ([[np.inf, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], {}, ValueError, "non-finite"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 3]], {}, ValueError,
     "invalid scene: mesh 0 ('array') triangle 0 uses vertex 3, but the mesh has 3 vertices"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, -1]], {}, ValueError, "uses vertex -1"),
    ([[0, 0], [1, 0], [0, 1]], [[0, 1, 2]], {}, ValueError,
     "vertices must have shape (N, 3), got (3, 2)"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [0, 1, 2], {}, ValueError,
     "faces must have shape (M, 3), got (3,)"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0.0, 1.0, 2.0]], {}, ValueError,
     "faces must be an integer array, got dtype float64"),
    ([["a", "b", "c"]], [[0, 0, 0]], {}, ValueError, "real numeric array"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], {"width": 0}, ValueError,
     "image width must be at least 1 pixel, got 0"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], {"height": 20000}, ValueError,
     "image height 20000 is over the limit of 16384"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], {"algo": "nope"}, ValueError,
     "unknown algo 'nope'"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], {"eye": (0.5, 0.5, 0)}, ValueError,
     "invalid camera"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]], {"threads": 0}, ValueError,
     "threads must be 1 to 1024, got 0"),
])
def test_bad_input_is_one_clear_exception(vertices, faces, kwargs, error, message):
    args = {"width": 16, "height": 16, **kwargs}
    with pytest.raises(error) as info:
        hider.render(np.array(vertices), np.array(faces), **args)
    assert message in str(info.value)
    assert "\n" not in str(info.value)


def test_a_memory_budget_is_a_memory_error(tmp_path):
    """The supersampled z-buffer at the largest size is over its budget
    (72 GB): a MemoryError, raised before the 16384 x 16384 frame is
    allocated (it took the process to 3 GB and 2-5 s before the hiders
    could check a size alone); so in a fresh interpreter the peak memory
    stays far below the frame's 2 GB of ids and depth."""
    import subprocess

    script = tmp_path / "budget.py"
    script.write_text(textwrap.dedent("""
        import sys
        sys.path.insert(0, sys.argv[1])
        import hider
        from conftest import uv_sphere
        v, f = uv_sphere(8, 4)
        for algo in ("ssaa-32", "ssaa-sorted", "abuffer", "oracle"):
            try:
                hider.render(v, f, width=16384, height=16384, algo=algo)
                print(algo, "rendered")
            except MemoryError as e:
                print(algo, "MemoryError", "bytes" in str(e))
        # The peak resident memory of this program since it started (not
        # ru_maxrss, which on Linux keeps the forking parent's peak).
        peak = 0
        if sys.platform.startswith("linux"):
            with open("/proc/self/status") as status:
                peak = next(int(line.split()[1]) for line in status
                            if line.startswith("VmHWM:")) // 1024
        print("peak MiB", peak)
    """))
    tests = str(pathlib.Path(__file__).parent)
    proc = subprocess.run([sys.executable, str(script), tests], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.split("\n")
    assert lines[:4] == [f"{a} MemoryError True"
                         for a in ("ssaa-32", "ssaa-sorted", "abuffer", "oracle")], lines
    if sys.platform.startswith("linux"):
        assert int(lines[4].split()[2]) < 500, lines


def test_the_gil_is_released_while_rendering():
    vertices, faces = uv_sphere(64, 32)
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(1)
            stop.wait(0.001)

    t = threading.Thread(target=tick)
    t.start()
    try:
        for _ in range(3):
            hider.render(vertices, faces, width=1024, height=1024, algo="oracle")
    finally:
        stop.set()
        t.join()
    assert len(ticks) > 5


def test_kept_memory_does_not_leak_between_calls():
    # Each thread keeps its last hider and frame: another scene, size or
    # hider in between must not change what a call returns.
    sphere, sphere_faces = uv_sphere(16, 8)
    first = hider.render(sphere, sphere_faces, width=50, height=40)
    other, other_faces = uv_sphere(7, 3)
    hider.render(other * 3, other_faces, width=50, height=40)
    hider.render(other, other_faces, width=31, height=77, algo="scanline")
    hider.render(other, other_faces, width=50, height=40, threads=2)
    again = hider.render(sphere, sphere_faces, width=50, height=40)
    np.testing.assert_array_equal(first[0], again[0])
    np.testing.assert_array_equal(first[1], again[1])
    # The arrays returned are the caller's own: writing into them changes
    # no later frame.
    again[0][:] = 7
    np.testing.assert_array_equal(hider.render(sphere, sphere_faces, width=50, height=40)[0],
                                  first[0])


def test_returned_arrays_are_never_reused_while_alive():
    # The arrays are the frame's own buffers, handed over without a copy,
    # and go back to a pool for later frames once numpy frees them: never
    # while an array, or a view of one, is alive.
    sphere, faces = uv_sphere(16, 8)
    size = dict(width=67, height=43, eye=(0, 0, 4), target=(0, 0, 0))
    first_ids, first_depth = hider.render(sphere, faces, **size)
    want_ids, want_depth = first_ids.copy(), first_depth.copy()
    assert first_ids.base is not None and first_depth.base is not None
    corner = first_ids[10:30, 20:50]
    del first_ids
    for k in range(6):
        ids, depth = hider.render(sphere + [0.1 * (k + 1), 0, 0], faces, **size)
        assert not np.array_equal(ids, want_ids)
        del ids, depth
    # The view kept the first frame's ids alive; its depths were kept too.
    np.testing.assert_array_equal(corner, want_ids[10:30, 20:50])
    np.testing.assert_array_equal(first_depth, want_depth)
    for threads in (1, 2):
        again = hider.render(sphere, faces, threads=threads, **size)
        np.testing.assert_array_equal(again[0], want_ids)
        np.testing.assert_array_equal(again[1], want_depth)


def test_a_frame_freed_before_the_next_call_is_drawn_into_again():
    # A caller done with a frame's arrays before the next call (as
    # visible_faces is) gets the same memory back, still in cache, rather
    # than a second set of buffers used in turn with the first.
    sphere, faces = uv_sphere(12, 6)
    size = dict(width=61, height=37)

    def addresses(arrays):
        return [a.__array_interface__["data"][0] for a in arrays]

    first = hider.render(sphere, faces, **size)
    where = addresses(first)
    want = [a.copy() for a in first]
    del first
    for k in range(3):
        again = hider.render(sphere, faces, **size)
        assert addresses(again) == where
        np.testing.assert_array_equal(again[0], want[0])
        np.testing.assert_array_equal(again[1], want[1])
        del again


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="counts /proc/self/task")
def test_the_main_thread_works_in_its_first_pool(tmp_path):
    """The main thread's first pool (``threads=2``) takes the main thread
    in as one of its workers, so it starts one thread, not two; other
    sizes and other threads get pools of their own threads; every one
    renders the buffers of one thread."""
    import subprocess

    script = tmp_path / "pools.py"
    script.write_text(textwrap.dedent("""
        import os, sys, threading
        sys.path.insert(0, sys.argv[1])
        import hider
        from conftest import uv_sphere
        v, f = uv_sphere(64, 32)
        tasks = lambda: len(os.listdir("/proc/self/task"))
        want, _ = hider.render(v, f, width=200, height=150)
        before = tasks()
        ids, _ = hider.render(v, f, width=200, height=150, threads=2)
        print("two", tasks() - before, bool((ids == want).all()))
        before = tasks()
        same = [bool((hider.render(v, f, width=200, height=150, threads=t)[0] == want).all())
                for t in (3, 2, 1, 3)]
        print("three", tasks() - before, all(same))
        seen = []
        t = threading.Thread(target=lambda: seen.append(
            bool((hider.render(v, f, width=200, height=150, threads=2)[0] == want).all())))
        t.start()
        t.join()
        print("other", seen)
    """))
    tests = str(pathlib.Path(__file__).parent)
    proc = subprocess.run([sys.executable, str(script), tests], capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.split("\n")[:3] == ["two 1 True", "three 3 True", "other [True]"], \
        (proc.stdout, proc.stderr)
