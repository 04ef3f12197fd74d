"""The atlas options as the library declares them (intrinsic atlas_option_table) are what every
Python shell offers: intrinsic.atlas's keywords, the batch runner's flags and the Blender add-on's
properties; the generated files are current; messages name keywords."""
import inspect
import os
import subprocess
import sys

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
