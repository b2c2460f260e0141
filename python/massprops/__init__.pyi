import os
from typing import Any, Dict, List, Optional, Sequence, Tuple

import numpy
from numpy.typing import ArrayLike, NDArray

from ._core import dynamics as dynamics

__version__: str
__all__ = ["load", "mass_properties", "fill", "Result", "dynamics", "body", "resting_poses", "drop_batch", "main"]

class Result:
    volume: float
    mass: float
    density: float
    center_of_mass: NDArray[numpy.float64]
    inertia_com: NDArray[numpy.float64]
    principal_moments: NDArray[numpy.float64]
    principal_axes: NDArray[numpy.float64]
    surface_area: float
    physically_valid: bool
    warnings: List[str]
    mesh: Dict[str, Any]
    unit: str
    model: str
    source: str
    part: Optional[str]
    instance: Optional[str]
    declared_unit: Optional[str]
    parts: List["Result"]
    brep: Optional[Dict[str, Any]]
    density_source: Optional[str]
    standard_errors: Optional[Dict[str, Any]]
    def __init__(self, record: Dict[str, Any], redo: Any = None, part_of: bool = False) -> None: ...
    def inertia_about(self, point: ArrayLike) -> NDArray[numpy.float64]: ...
    def picture(self, path: str | os.PathLike[str]) -> None: ...
    def to_dict(self) -> Dict[str, Any]: ...
    def __eq__(self, other: object) -> bool: ...
    def __getstate__(self) -> Dict[str, Any]: ...
    def __setstate__(self, record: Dict[str, Any]) -> None: ...

def load(path: str, **options: Any) -> Result: ...
def fill(
    path: str,
    output: Optional[str] = ...,
    *,
    density: float = ...,
    densities: Optional[Dict[str, Any]] = ...,
    keep_mass: bool = ...,
    source: str = ...,
    packages: Optional[Dict[str, str]] = ...,
    repair: bool = ...,
    allow_open: bool = ...,
) -> Tuple[Dict[str, Any], str]: ...
def mass_properties(vertices: Any, faces: Any = ..., *, name: str = ..., **options: Any) -> Result: ...
def body(result: Result) -> dynamics.RigidBody: ...
def drop_batch(path: str, first: int, count: int, **options: Any) -> List[Tuple[int, float]]: ...
def resting_poses(
    path: str, drops: int = ..., *, client: Any = ..., drops_per_task: int = ..., **options: Any
) -> Dict[str, Any]: ...
def main(argv: Optional[Sequence[str]] = ...) -> int: ...
