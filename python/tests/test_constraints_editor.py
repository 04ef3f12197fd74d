# Constraints and the boundary editor through Python equal the CLI
# (--constraints, `intrinsic edit`); Parameterizer reuses its factorization.
import json
import subprocess

import numpy as np
import pytest

import intrinsic
from conftest import cli_path, corpus, generated_mesh, mesh, read_obj_uv

CONSTRAINTS = {
    "points": [{"face": 40, "bary": [0.2, 0.3, 0.5], "uv": [0.45, 0.55]}, {"vertex": 60, "uv": [0.6, 0.5]}],
    "lines": [{"path": [{"vertex": 1156}, {"vertex": 1225}], "to": [[0.4, 0.45], [0.45, 0.7]]}],
}


# camel_b.obj (2,032 vertices), and a generated wave of about the same size
# (the constraints' faces and vertices exist in both).
MESHES = ["wave@26", *corpus("camel_b.obj")]


@pytest.mark.parametrize("name", MESHES)
@pytest.mark.parametrize("boundary", ["circle", "natural"])
def test_constraints_like_cli(cli, tmp_path, boundary, name):
    path = mesh(name)
    cfile = tmp_path / "c.json"
    cfile.write_text(json.dumps(CONSTRAINTS))
    c = cli([path, "--constraints", cfile, "--boundary", boundary])
    assert c.returncode == 0, c.stderr
    V, F = intrinsic.read_mesh(path)
    r = intrinsic.parameterize(V, F, boundary=boundary, constraints=CONSTRAINTS)
    np.testing.assert_allclose(r.uv, c.uv, rtol=0, atol=1e-12)
    assert [x["label"] for x in r.report["constraints"]] == [x["label"] for x in c.report["constraints"]]
    r2 = intrinsic.parameterize(V, F, boundary=boundary, constraints=cfile)  # a file path, as the CLI
    assert r2.report["constraints_file"] == str(cfile)
    np.testing.assert_allclose(r2.uv, c.uv, rtol=0, atol=1e-12)
    p = intrinsic.Parameterizer(V, F, boundary=boundary)
    p.set_constraints(CONSTRAINTS)  # after the factorization: Lagrange multipliers
    r3 = p.solve()
    np.testing.assert_allclose(r3.uv, c.uv, rtol=0, atol=1e-10)
    assert p.factorizations == 1


def test_bad_constraints_input_error():
    V, F = intrinsic.read_mesh(generated_mesh("wave@26"))
    with pytest.raises(intrinsic.InputError, match=r"constraints: points\[0\]: unknown key 'uvw'"):
        intrinsic.parameterize(V, F, constraints={"points": [{"vertex": 3, "uvw": [0, 0]}]})
    with pytest.raises(intrinsic.InputError):
        intrinsic.parameterize(V, F, constraints={"points": [{"vertex": 10**6, "uv": [0, 0]}]})


def write_fixed(path, fixed):
    path.write_text("".join(f"{v} {u!r} {w!r}\n" for v, u, w in fixed))


@pytest.mark.parametrize("name", MESHES)
def test_parameterizer_and_editor_like_cli(tmp_path, name):
    path = mesh(name)
    V, F = intrinsic.read_mesh(path)
    p = intrinsic.Parameterizer(V, F)
    base = p.solve()
    fixed = p.boundary
    np.testing.assert_array_equal(base.uv, intrinsic.parameterize(V, F).uv)
    moved = [(fixed[0][0], fixed[0][1] + 0.05, fixed[0][2] - 0.02), (fixed[7][0], 0.5, 0.9)]
    write_fixed(tmp_path / "base.txt", fixed)
    write_fixed(tmp_path / "move.txt", moved)
    out = tmp_path / "edited.obj"
    proc = subprocess.run([cli_path(), "edit", str(path), "--boundary", str(tmp_path / "base.txt"), "-o", str(out),
                           "--move", str(tmp_path / "move.txt"), "-q"], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    editor = intrinsic.BoundaryEditor(p, basis="lazy")
    uv = editor.move(moved)
    np.testing.assert_allclose(uv, read_obj_uv(out), rtol=0, atol=1e-12)
    assert editor.last_update["moved"] == 2
    # the same boundary through solve_with_boundary: no refactorization
    new = dict((v, (u, w)) for v, u, w in fixed)
    new.update((v, (u, w)) for v, u, w in moved)
    r = p.solve_with_boundary([(v, u, w) for v, (u, w) in new.items()])
    np.testing.assert_allclose(r.uv, uv, rtol=0, atol=1e-10)
    assert p.factorizations == 1
