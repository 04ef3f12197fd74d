# Each error kind raises its intrinsic.Error subclass with the CLI's message.
import numpy as np
import re

import pytest

import intrinsic
from conftest import generated_mesh

TETRA = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n"
BAD_INDEX = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"


def test_hierarchy():
    for cls, code in ((intrinsic.UsageError, 1), (intrinsic.InputError, 2), (intrinsic.NumericalError, 3),
                      (intrinsic.OutputError, 4)):
        assert issubclass(cls, intrinsic.Error) and cls.exit_code == code
    assert issubclass(intrinsic.Error, Exception)


@pytest.mark.parametrize("text", [TETRA, BAD_INDEX], ids=["closed", "bad-index"])
def test_input_errors_match_cli(cli, tmp_path, text):
    path = tmp_path / "in.obj"
    path.write_text(text)
    c = cli([path])
    assert c.returncode == 2
    with pytest.raises(intrinsic.InputError) as e:
        intrinsic.parameterize(str(path))
    assert str(e.value) == c.message


def test_closed_arrays_input_error():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
    F = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]], dtype=np.int32)
    with pytest.raises(intrinsic.InputError, match="closed"):
        intrinsic.parameterize(V, F)


def test_bad_index_arrays_input_error():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float64)
    with pytest.raises(intrinsic.InputError):
        intrinsic.parameterize(V, np.array([[0, 1, 8]], dtype=np.int32))
    with pytest.raises(intrinsic.InputError):
        intrinsic.parameterize(V, np.array([[0, 1, 2**40]], dtype=np.int64))


def test_read_mesh_bad_index_matches_cli(cli, tmp_path):
    path = tmp_path / "in.obj"
    path.write_text(BAD_INDEX)
    c = cli([path])
    try:
        V, F = intrinsic.read_mesh(path)  # the reader may accept it; validation refuses it
        with pytest.raises(intrinsic.InputError):
            intrinsic.parameterize(V, F)
    except intrinsic.InputError as e:
        assert str(e) == c.message


def test_numerical_error_matches_cli(cli):
    path = generated_mesh("wave")
    c = cli([path, "--solver", "bicgstab", "--max-residual", "1e-300"])
    assert c.returncode == 3
    with pytest.raises(intrinsic.NumericalError) as e:
        intrinsic.parameterize(*intrinsic.read_mesh(path), solver="bicgstab", max_residual=1e-300)
    assert str(e.value) == c.message


def test_output_error_matches_cli(cli, tmp_path):
    path = generated_mesh("wave")
    out = tmp_path / "missing-dir" / "x.obj"
    c = cli([path], output="missing-dir/x.obj")
    assert c.returncode == 4
    V, F = intrinsic.read_mesh(path)
    r = intrinsic.parameterize(V, F)
    with pytest.raises(intrinsic.OutputError) as e:
        intrinsic.write_mesh(out, V, F, r.uv)
    assert str(e.value) == c.message
    with pytest.raises(intrinsic.OutputError):
        intrinsic.render(V, F, r.uv, path=tmp_path / "missing-dir" / "x.png", size=(16, 16))


@pytest.mark.parametrize("options,args", [
    ({"method": "foo"}, ["--method", "foo"]),
    ({"spacing": "foo"}, ["--spacing", "foo"]),
    ({"method": "mixed"}, ["--method", "mixed"]),
    ({"lam": 0.5}, ["--lambda", "0.5"]),
    ({"method": "authalic", "boundary": "natural"}, ["--method", "authalic", "--boundary", "natural"]),
    ({"solver": "nope"}, ["--solver", "nope"]),
    ({"optimize_lambda": "edge", "optimize_boundary": "edge"}, ["--optimize-lambda", "edge",
                                                               "--optimize-boundary", "edge"]),
])
def test_usage_errors_match_cli(cli, options, args):
    """The same message, naming keywords where the command line names flags."""
    path = generated_mesh("wave")
    c = cli([path, *args])
    assert c.returncode == 1
    with pytest.raises(intrinsic.UsageError) as e:
        intrinsic.parameterize(*intrinsic.read_mesh(path), **options)
    keywords = re.sub(r"--([a-z][a-z-]*)", lambda m: m.group(1).replace("-", "_"), c.message)
    assert str(e.value) == keywords
    assert "--" not in str(e.value)


def test_usage_errors_name_keywords():
    V, F = intrinsic.read_mesh(generated_mesh("wave"))
    with pytest.raises(intrinsic.UsageError, match=r"^pins '3:x': expected VERTEX:U,V"):
        intrinsic.parameterize(V, F, boundary="natural", pins=["3:x"])
    with pytest.raises(intrinsic.UsageError,
                       match=r"^method: 'foo' is not one of conformal, authalic, mixed, tutte, floater$"):
        intrinsic.parameterize(V, F, method="foo")
    with pytest.raises(intrinsic.UsageError, match=r"^iterations: -1 is not at least 0$"):
        intrinsic.parameterize(V, F, optimize_boundary="edge", iterations=-1)


def test_unknown_option_and_lambda_spellings():
    V, F = intrinsic.read_mesh(generated_mesh("wave"))
    with pytest.raises(intrinsic.UsageError, match="unknown option 'colour'"):
        intrinsic.parameterize(V, F, colour="red")
    a = intrinsic.parameterize(V, F, method="mixed", lam=0.3, mu=0.7).uv
    b = intrinsic.parameterize(V, F, method="mixed", lambda_=0.3, mu=0.7).uv
    c = intrinsic.parameterize(V, F, method="mixed", mu=0.7, **{"lambda": 0.3}).uv
    assert np.array_equal(a, b) and np.array_equal(a, c)
    with pytest.raises(intrinsic.UsageError):
        intrinsic.parameterize(V, F, method="mixed", lam=0.3, lambda_=0.3)


def test_bad_arrays_are_usage_errors():
    with pytest.raises(intrinsic.UsageError, match="n x 3"):
        intrinsic.parameterize(np.zeros((4, 2)), np.zeros((1, 3), dtype=np.int32))
    with pytest.raises(intrinsic.UsageError, match="integer"):
        intrinsic.parameterize(np.zeros((4, 3)), np.zeros((1, 3)))


# ---- the built-in exceptions they also are ----------------------------------------------------

FILE_CLASSES = [("FileNotFoundError", FileNotFoundError), ("PermissionError", PermissionError),
                ("IsADirectoryError", IsADirectoryError), ("NotADirectoryError", NotADirectoryError),
                ("OSError", OSError)]


def test_builtin_bases():
    assert issubclass(intrinsic.UsageError, ValueError)
    for kind, base in (("Input", intrinsic.InputError), ("Output", intrinsic.OutputError)):
        for suffix, builtin in FILE_CLASSES:
            cls = getattr(intrinsic, kind + suffix)
            assert issubclass(cls, base) and issubclass(cls, builtin) and cls.exit_code == base.exit_code
            assert cls.__name__ == kind + suffix and cls.__module__ == "intrinsic"
    for cls in (intrinsic.InputError, intrinsic.NumericalError, intrinsic.OutputError, intrinsic.Error):
        assert not issubclass(cls, (ValueError, OSError))


def test_bad_keyword_value_is_a_value_error():
    V, F = intrinsic.read_mesh(generated_mesh("wave"))
    with pytest.raises(ValueError) as e:
        intrinsic.parameterize(V, F, method="foo")
    assert isinstance(e.value, intrinsic.UsageError) and e.value.exit_code == 1


def test_missing_mesh_is_file_not_found(cli, tmp_path):
    import errno
    path = tmp_path / "no-such-mesh.obj"
    c = cli([path])
    assert c.returncode == 2
    for call in (lambda: intrinsic.read_mesh(path), lambda: intrinsic.parameterize(str(path)),
                 lambda: intrinsic.atlas(str(path))):
        with pytest.raises(FileNotFoundError) as e:
            call()
        assert isinstance(e.value, intrinsic.InputError) and type(e.value) is intrinsic.InputFileNotFoundError
        assert e.value.errno == errno.ENOENT and str(e.value) == c.message


def test_missing_side_files_are_file_not_found(tmp_path):
    V, F = intrinsic.read_mesh(generated_mesh("wave"))
    with pytest.raises(FileNotFoundError, match="no-such-boundary.txt"):
        intrinsic.parameterize(V, F, boundary=str(tmp_path / "no-such-boundary.txt"))
    with pytest.raises(intrinsic.InputFileNotFoundError, match="no-such-constraints.json"):
        intrinsic.parameterize(V, F, constraints=str(tmp_path / "no-such-constraints.json"))


def test_directory_and_not_a_directory(tmp_path):
    import errno
    with pytest.raises(IsADirectoryError) as e:
        intrinsic.read_mesh(tmp_path)
    assert isinstance(e.value, intrinsic.InputError) and e.value.errno == errno.EISDIR
    (tmp_path / "file.obj").write_text(BAD_INDEX)
    with pytest.raises(NotADirectoryError) as e:
        intrinsic.read_mesh(tmp_path / "file.obj" / "x.obj")
    assert isinstance(e.value, intrinsic.InputError) and e.value.errno == errno.ENOTDIR


def test_output_file_errors(tmp_path):
    import errno
    V, F = intrinsic.read_mesh(generated_mesh("wave"))
    with pytest.raises(FileNotFoundError) as e:
        intrinsic.write_mesh(tmp_path / "missing-dir" / "x.obj", V, F)
    assert isinstance(e.value, intrinsic.OutputError) and e.value.errno == errno.ENOENT
    (tmp_path / "taken.obj").mkdir()
    with pytest.raises(IsADirectoryError) as e:
        intrinsic.write_mesh(tmp_path / "taken.obj", V, F)
    assert isinstance(e.value, intrinsic.OutputError)
    assert not list((tmp_path / "taken.obj").iterdir())  # nothing partial left behind


def test_permission_errors(tmp_path):
    """A file the process may not read, a folder it may not write in. Root may do both: then sysfs,
    which refuses new files to everyone, stands in for the second, where Python's own mkstemp there
    fails with EACCES too."""
    import errno
    import os
    import tempfile
    V, F = intrinsic.read_mesh(generated_mesh("wave"))
    if os.geteuid() != 0:
        secret = tmp_path / "secret.obj"
        secret.write_text(BAD_INDEX)
        secret.chmod(0)
        with pytest.raises(PermissionError) as e:
            intrinsic.read_mesh(secret)
        assert isinstance(e.value, intrinsic.InputError)
        locked = tmp_path / "locked"
        locked.mkdir()
        locked.chmod(0o500)
        target = locked / "x.obj"
    else:
        try:
            os.close(tempfile.mkstemp(dir="/sys")[0])
            pytest.skip("running as root and /sys takes new files: no folder refuses writing")
        except OSError as e:
            if e.errno != errno.EACCES:
                pytest.skip(f"running as root and /sys refuses new files with {errno.errorcode[e.errno]}")
        target = "/sys/intrinsic-test.obj"
    with pytest.raises(PermissionError) as e:
        intrinsic.write_mesh(target, V, F)
    assert isinstance(e.value, intrinsic.OutputError) and type(e.value) is intrinsic.OutputPermissionError


def test_errors_without_a_file_are_not_os_errors():
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
    F = np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]], dtype=np.int32)
    with pytest.raises(intrinsic.InputError) as e:
        intrinsic.parameterize(V, F)
    assert type(e.value) is intrinsic.InputError and not isinstance(e.value, OSError)
