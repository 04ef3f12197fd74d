"""intrinsic.atlas's lightmap and scene keywords (texels_per_unit, max_pages,
pack_only, keep_overlaps, instances, allow_missing_images) equal the command
line's flags: the same report and OBJ bytes, the same refusals."""
import json
import subprocess

import numpy as np
import pytest

import intrinsic

from conftest import cli_path, mesh  # noqa: E402


def run_cli(*args):
    return subprocess.run([cli_path(), *map(str, args)], capture_output=True, text=True)


def strip(report):
    return {k: v for k, v in report.items() if k not in ("timings_ms", "input", "output")}


def test_pages_equal_cli(tmp_path):
    path = str(mesh("genus2"))
    out, rep = str(tmp_path / "cli.obj"), str(tmp_path / "cli.json")
    r = run_cli("atlas", path, "-o", out, "--report", rep, "-q", "--texels-per-unit", "60", "--resolution", "256")
    assert r.returncode == 0, r.stderr
    a = intrinsic.atlas(path, texels_per_unit=60, resolution=256)
    mine = str(tmp_path / "py.obj")
    intrinsic.write_atlas(mine, a)
    assert open(mine, "rb").read() == open(out, "rb").read()
    assert strip(a.report) == strip(json.load(open(rep)))
    pages = a.report["pages"]
    assert pages >= 2 and len(a.report["page_utilization"]) == pages
    # Every chart inside its page's tile: u in [page, page + 1].
    page = np.array(a.report["chart_page"])[a.face_chart]
    u = a.uv[a.uv_index][:, :, 0]
    assert np.all(u >= page[:, None] - 1e-12) and np.all(u <= page[:, None] + 1 + 1e-12)


def test_max_pages_refused_like_the_cli(tmp_path):
    path = str(mesh("genus2"))
    with pytest.raises(intrinsic.InputError, match="pages"):
        intrinsic.atlas(path, texels_per_unit=60, resolution=256, max_pages=1)
    r = run_cli("atlas", path, "-o", tmp_path / "o.obj", "--texels-per-unit", "60", "--resolution", "256",
                "--max-pages", "1")
    assert r.returncode == 2 and "pages" in r.stderr


def test_pack_only_of_arrays_needs_uvs():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float64)
    F = np.array([[0, 1, 2]], dtype=np.int32)
    with pytest.raises(intrinsic.InputError, match="no texture coordinates"):
        intrinsic.atlas(V, F, pack_only=True)


def test_pack_only_of_a_file_keeps_chart_shapes(tmp_path):
    # An atlas OBJ (vt per corner) re-packed: every chart's edge vectors
    # are its input's turned by a quarter turn and scaled by one factor.
    first = str(tmp_path / "first.obj")
    intrinsic.write_atlas(first, intrinsic.atlas(str(mesh("torus"))))
    a = intrinsic.atlas(first, pack_only=True)
    r = run_cli("atlas", first, "-o", tmp_path / "cli.obj", "-q", "--pack-only")
    assert r.returncode == 0, r.stderr
    mine = str(tmp_path / "py.obj")
    intrinsic.write_atlas(mine, a)
    assert open(mine, "rb").read() == open(tmp_path / "cli.obj", "rb").read()
    assert a.report["overlapping"] == 0 and a.report["flipped"] == 0


def test_instances_keyword_is_checked():
    with pytest.raises(intrinsic.UsageError, match="instances"):
        intrinsic.atlas(str(mesh("torus")), instances="several")
    assert intrinsic.InstanceMode.UNIQUE is not None


def test_pack_only_of_arrays_equals_pack_only_of_the_file(tmp_path):
    # The arrays an Atlas gives (V, F, uv, uv_index) re-pack to the same
    # layout as the OBJ written from them.
    first = intrinsic.atlas(str(mesh("torus")))
    path = str(tmp_path / "first.obj")
    intrinsic.write_atlas(path, first)
    from_file = intrinsic.atlas(path, pack_only=True)
    from_arrays = intrinsic.atlas(first.V, first.F, uv=first.uv, uv_index=first.uv_index, pack_only=True)
    assert from_arrays.report["charts"] == from_file.report["charts"]
    assert np.allclose(from_arrays.uv[from_arrays.uv_index], from_file.uv[from_file.uv_index], atol=1e-6)
    with pytest.raises(intrinsic.UsageError, match="together"):
        intrinsic.atlas(first.V, first.F, uv=first.uv, pack_only=True)
