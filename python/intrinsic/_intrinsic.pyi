# Type stubs of the compiled module intrinsic._intrinsic (pybind11; see
# python/src/). The package intrinsic/__init__.py re-exports these names.
from os import PathLike
from typing import Any, ClassVar, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, PathLike]
_Fixed = Sequence[Tuple[int, float, float]]

__version__: str

class Error(Exception):
    exit_code: ClassVar[int]

class UsageError(Error, ValueError): ...
class InputError(Error): ...
class NumericalError(Error): ...
class OutputError(Error): ...

# A file that could not be opened, read or written: errno is set.
class InputFileNotFoundError(InputError, FileNotFoundError): ...
class InputPermissionError(InputError, PermissionError): ...
class InputIsADirectoryError(InputError, IsADirectoryError): ...
class InputNotADirectoryError(InputError, NotADirectoryError): ...
class InputOSError(InputError, OSError): ...
class OutputFileNotFoundError(OutputError, FileNotFoundError): ...
class OutputPermissionError(OutputError, PermissionError): ...
class OutputIsADirectoryError(OutputError, IsADirectoryError): ...
class OutputNotADirectoryError(OutputError, NotADirectoryError): ...
class OutputOSError(OutputError, OSError): ...

# The choice enums (pybind11 enums; bind_enums.cpp). `option` is the command
# line's spelling of the member ("eigen-llt" for SolverKind.EIGEN_LLT).
# _Enum names what they share; it is not a class of the module.
class _Enum:
    def __init__(self, value: int) -> None: ...
    def __eq__(self, other: object) -> bool: ...
    def __ne__(self, other: object) -> bool: ...
    def __hash__(self) -> int: ...
    def __index__(self) -> int: ...
    def __int__(self) -> int: ...
    @property
    def name(self) -> str: ...
    @property
    def value(self) -> int: ...
    @property
    def option(self) -> str: ...

class Method(_Enum):
    CONFORMAL: ClassVar[Method]
    AUTHALIC: ClassVar[Method]
    MIXED: ClassVar[Method]
    TUTTE: ClassVar[Method]
    FLOATER: ClassVar[Method]
    __members__: ClassVar[Dict[str, Method]]

class BoundaryShape(_Enum):
    CIRCLE: ClassVar[BoundaryShape]
    SQUARE: ClassVar[BoundaryShape]
    GIVEN: ClassVar[BoundaryShape]
    NATURAL: ClassVar[BoundaryShape]
    __members__: ClassVar[Dict[str, BoundaryShape]]

class Spacing(_Enum):
    ARCLENGTH: ClassVar[Spacing]
    UNIFORM: ClassVar[Spacing]
    __members__: ClassVar[Dict[str, Spacing]]

class ScaleMode(_Enum):
    UNIT: ClassVar[ScaleMode]
    SURFACE: ClassVar[ScaleMode]
    __members__: ClassVar[Dict[str, ScaleMode]]

class HoleRule(_Enum):
    FILL: ClassVar[HoleRule]
    FREE: ClassVar[HoleRule]
    NATURAL: ClassVar[HoleRule]
    __members__: ClassVar[Dict[str, HoleRule]]

class SolverKind(_Enum):
    AUTO: ClassVar[SolverKind]
    CHOLMOD: ClassVar[SolverKind]
    UMFPACK: ClassVar[SolverKind]
    EIGEN_LLT: ClassVar[SolverKind]
    EIGEN_LU: ClassVar[SolverKind]
    CG: ClassVar[SolverKind]
    BICGSTAB: ClassVar[SolverKind]
    SUPERNODAL_LU: ClassVar[SolverKind]
    SUPERNODAL_CHOLESKY: ClassVar[SolverKind]
    __members__: ClassVar[Dict[str, SolverKind]]

class LambdaEnergy(_Enum):
    EDGE: ClassVar[LambdaEnergy]
    AREA: ClassVar[LambdaEnergy]
    __members__: ClassVar[Dict[str, LambdaEnergy]]

class BoundaryEnergy(_Enum):
    EDGE: ClassVar[BoundaryEnergy]
    AREA: ClassVar[BoundaryEnergy]
    DIRICHLET: ClassVar[BoundaryEnergy]
    __members__: ClassVar[Dict[str, BoundaryEnergy]]

class GradientRoute(_Enum):
    ADJOINT: ClassVar[GradientRoute]
    RESPONSES: ClassVar[GradientRoute]
    __members__: ClassVar[Dict[str, GradientRoute]]

class Descent(_Enum):
    LBFGS: ClassVar[Descent]
    GRADIENT: ClassVar[Descent]
    __members__: ClassVar[Dict[str, Descent]]

class Segmentation(_Enum):
    NORMAL_CONES: ClassVar[Segmentation]
    COMPONENTS: ClassVar[Segmentation]
    __members__: ClassVar[Dict[str, Segmentation]]

class BasisMode(_Enum):
    FULL: ClassVar[BasisMode]
    LAZY: ClassVar[BasisMode]
    __members__: ClassVar[Dict[str, BasisMode]]

class AtlasScope(_Enum):
    WHOLE: ClassVar[AtlasScope]
    PER_MESH: ClassVar[AtlasScope]
    __members__: ClassVar[Dict[str, AtlasScope]]

class InstanceMode(_Enum):
    SHARED: ClassVar[InstanceMode]
    UNIQUE: ClassVar[InstanceMode]
    __members__: ClassVar[Dict[str, InstanceMode]]

def read_mesh(path: _Path, max_vertices: int = ...) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int32]]: ...
def write_mesh(path: _Path, V: npt.ArrayLike, F: npt.ArrayLike, uv: Optional[npt.ArrayLike] = None,
               binary: bool = False) -> None: ...
def _view_address(array: npt.ArrayLike, cols: int, integer: bool = False) -> int: ...

class Result:
    @property
    def uv(self) -> npt.NDArray[np.float64]: ...
    @property
    def residual(self) -> float: ...
    @property
    def flipped_triangles(self) -> int: ...
    @property
    def timings(self) -> Dict[str, float]: ...
    @property
    def report(self) -> Dict[str, Any]: ...
    @property
    def V(self) -> npt.NDArray[np.float64]: ...
    @property
    def F(self) -> npt.NDArray[np.int32]: ...

def parameterize(V: Union[npt.ArrayLike, _Path], F: Optional[npt.ArrayLike] = None, **options: Any) -> Result: ...

class Parameterizer:
    def __init__(self, V: Union[npt.ArrayLike, _Path], F: Optional[npt.ArrayLike] = None, **options: Any) -> None: ...
    def solve(self) -> Result: ...
    def solve_with_boundary(self, fixed: _Fixed) -> Result: ...
    def set_boundary(self, fixed: _Fixed) -> None: ...
    def set_constraints(self, constraints: Union[Dict[str, Any], _Path]) -> None: ...
    def set_constraint_targets(self, targets: Sequence[Tuple[float, float]]) -> None: ...
    def clear_constraints(self) -> None: ...
    @property
    def boundary(self) -> List[Tuple[int, float, float]]: ...
    @property
    def free_vertices(self) -> int: ...
    @property
    def factorizations(self) -> int: ...
    @property
    def constraint_setups(self) -> int: ...

class BoundaryEditor:
    def __init__(self, parameterizer: Parameterizer, basis: str = "lazy", memory_budget: float = 2.0,
                 resolve_above: int = 64) -> None: ...
    def move(self, positions: _Fixed) -> npt.NDArray[np.float64]: ...
    @property
    def uv(self) -> npt.NDArray[np.float64]: ...
    @property
    def boundary(self) -> List[Tuple[int, float, float]]: ...
    @property
    def precompute_ms(self) -> float: ...
    @property
    def basis_bytes(self) -> int: ...
    @property
    def responses(self) -> int: ...
    @property
    def last_update(self) -> Dict[str, Any]: ...

def metrics(V: npt.ArrayLike, F: npt.ArrayLike, uv: npt.ArrayLike) -> Dict[str, Any]: ...
def render(V: npt.ArrayLike, F: npt.ArrayLike, uv: npt.ArrayLike, mode: str = "checker",
           size: Tuple[int, int] = (1024, 1024), view: Union[str, Tuple[float, float]] = "auto",
           path: Optional[_Path] = None, on_surface: bool = False,
           log: bool = False) -> Optional[npt.NDArray[np.uint8]]: ...

class Atlas:
    @property
    def uv(self) -> npt.NDArray[np.float64]: ...
    @property
    def uv_index(self) -> npt.NDArray[np.int32]: ...
    @property
    def face_chart(self) -> npt.NDArray[np.int32]: ...
    @property
    def report(self) -> Dict[str, Any]: ...
    @property
    def V(self) -> npt.NDArray[np.float64]: ...
    @property
    def F(self) -> npt.NDArray[np.int32]: ...

def atlas(V: Union[npt.ArrayLike, _Path], F: Optional[npt.ArrayLike] = None, **options: Any) -> Atlas: ...
def write_atlas(path: _Path, atlas: Atlas) -> Optional[Dict[str, Any]]: ...
def atlas_option_table() -> List[Dict[str, Any]]: ...


def transfer_texture(old_uv: npt.ArrayLike, new_uv: npt.ArrayLike, image: npt.ArrayLike, *, width: int = 2048,
                     height: int = 2048, role: str = "color", padding: int = 4, wrap_u: str = "repeat",
                     wrap_v: str = "repeat", supersample: int = 1, normals: Optional[npt.ArrayLike] = None,
                     old_tangents: Optional[npt.ArrayLike] = None,
                     new_tangents: Optional[npt.ArrayLike] = None) -> npt.NDArray[np.float32]: ...
def compute_tangents(position: npt.ArrayLike, normal: npt.ArrayLike, uv: npt.ArrayLike) -> npt.NDArray[np.float64]: ...
