#!/usr/bin/env bash
# Installs the dependencies, builds the tool, and runs the main job on the
# built-in default input (a generated, irregularly sampled curved patch):
# writes out/wave_uv.obj (mesh + UVs), out/wave_report.json and
# out/wave_checker.png (checkerboard through the UVs); then an atlas of a
# generated closed torus: out/torus_atlas.obj, out/torus_checker.png (on the
# surface) and out/torus_layout.png (the packed charts).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build build --target intrinsic -j"$(nproc)"
mkdir -p out
./build/intrinsic generate wave -o out/wave.obj
./build/intrinsic param out/wave.obj -o out/wave_uv.obj --report out/wave_report.json --render out/wave_checker.png
./build/intrinsic generate torus --rings 40 -o out/torus.obj
./build/intrinsic atlas out/torus.obj -o out/torus_atlas.obj --report out/torus_atlas.json
./build/intrinsic render out/torus_atlas.obj -o out/torus_checker.png --mode checker
./build/intrinsic render out/torus_atlas.obj -o out/torus_layout.png --mode layout
echo "wrote out/wave_uv.obj, out/wave_report.json, out/wave_checker.png, out/torus_atlas.obj, out/torus_checker.png, out/torus_layout.png"
