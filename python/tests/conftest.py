# Shared fixtures of the Python tests: the built `intrinsic` CLI (INTRINSIC_CLI,
# set by CTest), the meshes (generated ones written by `intrinsic generate`,
# and the shared real meshes: INTRINSIC_SHARED_MESHES, default
# ../shared/meshes next to the source tree, never copied into the repository)
# and a helper running the CLI and reading back the UVs it wrote.
#
# The corpus: a test that reads a shared mesh carries the marker `corpus`
# (`corpus(...)` below marks parameters); ctest runs `-m corpus` as
# python_tests_corpus (label corpus) and `-m "not corpus"` as python_tests.
# Where ../shared/meshes is absent, corpus tests skip, saying why, and a run of
# corpus tests only exits 77, which ctest reports as Skipped.
import os
import subprocess
import tempfile
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
SOURCE_DIR = Path(os.environ.get("INTRINSIC_SOURCE_DIR", HERE.parent.parent))
SHARED = Path(os.environ.get("INTRINSIC_SHARED_MESHES", SOURCE_DIR.parent / "shared" / "meshes"))


def cli_path():
    p = os.environ.get("INTRINSIC_CLI") or str(SOURCE_DIR / "build" / "intrinsic")
    if not Path(p).exists():
        pytest.skip("the intrinsic CLI is not built (set INTRINSIC_CLI)")
    return p


CORPUS_SKIP_EXIT = 77
_current = {"corpus": False}  # whether the running test carries the corpus marker


def pytest_configure(config):
    config.addinivalue_line("markers", "corpus: reads the shared real meshes (../shared/meshes)")


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_setup(item):
    _current["corpus"] = item.get_closest_marker("corpus") is not None  # before any fixture runs


def pytest_sessionfinish(session, exitstatus):
    items = getattr(session, "items", [])
    if (exitstatus == 0 and items and not SHARED.is_dir()
            and all(i.get_closest_marker("corpus") for i in items)):
        print(f"\nSKIPPED: {SHARED} is absent: every selected test needs the shared real meshes")
        session.exitstatus = CORPUS_SKIP_EXIT


def corpus(*names):
    """Parameters that are shared meshes: marked corpus, named after the file."""
    return [pytest.param(n, marks=pytest.mark.corpus, id=n) for n in names]


def shared_mesh(name):
    """A shared real mesh; only in a test marked corpus. Where ../shared/meshes
    is absent the test skips; where it is present a missing mesh fails."""
    if not _current["corpus"]:
        pytest.fail(f"shared_mesh({name!r}) in a test without the corpus marker (@pytest.mark.corpus or corpus())")
    if not SHARED.is_dir():
        pytest.skip(f"{SHARED} is absent: this test needs the shared real meshes (marker corpus)")
    p = SHARED / name
    assert p.exists(), f"shared mesh {p} missing"
    return p


_generated = {}


def generated_mesh(name):
    """A surface of `intrinsic generate` written once per session: "wave",
    "strip", "cap", "flat", "torus", "genus2" (rings 8, or "wave@100" for
    rings 100), or "holed" (the wave at rings 16 with the faces around three
    interior vertices removed: 4 boundary loops, like test_support.h's)."""
    if name not in _generated:
        if "dir" not in _generated:
            _generated["dir"] = tempfile.TemporaryDirectory(prefix="intrinsic-generated-")
        out = Path(_generated["dir"].name) / (name.replace("@", "-") + ".obj")
        surface, _, rings = name.partition("@")
        if surface == "holed":
            import intrinsic
            V, F = intrinsic.read_mesh(generated_mesh("wave@16"))
            keep = ~np.isin(F, [3 * 10 * 9 + 5 + 1, 3 * 6 * 5 + 40 + 1, 3 * 12 * 11 + 20 + 1]).any(axis=1)
            intrinsic.write_mesh(out, V, np.ascontiguousarray(F[keep]))
        else:
            proc = subprocess.run([cli_path(), "generate", surface, "--rings", rings or "8", "-o", str(out)],
                                  capture_output=True, text=True)
            assert proc.returncode == 0, proc.stderr
        _generated[name] = out
    return _generated[name]


def mesh(name):
    """A file name with an extension is a shared mesh; otherwise a generated one."""
    return shared_mesh(name) if "." in name else generated_mesh(name)


def read_obj_uv(path):
    """The vt lines of an OBJ the CLI wrote (one per vertex, in order)."""
    rows = [line.split()[1:3] for line in open(path) if line.startswith("vt ")]
    return np.array(rows, dtype=np.float64)


class CliRun:
    def __init__(self, proc, uv, report):
        self.returncode = proc.returncode
        self.stderr = proc.stderr
        self.uv = uv
        self.report = report

    @property
    def message(self):
        """What the CLI printed after 'intrinsic: error: ' (or CLI11's first line)."""
        first = self.stderr.strip().splitlines()[0] if self.stderr.strip() else ""
        return first[len("intrinsic: error: "):] if first.startswith("intrinsic: error: ") else first


def run_cli(tmp_path, args, output="out.obj"):
    import json
    out = tmp_path / output
    report = tmp_path / "report.json"
    cmd = [cli_path(), "param", *map(str, args), "-o", str(out), "--report", str(report), "-q"]
    proc = subprocess.run(cmd, capture_output=True, text=True)
    uv = read_obj_uv(out) if proc.returncode == 0 and output.endswith(".obj") else None
    rep = json.loads(report.read_text()) if proc.returncode == 0 else None
    return CliRun(proc, uv, rep)


@pytest.fixture
def cli(tmp_path):
    return lambda args, output="out.obj": run_cli(tmp_path, args, output)
