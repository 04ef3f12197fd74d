"""The selected faces of an edit mesh, cut along seams, as one index mesh per
island: the input of `uv.intrinsic_unwrap` (docs/blender.md).

Blender's Unwrap maps each island of the selection on its own: faces joined
through edges that are not seams. Here every corner (a face's use of a
vertex) is grouped with the corners of the same vertex in the faces across
each non-seam edge whose two faces are both selected; each group becomes one
vertex of the library's mesh. A seam therefore cuts exactly its own edges and
nothing else, even where it only slits an island; edges with more than two
faces are cut too (the library takes manifold surfaces). The triangles are
Blender's own triangulation of each face (loop triangles), so quads and
n-gons are split as Blender splits them.
"""
import numpy as np


class Island:
    """One island: V (n x 3 float64), F (m x 3 int32) in local vertex
    indices, pins {local vertex: (u, v)} from pinned UVs, faces (count)."""

    def is_closed(self):
        """True when every edge has two triangles: no boundary to open it."""
        e = np.sort(self.F[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
        _, counts = np.unique(e, axis=0, return_counts=True)
        return bool(np.all(counts >= 2))

    def __init__(self):
        self.positions = []
        self.triangles = []
        self.pins = {}
        self.faces = 0
        self.V = None
        self.F = None


class Selection:
    """Islands of one edit mesh plus, per selected loop, its island and local
    vertex (to write the UVs back)."""

    def __init__(self, islands, loops, loop_island, loop_vertex):
        self.islands = islands
        self.loops = loops
        self.loop_island = loop_island
        self.loop_vertex = loop_vertex

    def corner_keys(self):
        """(face index, vertex index) of each selected loop, in order."""
        return [(loop.face.index, loop.vert.index) for loop in self.loops]


def _find(parent, i):
    while parent[i] != i:
        parent[i] = parent[parent[i]]  # path halving
        i = parent[i]
    return i


def _union(parent, a, b):
    ra, rb = _find(parent, a), _find(parent, b)
    if ra != rb:
        parent[max(ra, rb)] = min(ra, rb)  # the smaller index stays the root: deterministic


def _corners(faces):
    """Every selected loop once, and (face index, vertex index) -> its number."""
    loops, corner = [], {}
    for f in faces:
        fi = f.index
        for loop in f.loops:
            corner[(fi, loop.vert.index)] = len(loops)
            loops.append(loop)
    return loops, corner


def _join_across_edges(bm, face_pos, corner, corner_parent, face_parent):
    """Joins corners (per vertex) and faces (islands) across every uncut edge."""
    for e in bm.edges:
        if e.seam:
            continue
        linked = e.link_faces
        if len(linked) != 2:
            continue
        f1, f2 = linked
        p1, p2 = face_pos.get(f1.index), face_pos.get(f2.index)
        if p1 is None or p2 is None:
            continue
        _union(face_parent, p1, p2)
        for v in e.verts:
            _union(corner_parent, corner[(f1.index, v.index)], corner[(f2.index, v.index)])


def _number(loops, corner_parent, face_parent, face_pos, uv_layer):
    """Islands in order of their first face, vertices in order of first use."""
    island_of_root, islands = {}, []
    group_vertex = {}
    loop_island = np.empty(len(loops), dtype=np.int64)
    loop_vertex = np.empty(len(loops), dtype=np.int64)
    for c, loop in enumerate(loops):
        froot = _find(face_parent, face_pos[loop.face.index])
        k = island_of_root.get(froot)
        if k is None:
            k = island_of_root[froot] = len(islands)
            islands.append(Island())
        island = islands[k]
        g = _find(corner_parent, c)
        v = group_vertex.get(g)
        if v is None:
            v = group_vertex[g] = len(island.positions)
            island.positions.append(tuple(loop.vert.co))
        loop_island[c], loop_vertex[c] = k, v
        if uv_layer is not None:
            luv = loop[uv_layer]
            if luv.pin_uv and v not in island.pins:
                island.pins[v] = (float(luv.uv[0]), float(luv.uv[1]))
    return islands, loop_island, loop_vertex


def read_selection(bm, uv_layer):
    """The selected, visible faces of `bm` as islands (see the file comment)."""
    bm.faces.index_update()
    bm.verts.index_update()
    selected = [f for f in bm.faces if f.select and not f.hide]
    face_pos = {f.index: k for k, f in enumerate(selected)}
    loops, corner = _corners(selected)
    corner_parent = list(range(len(loops)))
    face_parent = list(range(len(selected)))
    _join_across_edges(bm, face_pos, corner, corner_parent, face_parent)
    islands, loop_island, loop_vertex = _number(loops, corner_parent, face_parent, face_pos, uv_layer)
    first = 0
    for f in selected:  # each face's first loop names its island
        islands[loop_island[first]].faces += 1
        first += len(f.loops)
    for tri in bm.calc_loop_triangles():
        pos = face_pos.get(tri[0].face.index)
        if pos is None:
            continue
        cs = [corner[(tri[0].face.index, loop.vert.index)] for loop in tri]
        islands[loop_island[cs[0]]].triangles.append([loop_vertex[c] for c in cs])
    for island in islands:
        island.V = np.array(island.positions, dtype=np.float64).reshape(-1, 3)
        island.F = np.array(island.triangles, dtype=np.int32).reshape(-1, 3)
    return Selection(islands, loops, loop_island, loop_vertex)
