#!/usr/bin/python3
"""Runs a fixed set of CLI commands on the shared assets and on generated
meshes, and prints the SHA-256 of every file they write and of their exit
codes, as JSON. Two builds that give the same digest write the same bytes.

Reports are compared without their "timings_ms" and other wall-clock keys
(the one part of an output that differs between runs). Used to check that a
change of structure changes no output:

    scripts/cli_digest.py build/intrinsic > before.json
    ... change, rebuild ...
    scripts/cli_digest.py build/intrinsic --compare before.json
"""
import argparse
import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.path.normpath(os.path.join(HERE, "..", "..", "shared", "meshes"))
SAMPLES = "/usr/share/assimp/models"
CLOCK_KEYS = ("timings_ms", "seconds", "elapsed_ms", "ms")


def cases():
    """(name, argv after the binary, produced files); {out} is the work folder."""
    a = os.path.join(SHARED, "assets")
    m = SHARED
    s = SAMPLES
    yield "generate-textured", ["generate", "textured", "-o", "{out}/textured.glb"]
    yield "generate-parts", ["generate", "parts", "--parts", "20", "-o", "{out}/parts.obj"]
    for mesh in ("spot.obj", "rocker-arm.obj", "3holes.off", "teapot.obj", "horse_quad.obj"):
        yield "atlas-" + mesh, ["atlas", f"{a}/{mesh}", "-o", "{out}/atlas.obj",
                                "--report", "{out}/report.json", "-q"]
    yield "atlas-glb", ["atlas", f"{a}/spot.obj", "-o", "{out}/spot.glb", "--report", "{out}/r.json", "-q"]
    yield "atlas-pages", ["atlas", f"{a}/truck.obj", "-o", "{out}/t.obj", "--texels-per-unit", "64",
                          "--resolution", "256", "--report", "{out}/r.json", "-q"]
    yield "atlas-per-mesh", ["atlas", "{out}/../generate-textured/textured.glb", "-o", "{out}/pm.glb",
                             "--atlas", "per-mesh", "--report", "{out}/r.json", "-q"]
    yield "atlas-transfer", ["atlas", "{out}/../generate-textured/textured.glb", "-o", "{out}/tt.glb",
                             "--uv-set", "0", "--replace-uv-set", "--transfer-textures",
                             "--texture-size", "256", "--report", "{out}/r.json", "-q"]
    yield "atlas-fbx", ["atlas", f"{s}/FBX/spider.fbx", "-o", "{out}/spider.glb", "--report", "{out}/r.json", "-q"]
    yield "atlas-box-gltf", ["atlas", f"{s}/glTF2/BoxTextured-glTF/BoxTextured.gltf", "-o", "{out}/box.gltf",
                         "--report", "{out}/r.json", "-q"]
    yield "atlas-engine", ["atlas", f"{s}/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb",
                          "-o", "{out}/e.obj", "--report", "{out}/r.json", "-q"]
    yield "atlas-bad", ["atlas", f"{m}/README.md", "-o", "{out}/x.obj"]
    for method in ("conformal", "authalic", "tutte", "floater"):
        yield "param-" + method, ["param", f"{m}/cat_head.obj", "-o", "{out}/p.obj", "--method", method,
                                  "--report", "{out}/r.json", "-q"]
    yield "param-natural", ["param", f"{m}/face-bff.obj", "-o", "{out}/p.ply", "--boundary", "natural", "-q"]
    yield "param-mixed", ["param", f"{m}/beetle.off", "-o", "{out}/p.obj", "--optimize-lambda", "edge", "-q"]
    yield "render-checker", ["render", "{out}/../param-conformal/p.obj", "-o", "{out}/c.png", "--size", "256,256"]
    yield "render-layout", ["render", "{out}/../atlas-spot.obj/atlas.obj", "-o", "{out}/l.png",
                            "--mode", "layout", "--size", "256,256"]
    yield "render-stretch", ["render", "{out}/../atlas-spot.obj/atlas.obj", "-o", "{out}/s.png",
                             "--mode", "stretch", "--size", "256,256"]
    yield "metrics", ["metrics", "{out}/../atlas-teapot.obj/atlas.obj"]
    yield "compare", ["compare", f"{m}/cat_head.obj", "-o", "{out}/cmp.png", "--size", "256,256"]


def without_clocks(value):
    if isinstance(value, dict):
        return {k: without_clocks(v) for k, v in value.items() if k not in CLOCK_KEYS}
    if isinstance(value, list):
        return [without_clocks(v) for v in value]
    return value


def digest_file(path):
    data = open(path, "rb").read()
    if path.endswith("cmp.png"):  # prints each method's solve time: only its size is compared
        return data[16:24].hex()
    if path.endswith(".json"):
        data = json.dumps(without_clocks(json.loads(data)), sort_keys=True).encode()
    return hashlib.sha256(data).hexdigest()


def run(binary, root):
    result = {}
    for name, argv in cases():
        out = os.path.join(root, name)
        os.makedirs(out, exist_ok=True)
        args = [binary] + [x.replace("{out}", out) for x in argv]
        proc = subprocess.run(args, capture_output=True, text=True)
        entry = {"exit": proc.returncode}
        for f in sorted(os.listdir(out)):
            entry[f] = digest_file(os.path.join(out, f))
        if name == "metrics":  # the printed report is its product
            text = json.dumps(without_clocks(json.loads(proc.stdout)), sort_keys=True)
            entry["stdout"] = hashlib.sha256(text.encode()).hexdigest()
        if proc.returncode != 0:
            entry["stderr"] = proc.stderr.strip().splitlines()[-1:] if proc.stderr else []
        result[name] = entry
    return result


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("binary")
    ap.add_argument("--compare", help="a digest written before: print the differences, exit 1 if any")
    args = ap.parse_args()
    if not os.path.isdir(SHARED):
        sys.exit(f"{SHARED} is missing: the digest runs on the shared meshes")
    # One fixed folder: reports name their input and output paths.
    root = os.path.join(tempfile.gettempdir(), "intrinsic-cli-digest")
    shutil.rmtree(root, ignore_errors=True)
    now = run(os.path.abspath(args.binary), root)
    shutil.rmtree(root, ignore_errors=True)
    if not args.compare:
        json.dump(now, sys.stdout, indent=1, sort_keys=True)
        print()
        return
    before = json.load(open(args.compare))
    differ = [n for n in sorted(set(before) | set(now)) if before.get(n) != now.get(n)]
    for n in differ:
        print(f"{n}: before {before.get(n)}\n{' ' * len(n)}  now    {now.get(n)}")
    files = sum(len(e) - 1 for e in now.values())
    print(f"{len(now)} commands, {files} outputs: {len(differ)} differ")
    sys.exit(1 if differ else 0)


if __name__ == "__main__":
    main()
