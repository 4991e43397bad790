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
./build/bench/gl-accuracy --data "$data" > results/gl-accuracy.md
mkdir -p results/examples
{
  echo "# roving measure on the derived models"
  echo
  echo "Produced by \`bash scripts/main.sh\`: the bunny (normalised, longest side 128) against its decimations and"
  echo "voxel models, every method; and the end-to-end run a user makes, loading included."
  for test in bunny-10459.ply bunny-800.ply bunny-vox128-thin.binvox bunny-vox32-thin.binvox; do
    for method in embree cgal roving cooperative v2p-aabb; do
      echo; echo "## $test, $method"; echo; echo '```'
      ./build/roving/roving measure build/datasets/bunny.ply "build/datasets/$test" --method "$method"
      echo '```'
    done
  done
  echo; echo "## End to end: the bunny (OBJ) against the 10,459-triangle mesh, Embree, loading included"; echo; echo '```'
  { time ./build/roving/roving measure build/datasets/bunny.obj build/datasets/bunny-10459.ply --method embree ; } 2>&1
  echo '```'
  echo; echo "## The teapot (Bezier patches) against its own tessellation, cooperative"; echo; echo '```'
  ./build/roving/roving measure build/datasets/teapot.bpt build/datasets/teapot.bpt --method cooperative --samples area:20000
  echo '```'
} > results/examples/measure.md
./build/bench/reference_benchmarks --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
  --benchmark_out=results/reference-benchmarks.json --benchmark_out_format=json > results/reference-benchmarks.txt
rm -f results/measure-bunny.md results/measure-end-to-end.md  # superseded by results/examples/
echo "results written to results/"
