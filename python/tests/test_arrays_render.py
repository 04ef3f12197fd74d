# Arrays (no conversion copy for C-contiguous float64/int32 input, dtypes
# converted otherwise, new C-contiguous outputs), read/write round trips,
# metrics and render equal to the CLI's, and the GIL released while solving.
import json
import subprocess
import threading
import time

import numpy as np
import pytest

import intrinsic
from intrinsic import _intrinsic
from conftest import cli_path, corpus, generated_mesh, mesh


def test_no_copy_for_c_contiguous_input():
    V, F = intrinsic.read_mesh(generated_mesh("wave"))
    assert V.dtype == np.float64 and F.dtype == np.int32 and V.flags.c_contiguous and F.flags.c_contiguous
    assert _intrinsic._view_address(V, 3) == V.ctypes.data
    assert _intrinsic._view_address(F, 3, True) == F.ctypes.data
    # other layouts or dtypes are converted (a copy), with the same result
    assert _intrinsic._view_address(np.asfortranarray(V), 3) != V.ctypes.data
    assert _intrinsic._view_address(F.astype(np.int64), 3, True) != F.ctypes.data
    a = intrinsic.parameterize(V, F).uv
    b = intrinsic.parameterize(np.asfortranarray(V), F.astype(np.int64)).uv
    assert np.array_equal(a, b)


@pytest.mark.parametrize("name", ["wave", *corpus("snail.obj")])
def test_read_write_round_trip(tmp_path, name):
    V, F = intrinsic.read_mesh(mesh(name))
    uv = intrinsic.parameterize(V, F).uv
    for name, binary in (("a.obj", False), ("a.ply", False), ("b.ply", True)):
        intrinsic.write_mesh(tmp_path / name, V, F, uv, binary=binary)
        V2, F2 = intrinsic.read_mesh(tmp_path / name)
        assert np.array_equal(V, V2) and np.array_equal(F, F2)


@pytest.mark.parametrize("name", ["cap", *corpus("alligator.obj")])
def test_metrics_like_cli(tmp_path, name):
    path = mesh(name)
    V, F = intrinsic.read_mesh(path)
    uv = intrinsic.parameterize(V, F, method="authalic").uv
    intrinsic.write_mesh(tmp_path / "uv.obj", V, F, uv)
    proc = subprocess.run([cli_path(), "metrics", str(tmp_path / "uv.obj")], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    cli = json.loads(proc.stdout)
    m = intrinsic.metrics(V, F, uv)
    for k in ("flipped_triangles", "angle_distortion", "area_distortion", "stretch_l2", "edge_length_energy",
              "area_energy", "faces", "boundary_loops", "stretch"):
        assert m[k] == pytest.approx(cli[k], rel=1e-12), k


@pytest.mark.parametrize("name", ["wave", *corpus("cat_head.obj")])
@pytest.mark.parametrize("mode", ["checker", "layout", "angle"])
def test_render_like_cli(tmp_path, mode, name):
    path = mesh(name)
    V, F = intrinsic.read_mesh(path)
    uv = intrinsic.parameterize(V, F).uv
    intrinsic.write_mesh(tmp_path / "uv.obj", V, F, uv)
    out = tmp_path / "cli.png"
    proc = subprocess.run([cli_path(), "render", str(tmp_path / "uv.obj"), "-o", str(out), "--mode", mode,
                           "--size", "200,150", "-q"], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    img = intrinsic.render(V, F, uv, mode=mode, size=(200, 150))
    assert img.shape == (150, 200, 3) and img.dtype == np.uint8
    assert intrinsic.render(V, F, uv, mode=mode, size=(200, 150), path=tmp_path / "py.png") is None
    assert (tmp_path / "py.png").read_bytes() == out.read_bytes()


@pytest.mark.parametrize("name", ["wave@100", *corpus("max-planck-partial.obj")])
def test_gil_released(name):
    """Two threads parameterizing at once take clearly less than twice one
    (asserted loosely: the machine may be busy)."""
    V, F = intrinsic.read_mesh(mesh(name))
    intrinsic.parameterize(V, F, solver="eigen-llt")
    t0 = time.perf_counter()
    intrinsic.parameterize(V, F, solver="eigen-llt")
    one = time.perf_counter() - t0
    ticks = []
    stop = threading.Event()

    def tick():  # runs only while the GIL is free
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.001)

    t = threading.Thread(target=tick)
    t.start()
    intrinsic.parameterize(V, F, solver="eigen-llt")
    stop.set()
    t.join()
    # Holding the GIL would leave the ticker a switch interval or two (5 ms each).
    assert one < 0.05 or len(ticks) > 10, (one, len(ticks))


def test_render_view_and_modes():
    V, F = intrinsic.read_mesh(generated_mesh("wave"))
    uv = intrinsic.parameterize(V, F).uv
    a = intrinsic.render(V, F, uv, size=(64, 48), view=(30, 45))
    b = intrinsic.render(V, F, uv, size=(64, 48), view="30,45")
    assert np.array_equal(a, b)
    assert intrinsic.render(V, F, uv, mode="stretch", size=(64, 48), on_surface=True, log=True).shape == (48, 64, 3)
    with pytest.raises(intrinsic.UsageError):
        intrinsic.render(V, F, uv, mode="checker", log=True)
    with pytest.raises(intrinsic.UsageError):
        intrinsic.render(V, F, uv, mode="nope")


def test_set_boundary_then_solve():
    V, F = intrinsic.read_mesh(generated_mesh("wave"))
    p = intrinsic.Parameterizer(V, F, boundary="square")
    fixed = [(v, 0.5 * u, 0.5 * w) for v, u, w in p.boundary]
    p.set_boundary(fixed)
    r = p.solve()
    np.testing.assert_allclose(r.uv, 0.5 * intrinsic.parameterize(V, F, boundary="square").uv, atol=1e-12)
    assert p.factorizations == 1 and r.report["factorizations"] == 1
