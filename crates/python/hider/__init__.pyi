"""Type stubs of ``hider`` (checked against the package by mypy's stubtest
in CI)."""

import os
from collections.abc import Sequence
from typing import Any, Literal, NamedTuple, overload

import numpy as np
import numpy.typing as npt

__all__ = ["render", "visible_faces", "plan", "Plan", "algorithms", "svg", "AUTO",
           "DEFAULT_ALGO", "KINDS", "OUTPUTS", "CONVENTIONS"]

__version__: str

DEFAULT_ALGO: str
AUTO: str
KINDS: tuple[str, ...]
OUTPUTS: tuple[str, ...]
CONVENTIONS: tuple[str, ...]

_Kind = Literal["exact", "approximate", "multisample", "reference"]
_Point = npt.ArrayLike | None
_Output = Literal["ids", "depth", "distance", "z", "barycentrics", "normals", "vertex_normals"]
_Convention = Literal["opengl", "opencv"]

def __dir__() -> list[str]: ...
def algorithms(kind: _Kind | None = None) -> list[str]: ...

class Plan(NamedTuple):
    algo: str
    reason: str
    summary: str

@overload
def render(
    vertices: npt.ArrayLike, faces: npt.ArrayLike, *, width: int, height: int,
    eye: _Point = None, target: _Point = None, up: _Point = None, fovy: float | None = None,
    near: float | None = None, far: float | None = None, pose: npt.ArrayLike | None = None,
    convention: _Convention | None = None, intrinsics: npt.ArrayLike | None = None,
    orthographic: float | None = None, normals: npt.ArrayLike | None = None,
    outputs: None = None, algo: str = ..., threads: int = 1, timeout: float | None = None,
) -> tuple[npt.NDArray[np.int32], npt.NDArray[np.float32]]: ...
@overload
def render(
    vertices: npt.ArrayLike, faces: npt.ArrayLike, *, width: int, height: int,
    eye: _Point = None, target: _Point = None, up: _Point = None, fovy: float | None = None,
    near: float | None = None, far: float | None = None, pose: npt.ArrayLike | None = None,
    convention: _Convention | None = None, intrinsics: npt.ArrayLike | None = None,
    orthographic: float | None = None, normals: npt.ArrayLike | None = None,
    outputs: Sequence[_Output], algo: str = ..., threads: int = 1,
    timeout: float | None = None,
) -> tuple[npt.NDArray[Any], ...]: ...
def plan(
    vertices: npt.ArrayLike, faces: npt.ArrayLike, *, width: int, height: int,
    eye: _Point = None, target: _Point = None, up: _Point = None, fovy: float | None = None,
    near: float | None = None, far: float | None = None, pose: npt.ArrayLike | None = None,
    convention: _Convention | None = None, intrinsics: npt.ArrayLike | None = None,
    orthographic: float | None = None, threads: int = 1,
) -> Plan: ...
def visible_faces(
    vertices: npt.ArrayLike, faces: npt.ArrayLike, *, width: int, height: int,
    eye: _Point = None, target: _Point = None, up: _Point = None, fovy: float | None = None,
    near: float | None = None, far: float | None = None, pose: npt.ArrayLike | None = None,
    convention: _Convention | None = None, intrinsics: npt.ArrayLike | None = None,
    orthographic: float | None = None, algo: str = ..., threads: int = 1,
    timeout: float | None = None,
) -> npt.NDArray[np.bool_]: ...
def svg(
    vertices: npt.ArrayLike, faces: npt.ArrayLike, path: str | os.PathLike[str], *, width: int,
    height: int, eye: _Point = None, target: _Point = None, up: _Point = None,
    fovy: float | None = None, near: float | None = None, far: float | None = None,
    pose: npt.ArrayLike | None = None, convention: _Convention | None = None,
    intrinsics: npt.ArrayLike | None = None, orthographic: float | None = None,
    mode: Literal["regions", "lines"] = "regions", crease_angle: float = 30.0,
    stroke_width: float = 1.0, stroke_mm: float | None = None,
    page_mm: tuple[float, float] | None = None, hidden: Literal["none", "dashed"] = "none",
    background: str | None = None, seams: bool = True, timeout: float | None = None,
) -> None: ...
