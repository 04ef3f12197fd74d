"""intrinsic.atlas equals `intrinsic atlas`: same OBJ bytes, same report
(timings and paths aside), on generated closed surfaces and on shared assets
(marker corpus)."""
import json
import subprocess

import numpy as np
import pytest

import intrinsic

from conftest import cli_path, corpus, mesh  # noqa: E402


def run_cli(*args):
    return subprocess.run([cli_path(), *map(str, args)], capture_output=True, text=True)


def strip(report):
    return {k: v for k, v in report.items() if k not in ("timings_ms", "input", "output")}


@pytest.mark.parametrize("name", ["torus", "genus2", *corpus("assets/teapot.obj", "assets/3holes.off", "cat_head.obj")])
def test_atlas_equals_cli(tmp_path, name):
    path = str(mesh(name))
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


def torus(tmp_path):
    path = str(tmp_path / "torus.obj")
    assert run_cli("generate", "torus", "--rings", "16", "-o", path).returncode == 0
    return path


def test_atlas_options_equal_cli(tmp_path):
    """max_stretch, max_charts, weld and seams (a file or an array) give the command line's bytes."""
    path = torus(tmp_path)
    V, F = intrinsic.read_mesh(path)
    edges = [(int(F[f, 0]), int(F[f, 1])) for f in range(0, 40, 4)]
    seams_file = tmp_path / "seams.txt"
    seams_file.write_text("# ten edges\n" + "".join(f"{a} {b}\n" for a, b in edges))
    cli = str(tmp_path / "cli.obj")
    r = run_cli("atlas", path, "-o", cli, "-q", "--max-stretch", "1.2", "--max-charts", "3", "--weld", "1e-6",
                "--seams", seams_file)
    assert r.returncode == 0, r.stderr
    for seams in (seams_file, str(seams_file), np.array(edges, dtype=np.int64)):
        a = intrinsic.atlas(path, max_stretch=1.2, max_charts=3, weld=1e-6, seams=seams)
        mine = str(tmp_path / "py.obj")
        intrinsic.write_atlas(mine, a)
        assert open(mine, "rb").read() == open(cli, "rb").read()
    # The winding and stretch-budget switches, without seams.
    r = run_cli("atlas", path, "-o", cli, "-q", "--keep-winding", "--per-chart-stretch")
    assert r.returncode == 0, r.stderr
    a = intrinsic.atlas(V, F, reorient=False, atlas_stretch_budget=False)
    intrinsic.write_atlas(mine, a)
    assert open(mine, "rb").read() == open(cli, "rb").read()
    assert a.report["atlas_stretch_budget"] is False and a.report["reorient"] is False
    # The stretch bounds, hard edges and the isometric refinement.
    r = run_cli("atlas", path, "-o", cli, "-q", "--max-stretch", "1.05", "--max-face-stretch", "1.5",
                "--hard-angle", "50", "--isometric-iterations", "3")
    assert r.returncode == 0, r.stderr
    a = intrinsic.atlas(V, F, max_stretch=1.05, max_face_stretch=1.5, hard_angle=50, isometric_iterations=3)
    intrinsic.write_atlas(mine, a)
    assert open(mine, "rb").read() == open(cli, "rb").read()
    assert a.report["max_face_stretch"] == 1.5 and a.report["hard_angle"] == 50
    assert a.report["chart_map"]["isometric_iterations"] == 3
    # Every param map per chart, spelled as parameterize() spells it.
    r = run_cli("atlas", path, "-o", cli, "-q", "--boundary", "square", "--method", "mixed", "--lambda", "0.5",
                "--max-stretch", "3")
    assert r.returncode == 0, r.stderr
    a = intrinsic.atlas(V, F, boundary="square", method="mixed", lambda_=0.5, max_stretch=3)
    intrinsic.write_atlas(mine, a)
    assert open(mine, "rb").read() == open(cli, "rb").read()
    assert a.report["chart_map"] == {"boundary": "square", "method": "mixed", "lambda": 0.5, "mu": 0.0}
    with pytest.raises(intrinsic.UsageError, match="fixed chart boundaries"):
        intrinsic.atlas(V, F, method="authalic")
    # How the seams are cut is checked against the seams file in tests/test_atlas.cpp.


def test_write_atlas_glb_equals_cli(tmp_path):
    path = torus(tmp_path)
    cli, mine = str(tmp_path / "cli.glb"), str(tmp_path / "py.glb")
    assert run_cli("atlas", path, "-o", cli, "-q").returncode == 0
    intrinsic.write_atlas(mine, intrinsic.atlas(path))
    assert open(mine, "rb").read() == open(cli, "rb").read()
    assert open(mine, "rb").read(4) == b"glTF"


def test_atlas_seams_errors(tmp_path):
    path = torus(tmp_path)
    V, F = intrinsic.read_mesh(path)
    bad = tmp_path / "bad.txt"
    bad.write_text("0 1\n0 999999\n")
    with pytest.raises(intrinsic.InputError, match="bad.txt:2"):
        intrinsic.atlas(path, seams=bad)
    with pytest.raises(intrinsic.InputError):
        intrinsic.atlas(V, F, seams=np.array([[0, len(V) + 5]]))
    far = [v for v in range(len(V)) if not np.any(np.any(F == 0, axis=1) & np.any(F == v, axis=1))][1]
    with pytest.raises(intrinsic.InputError):
        intrinsic.atlas(V, F, seams=np.array([[0, far]]))
    with pytest.raises((intrinsic.UsageError, ValueError, TypeError)):
        intrinsic.atlas(V, F, seams=np.zeros((2, 3), dtype=np.int32))
    with pytest.raises(intrinsic.UsageError, match="stretch"):
        intrinsic.atlas(V, F, max_stretch=0.5)


def test_face_groups_keep_pairs_in_one_chart():
    """face_groups: each pair of triangles across an edge (a quad) ends in one
    chart; a wrong length is a UsageError naming the count."""
    path = str(mesh("torus"))
    plain = intrinsic.atlas(path, max_stretch=1.02, min_chart_faces=0)
    F = plain.F
    edge_face = {}
    groups = -np.ones(len(F), dtype=np.int32)
    for f, tri in enumerate(F):
        for k in range(3):
            e = tuple(sorted((int(tri[k]), int(tri[(k + 1) % 3]))))
            g = edge_face.get(e)
            if g is not None and groups[g] < 0 and groups[f] < 0:
                groups[g] = groups[f] = f
            edge_face[e] = f
    a = intrinsic.atlas(plain.V, F, max_stretch=1.02, min_chart_faces=0, face_groups=groups)
    assert a.report["split_groups"] == 0
    for g in set(groups[groups >= 0]):
        assert len(set(a.face_chart[groups == g])) == 1
    assert a.report["flipped"] == 0 and a.report["overlapping"] == 0
    with pytest.raises(intrinsic.UsageError, match="face groups number"):
        intrinsic.atlas(plain.V, F, face_groups=groups[:-1])


def test_scope_per_mesh_is_the_cli_flag(tmp_path):
    """scope="per-mesh" equals `--atlas per-mesh` on an OBJ with two objects, and
    a mesh without objects to tell apart is a UsageError (the CLI's exit 1)."""
    V, F = intrinsic.read_mesh(str(mesh("torus")))
    obj = tmp_path / "two.obj"
    with open(obj, "w") as f:
        for x, y, z in np.vstack([V, V + [5.0, 0, 0]]):
            f.write(f"v {x!r} {y!r} {z!r}\n")
        for k, part in enumerate([F, F + len(V)]):
            f.write(f"o part{k}\n")
            for a, b, c in part + 1:
                f.write(f"f {a} {b} {c}\n")
    a = intrinsic.atlas(str(obj), scope=intrinsic.AtlasScope.PER_MESH)
    b = intrinsic.atlas(str(obj), scope="per-mesh")
    assert np.array_equal(a.uv, b.uv)
    out, rep = str(tmp_path / "cli.obj"), str(tmp_path / "cli.json")
    r = run_cli("atlas", str(obj), "-o", out, "--atlas", "per-mesh", "--report", rep, "-q")
    assert r.returncode == 0, r.stderr
    mine = str(tmp_path / "py.obj")
    intrinsic.write_atlas(mine, a)
    assert open(mine, "rb").read() == open(out, "rb").read()
    with pytest.raises(intrinsic.UsageError):
        intrinsic.atlas(V, F, scope="per-mesh")
