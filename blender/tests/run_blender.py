"""Runs a test script inside headless Blender with the add-on zip installed
into a temporary user scripts folder (the ctest `blender_addon`,
blender/CMakeLists.txt). Exit 77 (ctest: Skipped) with a message where
Blender is absent; Blender's own exit code otherwise (--python-exit-code 1:
1 when the script raises).

    python3 run_blender.py --blender BLENDER --zip intrinsic_blender.zip [--cli intrinsic] SCRIPT
    python3 run_blender.py --blender BLENDER --source-addon blender/intrinsic_uv --pythonpath build/python SCRIPT

The second form zips the add-on's source folder (no bundled module) and
puts an installed-looking `intrinsic` on PYTHONPATH: the fallback.
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--blender", default="blender")
    ap.add_argument("--zip")
    ap.add_argument("--source-addon", help="zip this add-on folder instead (no bundled module)")
    ap.add_argument("--pythonpath", help="PYTHONPATH for Blender (an installed module)")
    ap.add_argument("--cli", default="")
    ap.add_argument("--timeout", type=float, default=240)
    ap.add_argument("script")
    a = ap.parse_args()
    blender = shutil.which(a.blender) if a.blender and not a.blender.endswith("-NOTFOUND") else None
    if not blender:
        print("SKIPPED: blender not found (Debian package `blender`, scripts/install-deps.sh); "
              "the add-on test needs it", flush=True)
        return 77
    if a.zip and not os.path.isfile(a.zip):
        print(f"error: {a.zip} does not exist: build it first (cmake --build build --target blender_addon)")
        return 1
    with tempfile.TemporaryDirectory(prefix="intrinsic_blender_") as tmp:
        if a.source_addon:
            a.zip = shutil.make_archive(os.path.join(tmp, "source_addon"), "zip",
                                        os.path.dirname(os.path.abspath(a.source_addon)),
                                        os.path.basename(os.path.abspath(a.source_addon)))
        env = dict(os.environ)
        env.pop("PYTHONPATH", None)  # the add-on must find its own bundled module
        if a.pythonpath:
            env["PYTHONPATH"] = os.path.abspath(a.pythonpath)
        env.update(BLENDER_USER_SCRIPTS=os.path.join(tmp, "scripts"), BLENDER_USER_CONFIG=os.path.join(tmp, "config"),
                   INTRINSIC_ADDON_ZIP=os.path.abspath(a.zip), INTRINSIC_CLI=a.cli, INTRINSIC_TEST_TMP=tmp,
                   PYTHONDONTWRITEBYTECODE="1")
        cmd = [blender, "-b", "--factory-startup", "--python-exit-code", "1", "--python", a.script]
        try:
            return subprocess.run(cmd, env=env, timeout=a.timeout).returncode
        except subprocess.TimeoutExpired:
            print(f"error: Blender did not finish within {a.timeout:g} s")
            return 1


if __name__ == "__main__":
    sys.exit(main())
