"""intrinsic.atlas equals `intrinsic atlas`: same OBJ bytes, same report
(timings and paths aside), on a generated torus and on shared assets."""
import json
import subprocess

import numpy as np
import pytest

import intrinsic

from conftest import cli_path, shared_mesh  # noqa: E402


def run_cli(*args):
    return subprocess.run([cli_path(), *map(str, args)], capture_output=True, text=True)


def strip(report):
    return {k: v for k, v in report.items() if k not in ("timings_ms", "input", "output")}


@pytest.mark.parametrize("name", ["assets/teapot.obj", "assets/3holes.off", "cat_head.obj"])
def test_atlas_equals_cli(tmp_path, name):
    path = str(shared_mesh(name))
    out, rep = str(tmp_path / "cli.obj"), str(tmp_path / "cli.json")
    r = run_cli("atlas", path, "-o", out, "--report", rep, "-q", "--padding", "3")
    assert r.returncode == 0, r.stderr
    a = intrinsic.atlas(path, padding=3)
    mine = str(tmp_path / "py.obj")
    intrinsic.write_atlas(mine, a)
    assert open(mine, "rb").read() == open(out, "rb").read()
    assert strip(a.report) == strip(json.load(open(rep)))
    assert a.uv_index.shape == (a.F.shape[0], 3)
    assert a.face_chart.shape == (a.F.shape[0],)
    assert a.report["flipped"] == 0 and a.report["overlapping"] == 0
    assert np.all((a.uv >= 0) & (a.uv <= 1))


def test_atlas_of_arrays_equals_atlas_of_file(tmp_path):
    path = str(tmp_path / "torus.obj")
    assert run_cli("generate", "torus", "--rings", "12", "-o", path).returncode == 0
    V, F = intrinsic.read_mesh(path)
    a, b = intrinsic.atlas(V, F), intrinsic.atlas(path)
    assert np.array_equal(a.uv, b.uv) and np.array_equal(a.uv_index, b.uv_index)
    assert a.report["input"] is None and b.report["input"] == path


def test_atlas_errors(tmp_path):
    with pytest.raises(TypeError):
        intrinsic.atlas(np.zeros((3, 3)), np.array([[0, 1, 2]], dtype=np.int32), colour=1)
    with pytest.raises(intrinsic.UsageError, match="unknown option 'colour'"):
        intrinsic._intrinsic.atlas(np.zeros((3, 3)), np.array([[0, 1, 2]], dtype=np.int32), colour=1)
    with pytest.raises(intrinsic.UsageError, match="resolution"):
        intrinsic.atlas(np.eye(3), np.array([[0, 1, 2]], dtype=np.int32), resolution=0)
    with pytest.raises(intrinsic.InputError):
        intrinsic.atlas(np.eye(3), np.array([[0, 1, 7]], dtype=np.int32))
    a = intrinsic.atlas(np.eye(3), np.array([[0, 1, 2]], dtype=np.int32))
    with pytest.raises(intrinsic.UsageError, match=".obj"):
        intrinsic.write_atlas(str(tmp_path / "x.ply"), a)
    with pytest.raises(intrinsic.OutputError):
        intrinsic.write_atlas(str(tmp_path / "missing" / "x.obj"), a)
