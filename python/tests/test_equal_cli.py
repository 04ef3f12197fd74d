# The module's results equal the command line's, each reached its own way:
# the CLI runs in a subprocess (INTRINSIC_CLI, set by ctest) on a mesh file
# and writes its output file; this test parses that file itself (plain
# Python and numpy below, not the module's reader), and gives the module the
# same mesh as arrays it also parsed itself. The writers print the shortest
# digits that read back to the same double (std::to_chars) and binary PLY
# stores the doubles, so the UVs must be exactly equal, not just close; the
# reports (JSON) must agree to 1e-9 in every key.
import json
import subprocess

import numpy as np
import pytest

import intrinsic
from conftest import cli_path, corpus, generated_mesh, mesh

VOLATILE = {"input", "output", "timings_ms"}


# ---- plain parsers of what the command line writes ---------------------------------------------

def parse_obj(path):
    """v, vt and triangle f lines ("f a b c" or "f a/ta b/tb c/tc"): V, VT, F, FT (zero-based; FT None
    without texture indices). Anything else in the file is ignored."""
    V, VT, F, FT = [], [], [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                V.append([float(x) for x in parts[1:4]])
            elif parts[0] == "vt":
                VT.append([float(x) for x in parts[1:3]])
            elif parts[0] == "f":
                assert len(parts) == 4, f"{path}: not a triangle: {line!r}"
                corners = [c.split("/") for c in parts[1:]]
                F.append([int(c[0]) - 1 for c in corners])
                if len(corners[0]) > 1 and corners[0][1]:
                    FT.append([int(c[1]) - 1 for c in corners])
    return (np.array(V, dtype=np.float64).reshape(-1, 3), np.array(VT, dtype=np.float64).reshape(-1, 2),
            np.array(F, dtype=np.int32).reshape(-1, 3), np.array(FT, dtype=np.int32).reshape(-1, 3) if FT else None)


def parse_off(path):
    """An OFF file of triangles (the corpus meshes): V, F."""
    with open(path) as f:
        words = [w for line in f for w in line.split("#", 1)[0].split()]
    assert words[0] == "OFF"
    n, m = int(words[1]), int(words[2])
    V = np.array(words[4:4 + 3 * n], dtype=np.float64).reshape(n, 3)
    rows = np.array(words[4 + 3 * n:4 + 3 * n + 4 * m], dtype=np.int64).reshape(m, 4)
    assert (rows[:, 0] == 3).all(), f"{path}: not all triangles"
    return V, rows[:, 1:].astype(np.int32)


def parse_ply(path):
    """The PLY the command line writes, ASCII or binary little endian: vertex x y z [u v] (double), face
    list uchar int. Returns V, UV (None without u v), F."""
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    binary = "format binary_little_endian 1.0" in header
    n = int(next(h.split()[2] for h in header if h.startswith("element vertex")))
    m = int(next(h.split()[2] for h in header if h.startswith("element face")))
    props = [h.split()[2] for h in header[:header.index(next(h for h in header if h.startswith("element face")))]
             if h.startswith("property double")]
    k = len(props)
    if binary:
        verts = np.frombuffer(data, dtype="<f8", count=n * k, offset=end).reshape(n, k)
        faces = np.frombuffer(data, dtype=np.dtype([("c", "u1"), ("i", "<i4", (3,))]), count=m, offset=end + 8 * n * k)
        assert (faces["c"] == 3).all()
        F = faces["i"].astype(np.int32)
    else:
        lines = data[end:].decode().splitlines()
        verts = np.array([[float(x) for x in lines[i].split()] for i in range(n)], dtype=np.float64)
        rows = np.array([[int(x) for x in lines[n + j].split()] for j in range(m)], dtype=np.int64)
        assert (rows[:, 0] == 3).all()
        F = rows[:, 1:].astype(np.int32)
    UV = verts[:, 3:5].copy() if props[3:5] == ["u", "v"] else None
    return verts[:, :3].copy(), UV, F


def parse_mesh(path):
    """The input mesh as arrays, parsed here: OBJ or OFF."""
    path = str(path)
    if path.endswith(".off"):
        return parse_off(path)
    V, _, F, _ = parse_obj(path)
    return V, F


# ---- running the command line -------------------------------------------------------------------

def run(tmp_path, command, path, args, output):
    """`intrinsic COMMAND PATH ARGS -o OUTPUT --report ...`: (parsed report, output path)."""
    out, report = tmp_path / output, tmp_path / (output + ".json")
    proc = subprocess.run([cli_path(), command, str(path), *map(str, args), "-o", str(out), "--report", str(report),
                           "-q"], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    return json.loads(report.read_text()), out


def assert_same(name, a, b):
    """Bit for bit (the files keep every digit): a difference reports its size."""
    assert a.shape == b.shape, (name, a.shape, b.shape)
    if a.dtype.kind == "f":
        diff = np.max(np.abs(a - b)) if a.size else 0.0
        assert np.array_equal(a, b), f"{name}: differs by up to {diff:.3g}"
    else:
        assert np.array_equal(a, b), f"{name}: {np.count_nonzero(a != b)} entries differ"


def assert_reports_equal(py, cli, where="report"):
    """Same keys everywhere, same values (numbers to 1e-9), timings and file names aside."""
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


# ---- intrinsic param ----------------------------------------------------------------------------

# (keywords of parameterize, the same options on the command line)
PARAM_CASES = {
    "default": ({}, []),
    "natural": ({"boundary": "natural"}, ["--boundary", "natural"]),
    "authalic": ({"method": "authalic"}, ["--method", "authalic"]),
    "authalic-square": ({"method": "authalic", "boundary": "square"}, ["--method", "authalic", "--boundary", "square"]),
    "mixed-lambda": ({"method": "mixed", "lam": 0.3, "mu": 0.7},
                     ["--method", "mixed", "--lambda", "0.3", "--mu", "0.7"]),
    "tutte-uniform": ({"method": "tutte", "spacing": "uniform"}, ["--method", "tutte", "--spacing", "uniform"]),
    "floater-surface": ({"method": "floater", "scale": "surface"}, ["--method", "floater", "--scale", "surface"]),
    "optimize-lambda-edge": ({"optimize_lambda": "edge"}, ["--optimize-lambda", "edge"]),
    "optimize-lambda-area": ({"optimize_lambda": "area"}, ["--optimize-lambda", "area"]),
    "optimize-boundary": ({"optimize_boundary": "edge", "iterations": 5},
                          ["--optimize-boundary", "edge", "--iterations", "5"]),
    "pins": ({"boundary": "natural", "pins": [(0, 0.0, 0.0), (5, 1.0, 0.25)]},
             ["--boundary", "natural", "--pin", "0:0,0", "--pin", "5:1,0.25"]),
    "holes-natural": ({"holes": "natural"}, ["--holes", "natural"]),
    "holes-free-umfpack": ({"holes": "free", "solver": "umfpack"}, ["--holes", "free", "--solver", "umfpack"]),
}


def check_param(tmp_path, path, options, args, output="out.obj"):
    report, out = run(tmp_path, "param", path, args, output)
    V, F = parse_mesh(path)
    r = intrinsic.parameterize(V, F, **options)
    if output.endswith(".obj"):
        Vc, UVc, Fc, _ = parse_obj(out)
    else:
        Vc, UVc, Fc = parse_ply(out)
    assert_same("uv", r.uv, UVc)
    assert_same("V", r.V, Vc)
    assert_same("F", r.F, Fc)  # the validated faces, reoriented where needed, as written
    assert_same("input V", V, Vc)  # the writer's digits read back to the input's doubles
    assert_reports_equal(r.report, report)
    assert r.residual == r.report["residual"] and r.flipped_triangles == r.report["flipped_triangles"]
    return r


@pytest.mark.parametrize("case", sorted(PARAM_CASES))
@pytest.mark.parametrize("name", ["wave", "holed"])
def test_param_same_as_cli(tmp_path, name, case):
    options, args = PARAM_CASES[case]
    check_param(tmp_path, generated_mesh(name), options, args)


@pytest.mark.parametrize("output", ["out.ply", "out-binary.ply"])
def test_param_ply_same_as_cli(tmp_path, output):
    args = ["--binary"] if "binary" in output else []
    check_param(tmp_path, generated_mesh("strip"), {"method": "mixed", "lam": 0.5, "mu": 0.5},
                ["--method", "mixed", "--lambda", "0.5", "--mu", "0.5", *args], output)


@pytest.mark.parametrize("case", ["default", "natural", "authalic-square", "mixed-lambda", "optimize-lambda-edge"])
@pytest.mark.parametrize("name", ["wave@100", *corpus("cat_head.obj", "fairing-cross.off", "beetle.off",
                                                       "max-planck-partial.obj")])
def test_param_larger_same_as_cli(tmp_path, name, case):
    options, args = PARAM_CASES[case]
    check_param(tmp_path, mesh(name), options, args)


def test_file_input_same_as_cli(tmp_path):
    """parameterize(path) reads the file as the command line does; the report names it."""
    path = generated_mesh("holed")
    report, out = run(tmp_path, "param", path, ["--boundary", "natural"], "out.obj")
    r = intrinsic.parameterize(str(path), boundary="natural")
    assert_same("uv", r.uv, parse_obj(out)[1])
    assert r.report["input"] == report["input"]


def test_charts_same_as_cli(tmp_path):
    """Two components become two charts laid out side by side, on both sides."""
    V, F = parse_mesh(generated_mesh("wave"))
    V2 = np.vstack([V, V + [10.0, 0.0, 0.0]])
    F2 = np.vstack([F, F + V.shape[0]]).astype(np.int32)
    two = tmp_path / "two.obj"
    two.write_text("".join(f"v {x!r} {y!r} {z!r}\n" for x, y, z in V2.tolist()) +
                   "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F2.tolist()))
    r = check_param(tmp_path, two, {}, [])
    assert len(r.report["charts"]) == 2


def test_largest_component_same_as_cli(tmp_path):
    """Only the kept component's faces are in r.F, as in the file the command line writes."""
    two = tmp_path / "two.obj"
    fan = lambda o, n: [f"v {o + np.cos(t)!r} {np.sin(t)!r} 0" for t in np.linspace(0, 2 * np.pi, n, endpoint=False)]
    lines = ["v 0 0 0", *fan(0, 6), "v 5 0 0", *fan(5, 8)]
    lines += [f"f 1 {i + 2} {(i + 1) % 6 + 2}" for i in range(6)]
    lines += [f"f 8 {i + 9} {(i + 1) % 8 + 9}" for i in range(8)]
    two.write_text("\n".join(lines) + "\n")
    r = check_param(tmp_path, two, {"largest_component": True}, ["--largest-component"])
    assert r.F.shape == (8, 3)


@pytest.mark.parametrize("energy", ["edge", "area"])
def test_optimizer_wrappers_same_as_cli(tmp_path, energy):
    path = generated_mesh("wave")
    V, F = parse_mesh(path)
    report, out = run(tmp_path, "param", path, ["--optimize-lambda", energy], "lambda.obj")
    r = intrinsic.optimal_lambda(V, F, energy=energy)
    assert_same("uv", r.uv, parse_obj(out)[1])
    assert r.report["optimal_lambda"]["lambda"] == report["optimal_lambda"]["lambda"]
    report, out = run(tmp_path, "param", path, ["--optimize-boundary", energy, "--iterations", "3"], "boundary.obj")
    r = intrinsic.optimize_boundary(V, F, energy=energy, iterations=3)
    assert_same("uv", r.uv, parse_obj(out)[1])


# ---- intrinsic atlas ----------------------------------------------------------------------------

ATLAS_CASES = {
    "default": ({}, []),
    "padding": ({"padding": 4, "resolution": 256}, ["--padding", "4", "--resolution", "256"]),
    "hard-angle": ({"hard_angle": 40.0, "max_charts": 6}, ["--hard-angle", "40", "--max-charts", "6"]),
    "circle-authalic": ({"boundary": "circle", "method": "authalic"}, ["--boundary", "circle", "--method", "authalic"]),
    "square-optimal-lambda": ({"boundary": "square", "optimize_lambda": "edge"},
                              ["--boundary", "square", "--optimize-lambda", "edge"]),
}


@pytest.mark.parametrize("case", sorted(ATLAS_CASES))
@pytest.mark.parametrize("name", ["torus", "genus2", "holed"])
def test_atlas_same_as_cli(tmp_path, name, case):
    options, args = ATLAS_CASES[case]
    path = generated_mesh(name)
    report, out = run(tmp_path, "atlas", path, args, "atlas.obj")
    V, F = parse_mesh(path)
    a = intrinsic.atlas(V, F, **options)
    Vc, UVc, Fc, FTc = parse_obj(out)
    assert_same("uv", a.uv, UVc)
    assert_same("uv_index", a.uv_index, FTc)
    assert_same("F", a.F, Fc)
    assert_same("V", a.V, Vc)
    assert_same("input V", V, Vc)
    assert a.face_chart.shape == (F.shape[0],) and a.face_chart.max() + 1 == a.report["charts"]
    assert_reports_equal(a.report, report)
