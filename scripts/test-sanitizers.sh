#!/usr/bin/env bash
# Builds what the tests run with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/ and runs
# the test suite there; any report fails. Not the benchmark (roving-bench and its --check, which
# scripts/test.sh runs in the release build: its methods are the ones the suites drive) nor the
# roving-datasets command. -O1, as ASan's own docs advise: it compiles in about 60% of -O2's time
# (roving/cli/report.cpp: 62 s against 109 s).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# Through ccache as build.sh compiles: where the cache outlives a run (a developer's machine, a CI
# runner that keeps it) the next run recompiles only what changed; cold, it costs nothing measurable.
source scripts/compiler-cache.sh
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -DNDEBUG" \
  -DROVING_SANITIZE=ON -DROVING_BUILD_BENCHMARKS=OFF "${cache_options[@]}" >/dev/null
cmake --build build-asan --parallel "$(nproc)"
# The plain run's test times (scripts/test.sh ran it first) order these runs longest first: without
# them CTest starts the slowest GL test late and one core idles for minutes at the end.
if [[ -f build/Testing/Temporary/CTestCostData.txt ]]; then
  mkdir -p build-asan/Testing/Temporary
  cp build/Testing/Temporary/CTestCostData.txt build-asan/Testing/Temporary/
fi
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export LSAN_OPTIONS="suppressions=$PWD/tests/lsan.supp:print_suppressions=0"
# Every suite under LeakSanitizer too, but the GL suites (label gl): their tests set ASAN_OPTIONS
# without leak checking (tests/CMakeLists.txt), since Mesa's llvmpipe leaks from JIT code no
# suppression can name.
ASAN_OPTIONS=detect_leaks=1:halt_on_error=1 \
  ctest --test-dir build-asan --output-on-failure --timeout 900 -j 2
