# python3 -m intrinsic.batch with a 2-worker LocalCluster over a folder of
# generated surfaces plus one broken file: every good file done and equal to the
# CLI's output, the broken one recorded with the CLI's kind and message, a
# second run skips the done files and retries the failed one.
import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

import intrinsic
from conftest import cli_path, generated_mesh, read_obj_uv
from test_equal_cli import assert_reports_equal

MESHES = ["wave.obj", "strip.obj", "cap.obj", "flat.obj"]
OPTIONS = ["--method", "mixed", "--lambda", "0.5", "--mu", "0.5", "--boundary", "square"]
BROKEN = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 9\n"  # face index 9 out of range


def batch(*args, timeout=120):
    env = dict(os.environ)
    return subprocess.run([sys.executable, "-m", "intrinsic.batch", *map(str, args)], capture_output=True,
                          text=True, env=env, timeout=timeout)


def cli_message(stderr):
    first = stderr.strip().splitlines()[0]
    assert first.startswith("intrinsic: error: "), stderr
    return first[len("intrinsic: error: "):]


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    src = tmp_path_factory.mktemp("in")
    for m in MESHES:
        shutil.copy(generated_mesh(m[:-4]), src / m)
    (src / "broken.obj").write_text(BROKEN)
    (src / "notes.txt").write_text("not a mesh\n")
    return src


def load_manifest(out):
    doc = json.loads((out / "manifest.json").read_text())  # valid JSON
    return doc, {os.path.basename(e["input"]): e for e in doc["files"]}


def test_batch_equals_cli_and_reruns(folder, tmp_path):
    cli = cli_path()
    out = tmp_path / "out"
    r = batch(folder, out, *OPTIONS, "--workers", 2)
    assert r.returncode == 1, r.stderr  # one file failed
    doc, files = load_manifest(out)
    assert sorted(files) == sorted(MESHES + ["broken.obj"])
    assert doc["counts"] == {"done": 4, "skipped": 0, "failed": 1} and doc["complete"]

    for m in MESHES:
        e = files[m]
        assert e["status"] == "done" and e["kind"] is None and e["exit_code"] == 0, e
        assert e["output"] == str(out / m) and e["seconds"] > 0
        c_out, c_rep = tmp_path / f"cli_{m}", tmp_path / f"cli_{m}.json"
        p = subprocess.run([cli, "param", str(folder / m), *OPTIONS, "-o", str(c_out), "--report", str(c_rep),
                            "-q"], capture_output=True, text=True)
        assert p.returncode == 0, p.stderr
        np.testing.assert_allclose(read_obj_uv(e["output"]), read_obj_uv(c_out), rtol=0, atol=1e-12)
        Vb, Fb = intrinsic.read_mesh(e["output"])
        Vc, Fc = intrinsic.read_mesh(c_out)
        assert np.array_equal(Vb, Vc) and np.array_equal(Fb, Fc)
        rep_b, rep_c = json.loads(open(e["report"]).read()), json.loads(c_rep.read_text())
        assert_reports_equal(rep_b, rep_c)
        assert set(rep_b["timings_ms"]) == set(rep_c["timings_ms"])
        assert rep_b["output"] == e["output"] and rep_b["input"] == str(folder / m)

    b = files["broken.obj"]
    p = subprocess.run([cli, "param", str(folder / "broken.obj"), *OPTIONS, "-o", str(tmp_path / "x.obj"), "-q"],
                       capture_output=True, text=True)
    assert p.returncode == 2
    assert b["status"] == "failed" and b["kind"] == "input" and b["exit_code"] == 2
    assert b["message"] == cli_message(p.stderr)
    assert not os.path.exists(b["report"]) and not os.path.exists(b["output"])

    mtimes = {m: os.stat(files[m]["report"]).st_mtime_ns for m in MESHES}
    r2 = batch(folder, out, *OPTIONS, "--workers", 2)
    assert r2.returncode == 1, r2.stderr
    doc2, files2 = load_manifest(out)
    assert doc2["counts"] == {"done": 0, "skipped": 4, "failed": 1}
    for m in MESHES:
        assert files2[m]["status"] == "skipped" and os.stat(files2[m]["report"]).st_mtime_ns == mtimes[m]
    assert files2["broken.obj"]["status"] == "failed" and files2["broken.obj"]["seconds"] > 0  # retried
    assert files2["broken.obj"]["message"] == b["message"]


def test_incomplete_output_is_redone(folder, tmp_path):
    out = tmp_path / "out"
    one = tmp_path / "one"
    one.mkdir()
    shutil.copy(folder / "wave.obj", one / "wave.obj")
    assert batch(one, out, "--workers", 1, "-q").returncode == 0
    (out / "wave.obj").unlink()  # report left, output gone: not complete
    r = batch(one, out, "--workers", 1, "-q")
    assert r.returncode == 0, r.stderr
    doc, files = load_manifest(out)
    assert files["wave.obj"]["status"] == "done" and (out / "wave.obj").exists()


def test_atlas_batch_equals_cli(folder, tmp_path):
    """--command atlas: the broken file fails as `intrinsic atlas` says, the
    others give the CLI's bytes."""
    cli = cli_path()
    out = tmp_path / "out"
    r = batch(folder, out, "--command", "atlas", "--padding", "3", "--workers", 2, "-q")
    assert r.returncode == 1, r.stderr
    doc, files = load_manifest(out)
    assert doc["counts"] == {"done": 4, "skipped": 0, "failed": 1}
    for m in MESHES:
        c_out = tmp_path / ("cli-" + m)
        p = subprocess.run([cli, "atlas", str(folder / m), "--padding", "3", "-o", str(c_out), "-q"],
                           capture_output=True, text=True)
        assert p.returncode == 0, p.stderr
        # The same charts and corners; UVs equal up to the rounding of the
        # factorization, which follows the thread count (Dask workers run one).
        mine, theirs = (out / m).read_text().splitlines(), c_out.read_text().splitlines()
        assert [x for x in mine if not x.startswith("vt ")] == [x for x in theirs if not x.startswith("vt ")]
        uv = lambda lines: np.array([x.split()[1:] for x in lines if x.startswith("vt ")], dtype=float)  # noqa: E731
        assert np.abs(uv(mine) - uv(theirs)).max() < 1e-9
        assert json.loads((out / (m[:-4] + ".report.json")).read_text())["flipped"] == 0
    p = subprocess.run([cli, "atlas", str(folder / "broken.obj"), "-o", str(tmp_path / "x.obj"), "-q"],
                       capture_output=True, text=True)
    assert files["broken.obj"]["kind"] == "input" and files["broken.obj"]["message"] == cli_message(p.stderr)


def test_atlas_batch_glb_with_chart_options(folder, tmp_path):
    """--format glb and the atlas's stretch/chart options reach every file as
    on the command line: the same report (charts, stretch) per file."""
    cli = cli_path()
    out = tmp_path / "out"
    opts = ["--max-stretch", "1.2", "--max-charts", "2", "--weld", "1e-7"]
    r = batch(folder, out, "--command", "atlas", "--format", "glb", *opts, "--workers", 1, "-q")
    assert r.returncode == 1, r.stderr  # broken.obj
    for m in MESHES[:2]:
        name = m[:-4]
        assert (out / (name + ".glb")).read_bytes()[:4] == b"glTF"
        rep = tmp_path / (name + ".json")
        p = subprocess.run([cli, "atlas", str(folder / m), "-o", str(tmp_path / (name + ".glb")), "--report",
                            str(rep), "-q", *opts], capture_output=True, text=True)
        assert p.returncode == 0, p.stderr
        mine, theirs = json.loads((out / (name + ".report.json")).read_text()), json.loads(rep.read_text())
        assert mine["charts"] == theirs["charts"]
        assert abs(mine["stretch_l2_mean"] - theirs["stretch_l2_mean"]) < 1e-9


@pytest.mark.parametrize("args,needle", [
    (["--command", "atlas", "--spacing", "uniform"], "--spacing does not apply to --command atlas"),
    # atlas takes the chart map's options as intrinsic atlas does, checked by the library
    (["--command", "atlas", "--method", "authalic"], "method applies to fixed chart boundaries"),
    (["--padding", "3"], "--padding does not apply to --command param"),
    (["--command", "atlas", "--format", "ply"], "atlas writes .obj"),
    (["--no-such-option"], "unrecognized arguments"),
    (["--method", "mixed"], "--lambda"),               # intrinsic param's usage check, before any work
    (["--lambda", "0.5"], "lambda"),
    (["--workers", "2", "--scheduler", "tcp://127.0.0.1:1"], "not allowed with"),
])
def test_usage_errors_exit_2(folder, tmp_path, args, needle):
    r = batch(folder, tmp_path / "out", *args, timeout=60)
    assert r.returncode == 2, r.stderr
    assert needle in r.stderr
    assert not (tmp_path / "out").exists()
