#!/bin/sh
# Runs intrinsic_bench (and cgal_compare when built) and writes
# BUILD_DIR/benchmarks-latest.md (build/benchmarks-latest.md by default): the
# machine, the per-stage table, the scaling exponents and the CGAL ratios.
# docs/benchmarks.md quotes the figures of such a run, with its date and
# machine.
#   scripts/bench.sh [build-dir] [extra intrinsic_bench arguments...]
set -eu
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
[ $# -gt 0 ] && shift
out=$build/benchmarks-latest.md
work=${BENCH_WORKDIR:-/tmp/intrinsic-bench}
mkdir -p "$work"
cmake --build "$build" -j2 --target intrinsic_bench >/dev/null
{
  echo "# Benchmark run"
  echo
  echo "- date: $(date -u '+%Y-%m-%d %H:%M UTC')"
  echo "- cores (nproc): $(nproc)"
  echo "- CPU: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
  echo "- load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "- commit: $(git -C "$root" rev-parse --short HEAD)"
  echo
  echo "Seconds, median of the runs; peak MB is the case's child-process ru_maxrss;"
  echo "max rel. diff is against the plain reference solve (must be <= 1e-9)."
  echo
  "$build/bench/intrinsic_bench" --workdir "$work" \
    --mesh "$root/../shared/meshes/max-planck-partial-loop2.obj.gz" "$@"
  if [ -x "$build/bench/cgal_compare" ]; then
    echo
    echo "## CGAL $(grep -m1 'define CGAL_VERSION ' /usr/include/CGAL/version.h 2>/dev/null | awk '{print $3}') in the same run"
    echo
    "$build/bench/cgal_compare" --sizes "${CGAL_SIZES:-150000}"
  fi
  echo
  echo "- load average at end: $(cut -d' ' -f1-3 /proc/loadavg)"
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
