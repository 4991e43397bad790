#!/usr/bin/env bash
# Runs every fuzz harness for SECONDS (default 60) on its committed corpus plus new mutations,
# with the limits the reliability issue sets: 10 s per input, 2 GiB of memory. New inputs go
# to a scratch corpus, findings to build-fuzz/findings/; exits non-zero on any finding.
#   bash tests/fuzz/run.sh [SECONDS] [FORMAT...]
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds="${1:-60}"
shift || true
formats=("$@")
[ ${#formats[@]} -gt 0 ] || formats=(obj ply off stl binvox bpt xyz gltf glb 3mf png jpg mat part)
if [ ! -x build-fuzz/tests/fuzz/fuzz_obj ]; then
  CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DROVING_FUZZ=ON >/dev/null
fi
cmake --build build-fuzz --parallel "$(nproc)" >/dev/null
mkdir -p build-fuzz/findings
# Leaks inside libraries we do not own (assimp's importer state on a refused glTF) are not findings.
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
status=0
for format in "${formats[@]}"; do
  scratch="build-fuzz/corpus/$format"
  mkdir -p "$scratch"
  log="build-fuzz/findings/$format.log"
  if ./build-fuzz/tests/fuzz/fuzz_"$format" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -print_final_stats=1 -artifact_prefix="build-fuzz/findings/$format-" -dict="tests/fuzz/dict/$format.dict" \
      "$scratch" "tests/fuzz/corpus/$format" >"$log" 2>&1; then
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
    echo "fuzz_$format: $runs executions in $seconds s, no finding"
  else
    echo "fuzz_$format: FINDING (see $log)"
    grep -E 'ERROR|SUMMARY|#[0-9]+ 0x.* in roving' "$log" | head -12
    status=1
  fi
done
exit $status
