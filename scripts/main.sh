#!/usr/bin/env bash
# The main job: set up, build, and regenerate results/: the paper's tables and figures
# (roving-bench, full and quick), the full-size GL accuracy report, the reference benchmarks,
# and example `roving measure` reports on the derived models.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/step.sh
bash scripts/setup.sh browser  # chromium photographs the example web page
bash scripts/build.sh
data="${ROVING_DATA:-data}"
step "the derived models (roving-datasets -> build/datasets)" \
  ./build/datasets_gen/roving-datasets --data "$data" --out build/datasets
step "the paper's tables and figures (roving-bench -> results/)" ./build/bench/roving-bench --data "$data"
step "the quick tables CI checks (roving-bench --quick -> results/quick/)" \
  ./build/bench/roving-bench --data "$data" --quick
if /usr/bin/python3 -c 'import matplotlib' 2>/dev/null; then  # the charts, from roving-bench's CSVs
  for results in results results/quick; do step "charts of $results" /usr/bin/python3 bench/charts.py "$results"; done
else
  echo "matplotlib is not installed: charts not drawn (their data is in results/charts/*.csv)" >&2
fi
step "the GL methods against Embree at full size (gl-accuracy -> results/gl-accuracy.md)" \
  sh -c './build/bench/gl-accuracy --data "$1" > results/gl-accuracy.md' _ "$data"
step "example reports (results/examples/measure.md)" bash scripts/examples.sh
step "the example web page and its screenshot (results/examples/report.html, report.png)" bash scripts/html-example.sh
step "error bars: sampled figures against their intervals (results/error-bars.md, about 2 minutes)" \
  /usr/bin/python3 bench/error_bars.py --roving build/roving/roving --data build/datasets --out results
# Debian's libbenchmark is itself built without NDEBUG, so it warns "Library was built as DEBUG.
# Timings may be affected." That is about Google Benchmark's own loop, not the code it times (built
# Release here); the line is dropped and the reason recorded in results/reference-benchmarks.txt.
step "micro benchmarks of the building blocks (results/reference-benchmarks.txt)" bash -c '
  { echo "# Google Benchmark from Debian (libbenchmark-dev), itself built as DEBUG; the code timed is Release."
    ./build/bench/reference_benchmarks --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
      --benchmark_out=results/reference-benchmarks.json --benchmark_out_format=json \
      2> >(grep -v "Library was built as DEBUG" >&2); } > results/reference-benchmarks.txt'
echo "results written to results/"
