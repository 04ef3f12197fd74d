#!/usr/bin/python3
"""What survives `intrinsic atlas` on real scenes (docs/formats.md "Images travel
with the output", "Other formats (assimp)"), measured on Debian's
assimp-testmodels:

- glTF: every .gltf/.glb under models/glTF2 is validated (Khronos validator),
  atlased into a .glb in ANOTHER folder, and the output validated: a valid
  input must give 0 errors (IO errors included), an invalid one no more errors
  than it came in with.
- Other formats (FBX, Collada, 3DS, LWO, X, ...): each file assimp reads is
  atlased into a .glb, validated, and compared with assimp's own glTF export
  of the same file (`assimp_export_counts`, a small C++ helper built here
  against libassimp): triangles drawn (instances included), meshes (one
  primitive each), materials.

Usage: bench/scene_roundtrip.py [--cli build/intrinsic] [--models DIR] [--out DIR]
Prints one line per file and a summary; exit 0 always (a measurement).
"""
import argparse
import json
import os
import struct
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
VALIDATE = os.path.join(HERE, "..", "tests", "gltf_validator", "validate.mjs")
OTHER = (".fbx", ".dae", ".3ds", ".lwo", ".x", ".obj", ".blend", ".ase", ".ac", ".ms3d", ".b3d", ".off")


def validator_errors(path):
    r = subprocess.run(["node", VALIDATE, path], capture_output=True, text=True)
    first = (r.stdout.splitlines() or ["? ? ?"])[0].split()
    try:
        return int(first[0]), [l.strip() for l in r.stdout.splitlines()[1:] if l.strip().startswith("error")]
    except ValueError:
        return None, [r.stdout + r.stderr]


def glb_json(path):
    b = open(path, "rb").read()
    n = struct.unpack("<I", b[12:16])[0]
    return json.loads(b[20:20 + n])


def drawn_triangles(j):
    acc = j.get("accessors", [])
    n = 0
    for node in j.get("nodes", []):
        if "mesh" not in node:
            continue
        for p in j["meshes"][node["mesh"]]["primitives"]:
            if p.get("mode", 4) == 4 and "indices" in p:
                n += acc[p["indices"]]["count"] // 3
    return n


def atlas(cli, src, out):
    r = subprocess.run([cli, "atlas", src, "-o", out, "-q"], capture_output=True, text=True)
    return r.returncode, r.stderr.strip()


def gltf_files(root):
    for d, _, files in os.walk(root):
        for f in sorted(files):
            if f.lower().endswith((".gltf", ".glb")):
                yield os.path.join(d, f)


def run_gltf(cli, models, out):
    ok = worse = refused = 0
    for src in sorted(gltf_files(os.path.join(models, "glTF2"))):
        before, _ = validator_errors(src)
        dst = os.path.join(out, "gltf", os.path.relpath(src, models).replace("/", "_") + ".glb")
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        code, err = atlas(cli, src, dst)
        if code != 0:
            refused += 1
            print(f"refused  {os.path.relpath(src, models)} (in: {before} errors): {err[:150]}")
            continue
        after, msgs = validator_errors(dst)
        good = after is not None and before is not None and (after == 0 if before == 0 else after <= before)
        ok += good
        worse += not good
        print(f"{'ok  ' if good else 'WORSE'}     {os.path.relpath(src, models)}: {before} -> {after} errors"
              + ("" if good else " " + "; ".join(msgs[:3])))
    print(f"glTF: {ok} ok, {worse} with more errors out than in, {refused} refused")


def run_other(cli, models, out, counts):
    ok = bad = refused = 0
    for d, _, files in sorted(os.walk(models)):
        if "glTF" in d or "invalid" in d:
            continue
        for f in sorted(files):
            if not f.lower().endswith(OTHER) or f.lower().endswith((".obj", ".off")):
                continue
            src = os.path.join(d, f)
            ref = subprocess.run([counts, src], capture_output=True, text=True)
            if ref.returncode != 0:
                continue  # assimp itself cannot export it to glTF
            tri, meshes, materials = (int(x) for x in ref.stdout.split())
            if tri == 0:
                continue
            dst = os.path.join(out, "other", os.path.relpath(src, models).replace("/", "_") + ".glb")
            os.makedirs(os.path.dirname(dst), exist_ok=True)
            code, err = atlas(cli, src, dst)
            if code != 0:
                refused += 1
                print(f"refused  {os.path.relpath(src, models)}: {err[:150]}")
                continue
            errors, msgs = validator_errors(dst)
            j = glb_json(dst)
            # assimp's exporter puts the meshes one node draws into one glTF mesh,
            # one primitive each: primitives stand for the source's meshes.
            prims = sum(len(m.get("primitives", [])) for m in j.get("meshes", []))
            got = (drawn_triangles(j), prims, len(j.get("materials", [])))
            good = errors == 0 and got[0] >= tri and got[1] == meshes and got[2] == materials
            ok += good
            bad += not good
            print(f"{'ok  ' if good else 'BAD '}     {os.path.relpath(src, models)}: triangles {got[0]}/{tri}, "
                  f"meshes (primitives) {got[1]}/{meshes}, materials {got[2]}/{materials}, {errors} validator errors"
                  + ("" if errors == 0 else " " + "; ".join(msgs[:2])))
    print(f"other formats: {ok} ok, {bad} not, {refused} refused")


COUNTS_CPP = r"""
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <cstdio>
// Triangles drawn (per node, instances included), meshes with triangles and
// materials of assimp's own reading of a file.
static long drawn(const aiScene* s, const aiNode* n) {
  long t = 0;
  for (unsigned k = 0; k < n->mNumMeshes; ++k) {
    const aiMesh* m = s->mMeshes[n->mMeshes[k]];
    for (unsigned f = 0; f < m->mNumFaces; ++f) t += m->mFaces[f].mNumIndices == 3;
  }
  for (unsigned c = 0; c < n->mNumChildren; ++c) t += drawn(s, n->mChildren[c]);
  return t;
}
int main(int argc, char** argv) {
  Assimp::Importer imp;
  imp.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  const aiScene* s = imp.ReadFile(argv[1], aiProcess_Triangulate | aiProcess_ValidateDataStructure);
  if (!s || !s->mRootNode || s->mNumMeshes == 0) return 1;
  Assimp::Exporter ex;
  if (!ex.ExportToBlob(s, "glb2")) return 1;
  std::printf("%ld %u %u\n", drawn(s, s->mRootNode), s->mNumMeshes, s->mNumMaterials);
}
"""


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--cli", default=os.path.join(HERE, "..", "build", "intrinsic"))
    ap.add_argument("--models", default="/usr/share/assimp/models")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    out = a.out or tempfile.mkdtemp(prefix="scene-roundtrip-")
    os.makedirs(out, exist_ok=True)
    counts = os.path.join(out, "assimp_export_counts")
    with open(counts + ".cpp", "w") as f:
        f.write(COUNTS_CPP)
    subprocess.run(["g++", "-O1", counts + ".cpp", "-o", counts, "-lassimp"], check=True)
    run_gltf(a.cli, a.models, out)
    run_other(a.cli, a.models, out, counts)


if __name__ == "__main__":
    sys.exit(main())
