"""Baking a material's image textures into the atlas's layout (docs/blender.md),
for `uv.intrinsic_atlas` with Bake Textures: a re-atlas that keeps how the
object looks. Every Image Texture node of the object's materials that samples
through the UV map the atlas replaces (or, for a new map, the render-active
one the textures use) gets a new image in the new layout, made by the
library's texel transfer (`intrinsic.transfer_texture`: each texel maps back
through its triangle to the old UVs and samples the old image, charts
dilated against mipmap bleeding), packed into the .blend; the node then reads
it through the new map. Only the faces of each material slot are baked into
that slot's images.

Blender keeps images bottom row first with v up; the transfer's convention
is top row first with v down: both are flipped, which is the same mirror on
both sides. Colour images are filtered in linear light (role "color"),
Non-Color and float images as stored ("data"). Normal maps (an Image Texture
feeding a Normal Map node) are not baked (their tangent frame would need
Blender's own MikkTSpace tangents): reported and left as they are.
"""
import bpy
import numpy as np

WRAP = {"REPEAT": "repeat", "EXTEND": "clamp", "CLIP": "clamp", "MIRROR": "mirror"}


def render_active_map(me):
    for layer in me.uv_layers:
        if layer.active_render:
            return layer.name
    return me.uv_layers.active.name if me.uv_layers.active else None


def sampled_map(node, me):
    """The UV map an Image Texture node reads: a UV Map node's map, or the
    render-active one when its Vector input is free; None when anything
    else (a Mapping node, generated coordinates) drives it."""
    vector = node.inputs["Vector"]
    if not vector.is_linked:
        return render_active_map(me)
    source = vector.links[0].from_node
    if source.type == "UVMAP":
        return source.uv_map or render_active_map(me)
    return None


def feeds_normal_map(node):
    return any(link.to_node.type == "NORMAL_MAP" for out in node.outputs for link in out.links)


def image_array(image):
    """(h, w, 4) float32, top row first."""
    w, h = image.size
    px = np.empty(w * h * 4, dtype=np.float32)
    image.pixels.foreach_get(px)
    return np.ascontiguousarray(px.reshape(h, w, 4)[::-1])


def new_image(source, name, data):
    h, w = data.shape[:2]
    image = bpy.data.images.new(name, w, h, alpha=True, float_buffer=source.is_float)
    image.colorspace_settings.name = source.colorspace_settings.name
    image.pixels.foreach_set(np.ascontiguousarray(data[::-1]).ravel())
    image.pack()
    return image


def read_through(node, tree, uv_map):
    """Points the node's Vector input at a UV Map node reading `uv_map`."""
    vector = node.inputs["Vector"]
    if vector.is_linked and vector.links[0].from_node.type == "UVMAP":
        vector.links[0].from_node.uv_map = uv_map
        return
    uv_node = tree.nodes.new("ShaderNodeUVMap")
    uv_node.uv_map = uv_map
    uv_node.location = (node.location.x - 220, node.location.y)
    tree.links.new(uv_node.outputs["UV"], vector)


def own_material(obj, slot):
    """The slot's material, copied first when other objects use it too (its
    nodes are about to read this object's new images)."""
    mat = slot.material
    if mat.users > 1:
        mat = mat.copy()
        slot.material = mat
    return mat


def bake_object(lib, obj, source_map, target_map, old_uv, new_uv, tri_loops, tri_poly, size, padding):
    """Bakes obj's textures read through `source_map` into the new layout.
    old_uv/new_uv: per loop (Blender's v up); tri_loops: loop triangles'
    loops; tri_poly: their polygons. Returns (baked, notes): names of the
    new images and what was left as it was, and why."""
    me = obj.data
    poly_material = np.empty(len(me.polygons), dtype=np.int32)
    me.polygons.foreach_get("material_index", poly_material)
    tri_material = poly_material[tri_poly]
    baked, notes = [], []
    for index, slot in enumerate(obj.material_slots):
        if slot.material is None or not slot.material.use_nodes:
            continue
        tris = np.nonzero(tri_material == index)[0]
        nodes = [n for n in slot.material.node_tree.nodes if n.type == "TEX_IMAGE" and n.image is not None]
        if len(tris) == 0 or not nodes:
            continue
        loops = tri_loops[tris].ravel()
        old = old_uv[loops].copy()
        new = new_uv[loops].copy()
        old[:, 1] = 1 - old[:, 1]
        new[:, 1] = 1 - new[:, 1]
        mat = None
        for node in nodes:
            label = f"{slot.material.name}/{node.image.name}"
            if sampled_map(node, me) != source_map:
                notes.append(f"{label}: not read through {source_map}")
                continue
            if feeds_normal_map(node):
                notes.append(f"{label}: a normal map, not baked")
                continue
            if node.image.size[0] == 0 or node.image.size[1] == 0:
                notes.append(f"{label}: the image has no pixels (missing file?)")
                continue
            role = "data" if node.image.is_float or node.image.colorspace_settings.name == "Non-Color" else "color"
            wrap = WRAP.get(node.extension, "repeat")
            data = lib.transfer_texture(old, new, image_array(node.image), width=size, height=size, role=role,
                                        padding=padding, wrap_u=wrap, wrap_v=wrap)
            mat = mat or own_material(obj, slot)
            target = next(n for n in mat.node_tree.nodes if n.name == node.name)
            target.image = new_image(node.image, f"{node.image.name} {target_map}", data)
            read_through(target, mat.node_tree, target_map)
            baked.append(target.image.name)
    return baked, notes
