#!/usr/bin/env python3
"""Writes the seed corpus fuzz/corpus/<target>/: small valid and invalid files.

Run from anywhere; the files are committed, so this is only needed to change
them. Deterministic (gzip without timestamps)."""
import gzip
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

# A square split into 4 triangles around a centre vertex, and a 3x3 grid.
SQUARE_V = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0.5, 0.5, 0.1)]
SQUARE_F = [(0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]
GRID_V = [(x, y, 0.1 * ((x * y) % 2)) for y in range(3) for x in range(3)]
GRID_F = []
for y in range(2):
    for x in range(2):
        a = y * 3 + x
        GRID_F += [(a, a + 1, a + 4), (a, a + 4, a + 3)]
# The grid with its centre face removed ... too small for a hole; an annulus:
RING_V = [(x, y, 0) for y in range(4) for x in range(4)]
RING_F = []
for y in range(3):
    for x in range(3):
        if (x, y) == (1, 1):
            continue
        a = y * 4 + x
        RING_F += [(a, a + 1, a + 5), (a, a + 5, a + 4)]


def obj(V, F, uv=False):
    s = "# seed\n" + "".join("v %g %g %g\n" % v for v in V)
    if uv:
        s += "".join("vt %g %g\n" % (v[0], v[1]) for v in V)
        s += "".join("f %d/%d %d/%d %d/%d\n" % (a + 1, a + 1, b + 1, b + 1, c + 1, c + 1) for a, b, c in F)
    else:
        s += "".join("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in F)
    return s


def off(V, F):
    return "OFF\n%d %d 0\n" % (len(V), len(F)) + "".join("%g %g %g\n" % v for v in V) + \
        "".join("3 %d %d %d\n" % f for f in F)


def ply_header(fmt, nv, nf, uv=False):
    return ("ply\nformat %s 1.0\ncomment seed\nelement vertex %d\nproperty float x\nproperty float y\n"
            "property float z\n%selement face %d\nproperty list uchar int vertex_indices\nend_header\n"
            % (fmt, nv, "property float u\nproperty float v\n" if uv else "", nf))


def ply_ascii(V, F, uv=False):
    body = "".join(("%g %g %g %g %g\n" % (v + v[:2])) if uv else ("%g %g %g\n" % v) for v in V)
    body += "".join("3 %d %d %d\n" % f for f in F)
    return ply_header("ascii", len(V), len(F), uv) + body


def ply_binary(V, F, big=False, uv=False):
    e = ">" if big else "<"
    fmt = "binary_big_endian" if big else "binary_little_endian"
    b = ply_header(fmt, len(V), len(F), uv).encode()
    for v in V:
        b += struct.pack(e + ("5f" if uv else "3f"), *(v + v[:2] if uv else v))
    for f in F:
        b += struct.pack(e + "B3i", 3, *f)
    return b


def stl_ascii(V, F, name="seed", eol="\n"):
    s = "solid %s%s" % (name, eol)
    for f in F:
        s += "facet normal 0 0 1%souter loop%s" % (eol, eol)
        s += "".join("vertex %g %g %g%s" % (V[i] + (eol,)) for i in f)
        s += "endloop%sendfacet%s" % (eol, eol)
    return s + "endsolid %s%s" % (name, eol)


def stl_binary(V, F, header=b"seed"):
    b = header.ljust(80, b"\0") + struct.pack("<I", len(F))
    for f in F:
        b += struct.pack("<3f", 0, 0, 1)
        for i in f:
            b += struct.pack("<3f", *V[i])
        b += b"\0\0"
    return b


def stl_seeds():
    return {
        "square_ascii.stl": stl_ascii(SQUARE_V, SQUARE_F),
        "grid_crlf.stl": stl_ascii(GRID_V, GRID_F, eol="\r\n"),
        "two_solids.stl": stl_ascii(SQUARE_V, SQUARE_F[:2], "a") + stl_ascii(SQUARE_V, SQUARE_F[2:], "b"),
        "ring_binary.stl": stl_binary(RING_V, RING_F),
        "square_binary_solid_header.stl": stl_binary(SQUARE_V, SQUARE_F, b"solid square"),
        "truncated_binary.stl": stl_binary(GRID_V, GRID_F)[:-17],
        "huge_count.stl": stl_binary(SQUARE_V, SQUARE_F)[:80] + struct.pack("<I", 4000000000) + b"\0" * 60,
        "nan_binary.stl": stl_binary([(float("nan"), 0, 0)] + SQUARE_V[1:], SQUARE_F),
        "truncated_ascii.stl": stl_ascii(GRID_V, GRID_F)[:-40],
        "inf_ascii.stl": stl_ascii(SQUARE_V, SQUARE_F).replace("vertex 1 0 0", "vertex 1 inf 0"),
        "four_vertices.stl": stl_ascii(SQUARE_V, SQUARE_F).replace("endloop", "vertex 0 0 0\nendloop", 1),
    }


def gltf_doc(V, F, mode=4, extra=None, glb=False, sparse=False, material=False):
    """A one-primitive glTF document (float positions, uint16 indices): JSON
    with a base64 data URI, or the GLB container."""
    import base64
    import json
    pos = b"".join(struct.pack("<3f", *v) for v in V)
    idx = b"".join(struct.pack("<3H", *f) for f in F)
    while len(idx) % 4:
        idx += b"\0"
    binary = pos + idx
    views = [{"buffer": 0, "byteLength": len(pos), "target": 34962},
             {"buffer": 0, "byteOffset": len(pos), "byteLength": 6 * len(F), "target": 34963}]
    lo = [min(v[k] for v in V) for k in range(3)]
    hi = [max(v[k] for v in V) for k in range(3)]
    acc = [{"bufferView": 0, "componentType": 5126, "type": "VEC3", "count": len(V), "min": lo, "max": hi},
           {"bufferView": 1, "componentType": 5123, "type": "SCALAR", "count": 3 * len(F)}]
    if sparse:
        sp_at = len(binary)
        binary += struct.pack("<H", 1) + b"\0\0" + struct.pack("<3f", 1, 0, 0.5)
        views += [{"buffer": 0, "byteOffset": sp_at, "byteLength": 2},
                  {"buffer": 0, "byteOffset": sp_at + 4, "byteLength": 12}]
        acc[0]["sparse"] = {"count": 1, "indices": {"bufferView": 2, "componentType": 5123},
                            "values": {"bufferView": 3}}
        acc[0]["max"] = [max(hi[0], 1), hi[1], max(hi[2], 0.5)]
    prim = {"attributes": {"POSITION": 0}, "indices": 1, "mode": mode}
    if material:
        prim["attributes"]["TEXCOORD_0"] = 0
        prim["material"] = 0
    doc = {"asset": {"version": "2.0"}, "buffers": [{"byteLength": len(binary)}], "bufferViews": views,
           "accessors": acc, "meshes": [{"primitives": [prim]}],
           "nodes": [{"mesh": 0, "children": [1], "translation": [1, 0, 0]},
                     {"mesh": 0, "scale": [2, 2, 2], "rotation": [0, 0, 0.6, 0.8]}],
           "scenes": [{"nodes": [0]}], "scene": 0}
    if material:
        doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}},
                             "normalTexture": {"index": 0, "texCoord": 1,
                                               "extensions": {"KHR_texture_transform": {"texCoord": 0}}}}]
        doc["textures"] = [{"source": 0}]
        doc["images"] = [{"uri": "none.png"}]
    doc.update(extra or {})
    if not glb:
        doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(binary).decode()
        return json.dumps(doc)
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    body = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(binary), 0x004E4942) + binary
    return b"glTF" + struct.pack("<II", 2, 12 + len(body)) + body


def gltf_seeds():
    strip = [(0, 1, 2), (3, 4, 5)]  # read as 6 strip indices
    return {
        "square.gltf": gltf_doc(SQUARE_V, SQUARE_F),
        "grid.glb": gltf_doc(GRID_V, GRID_F, glb=True),
        "ring_sparse.gltf": gltf_doc(RING_V, RING_F, sparse=True),
        "strip.gltf": gltf_doc([(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0), (0, 2, 0), (1, 2, 0)], strip, mode=5),
        "fan.glb": gltf_doc(SQUARE_V, SQUARE_F, mode=6, glb=True),
        "loop.gltf": gltf_doc(SQUARE_V, SQUARE_F, extra={"nodes": [{"children": [1]}, {"children": [0], "mesh": 0}]}),
        "draco.gltf": gltf_doc(SQUARE_V, SQUARE_F, extra={"extensionsRequired": ["KHR_draco_mesh_compression"]}),
        "truncated.glb": gltf_doc(GRID_V, GRID_F, glb=True)[:-9],
        # A material whose textures read TEXCOORD_0 (here the positions'
        # accessor: only the set's use matters to the writer's check).
        "textured.gltf": gltf_doc(SQUARE_V, SQUARE_F, material=True),
    }


def write(target, name, data):
    d = os.path.join(HERE, "corpus", target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data.encode() if isinstance(data, str) else data)


def gz(data):
    return gzip.compress(data.encode() if isinstance(data, str) else data, mtime=0)


def main():
    o = {
        "square.obj": obj(SQUARE_V, SQUARE_F),
        "grid_uv.obj": obj(GRID_V, GRID_F, uv=True),
        "ring.obj": obj(RING_V, RING_F),
        "quad_negative.obj": "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nf -4//1 -3//1 -2//1 -1//1\n",
        "zero_index.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n",
        "nan.obj": "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        "huge_index.obj": "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n",
        "truncated.obj": obj(SQUARE_V, SQUARE_F)[:-7],
        "crlf.obj": obj(SQUARE_V, SQUARE_F).replace("\n", "\r\n"),
        # What the reader keeps for the atlas OBJ: mtllib, usemtl/g/o/s, normals.
        "materials.obj": "usemtl red\nmtllib a.mtl\no thing\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                         "vn 0 0 1\nvn 0 1 0\ng left right\ns off\nf 1//1 2//2 3//1 4//2\n"
                         "mtllib b.mtl c.mtl\nusemtl Material #25\ns 1\nf 1 3//-1 4//-2\n",
    }
    f = {
        "square.off": off(SQUARE_V, SQUARE_F),
        "grid.off": off(GRID_V, GRID_F),
        "ring.off": off(RING_V, RING_F),
        "coff.off": "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n3 0 1 2\n",
        "huge_counts.off": "OFF\n2000000000 2000000000 0\n0 0 0\n",
        "negative.off": "OFF\n-3 1 0\n",
        "truncated.off": off(SQUARE_V, SQUARE_F)[:-10],
        "inf.off": "OFF 3 1 0\n0 0 inf\n1 0 0\n0 1 0\n3 0 1 2\n",
    }
    p = {
        "square_ascii.ply": ply_ascii(SQUARE_V, SQUARE_F),
        "grid_uv_ascii.ply": ply_ascii(GRID_V, GRID_F, uv=True),
        "square_le.ply": ply_binary(SQUARE_V, SQUARE_F),
        "square_be.ply": ply_binary(SQUARE_V, SQUARE_F, big=True),
        "ring_le.ply": ply_binary(RING_V, RING_F),
        "grid_uv_be.ply": ply_binary(GRID_V, GRID_F, big=True, uv=True),
        "truncated_le.ply": ply_binary(SQUARE_V, SQUARE_F)[:-5],
        "huge_count.ply": ply_header("binary_little_endian", 4000000000, 1) + "xyz",
        "extra_element.ply": ply_header("ascii", 3, 1).replace(
            "end_header", "element edge 1\nproperty int a\nproperty list uchar float w\nend_header") +
            "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n7 2 0.5 0.5\n",
    }
    for k, v in o.items():
        write("obj", k, v)
    for k, v in f.items():
        write("off", k, v)
    for k, v in p.items():
        write("ply", k, v)
    for k, v in stl_seeds().items():
        write("stl", k, v)
    for k, v in gltf_seeds().items():
        write("gltf", k, v)
    write("gzip", "square.obj.gz", gz(o["square.obj"]))
    write("gzip", "ring.off.gz", gz(f["ring.off"]))
    write("gzip", "square_le.ply.gz", gz(p["square_le.ply"]))
    write("gzip", "two_members.gz", gz(o["square.obj"][:40]) + gz(o["square.obj"][40:]))
    write("gzip", "truncated.gz", gz(o["grid_uv.obj"])[:-12])
    write("gzip", "bomb.gz", gz(b"v 0 0 0\n" + b" " * 200000))
    write("gzip", "trailing_zeros.gz", gz(o["square.obj"]) + b"\0" * 8)
    b = {
        "square.txt": "# corners\n0 0 0\n1 1 0\n2 1 1\n3 0 1\n",
        "spaces.txt": "  7\t0.5  -0.25  # comment\n\n99 1e3 -1e-3\n",
        "duplicate.txt": "0 0 0\n0 1 1\n",
        "out_of_range.txt": "100 0 0\n",
        "not_number.txt": "1 x 0\n",
        "nan.txt": "1 nan 0\n",
        "extra.txt": "1 0 0 0\n",
    }
    for k, v in b.items():
        write("boundary", k, v)
    # Seams files for fuzz_seams' mesh (the same 5 x 5 grid without the quad
    # at (1, 1); faces (a, a+1, a+6) and (a, a+6, a+5)).
    sm = {
        "row.txt": "# across the grid\n5 6\n6 7\n7 8\n8 9\n",
        "slit.txt": "0 6\n12 18  # diagonal\n\n",
        "loop.txt": "6 7\n7 12\n12 11\n11 6\n",
        "repeated.txt": "0 1\n1 0\n",
        "not_edge.txt": "0 2\n",
        "out_of_range.txt": "0 25\n",
        "malformed.txt": "0 x\n1\n",
        "empty.txt": "# nothing\n",
    }
    for k, v in sm.items():
        write("seams", k, v)
    # Constraint files for fuzz_constraints' mesh: the 5 x 5 grid without the
    # quad at (1, 1) (vertex y * 5 + x, 30 faces; vertices 6, 7, 11, 12 on the
    # hole, the rest of rows and columns 1-3 interior).
    c = {
        "empty.json": "{}",
        "points.json": '{"points": [{"face": 0, "bary": [0.2, 0.3, 0.5], "uv": [0.4, 0.55]},\n'
                       '  {"vertex": 13, "uv": [0.6, 0.5]}, {"vertex": 17, "uv": [0.5, 0.7]}]}',
        "line_segment.json": '{"lines": [{"path": [{"face": 14, "bary": [0.3, 0.3, 0.4]}, '
                             '{"face": 27, "bary": [0.3, 0.3, 0.4]}], "to": [[0.2, 0.3], [0.8, 0.3]]}]}',
        "line_polyline.json": '{"lines": [{"path": [{"face": 10, "bary": [0.3, 0.3, 0.4]}, {"vertex": 18}, '
                              '{"face": 28, "bary": [0.1, 0.1, 0.8]}], "to": [[0.2, 0.3], [0.5, 0.5], [0.8, 0.9]]}],'
                              ' "points": [{"vertex": 8, "uv": [0.7, 0.2]}]}',
        "line_through_hole.json": '{"lines": [{"path": [{"face": 6, "bary": [0.3, 0.3, 0.4]}, '
                                  '{"face": 10, "bary": [0.3, 0.3, 0.4]}], "to": [[0.2, 0.3], [0.8, 0.3]]}]}',
        "on_boundary.json": '{"points": [{"vertex": 0, "uv": [0.5, 0.5]}, {"vertex": 1, "uv": [0.9, 0.1]}]}',
        "contradiction.json": '{"points": [{"vertex": 13, "uv": [0.1, 0.1]}, {"vertex": 13, "uv": [0.2, 0.1]}]}',
        "dependent.json": '{"points": [{"face": 20, "bary": [0.5, 0.5, 0], "uv": [0.1, 0.1]}, '
                          '{"face": 20, "bary": [0.25, 0.75, 0], "uv": [0.2, 0.1]}, '
                          '{"face": 20, "bary": [0.75, 0.25, 0], "uv": [0.3, 0.1]}]}',
        "unknown_key.json": '{"points": [{"vertex": 13, "uvw": [0, 0]}]}',
        "malformed.json": '{"points": [{"vertex": 13, "uv": [0, ',
        "bad_bary.json": '{"points": [{"face": 3, "bary": [0.2, 0.3, 0.4], "uv": [0, 0]}, '
                         '{"face": 4, "bary": [1.5, -0.5, 0], "uv": [0, 0]}]}',
        "out_of_range.json": '{"points": [{"vertex": 99, "uv": [0, 0]}, {"face": 30, "bary": [1, 0, 0], "uv": [0, 0]}]}',
        "line_to_missing_vertex.json": '{"lines": [{"path": [{"vertex": 13}, {"vertex": 999999}], '
                                       '"to": [[0, 0], [1, 1]]}]}',
        "huge_numbers.json": '{"points": [{"vertex": 18446744073709551615, "uv": [1e308, -1e308]}, '
                             '{"face": -1, "bary": [1e999, 0, 0], "uv": [0, 0]}]}',
        "wrong_types.json": '{"points": {"vertex": 1}, "lines": [{"path": "x", "to": [[0, 0]]}, 7, null]}',
    }
    for k, v in c.items():
        write("constraints", k, v)
    # Pipeline: one option byte, the mesh, optionally "\n===\n" + boundary file.
    pl = {
        "square_obj": b"\x00" + o["square.obj"].encode(),
        "grid_off_authalic": b"\x05" + f["grid.off"].encode(),
        "square_ply_mixed_free": bytes([2 | (2 << 2) | 64]) + p["square_ascii.ply"].encode(),
        "ring_obj_fill": b"\x00" + o["ring.obj"].encode(),
        "ring_obj_tutte_square": bytes([(3 << 2) | 32]) + o["ring.obj"].encode(),
        "square_given": b"\x00" + o["square.obj"].encode() + b"\n===\n" + b["square.txt"].encode(),
        "square_given_coincident": b"\x00" + o["square.obj"].encode() + b"\n===\n0 0 0\n1 0 0\n2 1 1\n3 0 1\n",
        "grid_floater_uniform": bytes([(4 << 2) | 128]) + o["grid_uv.obj"].encode(),
    }
    for k, v in pl.items():
        write("pipeline", k, v)
    # Atlas: one option byte (fuzz_atlas.cpp), then a mesh: closed, messy
    # (non-manifold edge and vertex, zero-area and repeated faces, an
    # unwelded seam, a Moebius band, inconsistent orientation).
    tet_v = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    tet_f = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)]
    cube_v = [(x, y, z) for z in (0, 1) for y in (0, 1) for x in (0, 1)]
    cube = "# seed\n" + "".join("v %g %g %g\n" % v for v in cube_v) + (
        "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n")
    fin = [(0, 0, 0), (1, 0, 0), (0.5, 1, 0), (0.5, 0.5, 1), (0.5, 0.5, -1)]  # three faces on one edge
    moebius_v, moebius_f = [], []
    n = 8
    import math
    for i in range(n):
        t = 2 * math.pi * i / n
        for s in (-0.3, 0.3):
            r = 1 + s * math.cos(t / 2)
            moebius_v.append((r * math.cos(t), r * math.sin(t), s * math.sin(t / 2)))
    for i in range(n):
        a, b = 2 * i, 2 * ((i + 1) % n)
        c, d = (b + 1, b) if i == n - 1 else (b, b + 1)  # the twist
        moebius_f += [(a, c, a + 1), (a + 1, c, d)]
    flipped_grid = list(GRID_F)
    flipped_grid[3] = flipped_grid[3][::-1]
    at = {
        "tet_obj": b"\x00" + obj(tet_v, tet_f).encode(),
        "tet_off_components": bytes([1 | 4]) + off(tet_v, tet_f).encode(),
        "cube_quads_weld": bytes([8 | (1 << 4)]) + cube.encode(),
        "fin_nonmanifold_edge": bytes([(2 << 4)]) + obj(fin, [(0, 1, 2), (0, 1, 3), (1, 0, 4)]).encode(),
        "bowtie_degenerate": b"\x00" + obj(SQUARE_V + [(2, 2, 0), (2, 3, 0), (3, 3, 0)],
                                           SQUARE_F + [(2, 5, 6), (2, 7, 6), (5, 5, 6), (0, 1, 1)]).encode(),
        "unwelded_pair_weld": bytes([8]) + obj([(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)],
                                                [(0, 1, 2), (3, 4, 5)]).encode(),
        "moebius": bytes([(1 << 4) | 64]) + obj(moebius_v, moebius_f).encode(),
        "grid_inconsistent_ply": bytes([2 | 128]) + ply_ascii(GRID_V, flipped_grid).encode(),
    }
    for k, v in at.items():
        write("atlas", k, v if isinstance(v, bytes) else v.encode())


if __name__ == "__main__":
    main()
