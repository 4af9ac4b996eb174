"""Stubs of the compiled extension (see src/*.rs); the public API is the
``hider`` package's."""

from typing import final

import numpy as np
import numpy.typing as npt

__all__ = ["render", "algorithms", "algorithm_kinds", "__version__", "plan", "screen_render",
           "screen_pieces", "svg", "Cancel",
           "SigintCancels", "CATCHES_SIGINT",
           "forget_threads_after_fork"]
__version__: str

_Point = tuple[float, float, float] | None
_Vertices = npt.NDArray[np.float64] | npt.NDArray[np.float32]
_Faces = npt.NDArray[np.int64] | npt.NDArray[np.int32] | npt.NDArray[np.uint32]

_Pose = tuple[tuple[float, float, float, float], tuple[float, float, float, float],
              tuple[float, float, float, float], tuple[float, float, float, float]] | None
_Intrinsics = tuple[float, float, float, float] | None
_F32 = npt.NDArray[np.float32]

@final
class Cancel:
    def __init__(self) -> None: ...
    def cancel(self) -> None: ...
    def reset(self) -> None: ...
    def set_timeout(self, seconds: float | None) -> None: ...
    def cancelled(self) -> bool: ...

CATCHES_SIGINT: bool

@final
class SigintCancels:
    def __new__(cls, timeout: float | None) -> SigintCancels: ...
    def __enter__(self) -> Cancel: ...
    def __exit__(self, exc_type: type[BaseException] | None, exc: BaseException | None,
                 traceback: object) -> bool: ...

def render(
    vertices: _Vertices, faces: _Faces, width: int, height: int,
    eye: _Point, target: _Point, up: _Point, fovy: float | None, near: float | None,
    far: float | None, algo: str, threads: int, pose: _Pose = None,
    intrinsics: _Intrinsics = None, orthographic: float | None = None,
    normals: _Vertices | None = None,
    want: tuple[bool, bool, bool, bool, bool] = ..., cancel: Cancel | None = None,
) -> tuple[tuple[npt.NDArray[np.int32], _F32],
           tuple[_F32 | None, _F32 | None, _F32 | None, _F32 | None, _F32 | None]]: ...
def forget_threads_after_fork() -> None: ...
def algorithms() -> list[str]: ...
def algorithm_kinds() -> list[tuple[str, str, str]]: ...
def plan(
    vertices: _Vertices, faces: _Faces, width: int, height: int,
    eye: _Point, target: _Point, up: _Point, fovy: float | None, near: float | None,
    far: float | None, threads: int, pose: _Pose = None, intrinsics: _Intrinsics = None,
    orthographic: float | None = None, cancel: Cancel | None = None,
) -> tuple[str, str, str]: ...
def screen_render(
    points: npt.NDArray[np.float64], faces: npt.NDArray[np.int64], width: int, height: int,
    algo: str, cancel: Cancel | None = None,
) -> tuple[npt.NDArray[np.int32], npt.NDArray[np.float32]]: ...
def screen_pieces(
    points: npt.NDArray[np.float64], faces: npt.NDArray[np.int64], width: int, height: int,
    max_splits: int | None = None, translucent: npt.NDArray[np.bool_] | None = None,
    cancel: Cancel | None = None,
) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64], npt.NDArray[np.float64],
           npt.NDArray[np.bool_]]: ...
def svg(
    vertices: _Vertices, faces: _Faces, path: str, width: int, height: int,
    eye: _Point, target: _Point, up: _Point, fovy: float | None, near: float | None,
    far: float | None, mode: str, crease_angle: float, stroke_width: float,
    stroke_mm: float | None, page_mm: tuple[float, float] | None, hidden: str,
    background: str | None, seams: bool, pose: _Pose = None, intrinsics: _Intrinsics = None,
    orthographic: float | None = None, cancel: Cancel | None = None,
) -> None: ...
