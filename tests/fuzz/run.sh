#!/usr/bin/env bash
# Runs every fuzz harness for SECONDS (default 60), one per core at a time, on its committed corpus plus new mutations,
# with the limits the reliability issue sets: 10 s per input, 2 GiB of memory. New inputs go
# to a scratch corpus, findings to build-fuzz/findings/; exits non-zero on any finding.
#   bash tests/fuzz/run.sh [SECONDS] [FORMAT...]
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds="${1:-60}"
shift || true
formats=("$@")
[ ${#formats[@]} -gt 0 ] || formats=(obj ply off stl binvox bpt xyz gltf glb 3mf png jpg mat part crop log closest)
if [ ! -x build-fuzz/tests/fuzz/fuzz_obj ]; then
  CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DROVING_FUZZ=ON >/dev/null
fi
cmake --build build-fuzz --parallel "$(nproc)" >/dev/null
mkdir -p build-fuzz/findings
# Leaks inside libraries we do not own (assimp's importer state on a refused glTF) are not findings.
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
# One harness per core at a time; each writes its verdict to a file, printed in order after.
fuzz_one() {
  local format="$1" scratch="build-fuzz/corpus/$1" log="build-fuzz/findings/$1.log"
  mkdir -p "$scratch"
  local dict=()  # a byte-choosing harness (closest) has no tokens to suggest
  [ -f "tests/fuzz/dict/$format.dict" ] && dict=(-dict="tests/fuzz/dict/$format.dict")
  if ./build-fuzz/tests/fuzz/fuzz_"$format" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -print_final_stats=1 -artifact_prefix="build-fuzz/findings/$format-" "${dict[@]}" \
      "$scratch" "tests/fuzz/corpus/$format" >"$log" 2>&1; then
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
    echo "fuzz_$format: $runs executions in $seconds s, no finding" >"$log.verdict"
  else
    { echo "fuzz_$format: FINDING (see $log)"
      grep -E 'ERROR|SUMMARY|#[0-9]+ 0x.* in roving' "$log" | head -12; } >"$log.verdict"
  fi
}
rm -f build-fuzz/findings/*.verdict
for format in "${formats[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$(nproc)" ]; do wait -n || true; done
  fuzz_one "$format" &
done
wait
status=0
for format in "${formats[@]}"; do
  verdict="build-fuzz/findings/$format.log.verdict"
  if [ -f "$verdict" ]; then cat "$verdict"; else echo "fuzz_$format: no verdict (the harness did not finish)"; status=1; fi
  grep -q FINDING "$verdict" 2>/dev/null && status=1
done
exit $status
