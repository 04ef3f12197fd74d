"""Intrinsic UV: Blender add-on for the Intrinsic library's parameterizations
(Desbrun, Meyer, Alliez 2002) and whole-asset UV atlases (docs/blender.md).

Two operators in the UV menu of the mesh edit mode (UV > Unwrap):
`uv.intrinsic_unwrap` (op_unwrap.py: the selection, island by island, with
the paper's choices, seams cut and pins kept) and `uv.intrinsic_atlas`
(op_atlas.py: whole objects, like Smart UV Project). The compiled module is
found by library.py (bundled in the zip, else an installed `intrinsic`).
`bl_info` serves Blender 3.x's *Install add-on*; blender_manifest.toml
serves Blender 4.2+'s extensions.
"""
import bpy

from . import op_atlas, op_unwrap

bl_info = {
    "name": "Intrinsic UV",
    "author": "the Intrinsic authors",
    "version": (0, 1, 0),
    "blender": (3, 4, 0),
    "location": "3D Viewport > Edit Mode > UV > Intrinsic Unwrap / Intrinsic Atlas",
    "description": "Intrinsic parameterizations (conformal, authalic, natural boundary) and UV atlases",
    "category": "UV",
}

CLASSES = (op_unwrap.INTRINSIC_OT_unwrap, op_atlas.INTRINSIC_OT_atlas)


def menu_entries(self, context):
    self.layout.separator()
    self.layout.operator(op_unwrap.INTRINSIC_OT_unwrap.bl_idname)
    self.layout.operator(op_atlas.INTRINSIC_OT_atlas.bl_idname)


# The 3D viewport's UV menu in edit mode, and the UV editor's Unwrap menu
# where this Blender has one.
MENUS = ("VIEW3D_MT_uv_map", "IMAGE_MT_uvs_unwrap")


def register():
    for cls in CLASSES:
        bpy.utils.register_class(cls)
    for name in MENUS:
        menu = getattr(bpy.types, name, None)
        if menu is not None:
            menu.append(menu_entries)


def unregister():
    for name in MENUS:
        menu = getattr(bpy.types, name, None)
        if menu is not None:
            menu.remove(menu_entries)
    for cls in reversed(CLASSES):
        bpy.utils.unregister_class(cls)
