"""The atlas and param options as the library declares them (atlas_option_table,
param_option_table) are what every Python shell offers: intrinsic.atlas's and
intrinsic.parameterize's keywords, the batch runner's flags and the Blender add-on's properties;
the generated files are current; messages name keywords."""
import inspect
import json
import os
import subprocess
import sys

import numpy as np
import pytest

import intrinsic
from intrinsic import _intrinsic

from conftest import cli_path  # noqa: E402

ROOT = os.environ.get("INTRINSIC_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
ARRAYS = {"face_groups", "uv", "uv_index"}


def table():
    return _intrinsic.atlas_option_table()


def test_generated_code_is_current():
    module_dir = os.path.dirname(os.path.dirname(intrinsic.__file__))
    r = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "generate_option_code.py"), "--check",
                        "--module-dir", module_dir], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


def test_atlas_keywords_are_the_table():
    params = inspect.signature(intrinsic.atlas).parameters
    names = set(params) - {"V", "F"}
    expected = set()
    for o in table():
        name = o["key"] if o["key"].isidentifier() and o["key"] != "lambda" else o["aliases"][0]
        expected.add(name)
    assert names == expected | ARRAYS
    assert all(params[n].default is None for n in names)


def test_table_entries_are_well_formed():
    seen = set()
    for o in table():
        assert o["flag"].startswith("--") and o["flag"] not in seen
        seen.add(o["flag"])
        assert o["type"] in ("bool", "int", "float", "choice", "path")
        assert not o["repeated"] and not o["value_name"]
        assert o["help"]
        if o["type"] == "choice":
            assert o["choices"] and (o["default"] is None or o["default"] in o["choices"])
        if o["default"] is not None and o["type"] in ("int", "float"):
            assert (o["min"] is None or o["min"] <= o["default"]) and (o["max"] is None or o["default"] <= o["max"])


def test_keyword_ranges_and_types_name_the_keyword():
    V = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
    F = [[0, 1, 2]]
    with pytest.raises(intrinsic.UsageError, match=r"max_stretch: 0.5 is not in \[1, 100\]"):
        intrinsic.atlas(V, F, max_stretch=0.5)
    with pytest.raises(intrinsic.UsageError, match="min_chart_faces: expected int, got float"):
        intrinsic.atlas(V, F, min_chart_faces=2.5)
    with pytest.raises(intrinsic.UsageError, match="scope: 'all' is not one of whole, per-mesh"):
        intrinsic.atlas(V, F, scope="all")
    with pytest.raises(intrinsic.UsageError, match="unknown option 'stretch'"):
        _intrinsic.atlas(V, F, stretch=1.2)
    # an enum value is its name
    a = intrinsic.atlas(V, F, scope=intrinsic.AtlasScope.WHOLE, padding=0)
    assert a.report["charts"] == 1


def test_texture_transfer_messages_name_keywords(tmp_path):
    glb = tmp_path / "in.glb"
    r = subprocess.run([cli_path(), "generate", "textured", "-o", str(glb)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with pytest.raises(intrinsic.UsageError, match="transfer_textures replaces the set the textures read: "
                                                    "add uv_set N"):
        intrinsic.atlas(glb, transfer_textures=True)
    with pytest.raises(intrinsic.UsageError, match=r"texture_size: 99999 is not in \[0, 16384\]"):
        intrinsic.atlas(glb, transfer_textures=True, uv_set=0, texture_size=99999)


def test_batch_offers_every_atlas_option():
    r = subprocess.run([sys.executable, "-m", "intrinsic.batch", "--help"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    for o in table():
        if o["key"] != "seams":  # the edges of one mesh
            assert o["flag"] in r.stdout, o["flag"]


def test_addon_properties_follow_the_table():
    sys.path.insert(0, os.path.join(ROOT, "blender", "intrinsic_uv"))
    try:
        import atlas_option_props
    finally:
        sys.path.pop(0)
    by_key = {o["key"]: o for o in table()}
    for prop, key in (("max_stretch", "max_stretch"), ("texel_density", "texels_per_unit"),
                      ("resolution", "resolution")):
        args = atlas_option_props.OPTION_PROPS[prop]
        assert args["default"] == by_key[key]["default"]
        assert args["min"] == by_key[key]["min"]
        assert args["description"] == by_key[key]["help"]


# ---- the param job ----------------------------------------------------------------------------

def param_table():
    return _intrinsic.param_option_table()


def python_name(o):
    return o["key"] if o["key"].isidentifier() and o["key"] != "lambda" else o["aliases"][0]


def test_param_keywords_are_the_table():
    params = inspect.signature(intrinsic.parameterize).parameters
    names = set(params) - {"V", "F", "kwargs"}
    assert names == {python_name(o) for o in param_table()} | {"verbose"}
    assert all(params[n].default is None for n in names)
    assert params["kwargs"].kind == inspect.Parameter.VAR_KEYWORD  # lam, **{"lambda": x}


def test_param_table_entries_are_well_formed():
    flags = [o["flag"] for o in param_table()]
    assert len(set(flags)) == len(flags) and all(f.startswith("--") for f in flags)
    kinds = {o["key"]: o["type"] for o in param_table()}
    assert kinds["boundary"] == "choice or path" and kinds["lambda_range"] == "pair" and kinds["pins"] == "str"
    by_key = {o["key"]: o for o in param_table()}
    assert by_key["pins"]["repeated"] and by_key["pins"]["flag"] == "--pin" and "pin" in by_key["pins"]["aliases"]
    assert by_key["lambda_range"]["default"] == (0.0, 1.0)
    assert {o["key"] for o in param_table() if o["group"] == "Optimizers"} == {
        "optimize_lambda", "lambda_range", "optimize_boundary", "iterations", "tolerance", "gradient", "descent"}


def test_param_keywords_equal_the_command_line(tmp_path):
    """Each value spelled as Python gives it lands where the flag does: the map equals the CLI's."""
    mesh = tmp_path / "wave.obj"
    r = subprocess.run([cli_path(), "generate", "wave", "--rings", "8", "-o", str(mesh)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    out, report = tmp_path / "out.obj", tmp_path / "r.json"
    r = subprocess.run([cli_path(), "param", str(mesh), "-o", str(out), "--report", str(report), "-q",
                        "--boundary", "natural", "--pin", "0:0,0", "--pin", "5:1.5,0.25", "--scale", "surface",
                        "--solver", "eigen-llt", "--max-residual", "1e-9"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    py = intrinsic.parameterize(mesh, boundary=intrinsic.BoundaryShape.NATURAL, pins=[(0, 0, 0), "5:1.5,0.25"],
                                scale="surface", solver=intrinsic.SolverKind.EIGEN_LLT, max_residual=1e-9)
    with open(report) as f:
        cli_report = json.load(f)
    for key in ("method", "boundary", "scale", "solver"):
        assert py.report[key] == cli_report[key], key
    with open(out) as f:  # one vt per vertex, in vertex order
        vt = np.array([[float(x) for x in line.split()[1:3]] for line in f if line.startswith("vt ")])
    assert vt.shape == py.uv.shape and np.allclose(vt, py.uv, rtol=0, atol=1e-12)
    assert np.allclose(py.uv[5], [1.5, 0.25], atol=1e-12) and np.allclose(py.uv[0], [0, 0], atol=1e-12)


def test_param_keyword_messages_name_the_keyword():
    V = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0.1]]
    F = [[0, 1, 2], [1, 3, 2]]
    with pytest.raises(intrinsic.UsageError, match=r"^max_vertices: 0 is not at least 1$"):
        intrinsic.parameterize(V, F, max_vertices=0)
    with pytest.raises(intrinsic.UsageError, match=r"^lambda_range: expected \(lo, hi\), got float$"):
        intrinsic.parameterize(V, F, optimize_lambda="edge", lambda_range=0.5)
    with pytest.raises(intrinsic.UsageError, match=r"^tolerance: expected float, got str$"):
        intrinsic.parameterize(V, F, optimize_boundary="edge", tolerance="small")
    with pytest.raises(intrinsic.UsageError, match=r"^unknown option 'optimize_lambda'$"):
        intrinsic.Parameterizer(V, F, optimize_lambda="edge")  # one fixed map: no optimizer
    with pytest.raises(intrinsic.UsageError, match=r"^optimize_lambda chooses the blend itself"):
        intrinsic.parameterize(V, F, optimize_lambda="edge", method="authalic")
    with pytest.raises(intrinsic.UsageError, match=r"^constraints cannot be combined with optimize_lambda"):
        intrinsic.parameterize(V, F, optimize_lambda="edge", constraints={"points": []})


def test_batch_offers_every_param_option():
    r = subprocess.run([sys.executable, "-m", "intrinsic.batch", "--help"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    for o in param_table():
        assert o["flag"] in r.stdout, o["flag"]
