# Python results equal the CLI's (UVs to 1e-12, same report) on generated
# surfaces and on the shared meshes (marker corpus), for every method and
# boundary mode.
import numpy as np
import pytest

import intrinsic
from conftest import corpus, generated_mesh, mesh

MESHES = ["wave", "strip", "holed", *corpus("cat_head.obj", "snail.obj", "camel_b.obj", "alligator.obj",
                                            "fairing-cross.off", "beetle.off")]
METHODS = [("conformal", {}), ("authalic", {}), ("mixed", {"lam": 0.5, "mu": 0.5}), ("tutte", {}),
           ("floater", {})]
# natural: the natural conformal map (conformal part needed)
CASES = [(m, kw, b) for m, kw in METHODS for b in ("circle", "square")] + [("conformal", {}, "natural")]
VOLATILE = {"input", "output", "timings_ms"}


def cli_args(method, kw, boundary):
    args = ["--method", method, "--boundary", boundary]
    if "lam" in kw:
        args += ["--lambda", kw["lam"]]
    if "mu" in kw:
        args += ["--mu", kw["mu"]]
    return args


def assert_reports_equal(py, cli, where="report"):
    """Same keys everywhere, same values (numbers to 1e-9), timings aside."""
    if isinstance(py, dict):
        assert isinstance(cli, dict) and set(py) == set(cli), (where, set(py) ^ set(cli))
        for k in set(py) - VOLATILE:
            assert_reports_equal(py[k], cli[k], f"{where}.{k}")
    elif isinstance(py, list):
        assert isinstance(cli, list) and len(py) == len(cli), where
        for i, (a, b) in enumerate(zip(py, cli)):
            assert_reports_equal(a, b, f"{where}[{i}]")
    else:
        assert py == pytest.approx(cli, rel=1e-9, abs=1e-12), where


@pytest.mark.parametrize("name", MESHES)
@pytest.mark.parametrize("method,kw,boundary", CASES)
def test_same_as_cli(cli, name, method, kw, boundary):
    path = mesh(name)
    c = cli([path, *cli_args(method, kw, boundary)])
    V, F = intrinsic.read_mesh(path)
    try:
        r = intrinsic.parameterize(V, F, method=method, boundary=boundary, **kw)
    except intrinsic.Error as e:  # the CLI must fail the same way
        assert c.returncode == e.exit_code and c.message == str(e)
        return
    assert c.returncode == 0, c.stderr
    assert r.uv.shape == (V.shape[0], 2) and r.uv.flags.c_contiguous
    np.testing.assert_allclose(r.uv, c.uv, rtol=0, atol=1e-12)
    assert_reports_equal(r.report, c.report)
    assert r.residual == r.report["residual"] and r.flipped_triangles == r.report["flipped_triangles"]


@pytest.mark.parametrize("options,args", [
    ({"spacing": "uniform", "scale": "surface"}, ["--spacing", "uniform", "--scale", "surface"]),
    ({"holes": "free"}, ["--holes", "free"]),
    ({"holes": "natural"}, ["--holes", "natural"]),
    ({"solver": "umfpack"}, ["--solver", "umfpack"]),
    ({"boundary": "natural", "pins": [(0, 0.0, 0.0), (5, 1.0, 0.25)]},
     ["--boundary", "natural", "--pin", "0:0,0", "--pin", "5:1,0.25"]),
    ({"optimize_lambda": "area"}, ["--optimize-lambda", "area"]),
    ({"optimize_boundary": "edge", "iterations": 5}, ["--optimize-boundary", "edge", "--iterations", "5"]),
])
@pytest.mark.parametrize("name", ["holed", *corpus("fairing-cross.off")])
def test_options_same_as_cli(cli, options, args, name):
    path = mesh(name)
    c = cli([path, *args])
    assert c.returncode == 0, c.stderr
    r = intrinsic.parameterize(str(path), **options)  # read from the file, as the CLI
    np.testing.assert_allclose(r.uv, c.uv, rtol=0, atol=1e-12)
    assert r.report["input"] == c.report["input"]
    assert_reports_equal(r.report, c.report)


@pytest.mark.parametrize("name", ["wave", *corpus("snail.obj")])
def test_optimizer_wrappers(cli, name):
    path = mesh(name)
    V, F = intrinsic.read_mesh(path)
    r = intrinsic.optimal_lambda(V, F, energy="edge")
    c = cli([path, "--optimize-lambda", "edge"])
    np.testing.assert_allclose(r.uv, c.uv, rtol=0, atol=1e-12)
    assert r.report["optimal_lambda"]["lambda"] == pytest.approx(c.report["optimal_lambda"]["lambda"], abs=1e-12)
    r = intrinsic.optimize_boundary(V, F, energy="area", iterations=3)
    c = cli([path, "--optimize-boundary", "area", "--iterations", "3"])
    np.testing.assert_allclose(r.uv, c.uv, rtol=0, atol=1e-12)


def test_charts_like_cli(cli):
    """Several components become charts, as on the command line."""
    V, F = intrinsic.read_mesh(generated_mesh("wave"))
    V2 = np.vstack([V, V + [10.0, 0.0, 0.0]])
    F2 = np.vstack([F, F + V.shape[0]]).astype(np.int32)
    import tempfile, os
    with tempfile.TemporaryDirectory() as d:
        p = os.path.join(d, "two.obj")
        intrinsic.write_mesh(p, V2, F2)
        c = cli([p])
    r = intrinsic.parameterize(V2, F2)
    assert len(r.report["charts"]) == 2
    np.testing.assert_allclose(r.uv, c.uv, rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", ["wave@100", *corpus("max-planck-partial.obj")])
def test_large_patch(cli, name):
    path = mesh(name)
    for method, boundary in (("conformal", "circle"), ("conformal", "natural")):
        c = cli([path, "--method", method, "--boundary", boundary])
        r = intrinsic.parameterize(*intrinsic.read_mesh(path), method=method, boundary=boundary)
        np.testing.assert_allclose(r.uv, c.uv, rtol=0, atol=1e-12)


@pytest.mark.parametrize("name", ["wave", *corpus("inverted-triangles.obj", "cat_head.obj")])
def test_result_mesh_is_what_cli_writes(cli, tmp_path, name):
    """r.V, r.F: the validated mesh (faces reoriented), the one `param -o` writes."""
    path = mesh(name)
    c = cli([path])
    assert c.returncode == 0, c.stderr
    r = intrinsic.parameterize(str(path))
    Vc, Fc = intrinsic.read_mesh(tmp_path / "out.obj")
    assert np.array_equal(r.V, Vc) and np.array_equal(r.F, Fc) and r.F.dtype == np.int32
    V, F = intrinsic.read_mesh(path)
    assert np.array_equal(r.V, V) and (r.report["reoriented_faces"] > 0) == (not np.array_equal(r.F, F))
    intrinsic.write_mesh(tmp_path / "py.obj", r.V, r.F, uv=r.uv)
    assert (tmp_path / "py.obj").read_bytes() == (tmp_path / "out.obj").read_bytes()


def test_result_mesh_largest_component(cli, tmp_path):
    """With largest_component only the kept component is in r.V, r.F (as the CLI writes)."""
    two = tmp_path / "two.obj"
    fan = lambda o, n: [f"v {o + np.cos(t)} {np.sin(t)} 0" for t in np.linspace(0, 2 * np.pi, n, endpoint=False)]
    lines = ["v 0 0 0", *fan(0, 6), "v 5 0 0", *fan(5, 8)]
    lines += [f"f 1 {i + 2} {(i + 1) % 6 + 2}" for i in range(6)]
    lines += [f"f 8 {i + 9} {(i + 1) % 8 + 9}" for i in range(8)]
    two.write_text("\n".join(lines) + "\n")
    c = cli([two, "--largest-component"])
    assert c.returncode == 0, c.stderr
    r = intrinsic.parameterize(str(two), largest_component=True)
    Vc, Fc = intrinsic.read_mesh(tmp_path / "out.obj")
    assert r.F.shape == (8, 3) and np.array_equal(r.V, Vc) and np.array_equal(r.F, Fc)
    np.testing.assert_allclose(r.uv, c.uv, rtol=0, atol=1e-12)
