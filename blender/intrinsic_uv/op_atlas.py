"""`uv.intrinsic_atlas`: whole selected mesh objects through the library's
atlas (`intrinsic.atlas`, the code of `intrinsic atlas`; docs/blender.md),
like Smart UV Project: cut into disk charts, each flattened by the natural
conformal map and packed into [0,1]^2 without flips or overlaps.

Each object is one atlas of its own (its own [0,1]^2), read from its
evaluated-free mesh data (no modifiers) in the object's world scale and
rotation, so charts are cut and sized as the surface appears in the scene.
With a Texel Density (lightmaps) the selected objects are one atlas
instead: their meshes are put side by side in one library call
(`texels_per_unit`), so every chart of the selection has the same density
and the charts share one set of pages of Page Size texels, page k at u in
[k, k+1] (UDIM tile 1001 + k); the result is split back per object.
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
from .atlas_option_props import OPTION_PROPS


# The last run's UVs per loop in double precision, per object name (Blender
# stores single precision; the add-on's test compares these to 1e-9).
LAST_UVS = {}
# The last run's winding per object name: {"reversed_faces": polygons
# reversed by Fix Winding, "orientation_cuts": edges cut because their two
# faces disagree}, and its info message (the test reads both).
LAST_WINDING = {}
LAST_MESSAGE = ""

# The last Texel Density run's pages: {"pages", "page_utilization",
# "shrunk_charts", "texels_per_unit", "page_size"} (None after a run without).
LAST_PAGES = None

# One object's solved atlas, ready to write: flip lists the polygons to
# reverse first (Fix Winding); T and P are the loop triangles after that.
Work = namedtuple("Work", "obj uv charts T P flip cuts")
# The pages of a Texel Density atlas of the selection (its library report's
# "pages", "page_utilization", "shrunk_charts") and its orientation cuts.
Pages = namedtuple("Pages", "count utilization shrunk cuts")


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


def loop_uvs(result, F, T, num_loops, rows=slice(None)):
    """Per loop, the atlas UV of its corner. The atlas may list a face
    reversed (reorient), so each corner is found by its vertex. rows: the
    atlas faces that are F (one object's part of a joint atlas; F then in
    the joint vertex numbering)."""
    out = np.zeros((num_loops, 2), dtype=np.float64)
    AF = np.asarray(result.F)[rows]
    AI = np.asarray(result.uv_index)[rows]
    for i in range(3):
        for j in range(3):
            hit = AF[:, j] == F[:, i]
            out[T[hit, i]] = result.uv[AI[hit, j]]
    return out


def reversed_polygons(result, F, P, rows=slice(None)):
    """The polygons whose triangles an atlas made with reorient=True
    reverses: it lists a reversed triangle 0, 2, 1, so its row differs
    from F. The triangles of one polygon agree, so any one decides.
    rows as for loop_uvs."""
    changed = (np.asarray(result.F)[rows] != F).any(axis=1)
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


def joined_arrays(parts):
    """One mesh of several objects' mesh_arrays (V, F, T, P): the objects
    side by side along x, each moved clear of the previous one's bounding
    box, so no vertex of one is welded to another's (the library welds
    vertices closer than a fraction of the whole box's diagonal). Moving
    an object changes neither its charts nor their sizes. Returns V, F
    (joint vertex numbering), P (polygon groups numbered apart per object),
    per object its rows of F and its F in the joint numbering, and the
    `weld` that keeps the largest object's own weld distance."""
    diag = [float(np.linalg.norm(V.max(axis=0) - V.min(axis=0))) for V, _, _, _ in parts]
    gap = max(max(diag), 1e-6)
    Vs, Fs, Ps, rows = [], [], [], []
    x = v0 = f0 = p0 = 0
    for (V, F, _, P), d in zip(parts, diag):
        shift = np.array([x - V[:, 0].min(), 0.0, 0.0])
        Vs.append(V + shift)
        Fs.append(F + v0)
        Ps.append(P + p0)
        rows.append(slice(f0, f0 + len(F)))
        x += float(V[:, 0].max() - V[:, 0].min()) + gap
        v0, f0, p0 = v0 + len(V), f0 + len(F), p0 + (int(P.max()) + 1 if len(P) else 0)
    V = np.ascontiguousarray(np.vstack(Vs))
    whole = float(np.linalg.norm(V.max(axis=0) - V.min(axis=0)))
    weld = 1e-7 * max(diag) / whole if whole > 0 else 1e-7
    return V, np.ascontiguousarray(np.vstack(Fs)), np.concatenate(Ps).astype(np.int32), rows, Fs, weld


def percent(x):
    return f"{100 * x:.0f}%"


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

    # The library's options keep the library's help, default and range
    # (atlas_option_props.py, generated from its option table); the add-on
    # adds labels, slider ranges and what a Blender user needs to know more.
    max_stretch: FloatProperty(name="Max Stretch", soft_max=3.0, **OPTION_PROPS["max_stretch"])
    hard_angle: FloatProperty(name="Hard Angle", **OPTION_PROPS["hard_angle"])
    padding: FloatProperty(name="Padding", **OPTION_PROPS["padding"])
    resolution: IntProperty(name="Resolution", soft_min=16, **OPTION_PROPS["resolution"])
    texel_density: FloatProperty(name="Texel Density", soft_max=1024.0, **{
        **OPTION_PROPS["texel_density"],
        "description": "Lightmaps: texels per unit of surface length for every chart of the selected objects, "
                       "which share pages of Page Size texels, page k at U from k to k+1 (UDIM tile 1001+k); "
                       "0: off, each object fills [0,1]^2"})
    page_size: IntProperty(name="Page Size", soft_min=16, **{
        **OPTION_PROPS["resolution"],
        "description": "With a Texel Density: the side of a page in texels (the padding is counted in them)"})
    max_pages: IntProperty(name="Max Pages", **OPTION_PROPS["max_pages"])
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

    def draw(self, context):
        layout = self.layout
        paged = self.texel_density > 0
        for name in ("max_stretch", "hard_angle", "padding"):
            layout.prop(self, name)
        row = layout.row()
        row.active = not paged
        row.prop(self, "resolution")
        layout.prop(self, "texel_density")
        for name in ("page_size", "max_pages"):
            row = layout.row()
            row.active = paged
            row.prop(self, name)
        for name in ("uv_map", "new_uv_map", "bake_textures", "texture_size", "fix_winding"):
            layout.prop(self, name)

    def texture_width(self):
        """The texture width the padding is counted in: a page's with a Texel Density."""
        return self.page_size if self.texel_density > 0 else self.resolution

    def call_atlas(self, lib, label, V, F, P, reorient, **extra):
        options = dict(max_stretch=self.max_stretch, hard_angle=self.hard_angle, padding=self.padding,
                       resolution=self.texture_width(), face_groups=P, reorient=reorient)
        if self.texel_density > 0:
            options.update(texels_per_unit=self.texel_density, max_pages=self.max_pages)
        try:
            return lib.atlas(V, F, **options, **extra)
        except lib.Error as e:
            raise ValueError(f"{label}: {e}") from None

    def solve_object(self, lib, obj):
        """One object's Work. Fix Winding: a first atlas with reorient=True
        names the polygons to reverse; when there are any, the atlas is made
        again on the reversed mesh (its loop triangles may differ)."""
        V, F, T, P = mesh_arrays(obj)
        flip = np.empty(0, dtype=np.int64)
        r = None
        if self.fix_winding:
            r = self.call_atlas(lib, obj.name, V, F, P, reorient=True)
            flip = reversed_polygons(r, F, P)
            if len(flip):
                V, F, T, P = flipped_arrays(obj, flip)
                r = None
        if r is None:
            r = self.call_atlas(lib, obj.name, V, F, P, reorient=False)
        charts = r.report.get("charts")
        charts = len(charts) if isinstance(charts, list) else charts
        return Work(obj, loop_uvs(r, F, T, len(obj.data.loops)), charts, T, P, flip,
                    int(r.report["cleaning"]["orientation_cuts"]))

    def solve_together(self, lib, objs):
        """The Texel Density atlas: every object's Work from one library call
        on the objects' meshes side by side (joined_arrays), and the Pages.
        Fix Winding as solve_object, on the joint mesh."""
        parts = [mesh_arrays(obj) for obj in objs]
        label = objs[0].name if len(objs) == 1 else f"{len(objs)} objects"
        flips = [np.empty(0, dtype=np.int64) for _ in objs]
        V, F, P, rows, Fs, weld = joined_arrays(parts)
        extra = {"weld": weld} if len(objs) > 1 else {}
        r = None
        if self.fix_winding:
            r = self.call_atlas(lib, label, V, F, P, reorient=True, **extra)
            flips = [reversed_polygons(r, Fk, part[3], rk) for Fk, part, rk in zip(Fs, parts, rows)]
            if any(len(f) for f in flips):
                parts = [flipped_arrays(obj, f) if len(f) else part for obj, f, part in zip(objs, flips, parts)]
                V, F, P, rows, Fs, weld = joined_arrays(parts)
                r = None
        if r is None:
            r = self.call_atlas(lib, label, V, F, P, reorient=False, **extra)
        chart = np.asarray(r.face_chart)
        rep = r.report
        cuts = int(rep["cleaning"]["orientation_cuts"])
        work = []
        for obj, (_, _, T, P_k), flip, Fk, rk in zip(objs, parts, flips, Fs, rows):
            charts = len(np.unique(chart[rk][chart[rk] >= 0]))
            work.append(Work(obj, loop_uvs(r, Fk, T, len(obj.data.loops), rk), charts, T, P_k, flip, 0))
        pages = Pages(int(rep["pages"]), [float(u) for u in rep["page_utilization"]],
                      len(rep.get("shrunk_charts") or []), cuts)
        return work, pages

    def check_objects(self, objs):
        for obj in objs:
            if len(obj.data.polygons) == 0:
                raise ValueError(f"{obj.name}: the mesh has no faces")
            if (self.new_uv_map or (self.uv_map and self.uv_map not in obj.data.uv_layers)) and \
                    len(obj.data.uv_layers) >= 8:
                raise ValueError(f"{obj.name}: the mesh has 8 UV maps already, Blender's limit")

    def solve(self, lib, objs, wm):
        """(work, pages): per object its Work; pages None without a Texel Density."""
        self.check_objects(objs)
        if self.texel_density > 0:
            work, pages = self.solve_together(lib, objs)
            if self.bake_textures and pages.count > 1:
                raise ValueError(f"Bake Textures writes one image per material: the charts take {pages.count} "
                                 "pages (raise Page Size or lower Texel Density so that they fit one)")
            wm.progress_update(len(objs))
            return work, pages
        work = []
        for k, obj in enumerate(objs):
            work.append(self.solve_object(lib, obj))
            wm.progress_update(k + 1)
        return work, None

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
            work, pages = self.solve(lib, objs, wm)
            LAST_UVS.clear()
            LAST_WINDING.clear()
            baked = []
            for obj, uv, _, T, P, flip, cuts in work:
                LAST_UVS[obj.name] = uv
                # With a Texel Density the cuts are counted for the selection (one library call).
                LAST_WINDING[obj.name] = {"reversed_faces": len(flip),
                                          "orientation_cuts": cuts if pages is None else pages.cuts}
                if len(flip):
                    flip_polygons(obj.data, flip)  # before the old UVs are read: they follow their loops
                source, old_uv = self.texture_source(obj.data) if self.bake_textures else (None, None)
                layer = target_layer(obj.data, self.uv_map, self.new_uv_map)
                layer.data.foreach_set("uv", uv.ravel())
                if source is not None:
                    padding = max(2, int(round(self.padding * self.texture_size / self.texture_width())))
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
        self.report_done(work, baked, pages)
        return {"FINISHED"}

    def pages_note(self, pages):
        """The info message's words on a Texel Density atlas's pages."""
        note = (f"; {pages.count} page{'s' if pages.count != 1 else ''} of {self.page_size} texels at "
                f"{self.texel_density:g} texels per unit, utilization " +
                ", ".join(percent(u) for u in pages.utilization))
        if pages.shrunk:
            note += f"; {pages.shrunk} charts larger than a page shrunk to fit one"
        if pages.cuts:
            note += f"; {pages.cuts} edges cut where faces are wound against their neighbours"
        return note

    def report_done(self, work, baked, pages=None):
        global LAST_MESSAGE, LAST_PAGES
        LAST_MESSAGE = ("Intrinsic Atlas: " + "; ".join(f"{w.obj.name} {w.charts} charts" + winding_note(w)
                                                        for w in work) +
                        (self.pages_note(pages) if pages else "") +
                        (f"; baked {len(baked)} images" if self.bake_textures else ""))
        if not self.fix_winding and (any(w.cuts for w in work) or (pages and pages.cuts)):
            LAST_MESSAGE += " (Fix Winding reverses such faces instead)"
        LAST_PAGES = None if pages is None else {
            "pages": pages.count, "page_utilization": pages.utilization, "shrunk_charts": pages.shrunk,
            "texels_per_unit": self.texel_density, "page_size": self.page_size}
        self.report({"INFO"}, LAST_MESSAGE)
