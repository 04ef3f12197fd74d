"""Intrinsic parameterizations of surface meshes (Desbrun, Meyer, Alliez 2002).

The Python face of the Intrinsic library: the same pipeline, options, reports
and error messages as the ``intrinsic`` command line (docs/python.md).

    import intrinsic
    V, F = intrinsic.read_mesh("face.obj")          # float64 n x 3, int32 m x 3
    r = intrinsic.parameterize(V, F, method="conformal", boundary="circle")
    r.uv                                            # n x 2 float64
    r.report["angle_distortion"]["mean"]            # the CLI's --report, as a dict
    img = intrinsic.render(V, F, r.uv, mode="checker", size=(512, 512))

Errors raise ``intrinsic.Error`` subclasses: ``UsageError`` (exit code 1;
also a ``ValueError``), ``InputError`` (2), ``NumericalError`` (3),
``OutputError`` (4), with the message the command line prints after
``intrinsic: error:``. A file that cannot be opened, read or written raises
a class that is also the matching ``OSError``: ``InputFileNotFoundError`` is
an ``InputError`` and a ``FileNotFoundError``; likewise ``...PermissionError``,
``...IsADirectoryError``, ``...NotADirectoryError``, ``...OSError``, each for
``Input`` and ``Output``.

Choices are enums as well as strings: ``intrinsic.Method.CONFORMAL``,
``intrinsic.SolverKind.EIGEN_LLT`` (``.option`` is the string, "eigen-llt").
``python3 -m intrinsic`` runs the command line (bundled by ``pip install``).

Arrays: a C-contiguous float64 V / int32 F is read in place (no conversion
copy); other dtypes or layouts are converted once by numpy. The library
stores column-major Eigen matrices, so the data is then copied once into
them (the library's own validation copies it again). Returned arrays are new
C-contiguous arrays. The GIL is released while reading, validating,
assembling, factoring and solving, so threads run in parallel.
"""

from typing import Any, Tuple, Union

from . import _intrinsic
from ._intrinsic import (  # noqa: F401  (re-exported)
    Atlas,
    AtlasScope,
    InstanceMode,
    BasisMode,
    BoundaryEditor,
    BoundaryEnergy,
    BoundaryShape,
    Descent,
    Error,
    GradientRoute,
    HoleRule,
    InputError,
    InputFileNotFoundError,
    InputIsADirectoryError,
    InputNotADirectoryError,
    InputOSError,
    InputPermissionError,
    LambdaEnergy,
    Method,
    NumericalError,
    OutputError,
    OutputFileNotFoundError,
    OutputIsADirectoryError,
    OutputNotADirectoryError,
    OutputOSError,
    OutputPermissionError,
    Parameterizer,
    Result,
    ScaleMode,
    Segmentation,
    SolverKind,
    Spacing,
    UsageError,
    compute_tangents,
    metrics,
    read_mesh,
    render,
    transfer_texture,
    write_atlas,
    write_mesh,
)

# atlas() and parameterize(): one keyword per option of the library's atlas
# and param option tables, generated from them (scripts/generate_option_code.py).
from ._atlas_keywords import atlas
from ._param_keywords import parameterize

__version__ = _intrinsic.__version__

_ERRORS = (
    "Error", "UsageError", "InputError", "NumericalError", "OutputError",
    "InputFileNotFoundError", "InputPermissionError", "InputIsADirectoryError", "InputNotADirectoryError",
    "InputOSError", "OutputFileNotFoundError", "OutputPermissionError", "OutputIsADirectoryError",
    "OutputNotADirectoryError", "OutputOSError",
)
_ENUMS = (
    "Method", "BoundaryShape", "Spacing", "ScaleMode", "HoleRule", "SolverKind", "LambdaEnergy", "BoundaryEnergy",
    "GradientRoute", "Descent", "Segmentation", "BasisMode", "AtlasScope", "InstanceMode",
)
__all__ = [
    *_ERRORS, *_ENUMS, "Atlas", "BoundaryEditor", "Parameterizer", "Result", "metrics", "optimal_lambda",
    "optimize_boundary", "parameterize", "read_mesh", "render", "write_atlas", "write_mesh", "atlas",
    "transfer_texture", "compute_tangents",
]


def optimal_lambda(V: Any, F: Any = None, energy: Union[str, LambdaEnergy] = "edge",
                   lambda_range: Tuple[float, float] = (0.0, 1.0), **options: Any) -> Result:
    """The map lambda*conformal + (1-lambda)*authalic with the lambda that
    minimises the edge-length (``energy="edge"``) or area distortion, exactly
    (paper 5.1; ``intrinsic param --optimize-lambda``). ``options`` as
    :func:`parameterize` (boundary, spacing, scale, holes, solver, ...; not
    method, lam or mu). ``result.report["optimal_lambda"]`` holds lambda*,
    E(lambda*), E(0), E(1) and the polynomial; ``result.report["lambda"]`` too.
    """
    return parameterize(V, F, optimize_lambda=energy, lambda_range=lambda_range, **options)


def optimize_boundary(V: Any, F: Any = None, energy: Union[str, BoundaryEnergy] = "edge",
                      **options: Any) -> Result:
    """Moves every boundary vertex to minimise the edge-length, area or
    symmetric Dirichlet (``energy="dirichlet"``) distortion, the interior
    following the chosen intrinsic map (paper 5.2; ``intrinsic param
    --optimize-boundary``). ``options`` as :func:`parameterize`, including
    ``iterations``, ``tolerance``, ``gradient``, ``descent``.
    ``result.report["boundary_optimization"]`` holds the energy history.
    """
    return parameterize(V, F, optimize_boundary=energy, **options)
