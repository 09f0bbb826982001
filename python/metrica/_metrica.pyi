# Types of the extension module metrica._metrica (python/src), for type
# checkers and editors; the package's own functions are typed by their
# source. Arrays: points float64 (n, 3), tets (m, 4), triangles (k, 3),
# ids int, metrics float64 (n, 6) in libMeshb's order (xx, xy, yy, xz, yz, zz).
from os import PathLike
from typing import Any, Callable, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

_Path = Union[str, PathLike[str]]
_Array = npt.ArrayLike
_Floats = npt.NDArray[np.float64]
_Ints = npt.NDArray[np.int64]

class InputError(ValueError): ...

class Mesh:
    def __init__(
        self,
        points: _Array,
        tets: _Array,
        triangles: Optional[_Array] = None,
        triangle_ids: Optional[_Array] = None,
        tet_ids: Optional[_Array] = None,
        *,
        ridge_angle: Optional[float] = None,
    ) -> None: ...
    @property
    def points(self) -> _Floats: ...
    @property
    def tets(self) -> _Ints: ...
    @property
    def triangles(self) -> _Ints: ...
    @property
    def triangle_ids(self) -> _Ints: ...
    @property
    def tet_ids(self) -> _Ints: ...
    @property
    def num_vertices(self) -> int: ...
    @property
    def num_tets(self) -> int: ...
    def check(self) -> None: ...
    def info(self) -> dict[str, Any]: ...
    def __copy__(self) -> Mesh: ...
    def __deepcopy__(self, memo: dict[int, Any]) -> Mesh: ...

def box(
    n: Union[int, Sequence[int]] = 3,
    lo: Sequence[float] = (0.0, 0.0, 0.0),
    hi: Sequence[float] = (1.0, 1.0, 1.0),
) -> Mesh: ...
def read(path: _Path, *, ridge_angle: Optional[float] = None) -> Mesh: ...
def write(
    mesh: Mesh,
    path: _Path,
    version: int = 0,
    binary: bool = False,
    metric: Optional[_Array] = None,
    fields: Optional[dict[str, _Array]] = None,
) -> None: ...
def read_field(path: _Path) -> list[_Floats]: ...
def write_field(path: _Path, values: _Array, version: int = 0) -> None: ...
def analytic_metric(mesh: Mesh, name: str, hmin: Optional[float] = None, hmax: Optional[float] = None) -> _Floats: ...
def analytic_field(mesh: Mesh, name: str) -> _Floats: ...
def multiscale_metric(
    mesh: Mesh,
    field: _Array,
    complexity: float,
    norm: float = 2.0,
    gradation: Optional[float] = None,
    hmin: Optional[float] = None,
    hmax: Optional[float] = None,
    max_anisotropy: Optional[float] = None,
) -> _Floats: ...
def hessian(mesh: Mesh, field: _Array) -> _Floats: ...
def hessian_metric(
    mesh: Mesh,
    hessian: _Array,
    complexity: float,
    norm: float = 2.0,
    gradation: Optional[float] = None,
    hmin: Optional[float] = None,
    hmax: Optional[float] = None,
    max_anisotropy: Optional[float] = None,
) -> _Floats: ...
def intersect(a: _Array, b: _Array) -> _Floats: ...
def complexity(mesh: Mesh, metric: _Array) -> float: ...
def interpolate(mesh: Mesh, field: _Array, to_mesh: Mesh, metric: bool = False) -> _Floats: ...
def error(
    mesh: Mesh,
    values: _Array,
    exact: Union[None, str, Callable[[_Floats], _Array]] = None,
    reference: Optional[Mesh] = None,
    reference_values: Optional[_Array] = None,
) -> float: ...
def quality(
    mesh: Mesh,
    metric: _Array,
    space: str = "log-euclidean",
    measures: bool = True,
    metric_mesh: Optional[Mesh] = None,
) -> dict[str, Any]: ...
def _adapt_settings() -> list[Tuple[str, str, float, str]]: ...
def _pipeline_rules() -> list[Tuple[str, str, float, str]]: ...
def _stage_kinds() -> list[Tuple[str, str, list[Tuple[str, str, str]]]]: ...
def _adapt(*args: Any) -> Tuple[Optional[Mesh], dict[str, Any]]: ...
def _run_pipeline(*args: Any) -> Tuple[Mesh, dict[str, Any]]: ...
