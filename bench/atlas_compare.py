#!/usr/bin/python3
"""intrinsic atlas against xatlas and Blender's Smart UV Project on the shared
assets, same machine, same run, measured for what a person sees.

For each asset under ../shared/meshes/assets: `intrinsic atlas` writes its
OBJ; xatlas runs through the npm package xatlasjs (WebAssembly, in Node:
bench/atlas_compare_xatlas.mjs; install with `npm ci` in bench/, which
scripts/install-deps.sh does) and Blender 3.4's Smart UV Project runs inside
Blender (bench/atlas_blender.py; Debian's `blender`, optional) on the same
triangles (polygons fan-triangulated as our reader does) with the same
padding and resolution, and both write an OBJ of the same shape (input
vertices, one vt per output vertex, f v/vt). Every OBJ is measured the same
way, twice where the two overlap:
- by `intrinsic metrics`: charts (UV-connected components), exact overlaps,
  flips per chart, mirrored charts, utilization; and, once it reports them,
  its "stretch" object and atlas seam_length / small_charts;
- here, with numpy, from the OBJ alone (`uv_measures`): per face the
  Jacobian from the 3D triangle's own 2D frame to UV, singular values
  s1 >= s2, UVs scaled so the total UV area equals the total 3D area; Sander
  L2 = sqrt(sum A (1/s1^2 + 1/s2^2)/2 / sum A) and L-inf = max 1/s2 (the
  stretch of the UV -> surface map, Sander et al. 2001); per-face stretch
  max(s1, 1/s2) with area-weighted percentiles; anisotropy s1/s2,
  area-weighted mean; seam length (3D length of the cut edges). Conventions
  as `metrics` (docs/maths.md 9.8): faces degenerate in 3D are left out; a
  face collapsed in UV is infinitely stretched, counts in the percentiles
  and maxima, not in the UV scale nor the means. When `metrics` reports
  the same keys, the two must agree to 1e-6 relative or a warning is
  printed.
- here too, per chart (`chart_measures`), with charts as `metrics` counts
  them (faces joined through UV edges two faces share, corners identified
  by UV and 3D position; a count that differs from `metrics`' is a
  warning): compactness, a chart's UV area over the area of its smallest
  enclosing rectangle of any orientation (hull of its UVs, every hull edge
  direction tried), 1 for a rectangle, the UV-area-weighted mean over the
  charts with UV area; and border turning, at each vertex of a chart's
  boundary (edges one face of the chart uses) the angle between the
  incoming and outgoing boundary edges (0 straight, 180 a reversal),
  reported as the share of boundary vertices over the atlas turning more
  than 60 degrees (vertices with other than two boundary edges in their
  chart, where a chart touches itself, are left out).

Table columns per tool: charts, utilization, seam length / sqrt(3D area),
Sander L2, p95 and max face stretch, mean anisotropy, compactness, share of
border turns over 60 degrees, flipped (folded or collapsed triangles),
overlapping triangles, seconds. On our row,
"dominates" says whether ours is at least as good as xatlas on every count
of DOMINANCE (below), or which counts it loses. Two summary lines follow:
medians of the ratios ours / xatlas (charts, seam, utilization) and on how
many meshes ours dominates; medians of ours and of xatlas's compactness and
turning, and on how many meshes ours is at least as compact; the same two
for Blender.

Times: computation only, median of --runs runs. Ours: the report's
clean+segment+flatten+merge+pack (no read or write); xatlas: addMesh and
generateAtlas inside Node (no Node start-up, no wasm compilation); Blender:
the smart_project operator call (unwrap + pack; no Blender start-up, no mesh
building). xatlasjs takes 16-bit indices: meshes with 65,536 vertices or
more are skipped for it. PLY inputs are read by neither peer here.

Usage: bench/atlas_compare.py [--cli build/intrinsic] [--runs 3] [--markdown]
                              [--node node] [--blender blender] [--json OUT]
                              [--check] [--skip-without DIR] [MESH ...]

--check (the ctest atlas_vs_xatlasjs): one run per mesh, xatlasjs only (no
Blender); exits non-zero unless every criterion of CHECK_CRITERIA holds on
every mesh, all measured by `intrinsic metrics`. A missing node or xatlasjs
(bench/node_modules) is a failure, not a skip; --skip-without DIR exits 77
(ctest's Skipped) when DIR, the shared meshes beside a clone, is absent.
"""
import argparse
import gzip
import json
import math
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

# What --check (the ctest) requires of ours against xatlasjs on every mesh:
# (description, test(ours, xatlas), the keys its failure message shows).
# Change the test here; the docstring and the ctest follow.
CHECK_CRITERIA = [
    ("utilization at least xatlasjs's", lambda o, x: o["utilization"] >= x["utilization"], "utilization"),
    ("no more charts than xatlasjs", lambda o, x: o["charts"] <= x["charts"], "charts"),
    ("p95 face stretch at most xatlasjs's + 0.02",
     lambda o, x: o["face_stretch_p95"] <= x["face_stretch_p95"] + 0.02, "face_stretch_p95"),
    ("Sander L2 at most xatlasjs's + 0.01", lambda o, x: o["sander_l2"] <= x["sander_l2"] + 0.01, "sander_l2"),
    ("no flipped or collapsed triangle", lambda o, x: o["flipped"] == 0, "flipped"),
    ("no mirrored chart", lambda o, x: o["mirrored_charts"] == 0, "mirrored_charts"),
    ("no overlapping triangle", lambda o, x: o["overlapping"] == 0, "overlapping"),
]

# What "ours dominates xatlas" means in the table, same shape.
DOMINANCE = [
    ("p95", lambda o, x: o["face_stretch_p95"] <= x["face_stretch_p95"] + 0.02, "face_stretch_p95"),
    ("L2", lambda o, x: o["sander_l2"] <= x["sander_l2"] + 0.01, "sander_l2"),
    ("charts", lambda o, x: o["charts"] <= x["charts"], "charts"),
    ("utilization", lambda o, x: o["utilization"] >= x["utilization"], "utilization"),
    ("overlaps", lambda o, x: o["overlapping"] == 0, "overlapping"),
]

# Keys of `metrics`' "stretch" object (and of its "atlas" object) that this
# script also computes; they are cross-checked when present.
STRETCH_KEYS = ["sander_l2", "sander_linf", "face_stretch_p50", "face_stretch_p95", "face_stretch_p99",
                "face_stretch_max", "anisotropy_mean"]
ATLAS_KEYS = ["seam_length"]
CROSS_CHECK_TOLERANCE = 1e-6


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
    if base.lower().endswith(".stl"):
        return parse_stl(path)
    return None  # PLY (igea): over xatlasjs's 16-bit limit anyway


def parse_stl(path):
    """STL, ASCII or binary, corners welded when their float32 coordinates are equal (as our reader)."""
    import struct
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rb") as f:
        data = f.read()
    corners = []
    if len(data) >= 84 and len(data) == 84 + 50 * struct.unpack_from("<I", data, 80)[0]:
        for k in range(struct.unpack_from("<I", data, 80)[0]):
            c = struct.unpack_from("<12f", data, 84 + 50 * k)
            corners.extend([tuple(c[3:6]), tuple(c[6:9]), tuple(c[9:12])])
    else:
        for line in data.decode("ascii", "replace").splitlines():
            t = line.split()
            if t and t[0].lower() == "vertex":
                corners.append(tuple(struct.unpack("<3f", struct.pack("<3f", *map(float, t[1:4])))))
    index, V = {}, []
    ids = [index.setdefault(c, len(index)) for c in corners]
    V = [list(c) for c in index]
    F = [ids[i:i + 3] for i in range(0, len(ids) - len(ids) % 3, 3)]
    return V, F


def read_uv_obj(path):
    """An atlas OBJ (v, vt, f v/vt; polygons fan-triangulated) as numpy arrays
    V (n,3), VT (m,2), F (k,3) and FT (k,3), 0-based."""
    V, VT, F, FT = [], [], [], []
    with open(path, errors="replace") as f:  # names in other encodings pass through
        for line in f:
            t = line.split()
            if not t:
                continue
            if t[0] == "v":
                V.append([float(x) for x in t[1:4]])
            elif t[0] == "vt":
                VT.append([float(x) for x in t[1:3]])
            elif t[0] == "f":
                c = [x.split("/") for x in t[1:]]
                vi = [int(x[0]) - 1 for x in c]
                ti = [int(x[1]) - 1 for x in c]
                for k in range(1, len(c) - 1):
                    F.append([vi[0], vi[k], vi[k + 1]])
                    FT.append([ti[0], ti[k], ti[k + 1]])
    return (np.array(V, float).reshape(-1, 3), np.array(VT, float).reshape(-1, 2),
            np.array(F, int).reshape(-1, 3), np.array(FT, int).reshape(-1, 3))


def seam_length(V, VT, F, FT):
    """3D length of the edges where the UVs are cut: each edge, named by its two
    3D positions (vertices split in the input meet), counts once for every
    distinct pair of UVs along it beyond the first (a manifold seam once)."""
    P, T = [tuple(p) for p in V.tolist()], [tuple(t) for t in VT.tolist()]
    uv_edges = {}
    for face, tface in zip(F.tolist(), FT.tolist()):
        for k in range(3):
            a, b, ta, tb = P[face[k]], P[face[(k + 1) % 3]], T[tface[k]], T[tface[(k + 1) % 3]]
            if a == b:
                continue
            key, uv = ((a, b), (ta, tb)) if a < b else ((b, a), (tb, ta))
            uv_edges.setdefault(key, set()).add(uv)
    return sum((len(s) - 1) * math.dist(a, b) for (a, b), s in uv_edges.items() if len(s) > 1)


def weighted_percentile(values, weights, p):
    """The smallest value whose area-weighted cumulative share reaches p (0..1),
    to 1e-12 of the total (so a share met exactly is met despite rounding)."""
    order = np.argsort(values, kind="stable")
    cum = np.cumsum(weights[order])
    i = int(np.searchsorted(cum, (p - 1e-12) * cum[-1], side="left"))
    return float(values[order][min(i, len(values) - 1)])


def singular_values(V, VT, F, FT):
    """Per face not degenerate in 3D: its 3D area and the singular values
    s1 >= s2 of the Jacobian from the triangle's own 2D frame (x along edge 01,
    y in its plane) to UV, with the UVs scaled so the total UV area is the
    total 3D area over the faces not collapsed. A face is degenerate when
    twice its area is at most 1e-12 of its longest edge squared (make_mesh's
    test); a collapsed UV face (zero area or a non-finite UV) gets s2 = 0.
    As docs/maths.md 9.8 defines them for `metrics`."""
    e1, e2 = V[F[:, 1]] - V[F[:, 0]], V[F[:, 2]] - V[F[:, 0]]
    twice = np.linalg.norm(np.cross(e1, e2), axis=1)
    longest = np.max([np.einsum("ij,ij->i", e, e) for e in (e1, e2, e2 - e1)], axis=0)
    ok = twice > 1e-12 * longest
    e1, e2, twice = e1[ok], e2[ok], twice[ok]
    a = np.linalg.norm(e1, axis=1)  # frame: q1 = (a, 0), q2 = (b, c)
    b, c = np.einsum("ij,ij->i", e1, e2) / a, twice / a
    d1, d2 = VT[FT[ok, 1]] - VT[FT[ok, 0]], VT[FT[ok, 2]] - VT[FT[ok, 0]]
    area_uv = 0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    counted = np.isfinite(area_uv) & (area_uv > 0)  # collapsed faces are left out of the scale
    scale = math.sqrt(0.5 * twice[counted].sum() / area_uv[counted].sum()) if counted.any() else math.inf
    # J = scale [d1 d2] [[a b] [0 c]]^-1: columns d1/a and (d2 - d1 b/a)/c.
    j1 = scale * d1 / a[:, None]
    j2 = (scale * d2 - j1 * b[:, None]) / c[:, None]
    # Closed-form 2x2 singular values: s1 = |E,H| + |F,G|, s2 = |det| / s1.
    E, Fh = (j1[:, 0] + j2[:, 1]) / 2, (j1[:, 0] - j2[:, 1]) / 2
    G, H = (j1[:, 1] + j2[:, 0]) / 2, (j1[:, 1] - j2[:, 0]) / 2
    s1 = np.hypot(E, H) + np.hypot(Fh, G)
    det = np.abs(j1[:, 0] * j2[:, 1] - j1[:, 1] * j2[:, 0])
    s2 = np.where(counted & (s1 > 0), det / np.where(s1 > 0, s1, 1), 0.0)
    return 0.5 * twice, s1, np.nan_to_num(s2, nan=0.0)


def uv_corners(V, VT, F, FT):
    """Per face corner (k, 3) an id of its texture coordinate as `metrics`
    identifies them (src/metrics/uv_mesh.cpp, uv_charts.cpp): corners with
    equal UV and equal 3D position are one, whatever their vt index; a corner
    with a non-finite UV or position stands alone (per vt and vertex index)."""
    key = np.concatenate([VT[FT].reshape(-1, 2), V[F].reshape(-1, 3)], axis=1) + 0.0  # -0.0 -> 0.0
    finite = np.isfinite(key).all(axis=1)
    ids = np.empty(len(key), np.int64)
    k = np.ascontiguousarray(key[finite])
    _, ids[finite] = np.unique(k.view(np.dtype((np.void, k.dtype.itemsize * 5))).ravel(), return_inverse=True)
    if not finite.all():
        pairs = np.stack([FT.ravel()[~finite], F.ravel()[~finite]], axis=1)
        _, inv = np.unique(pairs, axis=0, return_inverse=True)
        ids[~finite] = finite.sum() + inv.ravel()
    return ids.reshape(-1, 3)


def components(n, a, b):
    """Connected-component label (0..count-1) of n nodes joined by the pairs
    (a[i], b[i]): hooking of roots and pointer jumping, in numpy."""
    lab = np.arange(n)
    while len(a):
        la, lb = lab[a], lab[b]
        if (la == lb).all():
            break
        m = np.minimum(la, lb)
        np.minimum.at(lab, la, m)
        np.minimum.at(lab, lb, m)
        while True:
            nxt = lab[lab]
            if (nxt == lab).all():
                break
            lab = nxt
    return np.unique(lab, return_inverse=True)[1].ravel()


def uv_charts(T):
    """Chart per face, as `metrics`: faces are joined through a UV edge (two
    corner ids of T) that exactly two face sides use; an edge used by more
    joins nothing."""
    m = len(T)
    a, b = T.ravel(), T[:, [1, 2, 0]].ravel()
    face = np.repeat(np.arange(m), 3)
    keep = a != b
    lo, hi, face = np.minimum(a, b)[keep], np.maximum(a, b)[keep], face[keep]
    order = np.lexsort((hi, lo))
    lo, hi, face = lo[order], hi[order], face[order]
    start = np.r_[True, (lo[1:] != lo[:-1]) | (hi[1:] != hi[:-1])]
    first = np.flatnonzero(start)
    count = np.diff(np.r_[first, len(lo)])
    two = first[count == 2]
    return components(m, face[two], face[two + 1])


def convex_hull(P):
    """Counter-clockwise hull of the rows of P sorted by (x, y), collinear
    points dropped (Andrew's monotone chain)."""
    pts = P.tolist()
    if len(pts) < 3:
        return P

    def chain(seq):
        h = []
        for p in seq:
            while len(h) >= 2 and ((h[-1][0] - h[-2][0]) * (p[1] - h[-2][1])
                                   - (h[-1][1] - h[-2][1]) * (p[0] - h[-2][0])) <= 0:
                h.pop()
            h.append(p)
        return h

    lower, upper = chain(pts), chain(reversed(pts))
    return np.array(lower[:-1] + upper[:-1], float).reshape(-1, 2)


def min_rectangle_area(H):
    """Area of the smallest rectangle, of any orientation, enclosing the convex
    polygon H (ccw rows): one side of it lies along a hull edge (Freeman and
    Shapira 1975), so every hull edge direction is tried (the directions the
    rotating calipers visit; here all projections at once, O(h^2))."""
    if len(H) < 3:
        return 0.0
    P = H - H[0]
    E = np.roll(P, -1, axis=0) - P
    D = E / np.linalg.norm(E, axis=1)[:, None]
    U = P @ D.T  # along each edge direction
    W = P @ np.stack([-D[:, 1], D[:, 0]], axis=1).T  # across it
    return float(((U.max(0) - U.min(0)) * (W.max(0) - W.min(0))).min())


def chart_measures(V, VT, F, FT):
    """Charts as `metrics` counts them (components of faces joined through UV
    edges, less those whose faces are all degenerate in 3D), their compactness
    and the turning of their borders:
    - compactness: per chart its UV area over the area of its smallest
      enclosing rectangle (of the hull of its UVs, any orientation); the
      UV-area-weighted mean over charts with UV area (a chart folded over
      itself can exceed 1);
    - turning_over_60: the share of boundary vertices (a chart's corner ids
      on the edges exactly one face of that chart uses) whose turning angle,
      between the incoming and the outgoing boundary edge, exceeds 60 degrees
      (0 straight, 180 a reversal). A boundary vertex with more or fewer than
      two boundary edges in its chart (charts touching themselves at a
      vertex; edges used three times) has no single turn and is left out of
      both counts; a zero-length boundary edge counts as straight.
    Returns (charts, compactness, turning_over_60); 0.0 where undefined."""
    T = uv_corners(V, VT, F, FT)
    chart = uv_charts(T)
    nc = int(chart.max()) + 1
    X = [V[F[:, k]] for k in range(3)]
    longest = np.max([np.einsum("ij,ij->i", d, d) for d in (X[1] - X[0], X[2] - X[1], X[0] - X[2])], axis=0)
    with np.errstate(invalid="ignore"):
        solid = np.linalg.norm(np.cross(X[1] - X[0], X[2] - X[0]), axis=1) > 1e-12 * longest
    counted = np.zeros(nc, bool)
    counted[chart[solid]] = True
    U = [VT[FT[:, k]] for k in range(3)]
    d1, d2 = U[1] - U[0], U[2] - U[0]
    area = 0.5 * np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    area = np.where(np.isfinite(area), area, 0.0)
    chart_area = np.bincount(chart, area, nc)

    # Compactness: the (chart, corner) points of the charts with area, finite,
    # sorted by chart then (u, v); a hull and its rectangle per chart.
    uv_of = np.empty((int(T.max()) + 1, 2))
    uv_of[T.ravel()] = VT[FT.ravel()]
    nt = int(T.max()) + 1
    assert nc * nt * nt < 2 ** 63  # keys below pack (chart, corner[, corner]) in an int64
    cc = np.unique(np.repeat(chart, 3) * nt + T.ravel())
    cc = np.stack([cc // nt, cc % nt], axis=1)
    pts = uv_of[cc[:, 1]]
    keep = (chart_area[cc[:, 0]] > 0) & np.isfinite(pts).all(axis=1)
    cc, pts = cc[keep], pts[keep]
    order = np.lexsort((pts[:, 1], pts[:, 0], cc[:, 0]))
    cc, pts = cc[order], pts[order]
    cuts = np.flatnonzero(np.diff(cc[:, 0])) + 1
    num = den = 0.0
    for c, P in zip(cc[np.r_[0, cuts], 0] if len(cc) else [], np.split(pts, cuts)):
        rect = min_rectangle_area(convex_hull(P))
        if rect > 0:
            num += chart_area[c] * chart_area[c] / rect
            den += chart_area[c]
    compactness = num / den if den > 0 else 0.0

    # Turning: boundary edges per chart (corner pairs one face of the chart uses).
    a, b = T.ravel(), T[:, [1, 2, 0]].ravel()
    c3 = np.repeat(chart, 3)
    keep = (a != b) & counted[c3]
    key, count = np.unique((c3[keep] * nt + np.minimum(a, b)[keep]) * nt + np.maximum(a, b)[keep],
                           return_counts=True)
    key = key[count == 1]
    e = np.stack([key // (nt * nt), key // nt % nt, key % nt], axis=1)
    # (chart, vertex, neighbour), twice per edge, grouped by (chart, vertex).
    ends = np.concatenate([e[:, [0, 1, 2]], e[:, [0, 2, 1]]])
    ends = ends[np.lexsort((ends[:, 1], ends[:, 0]))]
    start = np.r_[True, (ends[1:, 0] != ends[:-1, 0]) | (ends[1:, 1] != ends[:-1, 1])] if len(ends) else []
    first = np.flatnonzero(start)
    degree = np.diff(np.r_[first, len(ends)])
    two = first[degree == 2]
    if not len(two):
        return int(counted.sum()), compactness, 0.0
    v, p, n = uv_of[ends[two, 1]], uv_of[ends[two, 2]], uv_of[ends[two + 1, 2]]
    d_in, d_out = v - p, n - v
    cross = d_in[:, 0] * d_out[:, 1] - d_in[:, 1] * d_out[:, 0]
    turn = np.degrees(np.arctan2(np.abs(cross), np.einsum("ij,ij->i", d_in, d_out)))
    return int(counted.sum()), compactness, float(np.mean(turn > 60))


def uv_measures(obj):
    """The stretch and seam measures of an atlas OBJ, by the names `metrics`
    gives them, and the charts' count ("uv_charts", to check `metrics`'),
    compactness and border turning (chart_measures). A collapsed UV face has infinite stretch: it counts in the
    percentiles and maxima and is left out of the means (as `metrics` does)."""
    V, VT, F, FT = read_uv_obj(obj)
    if len(F) == 0:
        return {k: 1.0 for k in STRETCH_KEYS} | {"seam_length": 0.0, "area_3d": 0.0, "uv_charts": 0,
                                                   "compactness": 0.0, "turning_over_60": 0.0}
    with np.errstate(divide="ignore", invalid="ignore"):
        A, s1, s2 = singular_values(V, VT, F, FT)
        inv1, inv2 = 1 / s1, np.where(s2 > 0, 1 / s2, np.inf)
        face = np.maximum(s1, inv2)
        fin = np.isfinite(face)
        l2 = (A[fin] * (inv1[fin] ** 2 + inv2[fin] ** 2) / 2).sum() / A[fin].sum()
        aniso = (A[fin] * s1[fin] / s2[fin]).sum() / A[fin].sum()
    r = {"sander_l2": math.sqrt(float(l2)), "sander_linf": float(inv2.max()), "face_stretch_max": float(face.max()),
         "anisotropy_mean": float(aniso)}
    for p in (50, 95, 99):
        r[f"face_stretch_p{p}"] = weighted_percentile(face, A, p / 100)
    r["seam_length"] = seam_length(V, VT, F, FT)
    r["area_3d"] = float(A.sum())
    r["uv_charts"], r["compactness"], r["turning_over_60"] = chart_measures(V, VT, F, FT)
    return r


def cross_check(name, ours, theirs, keys):
    """Warns when `metrics` and this script disagree on a measure both have."""
    for k in keys:
        if k not in theirs:
            continue
        a = float(ours[k])
        b = math.inf if theirs[k] is None else float(theirs[k])  # metrics writes an infinite figure as null
        if a == b or (math.isfinite(a) and math.isfinite(b) and abs(a - b) <= CROSS_CHECK_TOLERANCE * max(abs(a), abs(b))):
            continue
        print(f"warning: {name}: {k} is {b!r} by `intrinsic metrics`, {a!r} by atlas_compare.py", file=sys.stderr,
              flush=True)


def metrics(cli, obj, name=""):
    """Everything the table shows about one atlas OBJ."""
    out = subprocess.run([cli, "metrics", obj], capture_output=True, text=True, check=True).stdout
    m = json.loads(out)
    a = m["atlas"]
    r = {
        "charts": a["charts"],
        "utilization": a["utilization"],
        "utilization_of": a["utilization_of"],
        "stretch_mean": m["stretch_l2"]["mean"],
        "stretch_max": m["stretch_l2"]["max"],
        "angle_mean": m["angle_distortion"]["mean"],
        "flipped": a["flipped_triangles"] + a["collapsed_triangles"],
        "mirrored_charts": a["mirrored_charts"],
        "overlapping": a["overlapping_triangles"],
    }
    if "small_charts" in a:
        r["small_charts"] = a["small_charts"]
    mine = uv_measures(obj)
    cross_check(name, mine, m.get("stretch", {}), STRETCH_KEYS)
    cross_check(name, mine, a, ATLAS_KEYS)
    if mine["uv_charts"] != a["charts"]:
        print(f"warning: {name}: charts is {a['charts']} by `intrinsic metrics`, {mine['uv_charts']} by "
              "atlas_compare.py (compactness and turning are over the latter)", file=sys.stderr, flush=True)
    del mine["uv_charts"]
    r.update(mine)
    r["seam_per_sqrt_area"] = r["seam_length"] / math.sqrt(r["area_3d"])
    return r


def write_input_json(mesh, path, padding, resolution):
    """The mesh's triangles as the peers read them; (True, "") or (False, why)."""
    loaded = load(mesh)
    if loaded is None:
        return False, "not read by this script (PLY)"
    V, F = loaded
    with open(path, "w") as f:
        json.dump({"V": [c for v in V for c in v], "F": [i for t in F for i in t], "padding": padding,
                   "resolution": resolution}, f)
    return True, str(len(V))


def produce_ours(cli, mesh, obj, runs, padding, resolution):
    """Writes our atlas to obj; returns the median computation seconds. An
    image the input's materials name but its folder lacks (spider.obj's .mtl)
    does not stop it: the layout is measured, not the materials."""
    rep = obj + ".json"
    times = []
    for _ in range(runs):
        subprocess.run([cli, "atlas", mesh, "-o", obj, "--report", rep, "-q", "--padding", str(padding),
                        "--resolution", str(resolution), "--allow-missing-images"], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        with open(rep) as f:
            t = json.load(f)["timings_ms"]
        times.append(sum(t[k] for k in ("clean", "segment", "flatten", "merge", "pack")) / 1000)
    return statistics.median(times)


def run_peer(command, obj, runs, parse_seconds):
    """Runs a peer `runs` times; (median seconds, "") or (None, why)."""
    times = []
    for _ in range(runs):
        try:
            p = subprocess.run(command, capture_output=True, text=True, cwd=HERE)
        except OSError as e:
            return None, f"{command[0]} could not be run: {e}"
        if p.returncode != 0 or not os.path.exists(obj):
            lines = (p.stderr.strip() or p.stdout.strip()).splitlines() or [f"exit code {p.returncode}, no OBJ"]
            return None, "failed: " + next((l for l in lines if "Error" in l), lines[-1]).strip()
        try:
            times.append(parse_seconds(p.stdout))
        except (StopIteration, ValueError, KeyError, IndexError):
            return None, "failed: no timing in its output"
    return statistics.median(times), ""


def produce_xatlas(data, nv, obj, runs, node="node"):
    if nv >= 65536:
        return None, f"{nv} vertices: over xatlasjs's 16-bit indices"
    s, why = run_peer([node, os.path.join(HERE, "atlas_compare_xatlas.mjs"), data, obj], obj, runs,
                      lambda out: json.loads(out.strip().splitlines()[-1])["seconds"])
    return s, ("xatlas " + why if why else "")


def produce_blender(data, obj, runs, blender):
    def seconds(out):
        line = next(l for l in reversed(out.splitlines()) if l.startswith("ATLAS_BLENDER "))
        return json.loads(line.split(" ", 1)[1])["seconds"]

    cmd = [blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python",
           os.path.join(HERE, "atlas_blender.py"), "--", data, obj]
    s, why = run_peer(cmd, obj, runs, seconds)
    return s, ("Blender " + why if why else "")


def produce_all(args, mesh, tmp, tools, runs):
    """Every tool's atlas OBJ of one mesh under tmp: {tool: (obj or None, seconds or why)}."""
    out = {}
    obj = os.path.join(tmp, "intrinsic.obj")
    out["intrinsic"] = (obj, produce_ours(args.cli, mesh, obj, runs, args.padding, args.resolution))
    data = os.path.join(tmp, "input.json")
    ok, nv = write_input_json(mesh, data, args.padding, args.resolution)
    for tool in tools:
        obj = os.path.join(tmp, tool + ".obj")
        if os.path.exists(obj):
            os.remove(obj)
        if not ok:
            out[tool] = (None, nv)
            continue
        if tool == "xatlas":
            s, why = produce_xatlas(data, int(nv), obj, runs, args.node)
        else:
            s, why = produce_blender(data, obj, runs, args.blender)
        out[tool] = (obj, s) if s is not None else (None, why)
    return out


def measure_all(cli, name, produced):
    """{tool: (metrics dict with "seconds", "") or (None, why)}."""
    rows = {}
    for tool, (obj, s) in produced.items():
        if obj is None:
            rows[tool] = (None, s)
            continue
        r = metrics(cli, obj, f"{name} ({tool})")
        r["seconds"] = s
        rows[tool] = (r, "")
    return rows


def failed(criteria, ours, x):
    """The criteria ours fails against x, with both values."""
    return [(d, k) for d, test, k in criteria if not test(ours, x)]


def check(args, meshes):
    """The comparison as a test: every mesh, ours against xatlasjs, one run each."""
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in meshes:
            name = os.path.basename(mesh).split(".")[0]
            rows = measure_all(args.cli, name, produce_all(args, mesh, tmp, ["xatlas"], 1))
            ours, (x, why) = rows["intrinsic"][0], rows["xatlas"]
            if x is None:
                failures.append(f"{name}: xatlasjs did not run ({why}; `npm ci` in bench/ installs it)")
                continue
            print(f"{name}: charts {ours['charts']} vs xatlasjs {x['charts']}, utilization "
                  f"{ours['utilization']:.4f} vs {x['utilization']:.4f}, Sander L2 {ours['sander_l2']:.4f}",
                  flush=True)
            for d, k in failed(CHECK_CRITERIA, ours, x):
                failures.append(f"{name}: fails \"{d}\" (ours {ours[k]:.6g}, xatlasjs {x[k]:.6g})")
    for f in failures:
        print("FAIL " + f, flush=True)
    return 1 if failures else 0


COLUMNS = [("charts", "{:d}"), ("utilization", "{:.1%}"), ("seam_per_sqrt_area", "{:.3g}"), ("sander_l2", "{:.3f}"),
           ("face_stretch_p95", "{:.3f}"), ("face_stretch_max", "{:.3g}"), ("anisotropy_mean", "{:.3f}"),
           ("compactness", "{:.3f}"), ("turning_over_60", "{:.1%}"), ("flipped", "{:d}"), ("overlapping", "{:d}"),
           ("seconds", "{:.2f}")]
HEADERS = ["charts", "util", "seam/sqrtA", "L2", "p95", "max", "aniso", "compact", "turn>60", "flipped", "overlaps",
           "seconds"]


def dominance(rows):
    """'yes', 'no: p95, charts' or '' (no xatlas figures)."""
    ours, x = rows["intrinsic"][0], rows.get("xatlas", (None, ""))[0]
    if x is None:
        return ""
    lost = failed(DOMINANCE, ours, x)
    return "yes" if not lost else "no: " + ", ".join(d for d, _ in lost)


def print_row(cells, markdown):
    if markdown:
        print("| " + " | ".join(cells) + " |", flush=True)
    else:
        print(f"{cells[0]:>16} {cells[1]:>9} " + " ".join(f"{c:>10}" for c in cells[2:]), flush=True)


def print_summary(results, markdown, peer="xatlas"):
    """Medians of ours / peer and the dominance count over the meshes both ran."""
    both = [(r["intrinsic"][0], r[peer][0]) for r in results.values() if r.get(peer, (None,))[0]]
    if not both:
        return

    def med(k):
        return statistics.median(o[k] / x[k] for o, x in both if x[k] > 0)

    def each(k, i):
        return statistics.median(pair[i][k] for pair in both)

    wins = sum(1 for o, x in both if not failed(DOMINANCE, o, x))
    compact = sum(1 for o, x in both if o["compactness"] >= x["compactness"])
    line = (f"ours / {peer}, medians over {len(both)} meshes: charts {med('charts'):.2f}, "
            f"seam {med('seam_length'):.2f}, utilization {med('utilization'):.2f}; "
            f"ours dominates on {wins} of {len(both)}")
    shape = (f"ours vs {peer}, medians over {len(both)} meshes: compactness {each('compactness', 0):.3f} vs "
             f"{each('compactness', 1):.3f}, turning over 60 degrees {each('turning_over_60', 0):.1%} vs "
             f"{each('turning_over_60', 1):.1%}; ours at least as compact on {compact} of {len(both)}")
    print(("\n" if markdown else "") + line, flush=True)
    print(("\n" if markdown else "") + shape, flush=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("meshes", nargs="*")
    ap.add_argument("--cli", default=os.path.join(ROOT, "build", "intrinsic"))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--padding", type=float, default=2)
    ap.add_argument("--resolution", type=int, default=1024)
    ap.add_argument("--markdown", action="store_true", help="print a Markdown table")
    ap.add_argument("--node", default="node", help="the Node.js executable that runs xatlasjs")
    ap.add_argument("--blender", default=shutil.which("blender") or "",
                    help="the Blender executable for Smart UV Project (default: blender on PATH; '' skips it)")
    ap.add_argument("--json", help="also write every figure as JSON to this file")
    ap.add_argument("--check", action="store_true", help="exit non-zero unless ours meets CHECK_CRITERIA "
                    "against xatlasjs on every mesh (the ctest atlas_vs_xatlasjs)")
    ap.add_argument("--skip-without", metavar="DIR",
                    help="exit 77 (Skipped, for ctest) when DIR is absent: the shared meshes beside a clone")
    args = ap.parse_args()
    if args.skip_without and not os.path.isdir(args.skip_without):
        print(f"SKIPPED: {args.skip_without} is absent (the shared meshes are not beside this clone)", flush=True)
        return 77
    meshes = args.meshes or default_meshes()
    if args.check:
        return check(args, meshes)
    tools = ["xatlas"] + (["blender"] if args.blender else [])
    if not args.blender:
        print("note: no Blender (not on PATH, or --blender ''): its column is skipped", flush=True)
    head = ["mesh", "tool"] + HEADERS + ["dominates"]
    print_row(head, args.markdown)
    if args.markdown:
        print("|" + "---|" * len(head))
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in meshes:
            name = os.path.basename(mesh).split(".")[0]
            try:
                rows = measure_all(args.cli, name, produce_all(args, mesh, tmp, tools, args.runs))
            except subprocess.CalledProcessError as e:  # ours (or metrics) failed: say so, keep the other meshes
                last = (e.stderr or "").strip().splitlines()[-1:] or [f"exit code {e.returncode}"]
                why = f"failed: {os.path.basename(e.cmd[0])} {e.cmd[1]}: {last[0]}"
                print(f"warning: {name}: {why}", file=sys.stderr, flush=True)
                rows = {"intrinsic": (None, why)}
            results[name] = rows
            dom = dominance(rows)
            for tool, (r, why) in rows.items():
                cells = [name, tool] + ([f.format(r[c]) for c, f in COLUMNS] if r else [why] + [""] * (len(COLUMNS) - 1))
                print_row(cells + [dom if tool == "intrinsic" else ""], args.markdown)
    for peer in tools:
        print_summary(results, args.markdown, peer)
    if args.json:
        with open(args.json, "w") as f:
            json.dump({m: {t: (r if r else {"skipped": why}) for t, (r, why) in rows.items()}
                       for m, rows in results.items()}, f, indent=1)
    return 0


def default_meshes():
    d = os.environ.get("INTRINSIC_SHARED_MESHES", os.path.join(ROOT, "..", "shared", "meshes"))
    d = os.path.join(d, "assets")
    return sorted(os.path.join(d, n) for n in os.listdir(d) if n.split(".")[-1] in ("obj", "off", "ply", "gz"))


if __name__ == "__main__":
    sys.exit(main())
