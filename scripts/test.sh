#!/usr/bin/env bash
# Installs the dependencies, builds everything, and runs the whole test suite:
# the Release build, then the same tests under AddressSanitizer + UBSan.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
JOBS=${JOBS:-$(nproc)}
# The CGAL comparison is a benchmark of its own (slow to compile); not built here.
# ccache: the test python_pip_install builds the module and the CLI again in
# build-pip/ (as `pip install .` does); beside build/ and with paths taken
# relative to this folder it finds build/'s objects instead of compiling
# everything a second time.
LAUNCHER=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR="$PWD"
  LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
# The tests in unity batches of sixteen (INTRINSIC_UNITY_TESTS), as the
# sanitizer build below compiles them: they are no part of what is
# installed, and the CI budget needs the time. The library, the CLI and the
# module still compile source by source here.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DINTRINSIC_BENCH_CGAL=OFF -DINTRINSIC_UNITY_TESTS=ON "${LAUNCHER[@]}"
cmake --build build -j"$JOBS"
# ctest also runs the Python tests (python_tests and python_tests_corpus:
# /usr/bin/python3 -m pytest python/tests) and install_consumer (cmake
# --install into a temporary prefix, a find_package(intrinsic) project and the
# installed Python package). Tests labelled corpus read ../shared/meshes and
# report Skipped where it is absent (a clone alone).
(cd build && ctest --output-on-failure -j"$JOBS")
if [ "${INTRINSIC_SKIP_SANITIZERS:-0}" != 1 ]; then
  # No Python module here (INTRINSIC_SANITIZE turns it off: an ASan-instrumented
  # module cannot load into a plain python3), so no Python or consumer tests.
  # -g1 (line tables, enough for the sanitizers' stack traces) instead of -g:
  # the same code, about a quarter less compile time (20 s -> 14 s for
  # tests/test_atlas_stages.cpp), which the CI budget needs.
  # The library, the CLI and the tests in unity batches of sixteen sources
  # (INTRINSIC_UNITY_BUILD, INTRINSIC_UNITY_BATCH): the headers are parsed
  # once per batch instead of once per source, which the CI budget needs;
  # the Release build above compiles every source alone (so each stays valid
  # on its own, and ccache keeps its objects for python_pip_install).
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" \
    -DINTRINSIC_SANITIZE=ON -DINTRINSIC_BUILD_BENCH=OFF -DINTRINSIC_UNITY_BUILD=ON
  cmake --build build-asan -j"$JOBS"
  # The tests on the shared meshes (label corpus) run in the Release build
  # above; under the sanitizers they would take a third of the CI budget, so
  # here the generated meshes, the bad inputs, the Khronos and assimp sample
  # files and the solvers' own tests run. The browser editor's tests also run
  # only above (JavaScript in Chromium; the server's C++ has its own tests).
  (cd build-asan && INTRINSIC_SANITIZER_RUN=1 ctest --output-on-failure -j"$JOBS" \
    -LE corpus -E 'browser_editor')
fi
