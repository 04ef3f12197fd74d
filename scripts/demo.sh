#!/usr/bin/env bash
# Installs the dependencies, builds the tool, and runs the main job on the
# built-in default input (a generated, irregularly sampled curved patch):
# writes out/wave_uv.obj (mesh + UVs), out/wave_report.json and
# out/wave_checker.png (checkerboard through the UVs).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build --target intrinsic -j"$(nproc)"
mkdir -p out
./build/intrinsic generate wave -o out/wave.obj
./build/intrinsic param out/wave.obj -o out/wave_uv.obj --report out/wave_report.json --render out/wave_checker.png
echo "wrote out/wave_uv.obj, out/wave_report.json, out/wave_checker.png"
