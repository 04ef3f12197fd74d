#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (AddressSanitizer + UBSan + coverage)
# in build-fuzz/ and runs each for SECONDS (default 60), one after the other on
# one core:
#   scripts/fuzz.sh [SECONDS] [TARGET...]     targets: obj off ply stl gzip boundary constraints pipeline atlas seams gltf solve_request
# Seeds come from fuzz/corpus/<target>/ (read only); inputs the fuzzer finds go
# to build-fuzz/corpus/<target>/, crashes to build-fuzz/findings/<target>/, and
# the log to build-fuzz/logs/<target>.log. Exits non-zero if any target found
# something. Reproduce a finding: build-fuzz/fuzz/fuzz_<target> FILE
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH=${1:-60}
shift || true
TARGETS=("$@")
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(obj off ply stl gzip boundary constraints pipeline atlas seams gltf solve_request)
BUILD=${FUZZ_BUILD_DIR:-build-fuzz}

CC=clang CXX=clang++ cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DINTRINSIC_FUZZ=ON \
  -DINTRINSIC_SANITIZE=ON -DINTRINSIC_BUILD_TESTS=OFF -DINTRINSIC_BUILD_BENCH=OFF >/dev/null
cmake --build "$BUILD" -j"${JOBS:-2}" --target $(printf 'fuzz_%s ' "${TARGETS[@]}")

status=0
for t in "${TARGETS[@]}"; do
  mkdir -p "$BUILD/corpus/$t" "$BUILD/findings/$t" "$BUILD/logs"
  max_len=8192
  [ "$t" = pipeline ] && max_len=4097
  [ "$t" = atlas ] && max_len=4097
  echo "== fuzz_$t for ${SECONDS_EACH}s"
  # One process, one core (no -jobs/-workers): the machine is shared.
  if ! "$BUILD/fuzz/fuzz_$t" "$BUILD/corpus/$t" "fuzz/corpus/$t" \
      -max_total_time="$SECONDS_EACH" -rss_limit_mb=2048 -timeout=10 -max_len=$max_len \
      -artifact_prefix="$BUILD/findings/$t/" -print_final_stats=1 >"$BUILD/logs/$t.log" 2>&1; then
    echo "   FINDING: see $BUILD/logs/$t.log and $BUILD/findings/$t/"
    status=1
  fi
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$BUILD/logs/$t.log" | grep -o '[0-9]*$' || true)
  echo "   executions: ${runs:-?}"
done
exit $status
