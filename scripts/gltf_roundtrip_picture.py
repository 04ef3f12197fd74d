"""The picture of a round-tripped glTF asset in docs/formats.md
(docs/images/gltf-roundtrip.png): Khronos's 2CylinderEngine (Debian's
assimp-testmodels) after `intrinsic atlas IN.glb -o OUT.glb`, imported into
Blender and rendered with Cycles: left with the materials the file carried
(kept by the writer), right with a 64 x 64 checker through the new UV set.

    build/intrinsic atlas /usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb -o engine.glb
    blender -b --factory-startup --python scripts/gltf_roundtrip_picture.py -- engine.glb out.png

Both panels use one camera, framed on the asset's vertices.
"""
import bpy, sys, math
import numpy
if not hasattr(numpy, "bool"):
    numpy.bool = bool  # Blender 3.4's glTF importer still uses numpy.bool (gone in numpy 1.24)
argv = sys.argv[sys.argv.index("--") + 1:]
src, out = argv
out_mat, out_uv = out + '.materials.png', out + '.checker.png'
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=src)
objs = [o for o in bpy.context.scene.objects if o.type == "MESH"]
print("meshes", len(objs), "uv maps", [l.name for l in objs[0].data.uv_layers])
import mathutils
P = numpy.concatenate([numpy.array([o.matrix_world @ v.co for v in o.data.vertices]) for o in objs])
lo, hi = P.min(axis=0), P.max(axis=0)
ctr = mathutils.Vector((lo + hi) / 2); rad = float(numpy.linalg.norm(hi - lo)) / 2
cam = bpy.data.cameras.new("cam"); cam.clip_start = rad * 0.01; cam.clip_end = rad * 20; co = bpy.data.objects.new("cam", cam); bpy.context.scene.collection.objects.link(co)
d = mathutils.Vector((1.0, -1.3, 0.8)).normalized()
co.location = ctr + d * rad * 3.0
co.rotation_euler = (ctr - co.location).to_track_quat("-Z", "Y").to_euler()
bpy.context.scene.camera = co
sun = bpy.data.lights.new("sun", "SUN"); sun.energy = 3; so = bpy.data.objects.new("sun", sun); bpy.context.scene.collection.objects.link(so)
so.rotation_euler = (0.6, 0.2, 0.8)
world = bpy.data.worlds.new("w"); world.use_nodes = True; world.node_tree.nodes["Background"].inputs[1].default_value = 0.8
bpy.context.scene.world = world
sc = bpy.context.scene
sc.render.engine = "CYCLES"; sc.cycles.samples = 48; sc.cycles.device = "CPU"; sc.cycles.use_denoising = False
sc.render.resolution_x, sc.render.resolution_y = 800, 520
sc.render.filepath = out_mat
bpy.ops.render.render(write_still=True)
# checker through the last UV map (the atlas)
N, S = 2048, 64  # a 64 x 64 checker: squares of 32 texels
img = bpy.data.images.new("grid", N, N)
i = numpy.arange(N) // (N // S)
chk = ((i[:, None] + i[None, :]) % 2).astype(numpy.float32)
rgba = numpy.empty((N, N, 4), numpy.float32)
rgba[..., 0] = 0.15 + 0.8 * chk; rgba[..., 1] = 0.15 + 0.8 * chk; rgba[..., 2] = 0.2 + 0.75 * chk; rgba[..., 3] = 1
img.pixels.foreach_set(rgba.ravel())
mat = bpy.data.materials.new("grid"); mat.use_nodes = True
nt = mat.node_tree
tex = nt.nodes.new("ShaderNodeTexImage"); tex.image = img
uvn = nt.nodes.new("ShaderNodeUVMap")
nt.links.new(uvn.outputs["UV"], tex.inputs["Vector"])
nt.links.new(tex.outputs["Color"], nt.nodes["Principled BSDF"].inputs["Base Color"])
for o in objs:
    uvn.uv_map = o.data.uv_layers[-1].name
    o.data.materials.clear(); o.data.materials.append(mat)
sc.render.filepath = out_uv
bpy.ops.render.render(write_still=True)

# Side by side in one PNG; the two panels are removed.
import os
a = bpy.data.images.load(out_mat); b = bpy.data.images.load(out_uv)
w, h = a.size
A = numpy.array(a.pixels[:], numpy.float32).reshape(h, w, 4)
B = numpy.array(b.pixels[:], numpy.float32).reshape(h, w, 4)
both = bpy.data.images.new("both", 2 * w, h)
both.pixels.foreach_set(numpy.concatenate([A, B], axis=1).ravel())
both.filepath_raw = out; both.file_format = "PNG"; both.save()
os.remove(out_mat); os.remove(out_uv)
