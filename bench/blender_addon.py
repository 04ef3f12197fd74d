"""`uv.intrinsic_atlas` (the Blender add-on, blender/intrinsic_uv/) against
Blender's own Smart UV Project on one 100k-face object, in one Blender run
(docs/blender.md has the figures):

    blender -b --factory-startup --python bench/blender_addon.py -- --zip build/intrinsic_blender.zip
            [--mesh PATH] [--runs 3] [--unwrap]

The add-on is unpacked from the zip into a temporary folder and registered
from there (nothing is installed into the user's Blender). The object is a
torus of 400 x 125 quads split into 100,000 triangles with a bumpy tube
radius (so charts do not just follow the grid), or with --mesh a file read
by the bundled module (intrinsic.read_mesh), built from the arrays as they
are. With --unwrap, also uv.intrinsic_unwrap (natural boundary) against
Blender's Unwrap (CONFORMAL, i.e. LSCM: the same map) on an open wave grid
of 99,458 triangles. Each tool
runs --runs times on the same object; the medians are printed, with the
library's own share (intrinsic.atlas on the same arrays, outside the
operator) and the chart counts. Times are wall seconds of the operator call
only (no Blender start, no mesh building).
"""
import argparse
import math
import statistics
import sys
import tempfile
import time
import zipfile

import bpy
import numpy as np


def load_addon(zip_path, folder):
    with zipfile.ZipFile(zip_path) as z:
        z.extractall(folder)
    sys.path.insert(0, folder)
    import intrinsic_uv
    intrinsic_uv.register()
    from intrinsic_uv import library
    lib = library.load()
    if lib is None:
        raise SystemExit(library.failure())
    return lib


def mesh_from_arrays(name, V, F):
    """A new object with exactly these triangles (foreach_set: fast at 100k faces)."""
    me = bpy.data.meshes.new(name)
    me.vertices.add(len(V))
    me.vertices.foreach_set("co", np.ascontiguousarray(V, dtype=np.float32).ravel())
    me.loops.add(3 * len(F))
    me.loops.foreach_set("vertex_index", np.ascontiguousarray(F, dtype=np.int32).ravel())
    me.polygons.add(len(F))
    me.polygons.foreach_set("loop_start", np.arange(0, 3 * len(F), 3, dtype=np.int32))
    me.polygons.foreach_set("loop_total", np.full(len(F), 3, dtype=np.int32))
    me.update(calc_edges=True)
    obj = bpy.data.objects.new(name, me)
    bpy.context.scene.collection.objects.link(obj)
    bpy.context.view_layer.objects.active = obj
    return obj


def bumpy_torus(nu=400, nv=125, R=1.0, r=0.3):
    """400 x 125 quads, each split into two triangles: 100,000 faces."""
    u = np.repeat(np.arange(nu) * 2 * math.pi / nu, nv)
    v = np.tile(np.arange(nv) * 2 * math.pi / nv, nu)
    rr = r * (1 + 0.15 * np.sin(7 * u) * np.cos(3 * v))
    V = np.stack([(R + rr * np.cos(v)) * np.cos(u), (R + rr * np.cos(v)) * np.sin(u), rr * np.sin(v)], axis=1)
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    a, b = i * nv + j, ((i + 1) % nu) * nv + j
    c, d = ((i + 1) % nu) * nv + (j + 1) % nv, i * nv + (j + 1) % nv
    F = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    return mesh_from_arrays("bumpy_torus", V, F)


def mesh_from_file(lib, path):
    V, F = lib.read_mesh(path)
    return mesh_from_arrays("bench", V, F)


def select_only(obj):
    if bpy.context.mode != "OBJECT":
        bpy.ops.object.mode_set(mode="OBJECT")
    for o in bpy.context.scene.objects:
        o.select_set(o is obj)
    bpy.context.view_layer.objects.active = obj


def time_intrinsic(obj, runs, padding, resolution):
    select_only(obj)
    seconds = []
    for _ in range(runs):
        t0 = time.perf_counter()
        result = bpy.ops.uv.intrinsic_atlas(padding=padding, resolution=resolution)
        seconds.append(time.perf_counter() - t0)
        if result != {"FINISHED"}:
            raise SystemExit(f"uv.intrinsic_atlas: {result}")
    return seconds


def time_library(lib, obj, runs, padding, resolution):
    from intrinsic_uv import op_atlas
    seconds, reports, own = [], [], []
    for _ in range(runs):
        t0 = time.perf_counter()
        V, F, T, P = op_atlas.mesh_arrays(obj)
        t1 = time.perf_counter()
        r = lib.atlas(V, F, padding=padding, resolution=resolution, face_groups=P)
        t2 = time.perf_counter()
        uv = op_atlas.loop_uvs(r, F, T, len(obj.data.loops))
        obj.data.uv_layers.active.data.foreach_set("uv", uv.ravel())
        own.append(t1 - t0 + time.perf_counter() - t2)
        seconds.append(t2 - t1)
        reports.append(r.report)
    print(f"the add-on's own work (read arrays, corners to loops, write): median {statistics.median(own):.3f} s",
          flush=True)
    median_run = reports[sorted(range(runs), key=lambda k: seconds[k])[runs // 2]]
    stages = ", ".join(f"{k} {v / 1000:.2f}" for k, v in median_run["timings_ms"].items())
    print(f"intrinsic.atlas stages of the median run (s): {stages}", flush=True)
    charts = median_run["charts"]
    return seconds, charts if not isinstance(charts, list) else len(charts)


def wave_grid(n=224):
    """An open wave surface of 2 (n-1)^2 triangles (224: 99,458): one island for the unwraps."""
    x, y = np.meshgrid(np.linspace(0, 2, n), np.linspace(0, 2, n), indexing="ij")
    V = np.stack([x.ravel(), y.ravel(), 0.2 * (np.sin(3 * x) * np.cos(2 * y)).ravel()], axis=1)
    i, j = np.meshgrid(np.arange(n - 1), np.arange(n - 1), indexing="ij")
    a, b, c, d = i * n + j, (i + 1) * n + j, (i + 1) * n + j + 1, i * n + j + 1
    F = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    return mesh_from_arrays("wave_grid", V, F)


def time_unwraps(obj, runs):
    """uv.intrinsic_unwrap (natural boundary: the natural conformal map) and
    Blender's Unwrap (its CONFORMAL method is LSCM, the same map) on everything."""
    select_only(obj)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    ours, blender = [], []
    for _ in range(runs):
        t0 = time.perf_counter()
        if bpy.ops.uv.intrinsic_unwrap(boundary="NATURAL") != {"FINISHED"}:
            raise SystemExit("uv.intrinsic_unwrap failed")
        ours.append(time.perf_counter() - t0)
        t0 = time.perf_counter()
        bpy.ops.uv.unwrap(method="CONFORMAL", margin=0.02)
        blender.append(time.perf_counter() - t0)
    bpy.ops.object.mode_set(mode="OBJECT")
    return ours, blender


def time_smart_project(obj, runs, padding, resolution):
    select_only(obj)
    bpy.ops.object.mode_set(mode="EDIT")
    bpy.ops.mesh.select_all(action="SELECT")
    seconds = []
    for _ in range(runs):
        t0 = time.perf_counter()
        bpy.ops.uv.smart_project(angle_limit=math.radians(66), margin_method="FRACTION",
                                 island_margin=padding / resolution)
        seconds.append(time.perf_counter() - t0)
    bpy.ops.object.mode_set(mode="OBJECT")
    return seconds


def main():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    ap = argparse.ArgumentParser(prog="blender_addon.py")
    ap.add_argument("--zip", required=True)
    ap.add_argument("--mesh")
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--padding", type=float, default=2.0)
    ap.add_argument("--resolution", type=int, default=1024)
    ap.add_argument("--unwrap", action="store_true", help="also time the unwraps on a 99k-triangle wave grid")
    a = ap.parse_args(argv)
    with tempfile.TemporaryDirectory(prefix="intrinsic_addon_bench_") as folder:
        lib = load_addon(a.zip, folder)
        obj = mesh_from_file(lib, a.mesh) if a.mesh else bumpy_torus()
        faces = sum(len(p.vertices) - 2 for p in obj.data.polygons)
        print(f"object: {a.mesh or 'bumpy torus'}: {len(obj.data.vertices)} vertices, {faces} triangles", flush=True)
        ours = time_intrinsic(obj, a.runs, a.padding, a.resolution)
        library_s, charts = time_library(lib, obj, a.runs, a.padding, a.resolution)
        smart = time_smart_project(obj, a.runs, a.padding, a.resolution)
        unwrap = []
        if a.unwrap:
            grid = wave_grid()
            print(f"unwrap object: wave grid, {len(grid.data.vertices)} vertices, {len(grid.data.polygons)} triangles")
            ours_u, blender_u = time_unwraps(grid, a.runs)
            unwrap = [("uv.intrinsic_unwrap (natural)", ours_u), ("uv.unwrap (CONFORMAL)", blender_u)]
    for name, s in [("uv.intrinsic_atlas", ours), ("  of which intrinsic.atlas alone", library_s),
                    ("uv.smart_project", smart)] + unwrap:
        print(f"{name}: median {statistics.median(s):.3f} s of {len(s)} runs ({', '.join(f'{x:.3f}' for x in s)})",
              flush=True)
    print(f"intrinsic charts: {charts}", flush=True)


main()
