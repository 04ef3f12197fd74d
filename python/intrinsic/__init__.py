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


def atlas(
    V: Any,
    F: Any = None,
    *,
    padding: Optional[float] = None,
    resolution: Optional[int] = None,
    max_normal_deviation: Optional[float] = None,
    min_chart_faces: Optional[int] = None,
    max_stretch: Optional[float] = None,
    max_face_stretch: Optional[float] = None,
    hard_angle: Optional[float] = None,
    isometric_iterations: Optional[int] = None,
    max_charts: Optional[int] = None,
    weld: Optional[float] = None,
    reorient: Optional[bool] = None,
    atlas_stretch_budget: Optional[bool] = None,
    seams: Any = None,
    face_groups: Any = None,
    scope: Union[None, str, AtlasScope] = None,
    boundary: Union[None, str, BoundaryShape] = None,
    method: Union[None, str, Method] = None,
    lambda_: Optional[float] = None,
    mu: Optional[float] = None,
    optimize_lambda: Union[None, str, LambdaEnergy] = None,
    optimize_boundary: Union[None, str, BoundaryEnergy] = None,
    max_vertices: Optional[int] = None,
    uv_set: Optional[int] = None,
    replace_used_set: Optional[bool] = None,
    transfer_textures: Optional[bool] = None,
    texture_size: Optional[int] = None,
    texture_padding: Optional[int] = None,
    instances: Union[None, str, InstanceMode] = None,
    texels_per_unit: Optional[float] = None,
    max_pages: Optional[int] = None,
    allow_missing_images: Optional[bool] = None,
    pack_only: Optional[bool] = None,
    keep_overlaps: Optional[bool] = None,
    uv: Any = None,
    uv_index: Any = None,
) -> Atlas:
    """`intrinsic atlas` on arrays (V n x 3 float64, F m x 3 int32) or a mesh file (atlas(path)).

    Any triangle mesh (closed, higher genus, several components, non-manifold bits, zero-area faces) is
    cut into disk charts, each flattened by the paper's natural conformal map, and packed into [0,1]^2
    with `padding` texels (of a `resolution`-wide texture) between charts, without flipped or
    overlapping triangles. Returns an Atlas: uv (k x 2), uv_index (#F x 3, per face corner a row of
    uv), face_chart (#F, -1 for degenerate faces), V, F (the input, unchanged) and report (the
    command line's report as a dict). write_atlas(path, atlas) writes the command line's .obj or .glb.
    As on the command line (an option left out takes the library's default, as `intrinsic atlas`
    prints with --help): each chart is split while 5% of its surface is stretched or shrunk by more
    than `max_stretch` (per face max(s1, 1/s2)) or any face by more than `max_face_stretch`, and
    neighbours are merged within both; `hard_angle` (degrees, 0: none) makes sharper edges seams;
    `isometric_iterations` refines each natural map toward an isometry; `max_charts` (0: no limit)
    merges further; `weld` merges vertices closer than that fraction of the bounding box diagonal
    for the computation only; `seams`, a seams file's path or k x 2 vertex indices, cuts exactly
    those edges; `reorient=False` keeps the winding of faces listed against their piece (cut there)
    instead of writing them reversed; `atlas_stretch_budget=False` keeps every chart within
    `max_stretch` (`--per-chart-stretch`). `face_groups` (#F ints, -1: none) keeps faces of one
    group in one chart, e.g. the triangles of each polygon of a host that stores one UV per polygon
    corner; the report's "split_groups" counts groups that could not be kept whole. `scope="per-mesh"`
    (`--atlas per-mesh`) gives each glTF mesh or OBJ object its own atlas in [0,1]^2.
    Each chart's map: the natural conformal map by default; `boundary="circle"` or `"square"` fixes
    the chart's boundary, with `method`/`lambda_`/`mu` weights and optionally `optimize_lambda`
    ("edge" | "area") or `optimize_boundary` ("edge" | "area" | "dirichlet"), as `parameterize`.
    How write_atlas writes it: `uv_set` (glTF input: the TEXCOORD_n the atlas goes to, `--uv-set`),
    `replace_used_set`, and `transfer_textures=True` (`--transfer-textures`, docs/textures.md): the
    textures reading the replaced set are baked into the new layout, `texture_size` texels a side
    (0: each source's density), `texture_padding` texels of dilation; `allow_missing_images=True`
    writes even when an image or material file the input names is missing (`--allow-missing-images`).
    `texels_per_unit` (`--texels-per-unit`, lightmaps): every chart at that many texels per unit of
    surface length on pages of `resolution` texels (UDIM: page k at u in [k, k+1]), at most
    `max_pages` (0: no limit); the report lists "pages", "page_utilization" and "chart_page".
    `pack_only=True` (`--pack-only`) re-packs the input's own UVs (charts kept, quarter turns, one
    scale): a file's, or with arrays `uv` (k x 2) and `uv_index` (#F x 3 rows of uv, as an Atlas
    gives them); `keep_overlaps=True` leaves input charts that overlap each other on each other.
    `instances` (`--instances`): "shared" (default) charts a mesh several nodes draw once, "unique"
    gives each instance its own charts (docs/formats.md "Instances").
    Raises UsageError for bad options and InputError for unreadable or invalid input.
    """
    given = dict(padding=padding, resolution=resolution, max_normal_deviation=max_normal_deviation,
                 min_chart_faces=min_chart_faces, max_stretch=max_stretch, max_face_stretch=max_face_stretch,
                 hard_angle=hard_angle, isometric_iterations=isometric_iterations, max_charts=max_charts,
                 weld=weld, reorient=reorient, atlas_stretch_budget=atlas_stretch_budget, seams=seams,
                 face_groups=face_groups, scope=scope,
                 boundary=boundary, method=method, optimize_lambda=optimize_lambda,
                 optimize_boundary=optimize_boundary, max_vertices=max_vertices, mu=mu, uv_set=uv_set,
                 replace_used_set=replace_used_set, transfer_textures=transfer_textures,
                 texture_size=texture_size, texture_padding=texture_padding, instances=instances,
                 allow_missing_images=allow_missing_images, texels_per_unit=texels_per_unit,
                 max_pages=max_pages, pack_only=pack_only, keep_overlaps=keep_overlaps, uv=uv,
                 uv_index=uv_index)
    given["lambda"] = lambda_
    return _intrinsic.atlas(V, F, **{k: v for k, v in given.items() if v is not None})
