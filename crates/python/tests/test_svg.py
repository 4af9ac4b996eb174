"""hider.svg: the exact vector drawings of a mesh, with the command line's
vector flags as keywords."""

import re

import numpy as np
import pytest

import hider


def cube():
    v = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], dtype=float)
    quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    f = [t for a, b, c, d in quads for t in ((a, b, c), (a, c, d))]
    return v, np.array(f)


def test_regions_and_lines_are_written_with_their_options(tmp_path):
    v, f = cube()
    regions = tmp_path / "r.svg"
    hider.svg(v, f, regions, width=128, height=96, eye=(3, 2, 4), mode="regions",
              background="white")
    text = regions.read_text()
    assert text.startswith("<?xml") or text.startswith("<svg")
    assert 'width="128"' in text and 'height="96"' in text
    assert "white" in text  # the background asked for
    assert text.count("<path") >= 3  # three faces of the cube are seen

    lines = tmp_path / "l.svg"
    hider.svg(v, f, lines, width=128, height=96, eye=(3, 2, 4), mode="lines",
              hidden="dashed", stroke_width=2.5)
    text = lines.read_text()
    assert "stroke-dasharray" in text  # the hidden edges, dashed
    assert re.search(r'stroke-width="2\.5', text), text[:400]
    plain = tmp_path / "p.svg"
    hider.svg(v, f, plain, width=128, height=96, eye=(3, 2, 4), mode="lines")
    assert "stroke-dasharray" not in plain.read_text()


def test_bad_keywords_are_value_errors(tmp_path):
    v, f = cube()
    with pytest.raises(ValueError, match="mode must be 'regions' or 'lines'"):
        hider.svg(v, f, tmp_path / "x.svg", width=32, height=32, mode="pieces")
    with pytest.raises(ValueError, match="hidden must be"):
        hider.svg(v, f, tmp_path / "x.svg", width=32, height=32, hidden="dotted")
    with pytest.raises(ValueError, match="crease"):
        hider.svg(v, f, tmp_path / "x.svg", width=32, height=32, crease_angle=500)
    assert not (tmp_path / "x.svg").exists()


def polyline_points(path):
    """Every polyline corner of an SVG file, (n, 2) pixels."""
    corners = [c.split(",") for points in re.findall(r'points="([^"]*)"', path.read_text())
               for c in points.split()]
    assert corners, path.read_text()[:400]
    return np.array(corners, dtype=float)


def test_the_pose_intrinsics_and_orthographic_cameras_reach_the_drawing(tmp_path):
    """The cube seen straight down its +z face: orthographic, the face is a
    square centred in the picture; with intrinsics whose principal point
    is off centre, the drawing moves with it."""
    v, f = cube()
    pose = np.eye(4)
    pose[2, 3] = 5.0  # OpenGL: at z = 5 looking down -z
    ortho = tmp_path / "o.svg"
    hider.svg(v, f, ortho, width=100, height=100, pose=pose, convention="opengl",
              orthographic=2.0, mode="lines")
    pts = polyline_points(ortho)
    # Half height 2 over 50 pixels: the unit square spans pixels 25 to 75.
    assert pts.min() == pytest.approx(25, abs=0.01) and pts.max() == pytest.approx(75, abs=0.01)
    shifted = tmp_path / "s.svg"
    hider.svg(v, f, shifted, width=100, height=100, pose=pose, convention="opengl",
              intrinsics=(100, 100, 30, 50), mode="lines")
    pts = polyline_points(shifted)
    # The near face (z = 1, 4 units away) spans 100 / 4 = 25 pixels each
    # side of the principal point (30, 50).
    assert pts[:, 0].min() == pytest.approx(5, abs=0.01)
    assert pts[:, 0].max() == pytest.approx(55, abs=0.01)
