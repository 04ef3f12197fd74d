"""ctest python_pip_install: `pip install` from a source tree works like any
Python package's (docs/python.md "Installing with pip").

    python3 pip_install_check.py SOURCE_DIR

In a temporary folder: a fresh `python3 -m venv --system-site-packages`
(numpy from the system), `pip install --no-build-isolation --no-index SOURCE`
(offline: the system's setuptools and wheel; setup.py builds with CMake in
$INTRINSIC_PIP_BUILD_DIR, kept between runs), then the venv's python, run
outside the source and build trees without PYTHONPATH, must import intrinsic
from the venv, parameterize a mesh the bundled command line generates, and
give the same UVs as the command line (`python -m intrinsic`, and the
`intrinsic` console script). The source tree must be left as it was.
Not a pytest file (its name does not start with test_): python_tests does
not collect it.
"""
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def run(cmd, **kw):
    """Runs cmd; on failure prints its output and exits 1."""
    proc = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, **kw)
    if proc.returncode != 0:
        sys.stdout.write(proc.stdout[-20000:])
        sys.stderr.write(proc.stderr[-20000:])
        sys.exit(f"FAILED ({proc.returncode}): {' '.join(map(str, cmd))}")
    return proc


def fail(message):
    sys.exit("FAILED: " + message)


def top_level(source):
    """The source tree's top-level entries (what an in-tree build could litter)."""
    return {p.name for p in source.iterdir()}


# The module's UVs against the CLI's file (vt lines, one per vertex, shortest round-trip digits: exact),
# plus what holds for any default map: inside [0,1]^2 without flipped triangles.
CHECK = r"""
import sys, numpy as np, intrinsic
venv, mesh, cli_obj = sys.argv[1:4]
assert intrinsic.__file__.startswith(venv), ("imported from", intrinsic.__file__)
V, F = intrinsic.read_mesh(mesh)
r = intrinsic.parameterize(V, F)
assert r.uv.shape == (V.shape[0], 2) and np.isfinite(r.uv).all()
assert r.flipped_triangles == 0 and r.uv.min() >= -1e-12 and r.uv.max() <= 1 + 1e-12
uv = np.array([l.split()[1:3] for l in open(cli_obj) if l.startswith("vt ")], dtype=np.float64)
assert np.array_equal(r.uv, uv), np.abs(r.uv - uv).max()
assert issubclass(intrinsic.UsageError, ValueError) and intrinsic.Method.CONFORMAL.option == "conformal"
print("ok", intrinsic.__file__)
"""


def main():
    source = Path(sys.argv[1]).resolve()
    before = top_level(source)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "INTRINSIC_CLI")}
    env.setdefault("CMAKE_BUILD_PARALLEL_LEVEL", "2")
    with tempfile.TemporaryDirectory(prefix="intrinsic-pip-") as tmp:
        tmp = Path(tmp)
        venv = tmp / "venv"
        run([sys.executable, "-m", "venv", "--system-site-packages", venv], env=env)
        py = venv / "bin" / "python"
        start = time.monotonic()
        run([py, "-m", "pip", "install", "--no-build-isolation", "--no-index", source], env=env, cwd=tmp)
        print(f"pip install: {time.monotonic() - start:.0f} s")

        package = Path(run([py, "-c", "import intrinsic, os; print(os.path.dirname(intrinsic.__file__))"],
                           env=env, cwd=tmp).stdout.strip())
        if not str(package).startswith(str(venv)):
            fail(f"intrinsic imported from {package}, not from the venv {venv}")
        for f in ("bin/intrinsic", "_intrinsic.pyi", "py.typed", "__main__.py", "batch.py"):
            if not (package / f).is_file():
                fail(f"{f} is not installed in {package}")
        if not os.access(package / "bin" / "intrinsic", os.X_OK):
            fail("the bundled command line is not executable")

        help_text = run([py, "-m", "intrinsic", "--help"], env=env, cwd=tmp).stdout
        if "param" not in help_text:
            fail("python -m intrinsic --help does not list the param command:\n" + help_text)
        mesh = tmp / "wave.obj"
        run([py, "-m", "intrinsic", "generate", "wave", "--rings", "12", "-o", mesh], env=env, cwd=tmp)
        cli_obj = tmp / "wave_uv.obj"
        run([venv / "bin" / "intrinsic", "param", mesh, "-o", cli_obj, "-q"], env=env, cwd=tmp)  # console script
        print(run([py, "-c", CHECK, venv, mesh, cli_obj], env=env, cwd=tmp).stdout.strip())

    added = top_level(source) - before
    build_dir = Path(env.get("INTRINSIC_PIP_BUILD_DIR", source / "build-pip")).resolve()
    added.discard(build_dir.name if build_dir.parent == source else "")
    if added:
        fail(f"pip install left {sorted(added)} in the source tree")
    print("python_pip_install: ok")


if __name__ == "__main__":
    main()
