#!/usr/bin/python3
"""Runs every benchmark program docs/benchmarks.md reports, in one run, and
writes the whole page: the machine, the date, the commit, the load and the
run's wall time, then one section per thing measured (a fixed paragraph on
what is measured and by which program, then this run's figures).

    scripts/benchmarks.py [--build DIR] [--quick] [--out FILE] [--only KEY,...]
                          [--raw FILE] [--render RAW] [--no-pictures]

--build DIR   the CMake build tree with build/intrinsic and build/bench/*
              (default: build). Nothing is built here: build it first.
--quick       small sizes and one run each, a few minutes: for checking this
              script. Writes BUILD/benchmarks-quick.md unless --out is given.
--out FILE    the page (default docs/benchmarks.md; --quick: see above).
--only KEYS   run these sections only (keys: see SECTIONS); the others say
              they were not run. For working on one section.
--raw FILE    also keep every program's output as JSON (default
              BUILD/benchmarks-run.json): the page can be written again from
              it with --render FILE, without running anything.
--no-pictures do not redraw docs/images/atlas-compare-*.png.

When the page written is the repository's docs/benchmarks.md (the default,
full run), the run also redraws the atlas comparison pictures
(bench/atlas_pictures.py into docs/images) and rewrites README.md's
"Measured" table between its <!-- benchmarks --> markers, so that every
figure in the repository comes from this one run.

A peer that is absent (cgal_compare not built, no Blender, no Node or
xatlasjs in bench/node_modules, no Chromium or playwright-core in
web/test/node_modules, no gltf-validator in tests/gltf_validator/node_modules,
no ../shared/meshes) makes its section say so instead of failing; so does a
program that fails. Uses Debian's /usr/bin/python3 (numpy; Pillow for the
pictures).
"""
import argparse
import datetime
import json
import math
import os
import platform
import re
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
BENCH = os.path.join(ROOT, "bench")
DOCS = os.path.join(ROOT, "docs")
DEFAULT_OUT = os.path.join(DOCS, "benchmarks.md")

# Debian's assimp-testmodels held out from the atlas's tuning.
HELD_OUT = ["OBJ/spider.obj", "STL/Spider_binary.stl", "OBJ/WusonOBJ.obj", "OFF/Wuson.off", "STL/3DSMaxExport.STL",
            "STL/sphereWithHole.stl", "OBJ/regr01.obj"]
ASSIMP_MODELS = "/usr/share/assimp/models"
# `intrinsic generate` surfaces for the atlas comparison: (file name, arguments).
GENERATED = [("plate", ["plate"]), ("box", ["box"]), ("l-panel", ["l-panel"]), ("panel-strip", ["panel-strip"]),
             ("cylinder", ["cylinder"]), ("rectangle", ["rectangle"]), ("sphere", ["sphere"]), ("torus", ["torus"]),
             ("torus40", ["torus", "--rings", "40"]), ("genus2", ["genus2"])]
LIGHTMAP_MESHES = ["spot.obj", "truck.obj", "bumpy-cube.obj", "rocker-arm.obj", "teapot.obj", "suzanne.obj",
                   "fertility.off", "arm.obj"]


# ---------------------------------------------------------------------------
# Running programs


class Context:
    """Where things are, which sizes (quick or full), and the record of every
    program run (argv as shown on the page, output, exit code, wall and CPU
    seconds, peak resident MB)."""

    def __init__(self, build, quick, work, shared):
        self.build = build
        self.quick = quick
        self.work = work
        self.shared = shared
        self.cli = os.path.join(build, "intrinsic")

    def q(self, quick, full):
        return quick if self.quick else full

    def bench(self, name):
        return os.path.join(self.build, "bench", name)

    def have_bench(self, name):
        return os.access(self.bench(name), os.X_OK)

    def mesh(self, rel):
        """A shared mesh's path, or None when it is absent."""
        p = os.path.join(self.shared, rel)
        return p if os.path.exists(p) else None

    def show(self, argv):
        """argv as the page shows it: repository-relative paths, $WORK for the
        run's scratch folder, ../shared/meshes for the shared meshes."""
        out = []
        for a in argv:
            a = str(a)
            for prefix, name in ((self.work, "$WORK"), (self.shared, "../shared/meshes"),
                                 (self.build, os.path.relpath(self.build, ROOT) if self.build.startswith(ROOT) else self.build),
                                 (ROOT + os.sep, "")):
                if a.startswith(prefix):
                    a = name + a[len(prefix):] if name else a[len(prefix):]
                    break
            out.append(a if re.fullmatch(r"[\w@%+=:,./$-]*", a) else "'" + a + "'")
        return " ".join(out)

    def run(self, argv, cwd=None, timeout=None, show=None):
        """Runs argv, its output to files; returns the record (never raises for
        a failing program: rc says)."""
        argv = [str(a) for a in argv]
        log(self.show(argv))
        out_f = tempfile.TemporaryFile(mode="w+")
        err_f = tempfile.TemporaryFile(mode="w+")
        t0 = time.monotonic()
        try:
            p = subprocess.Popen(argv, stdout=out_f, stderr=err_f, cwd=cwd, start_new_session=True)
        except OSError as e:
            return {"argv": show or self.show(argv), "rc": 127, "stdout": "", "stderr": str(e), "wall_s": 0.0,
                    "cpu_s": 0.0, "maxrss_mb": 0.0}
        rc, ru = None, None
        while rc is None:
            pid, status, usage = os.wait4(p.pid, os.WNOHANG)
            if pid:
                rc = os.waitstatus_to_exitcode(status)
                ru = usage
                break
            if timeout and time.monotonic() - t0 > timeout:
                os.killpg(p.pid, signal.SIGKILL)
                _, status, ru = os.wait4(p.pid, 0)
                rc = "timeout"
                break
            time.sleep(0.05)
        p.returncode = rc if isinstance(rc, int) else -9  # reaped here; keep Popen from waiting again
        wall = time.monotonic() - t0
        out_f.seek(0)
        err_f.seek(0)
        rec = {"argv": show or self.show(argv), "rc": rc, "stdout": out_f.read(), "stderr": err_f.read()[-4000:],
               "wall_s": round(wall, 3), "cpu_s": round(ru.ru_utime + ru.ru_stime, 3),
               "maxrss_mb": round(ru.ru_maxrss / 1024, 1)}
        if rc != 0:
            log(f"  exit {rc}: {rec['stderr'].strip().splitlines()[-1:] or ''}")
        return rec


def log(msg):
    print(time.strftime("[%H:%M:%S] ") + msg, file=sys.stderr, flush=True)


def loadavg():
    with open("/proc/loadavg") as f:
        return " ".join(f.read().split()[:3])


def failed(rec):
    return rec["rc"] != 0


# ---------------------------------------------------------------------------
# Markdown helpers


def md_tables(text):
    """Every Markdown table in text: a list of tables, each a list of rows
    (lists of cell strings, header first, the |---| line left out)."""
    tables, cur = [], None
    for line in text.splitlines():
        s = line.strip()
        if s.startswith("|") and s.endswith("|") and len(s) > 1:
            cells = [c.strip() for c in s[1:-1].split("|")]
            if all(re.fullmatch(r":?-+:?", c) for c in cells if c) and any(cells):
                continue
            if cur is None:
                cur = []
                tables.append(cur)
            cur.append(cells)
        else:
            cur = None
    return tables


def md_dicts(text, index=0):
    """Table `index` of text as a list of {header: cell}."""
    tables = md_tables(text)
    if len(tables) <= index:
        return []
    head = tables[index][0]
    return [dict(zip(head, row)) for row in tables[index][1:]]


def table(head, rows):
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def code(text):
    return "\n".join("    " + l if l else "" for l in text.rstrip().splitlines())


def fnum(x, digits=3):
    """A figure with `digits` significant digits, plain notation."""
    if x is None:
        return "-"
    if isinstance(x, str):
        return x
    if x == 0:
        return "0"
    if not math.isfinite(x):
        return "inf"
    d = max(0, digits - 1 - int(math.floor(math.log10(abs(x)))))
    return f"{x:,.{d}f}"


def fval(x):
    """A measure as read: counts as integers, other figures to 3 significant digits."""
    return str(int(x)) if isinstance(x, int) or (isinstance(x, float) and x.is_integer()) else fnum(x)


def ms(x):
    """Milliseconds as a person reads them: 3 significant digits, seconds from 1000 ms."""
    return f"{fnum(x / 1000)} s" if x >= 1000 else f"{x:.3g} ms"


def upstream(version):
    """A Debian package version without its epoch and revision: 1:5.12.0+dfsg-2 -> 5.12.0."""
    return re.sub(r"(\.dfsg|[+~-]).*$", "", version.split(":", 1)[-1]) if version else version


def times(r):
    """A ratio as "19x" (or "2.4x" under 10)."""
    return f"{r:.1f}x" if r < 10 else f"{r:.0f}x"


def median(xs):
    xs = [x for x in xs if x is not None]
    return statistics.median(xs) if xs else None


def duration(s):
    s = int(round(s))
    return f"{s // 60} min {s % 60:02d} s" if s >= 60 else f"{s} s"


def commands_block(raw):
    """The commands a section ran, as the page shows them."""
    return code("\n".join(r["argv"] for r in raw.get("runs", [])))


def failure_note(rec):
    last = (rec["stderr"].strip() or rec["stdout"].strip()).splitlines()[-3:]
    return f"`{rec['argv']}` failed (exit {rec['rc']}): " + " / ".join(l.strip() for l in last)


# ---------------------------------------------------------------------------
# Sections: each has a key, a title, fixed prose (what is measured, by which
# program), measure(ctx) -> raw (JSON-able; "runs" lists the program runs)
# and render(raw) -> Markdown of this run's figures.

SECTIONS = []


def section(key, title, prose):
    def wrap(cls):
        cls.key, cls.title, cls.prose = key, title, prose.strip()
        SECTIONS.append(cls)
        return cls
    return wrap


@section("param", "`param` end to end", """
`intrinsic param` as a user runs it, from reading the OBJ to writing the OBJ
with UVs and measuring the map, per method, on generated irregular curved
disks (`generate_wavy_patch`, denser on one side, rings = sqrt(V/3)) written
to an OBJ once so that reading parses a real file, and on the shared scan
`max-planck-partial-loop2.obj.gz`. Program: `bench/intrinsic_bench`. Each
case runs in its own child process, so its peak memory (`ru_maxrss`) is its
own. Stages: read, validate, assemble (with the ordering and the symbolic
analysis running beside it on the other core), factor (what is left of the
ordering and analysis, then the numeric factorization), solve, write and
metrics. Write and metrics run at the same time (the OBJ on one thread, the
distortion figures on the other), so the total is the wall time of the whole
call, not the sum of the columns. Solvers under `auto`: supernodal Cholesky
(conformal), supernodal LU (authalic, mixed), complex supernodal Cholesky
(natural); see [performance.md](performance.md).

Every case up to the check size is checked against a plain reference solve
to 1e-9 relative (triplet assembly, Eigen's simplicial LDLᵀ for the symmetric
systems, UMFPACK with its default analysis otherwise). The natural map is
checked to 1e-11 against the exact solution of its system (CHOLMOD's complex
factor refined with the bench's own compensated residual of the real 2n x 2n
system until the correction is an ulp; it shares neither factor nor residual
code with the library), and the bench reports that map's **sensitivity**:
the same reference after multiplying every entry of the system and of the
right-hand side by (1 + u ε), u in [−1, 1] drawn per entry, i.e. how far
rounding of the input alone moves the map, the most any double-precision
pipeline can promise. The scaling exponent is the least-squares slope of
log(total) against log(V) over the generated disks.

Larger sizes are left out of the run for its time and memory; 10M vertices,
for example, run as `build/intrinsic generate wave --rings 1826 -o
wave10m.obj`, then `/usr/bin/time -v build/intrinsic param wave10m.obj
--boundary natural -o out.obj --report r.json`.
""")
class Param:
    @staticmethod
    def measure(ctx):
        sizes = ctx.q("10000,30000", "100000,300000,1000000")
        argv = [ctx.bench("intrinsic_bench"), "--sizes", sizes, "--runs", ctx.q(1, 3),
                "--check-max", ctx.q(30000, 300000), "--workdir", os.path.join(ctx.work, "param")]
        os.makedirs(os.path.join(ctx.work, "param"), exist_ok=True)
        scan = ctx.mesh("max-planck-partial-loop2.obj.gz")
        if scan and not ctx.quick:
            argv += ["--mesh", scan]
        return {"runs": [ctx.run(argv)], "sizes": sizes, "scan": bool(scan and not ctx.quick)}

    @staticmethod
    def render(raw):
        rec = raw["runs"][0]
        rows = md_dicts(rec["stdout"])
        if failed(rec) or not rows:
            return failure_note(rec)
        by = {}
        for r in rows:
            by.setdefault((r["mesh"], r["V"]), {})[r["method"]] = r
        out = []
        head = ["mesh", "vertices", "conformal s", "authalic s", "mixed s", "natural s",
                "peak MB (conformal / authalic / mixed / natural)"]
        body = []
        for (mesh, v), m in by.items():
            def cell(meth):
                r = m.get(meth)
                if not r or r.get("total s", "") in ("", None):
                    return "failed" if r else "-"
                t = float(r["total s"])
                base = m.get("conformal")
                if meth != "conformal" and base and base.get("total s"):
                    return f"{t:.2f} ({t / float(base['total s']):.2f}x)"
                return f"**{t:.2f}**" if meth == "conformal" else f"{t:.2f}"
            peaks = " / ".join(m[k]["peak MB"] if k in m else "-" for k in ("conformal", "authalic", "mixed", "natural"))
            name = "generated disk" if mesh.startswith("bench-wave-") else mesh
            body.append([name, f"{int(v):,}" if v.isdigit() else v] + [cell(k) for k in
                                                                         ("conformal", "authalic", "mixed", "natural")] + [peaks])
        out.append("Total seconds, median of the runs (ratio to conformal):\n")
        out.append(table(head, body))
        out.append("\nPer stage (seconds), solver, peak memory and the check:\n")
        stage_rows = []
        for r in rows:
            name = "disk" if r["mesh"].startswith("bench-wave-") else r["mesh"]
            stage_rows.append([name, r["V"], r["method"], r["solver"], r["read"], r["validate"], r["assemble"],
                               r["factor"], r["solve"], r["write"], r["metrics"], r["total s"], r["peak MB"],
                               r["max rel. diff"]])
        out.append(table(["mesh", "V", "method", "solver", "read", "validate", "assemble", "factor", "solve", "write",
                          "metrics", "total", "peak MB", "max rel. diff"], stage_rows))
        m = re.search(r"Scaling exponent[^:]*:(.*)", rec["stdout"])
        if m:
            out.append("\nScaling exponent of the total over the generated disks: " + m.group(1).strip().rstrip(";")
                       .replace(";", ",") + ".")
        return "\n".join(out)


@section("cgal", "Against CGAL", """
CGAL's `Surface_mesh_parameterization` against ours (`intrinsic::parameterize`:
assemble, factor, solve) on the same generated disk, both with the mesh in
memory (CGAL's built into a `CGAL::Surface_mesh`). Program:
`bench/cgal_compare` (built when Debian's `libcgal-dev` is found at configure
time; a benchmark-only dependency). Fixed-border methods get exactly the same
circle (CGAL's arc-length circle from its border half-edge, given to ours as
positions), so the UVs must agree to CGAL's solver tolerance: its default
solver for these is BiCGSTAB with an ILUT preconditioner. CGAL's LSCM gets
the same two pins as our natural map, but it is not the same map: it writes
each triangle's equation as (Z1 − Z0)(U2 − U0) = (Z2 − Z0)(U1 − U0) without
dividing by the triangle's size, which weights each triangle's conformal
energy by its area once more; on these irregular disks the layouts differ by
about 1e-2 (our natural map is tested against an independent per-triangle
LSCM instead). The program runs each method once per invocation; it is run
several times and the ratio of each run is shown.
""")
class Cgal:
    @staticmethod
    def measure(ctx):
        if not ctx.have_bench("cgal_compare"):
            return {"skipped": "`build/bench/cgal_compare` is not built (CGAL was not found at configure time, "
                               "or -DINTRINSIC_BENCH_CGAL=OFF)"}
        size = ctx.q("20000", "150000")
        return {"runs": [ctx.run([ctx.bench("cgal_compare"), "--sizes", size]) for _ in range(ctx.q(1, 3))]}

    @staticmethod
    def render(raw):
        per = {}
        vertices = None
        for rec in raw["runs"]:
            if failed(rec):
                return failure_note(rec)
            for r in md_dicts(rec["stdout"]):
                vertices = r["V"]
                per.setdefault(r["method"], []).append(r)
        if not per:
            return failure_note(raw["runs"][0])
        names = {"conformal": "conformal", "authalic": "authalic", "LSCM vs natural": "CGAL's LSCM against our natural map"}
        rows = []
        summary = {}
        for meth, rs in per.items():
            cg = [float(r["CGAL s"].split()[0]) for r in rs]
            ours = [float(r["ours (parameterize) s"]) for r in rs]
            ratios = [c / o for c, o in zip(cg, ours)]
            summary[meth] = median(ratios)
            rows.append([names.get(meth, meth), ", ".join(times(x) for x in ratios),
                         f"**{times(median(ratios))}**", f"{median(cg):.2f} / {median(ours):.3f}",
                         max((r["max UV diff"] for r in rs), key=float)])
        out = [f"{int(vertices):,} vertices, {len(raw['runs'])} run(s):\n",
               table(["method", "CGAL's time / ours, each run", "median", "median seconds: CGAL / ours",
                      "max UV difference"], rows)]
        return "\n".join(out)


@section("factor", "Sparse factorizations", """
The numeric factorizations alone, on the same symbolic analysis (CHOLMOD's,
on the library's nested-dissection ordering), so the flop counts agree and
the rows separate the kernels (CHOLMOD against ours on one thread) from the
parallelism (ours, one thread against all cores). The variants alternate
within each round; each row is the median of the rounds. Our flop count is of
the supernodal panels with their explicit zeros, hence slightly above
CHOLMOD's. Programs: `bench/supernodal_bench` (the conformal system by
CHOLMOD and our supernodal Cholesky; the authalic system by our supernodal
LU; the last columns are the largest relative residual of the unrefined
solves and the refinement steps the solver's rule would add) and
`bench/complex_cholesky_bench` (the natural map's complex Hermitian system
by CHOLMOD's complex supernodal factor and ours). `complex_cholesky_bench
--relax N R` compares supernode amalgamations (not run here).
""")
class Factor:
    @staticmethod
    def measure(ctx):
        n, rounds = ctx.q("50000", "1000000"), ctx.q("1", "2")
        runs = []
        for prog in ("supernodal_bench", "complex_cholesky_bench"):
            if ctx.have_bench(prog):
                runs.append(ctx.run([ctx.bench(prog), n, rounds]))
        if not runs:
            return {"skipped": "the factorization benches are not built"}
        return {"runs": runs}

    @staticmethod
    def render(raw):
        out = []
        for rec in raw["runs"]:
            name = os.path.basename(rec["argv"].split()[0])
            if failed(rec):
                out.append(failure_note(rec))
                continue
            text = rec["stdout"].strip()
            if "needs" in text and "|" not in text:
                out.append(f"`{name}`: {text}")
                continue
            lines = [l for l in text.splitlines() if l.strip() and not l.startswith("|")]
            out.append(f"`{name}`:\n")
            out += [f"- {l.strip()}" for l in lines]
            out.append("")
            out.append("\n".join(l for l in text.splitlines() if l.startswith("|")))
            out.append("")
        return "\n".join(out).rstrip()


@section("ordering", "Fill-reducing ordering", """
The library's nested-dissection ordering alone on the conformal system: its
CPU time on one thread and on all cores (with the calling thread's share, the
bound on its wall time on idle cores), then CHOLMOD's supernodal analysis on
it and the fill and flops that analysis counts, and a hash of the permutation
(the same for any thread count). No numeric factorization. Program:
`bench/intrinsic_bench --orderings-analysis N|FILE`; the two thread counts
alternate over two rounds and each figure is the median of the runs, the
rounds' two medians shown as "a, b". Then the same systems ordered by
CHOLMOD's AMD and by METIS 5.1 (`intrinsic_bench --orderings N|FILE`, one run):
the fill and flops are CHOLMOD's analysis of each permutation (machine
independent); the times are the ordering's CPU, CHOLMOD's analysis and the
numeric factorization (CHOLMOD's supernodal factor for every ordering).
""")
class Ordering:
    @staticmethod
    def measure(ctx):
        if not ctx.have_bench("intrinsic_bench"):
            return {"skipped": "`build/bench/intrinsic_bench` is not built"}
        runs, cases = [], []
        scan = ctx.mesh("max-planck-partial-loop2.obj.gz")
        what = ctx.q(["30000"], ["150000", "1000000"] + ([scan] if scan else []))
        for w in what:
            runs.append(ctx.run([ctx.bench("intrinsic_bench"), "--runs", ctx.q(1, 3), "--orderings-analysis", w]))
            cases.append(("analysis", w))
        for w in ctx.q(["20000"], ["100000", "300000"]):
            runs.append(ctx.run([ctx.bench("intrinsic_bench"), "--orderings", w]))
            cases.append(("orderings", w))
        return {"runs": runs, "cases": cases}

    @staticmethod
    def render(raw):
        def name(w):
            if w.isdigit():
                return f"generated disk {int(w) // 1000}k" if int(w) < 10 ** 6 else f"generated disk {int(w) / 1e6:g}M"
            return os.path.basename(w).split(".")[0] + " (scan)"

        out = []
        rows = []
        for (kind, w), rec in zip(raw["cases"], raw["runs"]):
            if kind != "analysis":
                continue
            if failed(rec):
                out.append(failure_note(rec))
                continue
            rs = md_dicts(rec["stdout"])
            one = [r for r in rs if r["threads"] == "1"]
            alls = [r for r in rs if r["threads"] != "1"]
            if not one or not alls:
                continue
            pair = lambda xs, k: ", ".join(x[k] for x in xs)
            rows.append([name(w), f"{int(one[0]['n (conformal)']):,}", pair(one, "order s (CPU)"),
                         pair(alls, "order s (CPU)") + " (" + pair(alls, "order s (calling thread's CPU)") + ")",
                         pair(alls, "order s (wall)"), pair(alls, "analyse s (CPU)"),
                         f"{int(one[0]['nnz(L)']):,}", one[0]["GFlop"], one[0]["permutation hash"]])
        if rows:
            out.append("The library's ordering, CPU seconds (medians):\n")
            out.append(table(["mesh (conformal system)", "n", "1 thread", "all cores (calling thread)",
                              "all cores, wall", "CHOLMOD analysis CPU", "nnz(L)", "GFlop", "permutation hash"], rows))
        rows = []
        for (kind, w), rec in zip(raw["cases"], raw["runs"]):
            if kind != "orderings":
                continue
            if failed(rec):
                out.append("\n" + failure_note(rec))
                continue
            by = {}
            for r in md_dicts(rec["stdout"]):
                by.setdefault(r["system"], {})[r["ordering"]] = r
            for system, o in by.items():
                cells = []
                for ordname in o:
                    r = o[ordname]
                    nnz = float(r["nnz(factor)"])
                    order = r["order s (CPU)"] if r["order s (CPU)"] not in ("", "-") else "(in analysis)"
                    cells.append(f"{ordname}: {nnz / 1e6:.2f}M / {float(r['GFlop']):.2f}; "
                                 f"{order} + {r['analyse s']} + {r['factor s']} s")
                rows.append([name(w), system, "<br>".join(cells)])
        if rows:
            out.append("\nOrderings compared: nnz(L) / GFlop; seconds to order (CPU) + analyse + factor:\n")
            out.append(table(["mesh", "system", "per ordering"], rows))
        return "\n".join(out)


@section("pattern", "Weight and free-block patterns", """
The weight matrix K's pattern and the free block's pattern (the ordering
thread's input) on a generated disk: building the free block's pattern from
the faces against cutting it out of K's pattern, each on one thread and on
all cores, alternately, medians of wall and process CPU time. Program:
`bench/pattern_bench N R`.
""")
class Pattern:
    @staticmethod
    def measure(ctx):
        if not ctx.have_bench("pattern_bench"):
            return {"skipped": "`build/bench/pattern_bench` is not built"}
        return {"runs": [ctx.run([ctx.bench("pattern_bench"), ctx.q("100000", "1000000"), ctx.q("1", "5")])]}

    @staticmethod
    def render(raw):
        rec = raw["runs"][0]
        if failed(rec):
            return failure_note(rec)
        text = rec["stdout"].strip()
        lines = [l for l in text.splitlines() if l.strip() and not l.startswith("|")]
        return " ".join(lines) + "\n\n" + "\n".join(l for l in text.splitlines() if l.startswith("|"))


@section("edit", "Boundary editing", """
`intrinsic edit` and the editor's update after the precompute (conformal map,
circle boundary): the construction (assemble, factor, first solve), a fresh
solve with the kept factorization, the full basis of responses (its
precompute time and memory), and one update for 1, 10 and all boundary
vertices moved, with the full basis (superposed responses) and with the lazy
basis, whose first drag of a set of vertices computes their responses; with
more than 64 vertices moved the lazy basis re-solves with the kept
factorization instead of superposing (`--resolve-above`, [cli.md](cli.md#edit)).
Then 10 interior point constraints added by block elimination against the
kept factor. Program: `bench/edit_bench MESH conformal REPS` (medians of REPS
updates after the first).
""")
class Edit:
    @staticmethod
    def measure(ctx):
        if not ctx.have_bench("edit_bench"):
            return {"skipped": "`build/bench/edit_bench` is not built"}
        meshes = []
        mp = ctx.mesh("max-planck-partial.obj")
        if mp:
            meshes.append(mp)
        runs = []
        if not ctx.quick or not mp:
            wave = os.path.join(ctx.work, "wave-%d.obj" % ctx.q(60, 183))
            runs.append(ctx.run([ctx.cli, "generate", "wave", "--rings", ctx.q(60, 183), "-o", wave]))
            meshes.append(wave)
        for m in meshes:
            runs.append(ctx.run([ctx.bench("edit_bench"), m, "conformal", ctx.q(3, 7)]))
        return {"runs": runs}

    @staticmethod
    def parse(text):
        d = {"basis": []}
        m = re.search(r"^(\S+): (\d+) vertices", text, re.M)
        d["mesh"], d["vertices"] = os.path.basename(m.group(1)), int(m.group(2))
        d["construct"] = float(re.search(r"construct \(.*?\) ([\d.]+) ms", text).group(1))
        d["resolve"] = float(re.search(r"solve_with_boundary .*?median ([\d.]+) ms", text).group(1))
        for block in re.split(r"^(?=\w+ basis:)", text, flags=re.M)[1:]:
            b = {"name": block.split()[0]}
            m = re.match(r"\w+ basis: precompute ([\d.]+) ms, (\d+) responses, ([\d.]+) MiB \(resolve above (\d+)\)", block)
            if m:
                b.update(precompute=float(m.group(1)), responses=int(m.group(2)), mib=float(m.group(3)),
                         resolve_above=int(m.group(4)), k=[])
                for km in re.finditer(r"k=(\d+)\s+first ([\d.]+) ms, then median ([\d.]+) ms \((\S+)\)", block):
                    b["k"].append((int(km.group(1)), float(km.group(2)), float(km.group(3)), km.group(4)))
            else:
                b["refused"] = block.split("refused:", 1)[-1].strip().splitlines()[0]
            d["basis"].append(b)
        m = re.search(r"10 point constraints, block elimination: set ([\d.]+) ms, solve ([\d.]+) ms", text)
        d["constraints"] = (float(m.group(1)), float(m.group(2))) if m else None
        d["augmented"] = re.findall(r"augmented \d+ x \d+, (\w+) factor: ([\d.]+) ms", text)
        return d

    @staticmethod
    def render(raw):
        out, rows, upd = [], [], []
        for rec in raw["runs"]:
            if "edit_bench" not in rec["argv"]:
                if failed(rec):
                    out.append(failure_note(rec))
                continue
            if failed(rec):
                out.append(failure_note(rec))
                continue
            d = Edit.parse(rec["stdout"])
            full = next((b for b in d["basis"] if b["name"] == "full"), {})
            nb = full["k"][-1][0] if full.get("k") else None
            pre = (f"{full['precompute'] / 1000:.2f} s, {full['mib']:.0f} MiB" if "precompute" in full
                   else "refused: " + full.get("refused", "?"))
            aug = ", ".join(f"{k} {float(ms):.0f} ms" for k, ms in d["augmented"])
            con = f"{d['constraints'][0]:.1f} / {d['constraints'][1]:.2f} ms" if d["constraints"] else "-"
            rows.append([d["mesh"], f"{d['vertices']:,}", nb if nb else "-", f"{d['construct'] / 1000:.2f} s",
                         f"{d['resolve']:.1f} ms", pre, con, aug])
            for b in d["basis"]:
                if "k" not in b:
                    continue
                label = "full" if b["name"] == "full" else f"lazy, re-solve above {b['resolve_above']}" \
                    if b["resolve_above"] < 1 << 29 else "lazy, always superposed"
                cells = []
                for k, first, med, how in b["k"]:
                    cells.append(ms(med) + (f" (first {ms(first)})" if b["name"] != "full" else "")
                                 + (", re-solved" if how == "re-solved" else ""))
                upd.append([d["mesh"], label] + cells)
        if rows:
            out.append(table(["mesh", "vertices", "boundary", "construct", "one re-solve", "full precompute",
                              "10 constraints: set / solve", "augmented matrix factored instead"], rows))
        if upd:
            out.append("\nOne update, median (lazy: the first drag of those vertices computes their responses):\n")
            out.append(table(["mesh", "basis", "1 moved", "10 moved", "all moved"], upd))
        return "\n".join(out)


@section("drag", "The browser editor: drags", """
One boundary vertex dragged in `intrinsic serve`'s page, in headless Debian
Chromium with SwiftShader (WebGL and compositing in software, no GPU),
through playwright-core. Program: `node web/test/drag_bench.mjs build/intrinsic
MESH MOVES`. Server side (Node's fetch against the server): the update time
of a one-vertex drag (`update_ms`) and the HTTP round trip. In the page: the
mouse event to the frame that shows the answer, the request to the parsed
answer (split into request to headers and body) and the frame callback (of
which buffer uploads), for the 3D and 2D views together and for the 2D view
alone; medians over the moves (in parentheses after the mouse-to-frame time:
the mouse event to the request being sent, the page's input delivery). The
mouse-to-frame time closes on the frame after the one that drew the answer,
so it cannot be under about 17 ms plus the answer.
""")
class Drag:
    @staticmethod
    def measure(ctx):
        script = os.path.join(ROOT, "web", "test", "drag_bench.mjs")
        if not os.path.isdir(os.path.join(ROOT, "web", "test", "node_modules", "playwright-core")):
            return {"skipped": "playwright-core is not installed (`npm ci` in web/test)"}
        if not shutil.which("node") or not os.path.exists("/usr/bin/chromium"):
            return {"skipped": "node or /usr/bin/chromium is absent"}
        meshes, runs = [], []
        mp = ctx.mesh("max-planck-partial.obj")
        if mp:
            meshes.append(mp)
        if not ctx.quick:
            for rings in (103, 183):
                wave = os.path.join(ctx.work, f"wave-{rings}.obj")
                if not os.path.exists(wave):
                    runs.append(ctx.run([ctx.cli, "generate", "wave", "--rings", rings, "-o", wave]))
                meshes.append(wave)
        for m in meshes:
            runs.append(ctx.run(["node", script, ctx.cli, m, ctx.q(5, 30)], cwd=os.path.dirname(script), timeout=900))
        return {"runs": runs}

    @staticmethod
    def render(raw):
        out, rows = [], []
        for rec in raw["runs"]:
            if "drag_bench" not in rec["argv"]:
                continue
            if failed(rec):
                out.append(failure_note(rec))
                continue
            t = rec["stdout"]
            mesh = os.path.basename(rec["argv"].split()[3])
            v = re.search(r"vertices (\d+)", t)
            srv = re.search(r"update_ms median ([\d.]+).*?round trip median ([\d.]+) ms", t)
            cells = {}
            for m in re.finditer(r"browser \(([^)]*)\): mouse event to frame median ([\d.]+) ms.*?"
                                 r"request to parsed answer median ([\d.]+) ms, frame callback .*?median ([\d.]+) ms"
                                 r"(?:\n\s+medians: event to request sent ([\d.]+) ms, request to headers ([\d.]+) ms"
                                 r" \(server update ([\d.]+) ms\), body \(UVs\) ([\d.]+) ms, buffer uploads ([\d.]+) ms)?",
                                 t, re.S):
                cells[m.group(1)] = m.groups()
            both, two = cells.get("3D and 2D views"), cells.get("2D view only")
            if not both:
                out.append(f"{mesh}: output not understood:\n\n" + code(t))
                continue
            rows.append([mesh, f"{int(v.group(1)):,}" if v else "-",
                         f"{float(srv.group(1)):.3f} ms / {float(srv.group(2)):.1f} ms" if srv else "-",
                         f"{both[2]} ms", f"{both[5]} / {both[7]} ms" if both[5] else "-",
                         f"{both[3]} ({both[8]}) ms" if both[8] else f"{both[3]} ms",
                         f"{both[1]} ms" + (f" ({float(both[4]):.0f} ms to the request)" if both[4] else ""),
                         (f"{two[1]} ms" + (f" ({float(two[4]):.0f} ms to the request)" if two[4] else "")) if two else "-"])
        if rows:
            out.append(table(["mesh", "vertices", "server: update / round trip", "page: request to answer",
                              "of which request to headers / body", "frame callback (uploads)",
                              "mouse event to frame, 3D + 2D", "same, 2D only"], rows))
        return "\n".join(out)


@section("optimize", "Section 5 optimizers", """
The paper's section 5 optimizers: the optimal λ (5.1: two solves and a pass
over the edges) for the edge-length and area energies, and boundary
optimization (5.2) by L-BFGS with adjoint gradients (one solve per gradient)
or response gradients (the precomputed responses of the boundary editor),
from the circle map at the surface scale, tolerance 1e-6, at most 200
iterations; a line search costs one solve, since the map is linear in the
boundary. On the paper's Figure 7 sphere strip (generated) and on the shared
scan `max-planck-partial.obj`. Program: `bench/optimize_bench RUNS MESH...`,
medians of RUNS.
""")
class Optimize:
    @staticmethod
    def measure(ctx):
        if not ctx.have_bench("optimize_bench"):
            return {"skipped": "`build/bench/optimize_bench` is not built"}
        argv = [ctx.bench("optimize_bench"), ctx.q(1, 3)]
        mp = ctx.mesh("max-planck-partial.obj")
        if mp and not ctx.quick:
            argv.append(mp)
        return {"runs": [ctx.run(argv)]}

    @staticmethod
    def render(raw):
        rec = raw["runs"][0]
        if failed(rec):
            return failure_note(rec)
        return "\n".join(l for l in rec["stdout"].splitlines() if l.startswith("|"))


def atlas_meshes(ctx):
    """(path, kind) of the atlas comparison's meshes; generated ones are written now."""
    out = []
    assets = os.path.join(ctx.shared, "assets")
    if os.path.isdir(assets):
        names = sorted(n for n in os.listdir(assets) if n.split(".")[-1] in ("obj", "off", "ply", "gz"))
        if ctx.quick:
            names = [n for n in names if n.split(".")[0] in ("spot", "suzanne")]
        out += [(os.path.join(assets, n), "shared") for n in names]
    for rel in ctx.q(HELD_OUT[5:6], HELD_OUT):
        p = os.path.join(ASSIMP_MODELS, rel)
        if os.path.exists(p):
            out.append((p, "held out"))
    gen_dir = os.path.join(ctx.work, "generated")
    os.makedirs(gen_dir, exist_ok=True)
    for name, args in ctx.q(GENERATED[1:2], GENERATED):
        p = os.path.join(gen_dir, name + ".obj")
        rec = ctx.run([ctx.cli, "generate"] + args + ["-o", p])
        if not failed(rec):
            out.append((p, "generated"))
    return out


@section("atlas", "Atlas layouts against xatlas and Blender", """
`intrinsic atlas`, xatlas (npm `xatlasjs`: xatlas compiled to WebAssembly,
run on one thread in Node) and Blender's Smart UV Project on the same
triangles (polygons fan-triangulated), at the same padding (2 texels) and
resolution (1024), every output measured by the same code. Program:
`bench/atlas_compare.py --runs R --json FILE MESH...` (with
`bench/atlas_compare_xatlas.mjs` and `bench/atlas_blender.py`). Meshes: the
shared assets under `../shared/meshes/assets` (igea is PLY, which neither
peer's loader in the script reads), seven held out from the atlas's tuning
(Debian's `assimp-testmodels`: spider.obj, Spider_binary.stl, WusonOBJ.obj,
Wuson.off, 3DSMaxExport.STL, sphereWithHole.stl, regr01.obj) and ten
generated by `intrinsic generate` (plate, box, l-panel, panel-strip,
cylinder, rectangle, sphere, torus at rings 20 and 40, genus2). xatlasjs
takes 16-bit indices: meshes of 65,536 vertices or more are not given to it.

Seconds are computation only, medians of the runs: ours the report's clean +
segment + flatten + merge + pack, xatlas `addMesh` + `generateAtlas` inside
Node (no start-up), Blender the `smart_project` operator call (unwrap and
pack). Native xatlas runs faster than its WebAssembly build, so the time
column compares against that build only. Blender gets the triangles through
`mesh.from_pydata`, Smart UV Project with its defaults (angle limit 66
degrees) and `island_margin` = padding / resolution.

Every atlas OBJ is measured by `intrinsic metrics` (charts = UV-connected
components, flipped, mirrored and overlapping triangles by an exact test,
utilization over [0,1]², with xatlas's UVs scaled by its atlas's longer side)
and by the script with numpy from the OBJ alone, cross-checked against
`metrics` to 1e-6 where both report a figure. Per face, J maps the triangle's
own 2D frame to UV, singular values s1 ≥ s2, the UVs scaled so that the
total UV area equals the total 3D area:

- **L2**: Sander's RMS stretch sqrt(Σ A (1/s1² + 1/s2²)/2 / Σ A);
- **p95**, **max**: area-weighted 95th percentile and maximum of the
  per-face stretch max(s1, 1/s2) (a face collapsed in UV is `inf`);
- **aniso**: area-weighted mean of s1/s2;
- **seam/sqrtA**: 3D length of the cut edges over sqrt(3D area);
- **compactness**: a chart's UV area over the area of its smallest enclosing
  rectangle, weighted by UV area; **turning**: the share of chart-border
  vertices where the border turns by more than 60 degrees.

"At least as good" is the list `DOMINANCE` in the script: p95 at most
xatlas's + 0.02, L2 at most its + 0.01, no more charts, at least its
utilization, no overlapping triangle. The ctest `atlas_vs_xatlasjs`
(`--check`) asks the same of four assets plus no flipped or mirrored
triangle.
""")
class Atlas:
    @staticmethod
    def measure(ctx):
        node_ok = shutil.which("node") and os.path.isdir(os.path.join(BENCH, "node_modules", "xatlasjs"))
        meshes = atlas_meshes(ctx)
        if not meshes:
            return {"skipped": "no meshes (../shared/meshes absent, and no generated mesh)"}
        js = os.path.join(ctx.work, "atlas-compare.json")
        blender = shutil.which("blender") or ""
        argv = ["/usr/bin/python3", os.path.join(BENCH, "atlas_compare.py"), "--cli", ctx.cli, "--runs",
                ctx.q(1, 3), "--json", js, "--blender", blender] + [m for m, _ in meshes]
        rec = ctx.run(argv)
        rec["argv"] = ctx.show(argv[:-len(meshes)]) + " MESH..."
        data = json.load(open(js)) if os.path.exists(js) else {}
        kinds = {os.path.basename(m).split(".")[0]: k for m, k in meshes}
        return {"runs": [rec], "data": data, "kinds": kinds, "xatlas": bool(node_ok), "blender": blender != ""}

    @staticmethod
    def render(raw):
        sys.path.insert(0, BENCH)
        from atlas_compare import DOMINANCE  # the script's own definition
        rec, data, kinds = raw["runs"][0], raw["data"], raw["kinds"]
        if not data:
            return failure_note(rec)
        out = []
        for w in sorted(set(re.findall(r"^warning: .*$", rec["stderr"], re.M)))[:10]:
            out.append(f"- {w}")
        if out:
            out.insert(0, "Warnings of the script (its measures and `metrics` disagreeing):\n")
            out.append("")

        def ok(m, tool):
            r = data[m].get(tool)
            return r if r and "skipped" not in r else None

        def lost(o, x):
            return [d for d, test, _ in DOMINANCE if not test(o, x)]

        names = list(data)
        both = [m for m in names if ok(m, "intrinsic") and ok(m, "xatlas")]
        real = [m for m in both if kinds.get(m) in ("shared", "held out")]
        skipped_x = {m: data[m].get("xatlas", {}).get("skipped", "") for m in names if not ok(m, "xatlas")}
        if both:
            def med(ms, k, tool):
                return median([data[m][tool][k] for m in ms])

            def medr(ms, k):
                return median([data[m]["intrinsic"][k] / data[m]["xatlas"][k] for m in ms if data[m]["xatlas"][k] > 0])

            dom = {}
            for kind in ("shared", "held out", "generated"):
                ms = [m for m in both if kinds.get(m) == kind]
                if ms:
                    dom[kind] = (sum(1 for m in ms if not lost(data[m]["intrinsic"], data[m]["xatlas"])), len(ms))
            compact = sum(1 for m in both if data[m]["intrinsic"]["compactness"] >= data[m]["xatlas"]["compactness"])
            t_o = sum(data[m]["intrinsic"]["seconds"] for m in both)
            t_x = sum(data[m]["xatlas"]["seconds"] for m in both)
            slower = [m for m in both if data[m]["intrinsic"]["seconds"] > data[m]["xatlas"]["seconds"]]
            u_o, u_x = med(real, "utilization", "intrinsic"), med(real, "utilization", "xatlas")
            rows = []
            if real:
                rows.append([f"utilization, median over the {len(real)} real meshes", f"**{u_o:.3f}** ({u_o / u_x:.2f}x)",
                             f"{u_x:.3f}"])
            ua, uxa = med(both, "utilization", "intrinsic"), med(both, "utilization", "xatlas")
            rows += [[f"utilization, median over all {len(both)}", f"{ua:.3f} ({ua / uxa:.2f}x)", f"{uxa:.3f}"],
                     ["charts, median ratio (real / all)",
                      f"{medr(real, 'charts') or 0:.2f}x / {medr(both, 'charts'):.2f}x" if real else f"{medr(both, 'charts'):.2f}x", "1"],
                     ["seam length, median ratio (real / all)",
                      f"{medr(real, 'seam_length') or 0:.2f}x / {medr(both, 'seam_length'):.2f}x" if real else
                      f"{medr(both, 'seam_length'):.2f}x", "1"],
                     ["compactness, median (all)",
                      f"{med(both, 'compactness', 'intrinsic'):.3f}, at least xatlas's on {compact} of {len(both)}",
                      f"{med(both, 'compactness', 'xatlas'):.3f}"],
                     ["border vertices turning over 60 degrees, median (all)",
                      f"{med(both, 'turning_over_60', 'intrinsic'):.1%}", f"{med(both, 'turning_over_60', 'xatlas'):.1%}"],
                     ["p95 per-face stretch, median (all)", f"{med(both, 'face_stretch_p95', 'intrinsic'):.3f}",
                      f"{med(both, 'face_stretch_p95', 'xatlas'):.3f}"],
                     ["Sander L2, median (all)", f"{med(both, 'sander_l2', 'intrinsic'):.3f}",
                      f"{med(both, 'sander_l2', 'xatlas'):.3f}"],
                     ["ours at least as good on every count (p95, L2, charts, utilization, overlaps)",
                      ", ".join(f"{a} of {n} {k}" for k, (a, n) in dom.items()), ""],
                     [f"computation, sum over the {len(both)}", f"{t_o:.1f} s", f"{t_x:.1f} s"],
                     ["faster", f"on {len(both) - len(slower)} of {len(both)}", ""]]
            out.append(table(["", "ours", "xatlas"], rows))
            notes = []
            for m in both:
                o, x = data[m]["intrinsic"], data[m]["xatlas"]
                keys = [(d, k) for d, test, k in DOMINANCE if not test(o, x)]
                if keys:
                    notes.append(f"{m} (" + ", ".join(
                        f"{d} {fval(o[k])} / {fval(x[k])}" if k != "utilization" else
                        f"{d} {o[k]:.1%} / {x[k]:.1%}" for d, k in keys) + ")")
            if notes:
                out.append("\nWhere ours is not at least as good (ours / xatlas): " + "; ".join(notes) + ".")
            if slower:
                out.append("\nSlower than xatlas on: " + ", ".join(
                    f"{m} ({data[m]['intrinsic']['seconds']:.2f} / {data[m]['xatlas']['seconds']:.2f} s)"
                    for m in slower) + ".")
            bad_x = [(m, data[m]["xatlas"]) for m in both]
            ov = [f"{m} {x['overlapping']}" for m, x in bad_x if x["overlapping"]]
            fl = [f"{m} {x['flipped']}" for m, x in bad_x if x["flipped"]]
            mir = [x["mirrored_charts"] / x["charts"] for _, x in bad_x if x["charts"]]
            ours_bad = [m for m in names if ok(m, "intrinsic") and (data[m]["intrinsic"]["flipped"]
                                                                    or data[m]["intrinsic"]["overlapping"]
                                                                    or data[m]["intrinsic"]["mirrored_charts"])]
            out.append(f"\nxatlas's layouts have overlapping triangles on {len(ov)} of {len(both)} meshes"
                       + (f" ({', '.join(ov)})" if ov else "") + f", folded or collapsed triangles on {len(fl)}"
                       + (f" ({', '.join(fl)})" if fl else "")
                       + (f", and lay out {median(mir):.0%} of their charts mirrored (median over the meshes)"
                          if mir and max(mir) > 0 else ", and no mirrored chart") + ". "
                       + ("Ours had no flipped, mirrored or overlapping triangle on any mesh." if not ours_bad else
                          "Ours had flipped, mirrored or overlapping triangles (by `metrics`' independent count) on: "
                          + ", ".join(f"{m} (" + ", ".join(f"{data[m]['intrinsic'][k]} {k.replace('_', ' ')}"
                                                           for k in ("flipped", "mirrored_charts", "overlapping")
                                                           if data[m]["intrinsic"][k]) + ")" for m in ours_bad) + "."))
        failed_ours = {m: data[m]["intrinsic"].get("skipped", "") for m in names if not ok(m, "intrinsic")}
        if failed_ours:
            out.append("\n**Ours failed on**: " + "; ".join(f"{m} ({why})" for m, why in failed_ours.items()) + ".")
        if skipped_x:
            out.append("\nNot given to xatlas: " + "; ".join(f"{m} ({why})" for m, why in skipped_x.items()) + ".")
        if not raw.get("xatlas"):
            out.append("\nxatlas did not run: Node or xatlasjs (`npm ci` in bench/) is absent.")

        out.append("\nPer mesh, ours (xatlas):\n")
        rows = []
        for m in names:
            o, x = ok(m, "intrinsic"), ok(m, "xatlas")
            if not o:
                continue

            def c(k, f):
                return f(o[k]) + (f" ({f(x[k])})" if x else " (-)")
            rows.append([m, kinds.get(m, ""), c("charts", str), c("utilization", lambda v: f"{v:.1%}"),
                         c("compactness", lambda v: f"{v:.2f}"), c("turning_over_60", lambda v: f"{v:.0%}"),
                         c("face_stretch_p95", lambda v: f"{v:.3f}"), c("sander_l2", lambda v: f"{v:.3f}"),
                         c("seconds", lambda v: f"{v:.2f}")])
        out.append(table(["mesh", "kind", "charts", "utilization", "compactness", "turning > 60", "p95 stretch",
                          "L2", "seconds"], rows))

        bl = [m for m in names if ok(m, "blender")]
        if not raw.get("blender"):
            out.append("\nBlender's Smart UV Project: not measured (no `blender` on PATH).")
        elif bl:
            out.append("\nBlender's Smart UV Project, same meshes:\n")
            rows = []
            for m in bl:
                b = data[m]["blender"]
                rows.append([m, b["charts"], f"{b['utilization']:.1%}", fnum(b["seam_per_sqrt_area"]),
                             f"{b['sander_l2']:.3f}", f"{b['face_stretch_p95']:.3f}", fnum(b["face_stretch_max"]),
                             f"{b['anisotropy_mean']:.3f}", b["flipped"], b["overlapping"], f"{b['seconds']:.2f}"])
            out.append(table(["mesh", "charts", "util", "seam/sqrtA", "L2", "p95", "max", "aniso", "flipped",
                              "overlaps", "seconds"], rows))
            ob = [m for m in bl if ok(m, "intrinsic")]
            if ob:
                ov = sum(1 for m in ob if data[m]["blender"]["overlapping"])
                out.append(f"\nOver these {len(ob)} meshes, medians: Blender's L2 "
                           f"{median([data[m]['blender']['sander_l2'] for m in ob]):.3f} against ours "
                           f"{median([data[m]['intrinsic']['sander_l2'] for m in ob]):.3f}, p95 "
                           f"{median([data[m]['blender']['face_stretch_p95'] for m in ob]):.3f} against "
                           f"{median([data[m]['intrinsic']['face_stretch_p95'] for m in ob]):.3f}, "
                           f"{median([data[m]['blender']['charts'] / data[m]['intrinsic']['charts'] for m in ob]):.1f}x "
                           f"our charts, utilization {median([data[m]['blender']['utilization'] for m in ob]):.3f} "
                           f"against {median([data[m]['intrinsic']['utilization'] for m in ob]):.3f}; "
                           f"overlapping triangles on {ov} of {len(ob)}.")
        return "\n".join(out)


@section("pictures", "Pictures", """
Per tool, the checkerboard on the surface (`intrinsic render --mode checker
--squares 32`, the squares counted across each atlas's UV square, so every
tool gets the same texture size) and the UV layout (`--mode layout`: a colour
per chart, folded or overlapping triangles red), with the figures as
captions. Program: `bench/atlas_pictures.py --out docs/images` (needs
`python3-pil`), on truck, spot, screwdriver and the generated torus and
plate; each mesh has a fixed view (`VIEWS` in the script). Redrawn only by a
run that writes docs/benchmarks.md itself.
""")
class Pictures:
    @staticmethod
    def measure(ctx):
        if not ctx.pictures:
            return {"skipped": "not redrawn in this run (only when the page written is docs/benchmarks.md); "
                               "the pictures below were drawn by an earlier run", "images": Pictures.images()}
        meshes = [p for p in (ctx.mesh(os.path.join("assets", n)) for n in ("truck.obj", "spot.obj", "screwdriver.off"))
                  if p]
        for name in ("torus", "plate"):  # the atlas section's generated meshes
            p = os.path.join(ctx.work, "generated", name + ".obj")
            if not os.path.exists(p):
                os.makedirs(os.path.dirname(p), exist_ok=True)
                ctx.run([ctx.cli, "generate", name, "-o", p])
            meshes.append(p)
        argv = ["/usr/bin/python3", os.path.join(BENCH, "atlas_pictures.py"), "--cli", ctx.cli, "--out",
                os.path.join(DOCS, "images")] + meshes
        rec = ctx.run(argv)
        drawn = [os.path.basename(l.strip()) for l in rec["stdout"].splitlines() if l.strip().endswith(".png")]
        return {"runs": [rec], "images": drawn}

    @staticmethod
    def images():
        d = os.path.join(DOCS, "images")
        return sorted(n for n in os.listdir(d) if n.startswith("atlas-compare-")) if os.path.isdir(d) else []

    @staticmethod
    def render(raw):
        out = []
        if raw.get("runs") and failed(raw["runs"][0]):
            out.append(failure_note(raw["runs"][0]))
        for n in raw.get("images", []):
            out.append(f"![{n[len('atlas-compare-'):-4]}](images/{n})")
        return "\n".join(out)


@section("atlas_large", "Atlas of a large closed mesh", """
`intrinsic atlas` end to end on a generated closed bumpy sphere (`intrinsic
generate sphere`), one run: wall and CPU time and peak memory of the process,
the report's stages (write: the wall time less the reported stages), charts,
utilization and the 95th percentile of face stretch.
""")
class AtlasLarge:
    @staticmethod
    def measure(ctx):
        rings = ctx.q(150, 1118)
        obj = os.path.join(ctx.work, f"sphere-{rings}.obj")
        out = os.path.join(ctx.work, f"sphere-{rings}-atlas.obj")
        rep = os.path.join(ctx.work, f"sphere-{rings}.json")
        runs = [ctx.run([ctx.cli, "generate", "sphere", "--rings", rings, "-o", obj])]
        runs.append(ctx.run([ctx.cli, "atlas", obj, "-o", out, "--report", rep, "-q"]))
        report = json.load(open(rep)) if os.path.exists(rep) else None
        for p in (obj, out, rep):
            if os.path.exists(p):
                os.remove(p)
        return {"runs": runs, "report": report}

    @staticmethod
    def render(raw):
        gen, rec = raw["runs"]
        if failed(gen):
            return failure_note(gen)
        if failed(rec) or not raw["report"]:
            return failure_note(rec)
        r = raw["report"]
        t = r["timings_ms"]
        stages = ["read", "clean", "segment", "flatten", "merge", "pack"]
        write = rec["wall_s"] - sum(t[k] for k in stages) / 1000
        p95 = r.get("stretch", {}).get("face_stretch_p95")
        return (f"{r['vertices']:,} vertices, {r['faces']:,} faces: **{rec['wall_s']:.1f} s wall**, "
                f"{rec['cpu_s']:.1f} s CPU, peak {rec['maxrss_mb'] / 1024:.2f} GB; {r['charts']} charts, utilization "
                f"{r['utilization']:.1%}" + (f", p95 face stretch {p95:.3f}" if p95 else "") + ". Stages, seconds:\n\n"
                + table(stages + ["write (rest)"], [[f"{t[k] / 1000:.2f}" for k in stages] + [f"{write:.2f}"]]))


@section("texture", "Texture transfer", """
A generated fragmented textured asset (`intrinsic generate textured --cells
92 --chart-cells 2 --texture-size 2048`: about 100k faces in about 12,700
tiny charts, a 2048 x 2048 source) read as .glb, re-atlased, its base colour
baked into a 2048 x 2048 texture of the new layout (supersample 2) and the
.glb written, timed as one job ([textures.md](textures.md)). Program:
`bench/texture_transfer_bench`, median of its runs. `bench/texture_bench
[RUNS] [RINGS]` times the texel transfer alone (not run here).
""")
class Texture:
    @staticmethod
    def measure(ctx):
        if not ctx.have_bench("texture_transfer_bench"):
            return {"skipped": "`build/bench/texture_transfer_bench` is not built"}
        argv = [ctx.bench("texture_transfer_bench")] + ctx.q(["--cells", 24, "--size", 512, "--runs", 1],
                                                            ["--runs", 3])
        return {"runs": [ctx.run(argv)]}

    @staticmethod
    def render(raw):
        rec = raw["runs"][0]
        m = re.search(r"textured asset: (\d+) faces, (\d+x\d+) source texture; .*?bake (\d+x\d+) \+ write: median (\d+) ms "
                      r"of (\d+) runs \(min (\d+), max (\d+)\)", rec["stdout"])
        if failed(rec) or not m:
            return failure_note(rec)
        return (f"{int(m.group(1)):,} faces, {m.group(2)} source, baked at {m.group(3)}: **{int(m.group(4)) / 1000:.2f} s**, "
                f"median of {m.group(5)} runs ({int(m.group(6)) / 1000:.2f}-{int(m.group(7)) / 1000:.2f} s).")


@section("obj_io", "OBJ extras", """
What keeping an OBJ's normals, materials, groups and smoothing groups costs:
reading a generated OBJ of quads and writing its atlas OBJ, plain (`v`, `f`
only) or carrying all of it (`vn` per corner, `usemtl`/`g`/`s` every 64 rows,
two `mtllib` lines); the atlas itself is not computed. One case per process,
so the peak memory is the case's own. Program: `bench/obj_io_bench
--quads-per-side N --runs R --case plain|extras`.
""")
class ObjIo:
    @staticmethod
    def measure(ctx):
        if not ctx.have_bench("obj_io_bench"):
            return {"skipped": "`build/bench/obj_io_bench` is not built"}
        return {"runs": [ctx.run([ctx.bench("obj_io_bench"), "--quads-per-side", ctx.q(200, 1000), "--runs",
                                  ctx.q(1, 3), "--case", c, "--workdir", ctx.work]) for c in ("plain", "extras")]}

    @staticmethod
    def render(raw):
        rows = []
        for rec in raw["runs"]:
            m = re.search(r"(\w+): (\d+) x \d+ quads \((\d+) triangles\), read ([\d.]+) ms, write ([\d.]+) ms "
                          r"\(medians of (\d+)\), peak RSS ([\d.]+) MB", rec["stdout"])
            if failed(rec) or not m:
                return failure_note(rec)
            rows.append([m.group(1), f"{int(m.group(3)):,}", f"{float(m.group(4)):.0f} ms", f"{float(m.group(5)):.0f} ms",
                         f"{float(m.group(7)):.0f} MB", m.group(6)])
        return table(["case", "triangles", "read", "write", "peak RSS", "runs"], rows)


@section("scenes", "Scenes in and out", """
Every file of Debian's assimp-testmodels (`/usr/share/assimp/models`) through
`intrinsic atlas FILE -o OTHER_FOLDER/FILE.glb`, the output checked by the
Khronos validator (npm gltf-validator) and against assimp's own reading of
the source (triangles drawn with every instance, meshes as primitives,
materials; a small C++ helper the script builds against libassimp). glTF
inputs: a valid input must come out with 0 errors (IO errors included:
images must travel with the output), an invalid one with no more errors than
it came in with. Other formats: 0 validator errors, at least assimp's
triangles drawn, as many primitives and materials as assimp's meshes and
materials. Program: `bench/scene_roundtrip.py`.
""")
class Scenes:
    @staticmethod
    def measure(ctx):
        if not os.path.isdir(ASSIMP_MODELS):
            return {"skipped": f"{ASSIMP_MODELS} is absent (Debian's assimp-testmodels)"}
        if not os.path.isdir(os.path.join(ROOT, "tests", "gltf_validator", "node_modules")) or not shutil.which("node"):
            return {"skipped": "the Khronos validator is not installed (`npm ci` in tests/gltf_validator)"}
        models = ASSIMP_MODELS
        if ctx.quick:  # two glTF folders and two files of two other formats
            models = os.path.join(ctx.work, "models")
            for rel in ("glTF2/BoxTextured-glTF", "glTF2/BoxTextured-glTF-Binary"):
                if os.path.isdir(os.path.join(ASSIMP_MODELS, rel)):  # copied: the script does not follow links
                    shutil.copytree(os.path.join(ASSIMP_MODELS, rel), os.path.join(models, rel))
            for rel in ("Collada", "3DS"):
                src = os.path.join(ASSIMP_MODELS, rel)
                if os.path.isdir(src):
                    os.makedirs(os.path.join(models, rel), exist_ok=True)
                    for f in sorted(f for f in os.listdir(src) if f.lower().endswith((".dae", ".3ds")))[:2]:
                        os.symlink(os.path.join(src, f), os.path.join(models, rel, f))
        argv = ["/usr/bin/python3", os.path.join(BENCH, "scene_roundtrip.py"), "--cli", ctx.cli, "--models", models,
                "--out", os.path.join(ctx.work, "scenes")]
        return {"runs": [ctx.run(argv)]}

    @staticmethod
    def render(raw):
        rec = raw["runs"][0]
        t = rec["stdout"]
        g = re.search(r"glTF: (\d+) ok, (\d+) with more errors out than in, (\d+) refused", t)
        o = re.search(r"other formats: (\d+) ok, (\d+) not, (\d+) refused", t)
        if failed(rec) or not g or not o:
            return failure_note(rec)
        lines = t.splitlines()
        split = next(i for i, l in enumerate(lines) if l.startswith("glTF:"))
        gl, ot = lines[:split], lines[split + 1:]

        def refused(ls):
            out = []
            for l in ls:
                m = re.match(r"refused\s+(\S+)(?: \(in: (\S+) errors\))?: (.*)", l)
                if m:
                    why = re.sub(r"^intrinsic: error: \S+?: ", "", m.group(3))  # the CLI's prefix and the path
                    why = re.sub(r" \(looked from.*$", "", why.replace(ASSIMP_MODELS + "/", ""))
                    out.append((m.group(1), m.group(2), why[:150] + ("..." if len(why) > 150 else "")))
            return out

        def bad(ls):
            return [l.split(None, 1)[1] for l in ls if l.startswith(("WORSE", "BAD"))]

        rows = [["glTF (.gltf, .glb under glTF2/)", int(g.group(1)) + int(g.group(2)), g.group(1), g.group(3)],
                ["other formats assimp reads and exports to glTF", int(o.group(1)) + int(o.group(2)), o.group(1),
                 o.group(3)]]
        out = [table(["inputs", "written", "checks met", "refused"], rows)]
        for label, ls in (("glTF", gl), ("other formats", ot)):
            b = bad(ls)
            if b:
                out.append(f"\nChecks not met ({label}):\n")
                out += [f"- {x}" for x in b]
            r = refused(ls)
            if r:
                out.append(f"\nRefused ({label}), with the message:\n")
                out += [f"- `{name}`" + ("" if n is None else " (a valid input)" if n == "0" else
                                          f" (the input has {n} validator errors)") + f": {why}" for name, n, why in r]
        return "\n".join(out)


@section("lightmap", "Lightmap pages against xatlas", """
Each mesh packed as a lightmap at one texel density on pages of 512 x 512
texels with padding 2, by `intrinsic atlas --texels-per-unit T --resolution
512` and by xatlas (npm xatlasjs; the same texelsPerUnit, resolution and
padding, its default chart options). T is chosen per mesh so that its surface
would fill 2 (then 6) pages exactly; the fill of a page is its charts' texels
over the page's. Page counts do not depend on the machine's load. Program:
`bench/lightmap_pages.py --fill 2 6 MESH...` (with
`bench/lightmap_pages_xatlas.mjs`).

![truck on 512-texel pages: three UDIM tiles side by side](images/lightmap-pages-truck.png)

*truck.obj at about 271 texels per unit on 512-texel pages (UDIM tiles
1001-1003 side by side; `intrinsic render --mode layout`).*
""")
class Lightmap:
    @staticmethod
    def measure(ctx):
        if not shutil.which("node") or not os.path.isdir(os.path.join(BENCH, "node_modules", "xatlasjs")):
            return {"skipped": "Node or xatlasjs (`npm ci` in bench/) is absent"}
        meshes = [p for p in (ctx.mesh(os.path.join("assets", n)) for n in ctx.q(LIGHTMAP_MESHES[:1], LIGHTMAP_MESHES))
                  if p]
        if not meshes:
            return {"skipped": "../shared/meshes/assets is absent"}
        argv = ["/usr/bin/python3", os.path.join(BENCH, "lightmap_pages.py"), "--cli", ctx.cli] + meshes + \
            ["--fill"] + ctx.q(["2"], ["2", "6"])
        return {"runs": [ctx.run(argv)]}

    @staticmethod
    def render(raw):
        rec = raw["runs"][0]
        rows = md_dicts(rec["stdout"])
        if failed(rec) or not rows:
            return failure_note(rec)
        fewer = same = more = 0
        for r in rows:
            try:
                a, b = int(r["intrinsic pages"]), int(r["xatlas pages"])
            except ValueError:
                continue
            fewer += a < b
            same += a == b
            more += a > b
        text = "\n".join(l for l in rec["stdout"].splitlines() if l.startswith("|"))
        return text + (f"\n\nFewer pages than xatlas on {fewer} of the {len(rows)} cases, as many on {same}, more on "
                       f"{more}. Pages are filled in turn, largest chart first, each chart to the first page with "
                       f"room; xatlas may put charts below the asked density when they do not fit (its page count "
                       f"is then not at T).")


# ---------------------------------------------------------------------------
# The machine


def sh(argv, default=""):
    try:
        p = subprocess.run(argv, capture_output=True, text=True, timeout=60)
        return p.stdout.strip() if p.returncode == 0 else default
    except (OSError, subprocess.TimeoutExpired):
        return default


def dpkg(pkg):
    return sh(["dpkg-query", "-W", "-f=${Version}", pkg]) or None


def machine(build):
    m = {}
    m["nproc"] = sh(["nproc"])
    cpu = {}
    with open("/proc/cpuinfo") as f:
        for line in f:
            k, _, v = line.partition(":")
            cpu.setdefault(k.strip(), v.strip())
    m["cpu"] = cpu.get("model name", platform.processor())
    flags = cpu.get("flags", "").split()
    m["simd"] = ", ".join(x.upper() for x in ("avx2", "fma", "avx512f") if x in flags)
    with open("/proc/meminfo") as f:
        kb = int(next(l for l in f if l.startswith("MemTotal")).split()[1])
    m["memory_gib"] = round(kb / 1048576, 1)
    m["debian"] = open("/etc/debian_version").read().strip() if os.path.exists("/etc/debian_version") else ""
    m["kernel"] = platform.release()
    cache = {}
    cpath = os.path.join(build, "CMakeCache.txt")
    if os.path.exists(cpath):
        for line in open(cpath, errors="replace"):
            k, _, v = line.strip().partition("=")
            cache[k.split(":")[0]] = v
    cxx = cache.get("CMAKE_CXX_COMPILER", "c++")
    m["compiler"] = (sh([cxx, "--version"]).splitlines() or [cxx])[0]
    m["build_type"] = cache.get("CMAKE_BUILD_TYPE", "")
    m["flags"] = (cache.get("CMAKE_CXX_FLAGS", "") + " " + cache.get(
        "CMAKE_CXX_FLAGS_" + m["build_type"].upper(), "")).strip()
    m["openblas_config"] = sh(["/usr/bin/python3", "-c",
                               "import ctypes; l = ctypes.CDLL('libopenblas.so.0'); "
                               "l.openblas_get_config.restype = ctypes.c_char_p; "
                               "l.openblas_get_corename.restype = ctypes.c_char_p; "
                               "print(l.openblas_get_config().decode(), '/ core', l.openblas_get_corename().decode())"])
    pk = {}
    for name in ("libopenblas0-pthread", "libsuitesparse-dev", "libmetis5", "libeigen3-dev", "libcgal-dev",
                 "libassimp5", "chromium"):
        pk[name] = upstream(dpkg(name))
    for lib, header in (("CHOLMOD", "cholmod_core.h"), ("UMFPACK", "umfpack.h")):
        try:
            text = open(os.path.join("/usr/include/suitesparse", header)).read()
            pk[lib] = ".".join(re.search(rf"#define {lib}_{k}_VERSION (\d+)", text).group(1)
                               for k in ("MAIN", "SUB", "SUBSUB"))
        except (OSError, AttributeError):
            pk[lib] = None
    m["packages"] = pk
    m["node"] = sh(["node", "--version"]) or None
    m["xatlasjs"] = npm_version(os.path.join(BENCH, "node_modules", "xatlasjs"))
    m["playwright"] = npm_version(os.path.join(ROOT, "web", "test", "node_modules", "playwright-core"))
    m["gltf_validator"] = npm_version(os.path.join(ROOT, "tests", "gltf_validator", "node_modules", "gltf-validator"))
    m["blender"] = (sh(["blender", "--version"]).splitlines() or [None])[0] if shutil.which("blender") else None
    m["env"] = {k: os.environ[k] for k in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS") if k in os.environ}
    return m


def npm_version(d):
    try:
        return json.load(open(os.path.join(d, "package.json")))["version"]
    except (OSError, ValueError, KeyError):
        return None


def render_header(meta):
    m = meta["machine"]
    pk = m["packages"]

    def v(name, label=None):
        return f"{label or name} {pk[name]}" if pk.get(name) else None

    blas = m.get("openblas_config", "")
    core = blas.split("/ core")[-1].strip() if "/ core" in blas else ""
    libs = [x for x in [
        f"OpenBLAS {pk['libopenblas0-pthread']} (pthreads" + (f", {core} kernels" if core else "") + ")"
        if pk.get("libopenblas0-pthread") else None,
        f"SuiteSparse {pk['libsuitesparse-dev']} (CHOLMOD {pk.get('CHOLMOD')}, UMFPACK {pk.get('UMFPACK')})"
        if pk.get("libsuitesparse-dev") else None,
        v("libmetis5", "METIS"), v("libeigen3-dev", "Eigen"), v("libassimp5", "assimp"),
        v("libcgal-dev", "CGAL") or "CGAL not installed"] if x]
    peers = [x for x in [
        f"Node {m['node']}" if m.get("node") else "no Node",
        f"xatlasjs {m['xatlasjs']}" if m.get("xatlasjs") else "no xatlasjs",
        m["blender"] or "no Blender",
        v("chromium", "Chromium"), f"playwright-core {m['playwright']}" if m.get("playwright") else None,
        f"gltf-validator {m['gltf_validator']}" if m.get("gltf_validator") else None] if x]
    rows = [
        ["date (UTC)", f"{meta['start_utc']} to {meta['end_utc']}"],
        ["commit", meta["commit"]],
        ["command", f"`{meta['command']}`"],
        ["total wall time", duration(meta["wall_s"])],
        ["load average (1, 5, 15 min)", f"{meta['load_start']} at the start, {meta['load_end']} at the end"],
        ["machine", f"{m['nproc']} cores (`nproc`), {m['cpu']}" + (f" ({m['simd']})" if m["simd"] else "")
         + f", {m['memory_gib']} GiB"],
        ["system", f"Debian {m['debian']}, Linux {m['kernel']}"],
        ["compiler", f"{m['compiler']}, {m['build_type']}" + (f" (`{m['flags']}`)" if m["flags"] else "")],
        ["libraries", "; ".join(libs)],
        ["peers and tools", "; ".join(peers)],
    ]
    if m.get("env"):
        rows.append(["environment", ", ".join(f"{k}={v}" for k, v in m["env"].items())])
    return table(["", ""], rows)


INTRO = """\
# Benchmarks

<!-- Written by scripts/benchmarks.py from one run; change the script, not this page. -->

Every figure on this page comes from one run of `scripts/benchmarks.py` on
the machine below, on the date and commit below: one section per thing
measured, each saying what is measured and by which program, then that run's
figures. How the library reaches them, and the measurements behind each
design choice, are in [performance.md](performance.md). The programs are in
`bench/` (built with the project, never part of ctest; the C++ ones land in
`build/bench/`), and

    scripts/benchmarks.py [--build build] [--quick] [--out docs/benchmarks.md]

runs them all again and rewrites this page (`--quick`: small sizes, a few
minutes, written to `build/benchmarks-quick.md`; `--only KEY,...` runs some
sections; `--render RAW` rewrites the page from a run's saved outputs).
A peer that is absent on the machine (CGAL, Blender, Node and its packages)
makes its section say so.

The machine may be shared with other work: the load averages at the start and
end of the run and of each section are given, and times under load are
slower than idle ones. Compare rows of this page, not pages. Unless a section
says otherwise, times are medians of 3 runs.
"""


def render_page(meta, raws):
    out = [INTRO, "## This run\n", render_header(meta), ""]
    if meta.get("quick"):
        out.append("**A `--quick` run: small sizes and one run each, for checking the generator; not the "
                   "reference figures.**\n")
    for cls in SECTIONS:
        raw = raws.get(cls.key)
        out.append(f"## {cls.title}\n")
        out.append(cls.prose + "\n")
        if raw is None:
            out.append("*Not run (`--only`).*\n")
            continue
        if "skipped" in raw and not raw.get("runs"):
            out.append(f"*Not measured in this run: {raw['skipped']}.*\n")
            if cls is Pictures:
                out.append(cls.render(raw) + "\n")
            continue
        if raw.get("runs"):
            out.append("Run:\n")
            out.append(commands_block(raw) + "\n")
        try:
            body = cls.render(raw)
        except Exception as e:  # a program's output this script does not understand: show it
            body = f"Output not understood ({type(e).__name__}: {e}):\n\n" + code(
                "\n".join(r["stdout"] for r in raw.get("runs", []))[-6000:])
        out.append(body.rstrip() + "\n")
        if "window" in raw:
            w = raw["window"]
            out.append(f"*{w['start']}-{w['end']} UTC, {duration(w['wall_s'])}; load average "
                       f"{w['load_start'].split()[0]} at the start, {w['load_end'].split()[0]} at the end.*\n")
    out.append("## Elsewhere\n")
    out.append("- The Python module's call overhead and threads: [python.md](python.md).\n"
               "- The Blender add-on against Blender's own Smart UV Project and Unwrap (`bench/blender_addon.py`): "
               "[blender.md](blender.md).\n"
               "- Tools not run here: `bench/atlas_stage_bench [--runs N] MESH...` (the atlas's `compute_charts` and "
               "`pack_charts` alone, wall and CPU medians, for the fixed costs of small assets), "
               "`bench/natural_accuracy_bench MESH` (where the natural map's distance to its exact solution comes "
               "from), `bench/complex_cholesky_bench --relax N R`, `bench/texture_bench [RUNS] [RINGS]`.\n"
               "- The fuzzing runs: [fuzzing.md](fuzzing.md).\n")
    return "\n".join(out).rstrip() + "\n"


# ---------------------------------------------------------------------------
# README's "Measured" table, from the same run


README_BEGIN = "<!-- benchmarks: written by scripts/benchmarks.py -->"
README_END = "<!-- /benchmarks -->"


def readme_table(meta, raws):
    """A few figures of this run for README.md, or None when a section they
    come from is missing."""
    rows = []
    p = raws.get("param")
    if p and p.get("runs") and not failed(p["runs"][0]):
        by = {}
        for r in md_dicts(p["runs"][0]["stdout"]):
            if r["mesh"].startswith("bench-wave-") and r.get("total s"):
                by.setdefault(r["method"], []).append((int(r["V"]), float(r["total s"]), r["peak MB"], r["max rel. diff"]))
        for meth, label in (("conformal", "conformal"), ("natural", "natural boundary")):
            xs = sorted(by.get(meth, []))
            if xs:
                sizes = " / ".join(f"{round(v, -3) // 1000:.0f}k" if v < 999500 else f"{v / 1e6:.0f}M" for v, *_ in xs)
                rows.append([f"`param`, {label}, {sizes} vertices",
                             " / ".join(f"{t:.2f} s" for _, t, *_ in xs) + f"; peak {float(xs[-1][2]) / 1024:.2f} GB at "
                             f"the largest"])
    c = raws.get("cgal")
    if c and c.get("runs") and not any(failed(r) for r in c["runs"]):
        per = {}
        v = None
        for rec in c["runs"]:
            for r in md_dicts(rec["stdout"]):
                v = r["V"]
                per.setdefault(r["method"], []).append(float(r["CGAL s"].split()[0]) / float(r["ours (parameterize) s"]))
        if per:
            rows.append([f"CGAL {meta['machine']['packages'].get('libcgal-dev') or ''}: same conformal / "
                         f"authalic map, LSCM against our natural map ({int(v):,} vertices)",
                         " / ".join(times(median(x)) for x in per.values()) + " our time (medians)"])
    a = raws.get("atlas")
    if a and a.get("data"):
        d, kinds = a["data"], a["kinds"]
        both = [m for m in d if "skipped" not in d[m].get("xatlas", {"skipped": 1}) and "skipped" not in d[m]["intrinsic"]]
        real = [m for m in both if kinds.get(m) in ("shared", "held out")]
        if real:
            uo = median([d[m]["intrinsic"]["utilization"] for m in real])
            ux = median([d[m]["xatlas"]["utilization"] for m in real])
            ch = median([d[m]["intrinsic"]["charts"] / d[m]["xatlas"]["charts"] for m in real])
            rows.append([f"atlas against xatlas, medians over {len(real)} real assets",
                         f"utilization {uo:.3f} against {ux:.3f} ({uo / ux:.2f}x), {ch:.2f}x its charts; computation "
                         f"{sum(d[m]['intrinsic']['seconds'] for m in both):.1f} s against "
                         f"{sum(d[m]['xatlas']['seconds'] for m in both):.1f} s over {len(both)} meshes"])
        if "spot" in both:
            o, x = d["spot"]["intrinsic"], d["spot"]["xatlas"]
            rows.append(["atlas of `spot`: charts, utilization, p95 stretch, seconds (ours / xatlas)",
                         f"{o['charts']} / {x['charts']}, {o['utilization']:.1%} / {x['utilization']:.1%}, "
                         f"{o['face_stretch_p95']:.3f} / {x['face_stretch_p95']:.3f}, {o['seconds']:.2f} / "
                         f"{x['seconds']:.2f}"])
    if not rows:
        return None
    m = meta["machine"]
    head = (f"{README_BEGIN}\nOne run of `scripts/benchmarks.py` ({meta['start_utc'][:10]}, commit "
            f"{meta['commit'].split()[0]}, {m['nproc']} cores, {m['cpu']}, load average {meta['load_start'].split()[0]}"
            f" at the start and {meta['load_end'].split()[0]} at the end); every figure, the commands and the machine are in "
            f"[docs/benchmarks.md](docs/benchmarks.md):\n\n")
    return head + table(["job", "figure"], rows) + "\n" + README_END


def update_readme(meta, raws):
    path = os.path.join(ROOT, "README.md")
    text = open(path).read()
    if README_BEGIN not in text or README_END not in text:
        log("README.md has no benchmarks markers: not updated")
        return
    new = readme_table(meta, raws)
    if not new:
        return
    a, b = text.index(README_BEGIN), text.index(README_END) + len(README_END)
    with open(path, "w") as f:
        f.write(text[:a] + new + text[b:])
    log("rewrote README.md's Measured table")


# ---------------------------------------------------------------------------


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--out")
    ap.add_argument("--only", help="comma-separated section keys: " + ", ".join(c.key for c in SECTIONS))
    ap.add_argument("--raw")
    ap.add_argument("--render", metavar="RAW", help="write the page from a saved run, running nothing")
    ap.add_argument("--no-pictures", action="store_true")
    ap.add_argument("--keep", action="store_true", help="keep the scratch folder ($WORK)")
    args = ap.parse_args()
    build = os.path.abspath(args.build)
    out = os.path.abspath(args.out or (os.path.join(build, "benchmarks-quick.md") if args.quick else DEFAULT_OUT))
    is_page = out == DEFAULT_OUT and not args.quick

    if args.render:
        saved = json.load(open(args.render))
        page = render_page(saved["meta"], saved["sections"])
        open(out, "w").write(page)
        log(f"wrote {out}")
        if is_page and not saved["meta"].get("quick"):
            update_readme(saved["meta"], saved["sections"])
        return 0

    keys = [c.key for c in SECTIONS]
    only = args.only.split(",") if args.only else keys
    unknown = [k for k in only if k not in keys]
    if unknown:
        ap.error("unknown section(s): " + ", ".join(unknown))
    if not os.access(os.path.join(build, "intrinsic"), os.X_OK):
        ap.error(f"{build}/intrinsic is not built (cmake --build {os.path.relpath(build)})")
    shared = os.path.abspath(os.environ.get("INTRINSIC_SHARED_MESHES", os.path.join(ROOT, "..", "shared", "meshes")))
    work = tempfile.mkdtemp(prefix="intrinsic-benchmarks-")
    ctx = Context(build, args.quick, work, shared)
    ctx.pictures = is_page and not args.no_pictures and not args.only

    commit = sh(["git", "-C", ROOT, "rev-parse", "--short=10", "HEAD"]) or "unknown"
    dirty = sh(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"])
    cmd = "scripts/benchmarks.py" + "".join(" " + a for a in sys.argv[1:])
    meta = {"start_utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M"),
            "load_start": loadavg(), "commit": commit + (" (with uncommitted changes)" if dirty else ""),
            "command": cmd, "quick": args.quick, "machine": machine(build)}
    log(f"scratch folder {work}; load {meta['load_start']}")
    t0 = time.monotonic()
    raws = {}
    for cls in SECTIONS:
        if cls.key not in only:
            continue
        log(f"== {cls.key}")
        s0, l0 = time.monotonic(), loadavg()
        start = datetime.datetime.now(datetime.timezone.utc).strftime("%H:%M")
        try:
            raw = cls.measure(ctx)
        except Exception as e:  # a section's own failure must not lose the rest of the run
            raw = {"skipped": f"the section failed ({type(e).__name__}: {e})"}
            log(f"  section failed: {e!r}")
        raw["window"] = {"start": start, "end": datetime.datetime.now(datetime.timezone.utc).strftime("%H:%M"),
                         "wall_s": time.monotonic() - s0, "load_start": l0, "load_end": loadavg()}
        raws[cls.key] = raw
    meta["wall_s"] = time.monotonic() - t0
    meta["end_utc"] = datetime.datetime.now(datetime.timezone.utc).strftime("%H:%M")
    meta["load_end"] = loadavg()

    raw_path = args.raw or os.path.join(build, "benchmarks-quick.json" if args.quick else "benchmarks-run.json")
    with open(raw_path, "w") as f:
        json.dump({"meta": meta, "sections": raws}, f, indent=1)
    page = render_page(meta, raws)
    with open(out, "w") as f:
        f.write(page)
    log(f"wrote {out} ({duration(meta['wall_s'])}); outputs in {raw_path}")
    if is_page and not args.only:
        update_readme(meta, raws)
    if args.keep:
        log(f"kept {work}")
    else:
        shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
