"""`uv.intrinsic_unwrap`: the selected faces of the edit mesh mapped by the
paper's intrinsic parameterizations, island by island (docs/blender.md).

Each island (islands.py: faces between seams) is one call of
`intrinsic.parameterize` with the operator's choices, so its UVs are those
of `intrinsic param` on that island: conformal, authalic or mixed weights
(paper section 3), a natural (free, eq. 7), circle or square boundary, the
optimal lambda (section 5.1) or an optimized boundary (section 5.2).
Pinned UVs are kept exactly: with the natural boundary they are the natural
map's pins (at least two per island), with a circle or square they are
point constraints. Unpinned islands get parameter area = 3D area and are
packed into [0,1]^2 (packing.py); pinned ones stay where their pins are.
Every island is solved before any UV is written, so a failure changes
nothing.
"""
import bmesh
import bpy
import numpy as np
from bpy.props import EnumProperty, FloatProperty

from . import islands as islands_mod
from . import library, packing

METHODS = [("CONFORMAL", "Conformal", "Discrete conformal map (angle preserving, paper eq. 3)"),
           ("AUTHALIC", "Authalic", "Discrete authalic map (area preserving, paper eq. 5)"),
           ("MIXED", "Mixed", "lambda * conformal + mu * authalic")]
BOUNDARIES = [("NATURAL", "Natural", "Free boundary: the natural conformal map (paper eq. 7)"),
              ("CIRCLE", "Circle", "Boundary on a circle, spaced by 3D arc length"),
              ("SQUARE", "Square", "Boundary on a square, spaced by 3D arc length")]
LAMBDA_ENERGIES = [("NONE", "Off", "Use the method above"),
                   ("EDGE", "Edge Length", "The lambda minimising edge-length distortion (paper 5.1)"),
                   ("AREA", "Area", "The lambda minimising area distortion (paper 5.1)")]
BOUNDARY_ENERGIES = [("NONE", "Off", "Keep the boundary above"),
                     ("EDGE", "Edge Length", "Move the boundary to minimise edge-length distortion (paper 5.2)"),
                     ("AREA", "Area", "Move the boundary to minimise area distortion (paper 5.2)"),
                     ("DIRICHLET", "Dirichlet", "Move the boundary to minimise the symmetric Dirichlet energy")]


# The last run's UVs in double precision, per object name: (polygon, vertex,
# uv) per selected loop (Blender stores UVs in single precision; the add-on's
# test compares these with the library to 1e-9).
LAST_UVS = {}


class UnwrapFailure(Exception):
    """A message for the user (the operator reports it and cancels)."""


def island_options(op, island):
    """The keywords of intrinsic.parameterize for one island."""
    o = {"boundary": op.boundary.lower()}
    if op.optimize_lambda != "NONE":
        o["optimize_lambda"] = op.optimize_lambda.lower()  # the mix is then lambda* conformal + (1 - lambda*) authalic
    else:
        o["method"] = op.method.lower()
        if op.method == "MIXED":
            o["lam"], o["mu"] = op.mix_lambda, op.mix_mu
    if op.optimize_boundary != "NONE":
        o["optimize_boundary"] = op.optimize_boundary.lower()
    if not island.pins:
        o["scale"] = "surface"  # comparable sizes for the packing
    elif op.boundary == "NATURAL":
        o["pins"] = [(v, u, w) for v, (u, w) in sorted(island.pins.items())]
    else:
        o["constraints"] = {"points": [{"vertex": v, "uv": [u, w]} for v, (u, w) in sorted(island.pins.items())]}
    return o


def solve_island(lib, op, obj_name, k, island):
    if op.boundary == "NATURAL" and len(island.pins) == 1:
        raise UnwrapFailure(f"{obj_name}: island {k} ({island.faces} faces) has one pinned UV: the natural "
                            "map needs at least two pins per island (translation, rotation and scale), or none")
    boundary = island.boundary_vertices()
    if len(boundary) == 0:
        raise UnwrapFailure(f"{obj_name}: island {k} ({island.faces} faces) is closed: mark seams that open it "
                            "into a disk, or use Intrinsic Atlas")
    on_boundary = np.intersect1d(boundary, list(island.pins)) if island.pins else []
    if op.boundary != "NATURAL" and len(on_boundary):
        raise UnwrapFailure(f"{obj_name}: island {k} ({island.faces} faces) has {len(on_boundary)} pinned UV(s) on "
                            f"its boundary, which the {op.boundary.lower()} places: pin interior UVs only, or use "
                            "the natural boundary")
    try:
        return lib.parameterize(island.V, island.F, **island_options(op, island)).uv
    except lib.Error as e:
        raise UnwrapFailure(f"{obj_name}: island {k} ({island.faces} faces): {e}") from None


def solve_object(lib, op, wm, obj, done):
    """Reads, solves and packs one edit mesh; returns what to write."""
    sel = islands_mod.read_selection(obj)
    uvs = []
    for k, island in enumerate(sel.islands):
        uvs.append(solve_island(lib, op, obj.name, k, island))
        done += island.faces
        wm.progress_update(done)
    packing.pack([uv for uv, island in zip(uvs, sel.islands) if not island.pins], op.margin)
    loop_uv = np.empty((len(sel.loops), 2))
    for k, uv in enumerate(uvs):
        mine = sel.loop_island == k
        loop_uv[mine] = uv[sel.loop_local[mine]]
    return (obj, sel, loop_uv), done


def write_object(obj, sel, loop_uv):
    """The UVs into the edit mesh. The selected loops are in mesh order:
    polygon by polygon, each from its first loop, as bmesh lists them."""
    bm = bmesh.from_edit_mesh(obj.data)
    layer = bm.loops.layers.uv.verify()
    bm.faces.ensure_lookup_table()
    values = iter(loop_uv.tolist())
    for fi in np.unique(sel.loop_poly).tolist():
        for loop in bm.faces[fi].loops:
            loop[layer].uv = next(values)
    bmesh.update_edit_mesh(obj.data, loop_triangles=False, destructive=False)
    LAST_UVS[obj.name] = (sel.loop_poly, sel.loop_vert, loop_uv)


def edit_objects(context):
    objs = getattr(context, "objects_in_mode_unique_data", None) or [context.edit_object]
    return [o for o in objs if o is not None and o.type == "MESH"]


def selected_faces(objs):
    return sum(o.data.total_face_sel for o in objs)


class INTRINSIC_OT_unwrap(bpy.types.Operator):
    """Unwrap the selected faces with the intrinsic parameterizations of Desbrun, Meyer and Alliez"""
    bl_idname = "uv.intrinsic_unwrap"
    bl_label = "Intrinsic Unwrap"
    bl_options = {"REGISTER", "UNDO"}

    method: EnumProperty(name="Method", items=METHODS, default="CONFORMAL")
    mix_lambda: FloatProperty(name="Lambda", description="Weight of the conformal part (mixed)", default=0.5)
    mix_mu: FloatProperty(name="Mu", description="Weight of the authalic part (mixed)", default=0.5)
    boundary: EnumProperty(name="Boundary", items=BOUNDARIES, default="NATURAL")
    optimize_lambda: EnumProperty(name="Optimal Lambda", items=LAMBDA_ENERGIES, default="NONE")
    optimize_boundary: EnumProperty(name="Optimize Boundary", items=BOUNDARY_ENERGIES, default="NONE")
    margin: FloatProperty(name="Margin", description="Gap between packed islands, a fraction of the square "
                          "root of their total area", default=0.02, min=0.0, max=1.0)

    @classmethod
    def poll(cls, context):
        return context.mode == "EDIT_MESH"

    def draw(self, context):
        col = self.layout.column()
        col.prop(self, "boundary")
        col.prop(self, "optimize_lambda")
        sub = col.column()
        sub.active = self.optimize_lambda == "NONE"
        sub.prop(self, "method")
        if self.method == "MIXED":
            sub.prop(self, "mix_lambda")
            sub.prop(self, "mix_mu")
        col.prop(self, "optimize_boundary")
        col.prop(self, "margin")

    def execute(self, context):
        return library.execute_reporting(self, "Intrinsic Unwrap", context)

    def run(self, context, lib):
        objs = edit_objects(context)
        total = selected_faces(objs)
        if total == 0:
            self.report({"ERROR"}, "Intrinsic Unwrap: no faces selected")
            return {"CANCELLED"}
        wm = context.window_manager
        wm.progress_begin(0, total)  # progress counts the faces of the islands solved
        try:
            work, done = [], 0
            for obj in objs:
                if obj.data.total_face_sel:
                    item, done = solve_object(lib, self, wm, obj, done)
                    work.append(item)
        except UnwrapFailure as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        finally:
            wm.progress_end()
        LAST_UVS.clear()
        for item in work:  # only once every island of every object is solved
            write_object(*item)
        n = sum(len(sel.islands) for _, sel, _ in work)
        self.report({"INFO"}, f"Intrinsic Unwrap: {n} island{'s' if n != 1 else ''}")
        return {"FINISHED"}
