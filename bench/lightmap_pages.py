#!/usr/bin/python3
"""Lightmap pages against xatlas (docs/benchmarks.md "Lightmap pages"): each
mesh packed at one texel density on pages of R texels by `intrinsic atlas
--texels-per-unit T --resolution R` and by xatlas (npm xatlasjs, same
texelsPerUnit, resolution and padding); prints pages and per-page fill for
both. T is given per mesh as a multiple of the density at which the mesh's
surface would fill one page (--fill 2 4: about two and four pages' worth).

Usage: bench/lightmap_pages.py [--cli build/intrinsic] [--fill 2 4] MESH...
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)


def read_obj_like(cli, path, tmp):
    """V and F of any mesh the CLI reads, through an OBJ it writes (atlas)."""
    out = os.path.join(tmp, "plain.obj")
    subprocess.run([cli, "atlas", path, "-o", out, "-q"], check=True)
    V, F = [], []
    for line in open(out):
        if line.startswith("v "):
            V.extend(float(x) for x in line.split()[1:4])
        elif line.startswith("f "):
            F.extend(int(c.split("/")[0]) - 1 for c in line.split()[1:4])
    return V, F


def surface_area(V, F):
    a = 0.0
    for f in range(0, len(F), 3):
        p = [V[3 * F[f + k]:3 * F[f + k] + 3] for k in range(3)]
        u = [p[1][i] - p[0][i] for i in range(3)]
        v = [p[2][i] - p[0][i] for i in range(3)]
        c = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        a += math.sqrt(sum(x * x for x in c)) / 2
    return a


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", default=os.path.join(HERE, "..", "build", "intrinsic"))
    ap.add_argument("--resolution", type=int, default=512)
    ap.add_argument("--padding", type=float, default=2)
    ap.add_argument("--fill", type=float, nargs="+", default=[2, 4])
    ap.add_argument("meshes", nargs="+")
    a = ap.parse_args()
    tmp = tempfile.mkdtemp(prefix="lightmap-pages-")
    print("| mesh | pages' worth | T | intrinsic pages | fill per page | xatlas pages |")
    print("|---|---|---|---|---|---|")
    for path in a.meshes:
        V, F = read_obj_like(a.cli, path, tmp)
        area = surface_area(V, F)
        for fill in a.fill:
            t = math.sqrt(fill * a.resolution ** 2 / area)
            rep = os.path.join(tmp, "r.json")
            subprocess.run([a.cli, "atlas", path, "-o", os.path.join(tmp, "o.obj"), "-q", "--report", rep,
                            "--texels-per-unit", str(t), "--resolution", str(a.resolution),
                            "--padding", str(a.padding)], check=True)
            r = json.load(open(rep))
            js = os.path.join(tmp, "m.json")
            json.dump({"V": V, "F": F, "padding": a.padding, "resolution": a.resolution, "texels_per_unit": t},
                      open(js, "w"))
            x = subprocess.run(["node", os.path.join(HERE, "lightmap_pages_xatlas.mjs"), js],
                               capture_output=True, text=True, cwd=HERE)
            xp = json.loads(x.stdout)["pages"] if x.returncode == 0 else "failed: " + x.stderr[-80:]
            fills = " ".join(f"{u:.2f}" for u in r["page_utilization"])
            print(f"| {os.path.basename(path)} | {fill:g} | {t:.1f} | {r['pages']} | {fills} | {xp} |")


if __name__ == "__main__":
    main()
