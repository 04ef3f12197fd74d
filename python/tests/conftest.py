# Shared fixtures of the Python tests: the built `intrinsic` CLI (INTRINSIC_CLI,
# set by CTest), the shared meshes (INTRINSIC_SHARED_MESHES, default
# ../shared/meshes next to the source tree; never copied into the repository)
# and a helper running the CLI and reading back the UVs it wrote.
import os
import subprocess
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


def shared_mesh(name):
    p = SHARED / name
    if not p.exists():
        pytest.skip(f"shared mesh {p} not available")
    return p


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
