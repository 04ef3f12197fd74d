"""`uv.intrinsic_atlas`: whole selected mesh objects through the library's
atlas (`intrinsic.atlas`, the code of `intrinsic atlas`; docs/blender.md),
like Smart UV Project: cut into disk charts, each flattened by the natural
conformal map and packed into [0,1]^2 without flips or overlaps.

Each object is one atlas of its own (its own [0,1]^2), read from its
evaluated-free mesh data (no modifiers) in the object's world scale and
rotation, so charts are cut and sized as the surface appears in the scene.
The atlas triangles are Blender's loop triangles, grouped by polygon
(the library's face groups), so every polygon lies in one chart: a loop
stores one UV per polygon corner, and a quad cut along its diagonal would
have its shared corners in one chart and stretch across the atlas. All
objects are solved before any UV or face is changed.

Winding: the library is called with reorient=False, so faces listed
against their neighbours' orientation are cut from them (a seam) and every
chart is laid out counter-clockwise in the faces' own winding; with
reorient=True it would lay such faces out reversed, and as the loops keep
Blender's winding they would be mirrored against their chart. Fix Winding
instead reverses in Blender the polygons the library would reverse (found by
a first call with reorient=True) and makes the atlas of the reversed mesh.
"""
from collections import namedtuple

import bmesh
import bpy
import numpy as np
from bpy.props import BoolProperty, FloatProperty, IntProperty, StringProperty

from . import library, texture_bake


# The last run's UVs per loop in double precision, per object name (Blender
# stores single precision; the add-on's test compares these to 1e-9).
LAST_UVS = {}
# The last run's winding per object name: {"reversed_faces": polygons
# reversed by Fix Winding, "orientation_cuts": edges cut because their two
# faces disagree}, and its info message (the test reads both).
LAST_WINDING = {}
LAST_MESSAGE = ""

# One object's solved atlas, ready to write: flip lists the polygons to
# reverse first (Fix Winding); T and P are the loop triangles after that.
Work = namedtuple("Work", "obj uv charts T P flip cuts")


def mesh_arrays(obj, me=None):
    """V (world-scaled, n x 3), F (loop triangles' vertices), T (their loops),
    P (each loop triangle's polygon) of obj's mesh, or of `me` placed as obj."""
    me = obj.data if me is None else me
    me.calc_loop_triangles()
    V = np.empty(len(me.vertices) * 3, dtype=np.float64)
    me.vertices.foreach_get("co", V)
    V = V.reshape(-1, 3) @ np.array(obj.matrix_world.to_3x3(), dtype=np.float64).T
    F = np.empty(len(me.loop_triangles) * 3, dtype=np.int32)
    me.loop_triangles.foreach_get("vertices", F)
    T = np.empty(len(me.loop_triangles) * 3, dtype=np.int64)
    me.loop_triangles.foreach_get("loops", T)
    P = np.empty(len(me.loop_triangles), dtype=np.int32)
    me.loop_triangles.foreach_get("polygon_index", P)
    return np.ascontiguousarray(V), F.reshape(-1, 3), T.reshape(-1, 3), P


def loop_uvs(result, F, T, num_loops):
    """Per loop, the atlas UV of its corner. The atlas may list a face
    reversed (reorient), so each corner is found by its vertex."""
    out = np.zeros((num_loops, 2), dtype=np.float64)
    AF = np.asarray(result.F)
    AI = np.asarray(result.uv_index)
    for i in range(3):
        for j in range(3):
            hit = AF[:, j] == F[:, i]
            out[T[hit, i]] = result.uv[AI[hit, j]]
    return out


def reversed_polygons(result, F, P):
    """The polygons whose triangles an atlas made with reorient=True
    reverses: it lists a reversed triangle 0, 2, 1, so its row differs
    from F. The triangles of one polygon agree, so any one decides."""
    changed = (np.asarray(result.F) != F).any(axis=1)
    return np.unique(P[changed])


def flip_polygons(me, polys):
    """Reverses the winding of the given polygons; each loop keeps its data
    (UVs, colours), so only the order of the polygon's corners changes."""
    bm = bmesh.new()
    try:
        bm.from_mesh(me)
        bm.faces.ensure_lookup_table()
        bmesh.ops.reverse_faces(bm, faces=[bm.faces[i] for i in polys.tolist()])
        bm.to_mesh(me)
    finally:
        bm.free()
    me.update()


def flipped_arrays(obj, polys):
    """mesh_arrays of obj's mesh as it will be once `polys` are reversed,
    read from a reversed copy: the object is changed only after every
    object is solved. The reversal is deterministic, so the copy's loop
    order is the one the mesh gets."""
    me = obj.data.copy()
    try:
        flip_polygons(me, polys)
        return mesh_arrays(obj, me)
    finally:
        bpy.data.meshes.remove(me)


def winding_note(work):
    """The info message's words on winding for one object ('' when nothing
    was reversed or cut)."""
    notes = []
    if len(work.flip):
        notes.append(f"{len(work.flip)} faces reversed")
    if work.cuts:
        notes.append(f"{work.cuts} edges cut where faces are wound against their neighbours")
    return "".join(", " + n for n in notes)


def target_layer(me, name, new):
    """The UV map to write: a new one, the named one, or the active one."""
    if new or (name and name not in me.uv_layers):
        base = name or "Lightmap"
        return me.uv_layers.new(name=base, do_init=False)
    if name:
        return me.uv_layers[name]
    return me.uv_layers.active or me.uv_layers.new(name="UVMap", do_init=False)


class INTRINSIC_OT_atlas(bpy.types.Operator):
    """UV atlas of the whole selected objects (disk charts, natural conformal maps, packed without overlaps)"""
    bl_idname = "uv.intrinsic_atlas"
    bl_label = "Intrinsic Atlas"
    bl_options = {"REGISTER", "UNDO"}

    max_stretch: FloatProperty(name="Max Stretch", description="Split charts while 5% of their surface is "
                               "stretched or shrunk by more than this", default=1.08, min=1.0, soft_max=3.0)
    hard_angle: FloatProperty(name="Hard Angle", description="Edges whose faces turn by more than this are "
                              "seams (degrees, 0: none; 80 for lightmaps)", default=0.0, min=0.0, max=180.0)
    padding: FloatProperty(name="Padding", description="Texels between charts", default=2.0, min=0.0)
    resolution: IntProperty(name="Resolution", description="Texture width the padding is measured in",
                            default=1024, min=16)
    uv_map: StringProperty(name="UV Map", description="UV map to write (empty: the active one)", default="")
    new_uv_map: BoolProperty(name="New UV Map", description="Write a new UV map (e.g. a lightmap), keeping "
                             "the others", default=False)
    bake_textures: BoolProperty(name="Bake Textures", description="Move the images the materials read through "
                                "the replaced UV map (or, for a new map, the render-active one) into the new "
                                "layout, so the object looks the same", default=False)
    texture_size: IntProperty(name="Texture Size", description="Width and height of the baked images",
                              default=2048, min=16, max=16384)
    fix_winding: BoolProperty(name="Fix Winding", description="Reverse the faces wound against the rest of "
                              "their piece of surface before the atlas is made (off: such faces are cut from "
                              "their neighbours, their winding kept)", default=False)

    @classmethod
    def poll(cls, context):
        return any(o.type == "MESH" for o in context.selected_objects) or (
            context.mode == "EDIT_MESH" and context.edit_object is not None)

    def objects(self, context):
        objs = [o for o in context.selected_objects if o.type == "MESH"]
        if context.mode == "EDIT_MESH":
            objs += [o for o in getattr(context, "objects_in_mode_unique_data", []) if o not in objs]
        seen, out = set(), []
        for o in objs:
            if o.data.name not in seen:  # linked duplicates share one mesh: one atlas
                seen.add(o.data.name)
                out.append(o)
        return out

    def call_atlas(self, lib, obj, V, F, P, reorient):
        try:
            return lib.atlas(V, F, max_stretch=self.max_stretch, hard_angle=self.hard_angle, padding=self.padding,
                             resolution=self.resolution, face_groups=P, reorient=reorient)
        except lib.Error as e:
            raise ValueError(f"{obj.name}: {e}") from None

    def solve_object(self, lib, obj):
        """One object's Work. Fix Winding: a first atlas with reorient=True
        names the polygons to reverse; when there are any, the atlas is made
        again on the reversed mesh (its loop triangles may differ)."""
        V, F, T, P = mesh_arrays(obj)
        flip = np.empty(0, dtype=np.int64)
        r = None
        if self.fix_winding:
            r = self.call_atlas(lib, obj, V, F, P, reorient=True)
            flip = reversed_polygons(r, F, P)
            if len(flip):
                V, F, T, P = flipped_arrays(obj, flip)
                r = None
        if r is None:
            r = self.call_atlas(lib, obj, V, F, P, reorient=False)
        charts = r.report.get("charts")
        charts = len(charts) if isinstance(charts, list) else charts
        return Work(obj, loop_uvs(r, F, T, len(obj.data.loops)), charts, T, P, flip,
                    int(r.report["cleaning"]["orientation_cuts"]))

    def solve(self, lib, objs, wm):
        work = []
        for k, obj in enumerate(objs):
            if len(obj.data.polygons) == 0:
                raise ValueError(f"{obj.name}: the mesh has no faces")
            if (self.new_uv_map or (self.uv_map and self.uv_map not in obj.data.uv_layers)) and \
                    len(obj.data.uv_layers) >= 8:
                raise ValueError(f"{obj.name}: the mesh has 8 UV maps already, Blender's limit")
            work.append(self.solve_object(lib, obj))
            wm.progress_update(k + 1)
        return work

    def texture_source(self, me):
        """The UV map the textures read before the atlas is written (the one
        it replaces, or the render-active one when a new map is made) and
        its UVs per loop; (None, None) when the mesh has none."""
        creating = self.new_uv_map or (self.uv_map and self.uv_map not in me.uv_layers)
        if creating:
            name = texture_bake.render_active_map(me)
        else:
            name = self.uv_map or (me.uv_layers.active.name if me.uv_layers.active else None)
        if name is None:
            return None, None
        uv = np.empty(len(me.loops) * 2, dtype=np.float64)
        me.uv_layers[name].data.foreach_get("uv", uv)
        return name, uv.reshape(-1, 2)

    def execute(self, context):
        return library.execute_reporting(self, "Intrinsic Atlas", context)

    def run(self, context, lib):
        objs = self.objects(context)
        if not objs:
            self.report({"ERROR"}, "Intrinsic Atlas: no mesh object selected")
            return {"CANCELLED"}
        edit = context.mode == "EDIT_MESH"
        if edit:
            bpy.ops.object.mode_set(mode="OBJECT")  # the mesh data, not the edit mesh, is read and written
        wm = context.window_manager
        wm.progress_begin(0, len(objs))
        try:
            work = self.solve(lib, objs, wm)
            LAST_UVS.clear()
            LAST_WINDING.clear()
            baked = []
            for obj, uv, _, T, P, flip, cuts in work:
                LAST_UVS[obj.name] = uv
                LAST_WINDING[obj.name] = {"reversed_faces": len(flip), "orientation_cuts": cuts}
                if len(flip):
                    flip_polygons(obj.data, flip)  # before the old UVs are read: they follow their loops
                source, old_uv = self.texture_source(obj.data) if self.bake_textures else (None, None)
                layer = target_layer(obj.data, self.uv_map, self.new_uv_map)
                layer.data.foreach_set("uv", uv.ravel())
                if source is not None:
                    padding = max(2, int(round(self.padding * self.texture_size / self.resolution)))
                    images, notes = texture_bake.bake_object(lib, obj, source, layer.name, old_uv, uv, T, P,
                                                             self.texture_size, padding)
                    baked += images
                    for note in notes:
                        self.report({"WARNING"}, f"Intrinsic Atlas: {obj.name}: {note}")
        except ValueError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        finally:
            wm.progress_end()
            if edit:
                bpy.ops.object.mode_set(mode="EDIT")
        self.report_done(work, baked)
        return {"FINISHED"}

    def report_done(self, work, baked):
        global LAST_MESSAGE
        LAST_MESSAGE = ("Intrinsic Atlas: " + "; ".join(f"{w.obj.name} {w.charts} charts" + winding_note(w)
                                                        for w in work) +
                        (f"; baked {len(baked)} images" if self.bake_textures else ""))
        if not self.fix_winding and any(w.cuts for w in work):
            LAST_MESSAGE += " (Fix Winding reverses such faces instead)"
        self.report({"INFO"}, LAST_MESSAGE)
