#!/usr/bin/python3
"""intrinsic atlas against xatlas on the shared assets (issue 13, "Benchmark
against xatlas"), same machine, same run.

For each asset under ../shared/meshes/assets: `intrinsic atlas` writes its
OBJ; xatlas runs through the npm package xatlasjs (WebAssembly, in Node:
bench/atlas_compare_xatlas.mjs; install with `npm ci` in bench/, which
scripts/install-deps.sh does) on the same triangles (polygons fan-triangulated
as our reader does) with the same padding and resolution, and writes an OBJ of
the same shape (input vertices, one vt per output vertex, f v/vt). Both OBJs
are then measured by `intrinsic metrics` (charts as UV-connected components,
exact overlaps, flips per chart, utilization, area-weighted L2 stretch and
angle distortion) and here (seam length), so both are measured the same way.

Times: computation only, median of --runs runs. Ours: the report's
clean+segment+flatten+merge+pack (no read or write); xatlas: addMesh and
generateAtlas inside Node (no Node start-up, no wasm compilation). xatlasjs
takes 16-bit indices: meshes with 65,536 vertices or more are skipped for it.

Usage: bench/atlas_compare.py [--cli build/intrinsic] [--runs 3] [--markdown]
                              [--node node] [--check] [--skip-without DIR] [MESH ...]

--check (the ctest atlas_vs_xatlasjs): one run per mesh; exits non-zero
unless on every mesh our utilization is at least xatlasjs's, our charts are
at most half of its, and ours has no flipped, mirrored or overlapping
triangle, all measured by `intrinsic metrics`. A missing node or xatlasjs
(bench/node_modules) is a failure, not a skip; --skip-without DIR exits 77
(ctest's Skipped) when DIR, the shared meshes beside a clone, is absent.
"""
import argparse
import gzip
import json
import math
import os
import statistics
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def read_mesh_text(path):
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rt", errors="replace") as f:
        return f.read()


def parse_obj(text):
    V, F = [], []
    for line in text.splitlines():
        t = line.split()
        if not t:
            continue
        if t[0] == "v":
            V.append([float(x) for x in t[1:4]])
        elif t[0] == "f":
            idx = []
            for c in t[1:]:
                i = int(c.split("/")[0])
                idx.append(i - 1 if i > 0 else len(V) + i)
            for k in range(1, len(idx) - 1):  # fan, as our reader does
                F.append([idx[0], idx[k], idx[k + 1]])
    return V, F


def parse_off(text):
    tokens = []
    for line in text.splitlines():
        line = line.split("#")[0]
        tokens.extend(line.split())
    assert tokens[0].endswith("OFF")
    nv, nf = int(tokens[1]), int(tokens[2])
    p = 4
    V = []
    for _ in range(nv):
        V.append([float(x) for x in tokens[p:p + 3]])
        p += 3
    F = []
    for _ in range(nf):
        n = int(tokens[p])
        idx = [int(x) for x in tokens[p + 1:p + 1 + n]]
        p += 1 + n
        for k in range(1, n - 1):
            F.append([idx[0], idx[k], idx[k + 1]])
    return V, F


def load(path):
    base = path[:-3] if path.endswith(".gz") else path
    if base.endswith(".obj"):
        return parse_obj(read_mesh_text(path))
    if base.endswith(".off"):
        return parse_off(read_mesh_text(path))
    return None  # PLY (igea): over xatlasjs's 16-bit limit anyway


def seam_length(obj_path):
    """3D length of the edges where the UVs are cut: for each input edge, every
    distinct UV edge beyond the first (a manifold seam edge counts once)."""
    V, faces = [], []
    with open(obj_path) as f:
        for line in f:
            if line.startswith("v "):
                V.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                faces.append([tuple(int(x) - 1 for x in c.split("/")[:2]) for c in line.split()[1:]])
    uv_edges = {}
    for face in faces:
        for k in range(3):
            (a, ta), (b, tb) = face[k], face[(k + 1) % 3]
            if a == b:
                continue
            key = (min(a, b), max(a, b))
            uv = (ta, tb) if a < b else (tb, ta)
            uv_edges.setdefault(key, set()).add(uv)
    total = 0.0
    for (a, b), s in uv_edges.items():
        if len(s) > 1:
            total += (len(s) - 1) * math.dist(V[a], V[b])
    return total


def metrics(cli, obj):
    out = subprocess.run([cli, "metrics", obj], capture_output=True, text=True, check=True).stdout
    m = json.loads(out)
    a = m["atlas"]
    return {
        "charts": a["charts"],
        "utilization": a["utilization"],
        "utilization_of": a["utilization_of"],
        "stretch_mean": m["stretch_l2"]["mean"],
        "stretch_max": m["stretch_l2"]["max"],
        "angle_mean": m["angle_distortion"]["mean"],
        "flipped": a["flipped_triangles"] + a["collapsed_triangles"],
        "mirrored_charts": a["mirrored_charts"],
        "overlapping": a["overlapping_triangles"],
        "seam": seam_length(obj),
    }


def run_ours(cli, mesh, tmp, runs, padding, resolution):
    obj, rep = os.path.join(tmp, "ours.obj"), os.path.join(tmp, "ours.json")
    times = []
    for _ in range(runs):
        subprocess.run([cli, "atlas", mesh, "-o", obj, "--report", rep, "-q", "--padding", str(padding),
                        "--resolution", str(resolution)], check=True)
        t = json.load(open(rep))["timings_ms"]
        times.append(sum(t[k] for k in ("clean", "segment", "flatten", "merge", "pack")) / 1000)
    r = metrics(cli, obj)
    r["seconds"] = statistics.median(times)
    return r


def run_xatlas(cli, mesh, tmp, runs, padding, resolution, node="node"):
    loaded = load(mesh)
    if loaded is None:
        return None, "not read by this script (PLY)"
    V, F = loaded
    if len(V) >= 65536:
        return None, f"{len(V)} vertices: over xatlasjs's 16-bit indices"
    data = os.path.join(tmp, "x.json")
    with open(data, "w") as f:
        json.dump({"V": [c for v in V for c in v], "F": [i for t in F for i in t], "padding": padding,
                   "resolution": resolution}, f)
    obj = os.path.join(tmp, "x.obj")
    times = []
    for _ in range(runs):
        try:
            p = subprocess.run([node, os.path.join(HERE, "atlas_compare_xatlas.mjs"), data, obj], capture_output=True,
                               text=True, cwd=HERE)
        except OSError as e:
            return None, f"node ({node}) could not be run: {e}"
        if p.returncode != 0:
            lines = p.stderr.strip().splitlines() or ["?"]
            return None, "xatlas failed: " + next((l for l in lines if "Error" in l), lines[-1]).strip()
        times.append(json.loads(p.stdout.strip().splitlines()[-1])["seconds"])
    r = metrics(cli, obj)
    r["seconds"] = statistics.median(times)
    return r, ""


COLUMNS = [("charts", "{:d}"), ("utilization", "{:.1%}"), ("stretch_mean", "{:.3f}"), ("stretch_max", "{:.3g}"),
           ("angle_mean", "{:.3f}"), ("seam", "{:.3g}"), ("flipped", "{:d}"), ("mirrored_charts", "{:d}"),
           ("overlapping", "{:d}"), ("seconds", "{:.2f}")]


def check(args, meshes):
    """The comparison as a test: every mesh, ours against xatlasjs, one run each."""
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in meshes:
            name = os.path.basename(mesh).split(".")[0]
            ours = run_ours(args.cli, mesh, tmp, 1, args.padding, args.resolution)
            x, why = run_xatlas(args.cli, mesh, tmp, 1, args.padding, args.resolution, args.node)
            if x is None:
                failures.append(f"{name}: xatlasjs did not run ({why}; `npm ci` in bench/ installs it)")
                continue
            print(f"{name}: charts {ours['charts']} vs xatlasjs {x['charts']}, utilization "
                  f"{ours['utilization']:.4f} vs {x['utilization']:.4f}, stretch {ours['stretch_mean']:.4f}",
                  flush=True)
            if ours["utilization"] < x["utilization"]:
                failures.append(f"{name}: utilization {ours['utilization']:.4f} below xatlasjs's {x['utilization']:.4f}")
            if 2 * ours["charts"] > x["charts"]:
                failures.append(f"{name}: {ours['charts']} charts, more than half of xatlasjs's {x['charts']}")
            for k in ("flipped", "mirrored_charts", "overlapping"):
                if ours[k] != 0:
                    failures.append(f"{name}: {ours[k]} {k}")
    for f in failures:
        print("FAIL " + f, flush=True)
    return 1 if failures else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("meshes", nargs="*")
    ap.add_argument("--cli", default=os.path.join(ROOT, "build", "intrinsic"))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--padding", type=float, default=2)
    ap.add_argument("--resolution", type=int, default=1024)
    ap.add_argument("--markdown", action="store_true", help="print a Markdown table")
    ap.add_argument("--node", default="node", help="the Node.js executable that runs xatlasjs")
    ap.add_argument("--check", action="store_true",
                    help="exit non-zero unless ours has at least xatlasjs's utilization and at most half its charts")
    ap.add_argument("--skip-without", metavar="DIR",
                    help="exit 77 (Skipped, for ctest) when DIR is absent: the shared meshes beside a clone")
    args = ap.parse_args()
    if args.skip_without and not os.path.isdir(args.skip_without):
        print(f"SKIPPED: {args.skip_without} is absent (the shared meshes are not beside this clone)", flush=True)
        return 77
    meshes = args.meshes
    if not meshes:
        d = os.environ.get("INTRINSIC_SHARED_MESHES", os.path.join(ROOT, "..", "shared", "meshes"))
        d = os.path.join(d, "assets")
        meshes = sorted(os.path.join(d, n) for n in os.listdir(d) if n.split(".")[-1] in ("obj", "off", "ply", "gz"))
    if args.check:
        return check(args, meshes)
    head = ["mesh", "tool"] + [c for c, _ in COLUMNS]
    if args.markdown:
        print("| " + " | ".join(head) + " |")
        print("|" + "---|" * len(head))
    else:
        print(" ".join(f"{h:>12}" for h in head))
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in meshes:
            name = os.path.basename(mesh).split(".")[0]
            rows = [("intrinsic", run_ours(args.cli, mesh, tmp, args.runs, args.padding, args.resolution), "")]
            x, why = run_xatlas(args.cli, mesh, tmp, args.runs, args.padding, args.resolution, args.node)
            rows.append(("xatlas", x, why))
            for tool, r, why in rows:
                cells = [name, tool] + ([f.format(r[c]) for c, f in COLUMNS] if r else [why] + [""] * (len(COLUMNS) - 1))
                if args.markdown:
                    print("| " + " | ".join(cells) + " |", flush=True)
                else:
                    print(" ".join(f"{c:>12}" for c in cells), flush=True)


if __name__ == "__main__":
    sys.exit(main())
