"""The add-on without a bundled module (its source folder zipped by
run_blender.py --source-addon) uses the `intrinsic` found on PYTHONPATH
(an installed module), and unwraps with it. Any failure raises."""
import os

import bpy

bpy.ops.preferences.addon_install(filepath=os.environ["INTRINSIC_ADDON_ZIP"], overwrite=True)
bpy.ops.preferences.addon_enable(module="intrinsic_uv")
from intrinsic_uv import library  # noqa: E402

lib = library.load()
assert lib is not None, library.failure()
assert library.origin() == "installed", library.origin()
assert os.path.dirname(lib.__file__).startswith(os.environ["PYTHONPATH"]), lib.__file__
bpy.ops.mesh.primitive_grid_add(x_subdivisions=5, y_subdivisions=4)
bpy.ops.object.mode_set(mode="EDIT")
bpy.ops.mesh.select_all(action="SELECT")
assert bpy.ops.uv.intrinsic_unwrap() == {"FINISHED"}
print("blender add-on fallback test: passed", flush=True)
