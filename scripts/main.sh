#!/usr/bin/env bash
# The main job: set up, build, and regenerate results/: the paper's tables and figures
# (roving-bench, full and quick), the full-size GL accuracy report, the reference benchmarks,
# and example `roving measure` reports on the derived models.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
data="${ROVING_DATA:-../shared/data}"
./build/datasets_gen/roving-datasets --data "$data" --out build/datasets
./build/bench/roving-bench --data "$data"          # results/: Tables 1-3, Figure 6, H x V study
./build/bench/roving-bench --data "$data" --quick  # results/quick/: what `--check` compares in CI
if /usr/bin/python3 -c 'import matplotlib' 2>/dev/null; then  # the charts, from roving-bench's CSVs
  for results in results results/quick; do /usr/bin/python3 bench/charts.py "$results"; done
else
  echo "matplotlib is not installed: charts not drawn (their data is in results/charts/*.csv)" >&2
fi
./build/bench/gl-accuracy --data "$data" > results/gl-accuracy.md
bash scripts/examples.sh
./build/bench/reference_benchmarks --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
  --benchmark_out=results/reference-benchmarks.json --benchmark_out_format=json > results/reference-benchmarks.txt
echo "results written to results/"
