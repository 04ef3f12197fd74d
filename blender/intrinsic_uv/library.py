"""Finds the Intrinsic Python module for the add-on (docs/blender.md).

The zip built by the CMake target `blender_addon` carries the compiled
module and its package files in `lib/intrinsic/` inside this folder, so that
*Install add-on* from the zip is all a user does. Without that folder (the
add-on copied from the source tree) an installed `intrinsic` package is used
instead (`cmake --install build`). The bundled folder goes first on sys.path
so that the package's own absolute imports (`import intrinsic`) find it.
"""
import os
import sys

BUNDLED_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "lib")

_module = None
_failure = None


def load():
    """The `intrinsic` module, or None (then `failure()` says why)."""
    global _module, _failure
    if _module is not None or _failure is not None:
        return _module
    if os.path.isdir(os.path.join(BUNDLED_DIR, "intrinsic")) and BUNDLED_DIR not in sys.path:
        sys.path.insert(0, BUNDLED_DIR)
    try:
        import intrinsic  # noqa: PLC0415  (found only when an operator first runs)
    except ImportError as e:
        _failure = (f"the Intrinsic Python module could not be imported ({e}); install the add-on from "
                    "build/intrinsic_blender.zip, or install the module (cmake --install build)")
        return None
    _module = intrinsic
    return _module


def failure():
    return _failure


def origin():
    """'bundled' or 'installed': where the loaded module came from."""
    if _module is None:
        return None
    path = os.path.abspath(_module.__file__)
    return "bundled" if path.startswith(BUNDLED_DIR + os.sep) else "installed"


def execute_reporting(op, title, context):
    """An operator's execute: loads the module and calls op.run(context, lib);
    a missing module or any failure becomes an error report (never a
    traceback in the user's face) and CANCELLED."""
    lib = load()
    if lib is None:
        op.report({"ERROR"}, failure())
        return {"CANCELLED"}
    try:
        return op.run(context, lib)
    except Exception as e:  # noqa: BLE001  (a report, never a traceback)
        op.report({"ERROR"}, f"{title} failed: {type(e).__name__}: {e}")
        return {"CANCELLED"}
