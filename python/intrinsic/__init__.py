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

from os import PathLike
from typing import Any, Dict, Optional, Sequence, Tuple, Union

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

# atlas(): one keyword per option of the library's atlas option table,
# generated from it (scripts/generate_option_code.py).
from ._atlas_keywords import atlas

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

Path = Union[str, PathLike]


def parameterize(
    V: Any,
    F: Any = None,
    *,
    method: Union[str, Method] = "conformal",
    boundary: Union[Path, BoundaryShape] = "circle",
    lam: Optional[float] = None,
    lambda_: Optional[float] = None,
    mu: Optional[float] = None,
    spacing: Union[str, Spacing] = "arclength",
    scale: Union[str, ScaleMode] = "unit",
    holes: Union[str, HoleRule] = "fill",
    largest_component: bool = False,
    solver: Union[str, SolverKind] = "auto",
    pins: Optional[Sequence[Union[str, Tuple[int, float, float]]]] = None,
    max_residual: float = 1e-8,
    constraints: Union[None, Dict[str, Any], Path] = None,
    max_vertices: int = 50_000_000,
    optimize_lambda: Union[None, str, LambdaEnergy] = None,
    lambda_range: Tuple[float, float] = (0.0, 1.0),
    optimize_boundary: Union[None, str, BoundaryEnergy] = None,
    iterations: int = 200,
    tolerance: float = 1e-6,
    gradient: Union[str, GradientRoute] = "adjoint",
    descent: Union[str, Descent] = "lbfgs",
    verbose: bool = False,
    **kwargs: Any,
) -> Result:
    """Parameterize a mesh: ``intrinsic param`` without the files.

    ``V, F``: float64 n x 3 positions and int32 m x 3 faces, or ``V`` a mesh
    file path and ``F`` None (read exactly as the command line reads it; the
    report's ``input`` is then the path). Several components become charts
    laid out side by side, as on the command line.

    The keywords are the command line's long options with dashes as
    underscores (docs/cli.md); a choice is its string or the enum member
    (``method=intrinsic.Method.AUTHALIC`` is ``method="authalic"``):

    - ``method``: conformal | authalic | mixed | tutte | floater.
    - ``lam`` / ``lambda_`` (``lambda`` is a Python keyword; ``**{"lambda": x}``
      works too) and ``mu``: coefficients of ``mixed`` (--lambda, --mu).
    - ``boundary``: circle | square | natural | a boundary file path.
    - ``spacing`` (arclength | uniform), ``scale`` (unit | surface),
      ``holes`` (fill | free | natural), ``largest_component``.
    - ``solver``: auto | cholmod | umfpack | eigen-llt | eigen-lu | cg | bicgstab | supernodal-lu | supernodal-cholesky.
    - ``pins``: natural boundary, ``[(vertex, u, v), ...]`` or ``["V:U,V", ...]``.
    - ``max_residual``: NumericalError above this relative residual.
    - ``constraints``: a dict shaped like the JSON constraint file
      (``{"points": [...], "lines": [...]}``; messages then name it
      ``constraints``) or the path of such a file.
    - ``optimize_lambda`` (edge | area) with ``lambda_range``;
      ``optimize_boundary`` (edge | area | dirichlet) with ``iterations``,
      ``tolerance``, ``gradient``, ``descent``; ``verbose`` prints the boundary
      optimization's progress lines on standard error.

    Returns a :class:`Result`: ``uv`` (n x 2), ``residual``,
    ``flipped_triangles``, ``timings`` and ``report`` (the dict the command
    line's ``--report`` writes, built by the same code; ``output`` is None).
    Raises UsageError, InputError, NumericalError with the command line's
    messages.
    """
    options: Dict[str, Any] = dict(
        method=method, boundary=boundary, mu=mu, spacing=spacing, scale=scale, holes=holes,
        largest_component=largest_component, solver=solver, pins=pins, max_residual=max_residual,
        constraints=constraints, max_vertices=max_vertices, optimize_lambda=optimize_lambda,
        lambda_range=tuple(lambda_range), optimize_boundary=optimize_boundary, iterations=iterations,
        tolerance=tolerance, gradient=gradient, descent=descent, verbose=verbose)
    if lam is not None:
        options["lam"] = lam
    if lambda_ is not None:
        options["lambda_"] = lambda_
    options.update(kwargs)  # "lambda", or unknown keys (UsageError)
    return _intrinsic.parameterize(V, F, **options)


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
