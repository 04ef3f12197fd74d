#!/usr/bin/env bash
# Installs the Debian 12 packages the project builds with (see
# docs/dependencies.md). Run as root (or with sudo available).
set -euo pipefail
SUDO=""
if [ "$(id -u)" != 0 ]; then SUDO="sudo"; fi
PACKAGES=(
  build-essential cmake pkg-config
  ccache                   # the pip-install test's own build reuses the main build's objects
  libeigen3-dev            # matrices and sparse assembly
  libsuitesparse-dev       # CHOLMOD (Cholesky), UMFPACK (LU)
  libopenblas-dev          # fast BLAS for CHOLMOD's supernodal factorization
  libmetis-dev             # graph partitioning (linked by SuiteSparse)
  libcli11-dev             # command line
  nlohmann-json3-dev       # JSON reports and constraint files
  libpng-dev zlib1g-dev    # PNG pictures, gzip meshes
  libstb-dev               # stb_easy_font for picture labels; stb_image to turn TGA/BMP/... images into PNG for glTF outputs
  libjpeg62-turbo-dev      # JPEG textures (texture transfer): libjpeg-turbo, hardened against hostile files
  libtinygltf-dev          # glTF 2.0 binary (.glb) output of `intrinsic atlas`
  libassimp-dev            # every other asset format (FBX, Collada, 3DS, LWO, X, .blend...: src/io/assimp_reader.cpp)
  libdraco-dev             # glTF KHR_draco_mesh_compression: decoding on read (src/io/gltf_draco.cpp), encoding in tests
  assimp-testmodels        # sample models for tests/test_gltf.cpp (GltfSamples) and tests/test_io_assimp.cpp (AssimpSamples); skipped without
  libgtest-dev libbenchmark-dev
  libcpp-httplib-dev       # `intrinsic serve` (the browser editor)
  chromium                 # the editor's browser test (headless; node + npm from the system)
  blender                  # the Blender add-on's test (ctest blender_addon) and bench/blender_addon.py
  # The Python module and its tests (Debian's /usr/bin/python3 and its packages)
  python3-dev pybind11-dev python3-pybind11 python3-numpy python3-pytest python3-distributed
  # `pip install --no-build-isolation .` offline (pyproject.toml, setup.py) and
  # its test python_pip_install, which makes a venv
  python3-pip python3-setuptools python3-wheel python3-venv
)
export DEBIAN_FRONTEND=noninteractive
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
# Node runs xatlasjs for the test atlas_vs_xatlasjs (and the browser test):
# Debian's when the system has none of its own.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  $SUDO apt-get install -y -qq --no-install-recommends nodejs npm
fi
# playwright-core for the browser test (web/test/package-lock.json).
if command -v npm >/dev/null; then
  (cd "$(dirname "$0")/../web/test" && npm ci --no-audit --no-fund) ||
    echo "install-deps: npm ci failed in web/test: the browser test will not be registered" >&2
  # xatlasjs for bench/atlas_compare.py and the test atlas_vs_xatlasjs (bench/package-lock.json).
  (cd "$(dirname "$0")/../bench" && npm ci --no-audit --no-fund) ||
    echo "install-deps: npm ci failed in bench: the test atlas_vs_xatlasjs will fail" >&2
  # The Khronos glTF validator for the glTF tests (tests/gltf_validator/package-lock.json).
  (cd "$(dirname "$0")/../tests/gltf_validator" && npm ci --no-audit --no-fund) ||
    echo "install-deps: npm ci failed in tests/gltf_validator: the glTF validator checks will skip" >&2
fi
