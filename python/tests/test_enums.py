# The choice enums (intrinsic.Method.CONFORMAL, ...): every member's `option`
# is a spelling the command line takes, and together they are every choice
# it lists in --help (the command line, run in a subprocess, is the second
# source).
import re
import subprocess

import pytest

import intrinsic
from conftest import cli_path, generated_mesh

# enum, command, option whose --help lists the choices {a,b,...}
LISTED = [
    (intrinsic.Method, "param", "--method"),
    (intrinsic.Spacing, "param", "--spacing"),
    (intrinsic.ScaleMode, "param", "--scale"),
    (intrinsic.HoleRule, "param", "--holes"),
    (intrinsic.LambdaEnergy, "param", "--optimize-lambda"),
    (intrinsic.BoundaryEnergy, "param", "--optimize-boundary"),
    (intrinsic.GradientRoute, "param", "--gradient"),
    (intrinsic.Descent, "param", "--descent"),
    (intrinsic.BasisMode, "edit", "--basis"),
]


def listed_choices(command, option):
    text = subprocess.run([cli_path(), command, "--help"], capture_output=True, text=True).stdout
    m = re.search(re.escape(option) + r" TEXT:\{([^}]*)\}", text)
    assert m, f"intrinsic {command} --help does not list the choices of {option}"
    return set(m.group(1).split(","))


@pytest.mark.parametrize("enum,command,option", LISTED, ids=[e.__name__ for e, _, _ in LISTED])
def test_members_are_the_cli_choices(enum, command, option):
    assert {m.option for m in enum.__members__.values()} == listed_choices(command, option)


def test_every_enum_is_exported():
    for name in intrinsic._ENUMS:
        enum = getattr(intrinsic, name)
        assert name in intrinsic.__all__ and enum.__members__, name
        for member_name, member in enum.__members__.items():
            assert member.name == member_name and member_name == member_name.upper()
            assert member.option == member_name.lower().replace("_", "-")
            assert getattr(enum, member_name) == member and enum(int(member)) == member


@pytest.mark.parametrize("member", [m for m in intrinsic.SolverKind.__members__.values()], ids=str)
def test_solver_spellings_are_accepted(tmp_path, member):
    """--solver does not list its choices: each spelling runs (or fails for another reason than the
    spelling, where a solver is not built in)."""
    proc = subprocess.run([cli_path(), "param", str(generated_mesh("strip")), "--solver", member.option, "-o",
                           str(tmp_path / "out.obj"), "-q"], capture_output=True, text=True)
    assert proc.returncode != 1, proc.stderr
    bogus = subprocess.run([cli_path(), "param", str(generated_mesh("strip")), "--solver", "no-such-solver", "-o",
                            str(tmp_path / "out.obj"), "-q"], capture_output=True, text=True)
    assert bogus.returncode == 1


@pytest.mark.parametrize("member", [intrinsic.BoundaryShape.CIRCLE, intrinsic.BoundaryShape.SQUARE,
                                    intrinsic.BoundaryShape.NATURAL], ids=str)
def test_boundary_spellings_are_accepted(tmp_path, member):
    """BoundaryShape.GIVEN aside (the keyword takes a boundary file's path for it)."""
    proc = subprocess.run([cli_path(), "param", str(generated_mesh("strip")), "--boundary", member.option, "-o",
                           str(tmp_path / "out.obj"), "-q"], capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr


def test_members_are_distinct_and_hashable():
    for name in intrinsic._ENUMS:
        members = list(getattr(intrinsic, name).__members__.values())
        assert len(set(members)) == len(members) == len({int(m) for m in members})


@pytest.mark.parametrize("options", [
    dict(method="authalic", boundary="square", spacing="uniform"),
    dict(boundary="natural", scale="surface"),
    dict(method="mixed", lam=0.3, mu=0.7, holes="free", solver="umfpack"),
    dict(optimize_lambda="area"),
], ids=["authalic-square", "natural", "mixed", "optimal-lambda"])
def test_members_as_keyword_values_equal_their_spelling(options):
    """A keyword takes the enum member or its spelling; both give the same map."""
    keyword_enum = {"method": intrinsic.Method, "boundary": intrinsic.BoundaryShape, "spacing": intrinsic.Spacing,
                    "scale": intrinsic.ScaleMode, "holes": intrinsic.HoleRule, "solver": intrinsic.SolverKind,
                    "optimize_lambda": intrinsic.LambdaEnergy}
    as_members = {k: (getattr(keyword_enum[k], v.upper().replace("-", "_")) if k in keyword_enum else v)
                  for k, v in options.items()}
    mesh = str(generated_mesh("wave"))
    by_name = intrinsic.parameterize(mesh, **options)
    by_member = intrinsic.parameterize(mesh, **as_members)
    assert (by_name.uv == by_member.uv).all()
    assert by_name.report["method"] == by_member.report["method"]


def test_member_of_the_wrong_enum_is_refused():
    with pytest.raises(ValueError, match="method"):
        intrinsic.parameterize(str(generated_mesh("wave")), method=intrinsic.Spacing.UNIFORM)
