"""Blender's Smart UV Project on one mesh, for bench/atlas_compare.py: the
second peer next to xatlas. Runs inside Blender (3.4, Debian's package):

    blender -b --factory-startup --python-exit-code 1 --python bench/atlas_blender.py -- IN.json OUT.obj

IN.json is what bench/atlas_compare.py gives xatlas: {"V": [x,y,z,...],
"F": [i,j,k,...], "padding": P, "resolution": R}. The mesh is built from
these lists directly (mesh.from_pydata) rather than through Blender's OBJ
importer, so Blender sees exactly the triangles the other tools see, in the
same order, with nothing merged, split or re-oriented.

Smart UV Project keeps Blender's defaults (angle limit 66 degrees, no area
weight, aspect correction, islands rotated to fit) except the margin: the
margin method FRACTION makes island_margin an exact fraction of the final
UV square, which is what our padding is (padding texels / resolution); the
default SCALED method scales the margin with the islands, so it would not be
the same gap.

OUT.obj is written like the other tools' OBJs: the input vertices, one `vt`
per distinct (vertex, UV) pair, faces `f v/vt` in the input order, so
`intrinsic metrics` and atlas_compare.py's own measures read all three the
same way. The last line on stdout is `ATLAS_BLENDER {json}` with the seconds
of the unwrap and pack (the operator call only: no Blender start-up, no mesh
building, no OBJ writing).
"""
import json
import math
import sys
import time

import bpy


def build_object(V, F):
    """A new object with exactly these triangles, active and selected."""
    mesh = bpy.data.meshes.new("atlas_input")
    verts = [tuple(V[i:i + 3]) for i in range(0, len(V), 3)]
    faces = [tuple(F[i:i + 3]) for i in range(0, len(F), 3)]
    mesh.from_pydata(verts, [], faces)
    mesh.update(calc_edges=True)
    obj = bpy.data.objects.new("atlas_input", mesh)
    bpy.context.scene.collection.objects.link(obj)
    for o in bpy.context.scene.objects:
        o.select_set(o is obj)
    bpy.context.view_layer.objects.active = obj
    return obj


def smart_project(obj, margin):
    """Edit mode, everything selected, Smart UV Project; returns its seconds."""
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    t0 = time.perf_counter()
    bpy.ops.uv.smart_project(angle_limit=math.radians(66), margin_method="FRACTION", island_margin=margin)
    seconds = time.perf_counter() - t0
    bpy.ops.object.mode_set(mode="OBJECT")
    return seconds


def write_obj(path, V, obj):
    """Input vertices, one vt per distinct (vertex, u, v), faces in input order."""
    mesh = obj.data
    uv = mesh.uv_layers.active.data
    vt_index, vts, faces = {}, [], []
    for poly in mesh.polygons:
        corners = []
        for li in poly.loop_indices:
            v = mesh.loops[li].vertex_index
            key = (v, uv[li].uv[0], uv[li].uv[1])
            t = vt_index.get(key)
            if t is None:
                t = vt_index[key] = len(vts)
                vts.append(key[1:])
            corners.append(f"{v + 1}/{t + 1}")
        faces.append("f " + " ".join(corners))
    with open(path, "w") as f:
        f.write(f"# Blender {bpy.app.version_string} Smart UV Project\n")
        for i in range(0, len(V), 3):
            f.write(f"v {V[i]!r} {V[i + 1]!r} {V[i + 2]!r}\n")
        for u, v in vts:
            f.write(f"vt {u!r} {v!r}\n")
        f.write("\n".join(faces) + "\n")
    return len(vts), len(faces)


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    if len(argv) != 2:
        raise SystemExit("usage: blender -b --factory-startup --python-exit-code 1 --python atlas_blender.py -- "
                         "IN.json OUT.obj")
    with open(argv[0]) as f:
        data = json.load(f)
    obj = build_object(data["V"], data["F"])
    if len(obj.data.polygons) != len(data["F"]) // 3:
        raise SystemExit(f"Blender kept {len(obj.data.polygons)} of {len(data['F']) // 3} faces")
    seconds = smart_project(obj, data["padding"] / data["resolution"])
    n_vt, n_f = write_obj(argv[1], data["V"], obj)
    print("ATLAS_BLENDER " + json.dumps({"seconds": seconds, "version": bpy.app.version_string,
                                         "vertices_out": n_vt, "faces_out": n_f}), flush=True)


main()
