# scripts/benchmarks.py's page writer on canned program output: no benchmark
# runs, no timing asserted; what is checked is that each section's output is
# understood and lands in the page, that absent peers and failed programs are
# said so, and that ratios against a peer come from the runs given.
import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent.parent
spec = importlib.util.spec_from_file_location("benchmarks_page", ROOT / "scripts" / "benchmarks.py")
bp = importlib.util.module_from_spec(spec)
spec.loader.exec_module(bp)


def rec(argv, stdout, rc=0, stderr="", wall=1.0):
    return {"argv": argv, "rc": rc, "stdout": stdout, "stderr": stderr, "wall_s": wall, "cpu_s": wall,
            "maxrss_mb": 100.0}


META = {"start_utc": "2000-01-01 00:00", "end_utc": "00:40", "load_start": "1.00 1.00 1.00",
        "load_end": "2.00 1.50 1.00", "commit": "0123456789", "command": "scripts/benchmarks.py", "quick": False,
        "wall_s": 2400.0,
        "machine": {"nproc": "2", "cpu": "Some CPU", "simd": "AVX2", "memory_gib": 8.0, "debian": "12.0",
                    "kernel": "6.1", "compiler": "g++ 12", "build_type": "Release", "flags": "-O3",
                    "openblas_config": "OpenBLAS 0.3.21 / core Zen",
                    "packages": {"libopenblas0-pthread": "0.3.21", "libsuitesparse-dev": "5.12.0",
                                 "CHOLMOD": "3.0.14", "UMFPACK": "5.7.9", "libcgal-dev": "5.5.1"},
                    "node": "v20", "xatlasjs": "0.2.0", "blender": None, "playwright": None, "gltf_validator": None,
                    "env": {}}}

PARAM = """| mesh | V | method | solver | read | validate | assemble | factor | solve | write | metrics | total s | peak MB | max rel. diff |
|---|---|---|---|---|---|---|---|---|---|---|---|---|---|
| bench-wave-10000.obj | 10267 | conformal | supernodal-cholesky | 0.015 | 0.008 | 0.012 | 0.055 | 0.007 | 0.028 | 0.009 | 0.10 | 16 | 8.4e-15 |
| bench-wave-10000.obj | 10267 | natural | supernodal-cholesky | 0.015 | 0.008 | 0.016 | 0.13 | 0.020 | 0.067 | 0.002 | 0.20 | 21 | 3.5e-18; sensitivity 3.5e-11 |
| bench-wave-30000.obj | 30301 | conformal | supernodal-cholesky | 0.043 | 0.023 | 0.072 | 0.19 | 0.049 | 0.13 | 0.12 | 0.50 | 35 | not checked |
| bench-wave-30000.obj | 30301 | natural | supernodal-cholesky | 0.064 | 0.029 | 0.089 | 0.43 | 0.084 | 0.11 | 0.042 | 1.00 | 49 | not checked |

Scaling exponent (least-squares slope of log total time against log V, generated meshes): conformal 1.45; natural 1.50;
"""

CGAL = """| V | method | CGAL s | ours (parameterize) s | ratio | ours end to end s* | max UV diff |
|---|---|---|---|---|---|---|
| 151201 | conformal | {c} | 0.400 | 19x | 0.5 | 7.5e-14 |
| 151201 | authalic | 8.00 | 0.400 | 20x | 0.5 | 3.1e-14 |
| 151201 | LSCM vs natural | 11.00 | 0.500 | 22x | 0.6 | 8.8e-03 |
"""

EDIT = """/m/max-planck-partial.obj: 31894 vertices, read+validate 114 ms, method conformal
construct (assemble + factor + first solve) 352.7 ms, solver supernodal-cholesky
solve_with_boundary (same fixed set, 2 rhs): median 19.90 ms, factorizations 1
full basis: precompute 3609.5 ms, 439 responses, 106.8 MiB (resolve above 1073741824)
  full k=1     first 0.358 ms, then median 0.017 ms (superposed)
  full k=10    first 0.926 ms, then median 0.229 ms (superposed)
  full k=439   first 31.543 ms, then median 14.740 ms (superposed)
lazy basis: precompute 9.9 ms, 0 responses, 0.0 MiB (resolve above 64)
  lazy k=1     first 7.057 ms, then median 0.017 ms (superposed)
  lazy k=10    first 17.429 ms, then median 0.149 ms (superposed)
  lazy k=439   first 7.201 ms, then median 7.257 ms (re-solved)
10 point constraints, block elimination: set 24.0 ms, solve 8.26 ms
augmented 31465 x 31465, umfpack factor: 344.7 ms
"""

DRAG = """vertices 31894 boundary 439 factor 346.8 ms, round trip 430 ms
server: update_ms median 0.0459 (first 0.04, max 13.99), round trip median 59.4 ms over 5 moves { responses: 5 }
browser (3D and 2D views): mouse event to frame median 259.4 ms (min 82.6, max 288.7) over 5 moves; of which request to parsed answer median 58.2 ms, frame callback (uploads, overlay, GL calls) median 4.7 ms
  medians: event to request sent 173.50 ms, request to headers 21.40 ms (server update 0.04 ms), body (UVs) 32.80 ms, buffer uploads 0.10 ms, frame callback without uploads 4.60 ms
browser (2D view only): mouse event to frame median 97.3 ms (min 60.0, max 271.3) over 5 moves; of which request to parsed answer median 26.6 ms, frame callback (uploads, overlay, GL calls) median 2.6 ms
"""


def atlas_row(charts, util, p95, l2, seconds, overlapping=0):
    return {"charts": charts, "utilization": util, "face_stretch_p95": p95, "sander_l2": l2, "seconds": seconds,
            "overlapping": overlapping, "flipped": 0, "mirrored_charts": 0, "compactness": 0.6,
            "turning_over_60": 0.3, "seam_length": 10.0, "seam_per_sqrt_area": 5.0, "face_stretch_max": 1.5,
            "anisotropy_mean": 1.05}


ATLAS = {"spot": {"intrinsic": atlas_row(21, 0.62, 1.075, 1.001, 0.4),
                  "xatlas": atlas_row(39, 0.56, 1.095, 1.003, 0.7, overlapping=3)},
         "box": {"intrinsic": atlas_row(6, 0.70, 1.0, 1.0, 0.1), "xatlas": atlas_row(6, 0.75, 1.0, 1.0, 0.2)},
         "igea": {"intrinsic": atlas_row(300, 0.73, 1.03, 1.0, 3.9),
                  "xatlas": {"skipped": "not read by this script (PLY)"}},
         "spider": {"intrinsic": {"skipped": "failed: intrinsic atlas: no faces"}}}


def sections():
    return {
        "param": {"runs": [rec("build/bench/intrinsic_bench --sizes 10000,30000", PARAM)]},
        "cgal": {"runs": [rec("build/bench/cgal_compare --sizes 150000", CGAL.format(c=c)) for c in ("7.60", "8.00", "9.20")]},
        "factor": {"runs": [rec("build/bench/supernodal_bench 1000000 2", "", rc=1, stderr="out of memory")]},
        "edit": {"runs": [rec("build/bench/edit_bench m conformal 7", EDIT)]},
        "drag": {"runs": [rec("node web/test/drag_bench.mjs build/intrinsic ../shared/meshes/max-planck-partial.obj 5",
                              DRAG)]},
        "optimize": {"skipped": "`build/bench/optimize_bench` is not built"},
        "atlas": {"runs": [rec("bench/atlas_compare.py MESH...", "")], "data": ATLAS,
                  "kinds": {"spot": "shared", "box": "generated", "igea": "shared", "spider": "held out"}, "xatlas": True, "blender": False},
    }


def test_tables_are_read():
    t = bp.md_dicts(PARAM)
    assert len(t) == 4 and t[0]["method"] == "conformal" and t[3]["total s"] == "1.00"
    assert bp.md_tables("text\n| a | b |\n|---|---|\n| 1 | 2 |\nmore\n") == [[["a", "b"], ["1", "2"]]]


def test_page_has_every_section_and_this_runs_figures():
    page = bp.render_page(META, sections())
    for cls in bp.SECTIONS:
        assert f"## {cls.title}\n" in page
    assert "Output not understood" not in page
    assert "2000-01-01 00:00 to 00:40" in page and "0123456789" in page and "40 min 00 s" in page
    # param: totals and the ratio to conformal
    assert "| generated disk | 30,301 | **0.50** |" in page and "1.00 (2.00x)" in page
    # CGAL: the three runs' ratios and their median, from these runs only
    assert "19x, 20x, 23x" in page and "**20x**" in page
    # a failed program and a missing peer are said, not fatal
    assert "`build/bench/supernodal_bench 1000000 2` failed (exit 1): out of memory" in page
    assert "*Not measured in this run: `build/bench/optimize_bench` is not built.*" in page
    assert "*Not run (`--only`).*" in page  # e.g. scenes, not in the canned run
    # edit: the full basis's precompute and the lazy first drag
    assert "3.61 s, 107 MiB" in page and "0.017 ms (first 7.06 ms)" in page
    # drag: server update and the page's figures
    assert "0.046 ms / 59.4 ms" in page and "259.4 ms (174 ms to the request)" in page
    # atlas: medians over the meshes both tools ran, the PLY one said
    assert "utilization, median over the 1 real meshes | **0.620** (1.11x) | 0.560" in page
    assert "1 of 1 shared, 0 of 1 generated" in page
    assert "box (utilization 70.0% / 75.0%)" in page
    assert "overlapping triangles on 1 of 2 meshes (spot 3)" in page
    assert "igea (not read by this script (PLY))" in page
    assert "| igea | shared | 300 (-) |" in page
    assert "**Ours failed on**: spider (failed: intrinsic atlas: no faces)" in page
    assert "Blender's Smart UV Project: not measured" in page
    # no history on the page
    for word in ("Session", "session ", "before/after"):
        assert word not in page


def test_readme_table_comes_from_the_same_run():
    block = bp.readme_table(META, sections())
    assert block.startswith(bp.README_BEGIN) and block.endswith(bp.README_END)
    assert "0.10 s / 0.50 s" in block  # conformal at 10k / 30k
    assert "20x / 20x / 22x our time" in block
    assert "21 / 39, 62.0% / 56.0%" in block


@pytest.mark.parametrize("version, upstream", [("1:5.12.0+dfsg-2", "5.12.0"), ("0.3.21+ds-4", "0.3.21"),
                                               ("5.1.0.dfsg-7", "5.1.0"), ("3.4.0-4", "3.4.0")])
def test_package_versions(version, upstream):
    assert bp.upstream(version) == upstream
