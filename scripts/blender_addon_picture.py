"""The picture of the Blender add-on in docs/blender.md (docs/images/blender-addon.png):
Blender's UV Editing workspace after *UV > Intrinsic Atlas* on Suzanne
subdivided once, a colour grid through the new UVs, and the UV menu open
with the add-on's two entries. Blender needs a display for its interface,
so this runs under a virtual one:

    xvfb-run -a -s "-screen 0 1600x900x24" blender --factory-startup \
        --python scripts/blender_addon_picture.py

with ZIP=build/intrinsic_blender.zip (the add-on, `cmake --build build
--target blender_addon`) and OUT=docs/images/blender-addon.png in the
environment. Blender's own timers step through the scene set-up, the
operator, the menu and the screenshot, so each step is drawn before the next.
"""
import bpy, os
OUT = os.environ.get("OUT", "blender-addon.png")
ZIP = os.environ["ZIP"]
bpy.ops.preferences.addon_install(filepath=ZIP, overwrite=True)
bpy.ops.preferences.addon_enable(module="intrinsic_uv")

def areas(scr, kind):
    return [a for a in scr.areas if a.type == kind]

def win_region(area):
    return [r for r in area.regions if r.type == "WINDOW"][0]

def setup():
    win = bpy.context.window_manager.windows[0]
    win.workspace = bpy.data.workspaces["UV Editing"]

def build():
    win = bpy.context.window_manager.windows[0]
    scr = win.screen
    for o in list(bpy.data.objects):
        bpy.data.objects.remove(o)
    bpy.ops.mesh.primitive_monkey_add()
    obj = bpy.context.active_object
    mod = obj.modifiers.new("s", "SUBSURF"); mod.levels = 1
    img = bpy.data.images.new("Checker", 1024, 1024)
    img.generated_type = "COLOR_GRID"
    mat = bpy.data.materials.new("Checker"); mat.use_nodes = True
    tex = mat.node_tree.nodes.new("ShaderNodeTexImage"); tex.image = img
    bsdf = mat.node_tree.nodes["Principled BSDF"]
    mat.node_tree.links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
    obj.data.materials.append(mat)
    for a in areas(scr, "VIEW_3D"):
        sp = a.spaces.active
        sp.shading.type = "SOLID"; sp.shading.color_type = "TEXTURE"
        sp.overlay.show_floor = False; sp.overlay.show_axis_x = False; sp.overlay.show_axis_y = False
    for a in areas(scr, "IMAGE_EDITOR"):
        a.spaces.active.image = img
    bpy.context.scene.tool_settings.use_uv_select_sync = True
    v3d = areas(scr, "VIEW_3D")[0]
    with bpy.context.temp_override(window=win, area=v3d, region=win_region(v3d), active_object=obj, object=obj):
        bpy.ops.object.modifier_apply(modifier="s")
        bpy.ops.object.mode_set(mode="EDIT")
        bpy.ops.mesh.select_all(action="SELECT")
        bpy.ops.view3d.view_axis(type="FRONT")
        bpy.ops.view3d.view_selected()
        bpy.ops.uv.intrinsic_atlas("EXEC_DEFAULT", max_stretch=1.08, padding=4)
        bpy.ops.mesh.select_all(action="DESELECT")

def popup():
    win = bpy.context.window_manager.windows[0]
    scr = win.screen
    v3d = areas(scr, "VIEW_3D")[0]
    ie = areas(scr, "IMAGE_EDITOR")[0]
    with bpy.context.temp_override(window=win, area=ie, region=win_region(ie)):
        bpy.ops.image.view_all(fit_view=True)
        bpy.ops.image.view_zoom_out()
    with bpy.context.temp_override(window=win, area=v3d, region=win_region(v3d)):
        try:
            bpy.ops.wm.call_menu(name="VIEW3D_MT_uv_map")
        except Exception as e:
            print("call_menu:", e)

def shot():
    win = bpy.context.window_manager.windows[0]
    with bpy.context.temp_override(window=win):
        bpy.ops.screen.screenshot(filepath=OUT)

seq = [setup, build, popup, shot]
def run():
    f = seq.pop(0)
    try:
        f()
    except Exception as e:
        import traceback; traceback.print_exc()
    if seq: return 1.0
    bpy.app.timers.register(lambda: (bpy.ops.wm.quit_blender(), None)[1], first_interval=0.5)
    return None
bpy.app.timers.register(run, first_interval=1.0)
