# The CMake step of `pip install .` (pyproject.toml holds the metadata):
# configures this repository in Release with the installing interpreter,
# builds the module intrinsic._intrinsic and the `intrinsic` command line,
# and puts them into the package (the CLI as intrinsic/bin/intrinsic, which
# `python3 -m intrinsic` runs). docs/python.md "Installing with pip".
#
# Environment:
#   INTRINSIC_PIP_BUILD_DIR  the CMake build folder (default build-pip in
#                            this tree; setuptools' own files go into it
#                            too); kept, so a second install only rebuilds
#                            what changed. Beside a developer's build/ (same
#                            depth), ccache with CCACHE_BASEDIR finds the
#                            objects that build compiled.
#   INTRINSIC_CMAKE_ARGS     more CMake arguments (split like a shell would).
#   CMAKE_BUILD_PARALLEL_LEVEL  build jobs (default: the CPU count).
# ccache is used when installed.
import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = Path(__file__).resolve().parent
BUILD = Path(os.environ.get("INTRINSIC_PIP_BUILD_DIR") or ROOT / "build-pip").resolve()


class CMakeExtension(Extension):
    """The compiled module, built by CMake rather than by setuptools."""

    def __init__(self, name):
        super().__init__(name, sources=[])


class CMakeBuild(build_ext):
    def build_extension(self, ext):
        cmake_dir = BUILD
        configure = [
            "cmake", "-S", str(ROOT), "-B", str(cmake_dir), "-DCMAKE_BUILD_TYPE=Release",
            f"-DPython3_EXECUTABLE={sys.executable}",  # the interpreter that installs is the one that imports
            "-DINTRINSIC_BUILD_PYTHON=ON", "-DINTRINSIC_BUILD_TESTS=OFF", "-DINTRINSIC_BUILD_BENCH=OFF",
            "-DINTRINSIC_INSTALL=OFF",
        ]
        if shutil.which("ccache"):
            configure.append("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache")
        configure += shlex.split(os.environ.get("INTRINSIC_CMAKE_ARGS", ""))
        subprocess.run(configure, check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(os.cpu_count() or 1)
        subprocess.run(["cmake", "--build", str(cmake_dir), "--target", "intrinsic_python", "intrinsic",
                        "--parallel", jobs], check=True)

        module = Path(self.get_ext_fullpath(ext.name))
        built = cmake_dir / "python" / "intrinsic" / module.name
        if not built.is_file():
            sys.exit(f"setup.py: CMake did not build {built} (is pybind11 found? see the configure output)")
        module.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy2(built, module)
        bin_dir = module.parent / "bin"
        bin_dir.mkdir(exist_ok=True)
        shutil.copy2(cmake_dir / "intrinsic", bin_dir / "intrinsic")  # keeps the executable bit


(BUILD / "setuptools").mkdir(parents=True, exist_ok=True)
setup(
    ext_modules=[CMakeExtension("intrinsic._intrinsic")],
    cmdclass={"build_ext": CMakeBuild},
    # Out of the source tree's top: setuptools' own build/ would mix with a
    # CMake build folder of that name, and egg-info with the sources.
    options={"build": {"build_base": str(BUILD / "setuptools")}, "egg_info": {"egg_base": str(BUILD / "setuptools")}},
)
