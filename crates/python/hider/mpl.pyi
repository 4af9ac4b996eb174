"""Type stubs of ``hider.mpl`` (checked against the module by mypy's
stubtest in CI)."""

from typing import Any, NamedTuple

import numpy as np
import numpy.typing as npt
from matplotlib.collections import PolyCollection
from matplotlib.axes import Axes

__all__ = ["resolve", "unresolve", "Resolved", "ResolveWarning", "Projected",
           "project", "zbuffer"]

def __dir__() -> list[str]: ...

class ResolveWarning(UserWarning): ...

class Projected(NamedTuple):
    points: npt.NDArray[np.float64]
    faces: npt.NDArray[np.int64]
    polygon: npt.NDArray[np.int64]
    collection: npt.NDArray[np.int64]
    facecolors: npt.NDArray[np.float64]
    collections: list[Any]
    size: tuple[int, int]

class Resolved(PolyCollection):
    sources: list[Any]
    line_sources: list[Any]
    marker_sources: list[Any]
    max_splits: int | None
    timeout: float | None
    pieces: int
    fallback: str | None
    def __init__(self, ax: Axes, sources: list[Any], lines: list[Any], markers: list[Any],
                 max_splits: int | None = None, timeout: float | None = None) -> None: ...
    def do_3d_projection(self) -> float: ...
    def draw(self, renderer: Any) -> None: ...

def project(ax: Axes, width: int | None = None, height: int | None = None) -> Projected: ...
def zbuffer(ax: Axes, algo: str = "zbuffer") -> tuple[npt.NDArray[np.int32],
                                                        npt.NDArray[np.float32]]: ...
def resolve(ax: Axes, *, max_splits: int | None = None,
            timeout: float | None = None) -> Resolved: ...
def unresolve(ax: Axes) -> None: ...
