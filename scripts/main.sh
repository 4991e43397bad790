#!/usr/bin/env bash
# The main job (until roving-bench exists): set up, build, make the derived models, measure the
# bunny against its quadric decimations with every method, check the GL methods against Embree
# at full size, and time the references, writing everything into results/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
data="${ROVING_DATA:-../shared/data}"
./build/datasets_gen/roving-datasets --data "$data" --out build/datasets
mkdir -p results
{
  echo "# roving measure: Stanford bunny (normalised, longest side 128) against its quadric decimations"
  echo
  echo "Produced by \`bash scripts/main.sh\` on $(nproc) cores, $(lscpu | sed -n 's/^Model name: *//p'), commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)."
  for test in bunny-vox128 bunny-vox32; do
    for method in embree cgal roving cooperative; do
      echo; echo "## $test (conservative voxels), $method, first-hit"; echo; echo '```'
      ./build/roving/roving measure build/datasets/bunny.ply "build/datasets/$test.binvox" --method "$method"
      echo '```'
    done
  done
  for test in bunny-10459 bunny-800; do
    for method in embree cgal; do
      for semantics in first-hit nearest closest; do
        echo; echo "## $test, $method, $semantics"; echo; echo '```'
        ./build/roving/roving measure build/datasets/bunny.ply "build/datasets/$test.ply" --method "$method" --semantics "$semantics"
        echo '```'
      done
    done
    for method in roving cooperative viewpoint; do
      echo; echo "## $test, $method (GL, OSMesa), first-hit"; echo; echo '```'
      ./build/roving/roving measure build/datasets/bunny.ply "build/datasets/$test.ply" --method "$method"
      echo '```'
    done
    for method in v2v-naive v2v-kdtree v2p-naive v2p-aabb; do
      echo; echo "## $test, $method"; echo; echo '```'
      ./build/roving/roving measure build/datasets/bunny.ply "build/datasets/$test.ply" --method "$method"
      echo '```'
    done
  done
} > results/measure-bunny.md
# End to end as a user runs it, loading included: the bunny (OBJ) against the 10,459-triangle PLY.
{
  echo '```'
  echo "\$ time roving measure build/datasets/bunny.obj build/datasets/bunny-10459.ply --method embree"
  { time ./build/roving/roving measure build/datasets/bunny.obj build/datasets/bunny-10459.ply --method embree ; } 2>&1
  echo '```'
} > results/measure-end-to-end.md
./build/bench/gl-accuracy --data "$data" > results/gl-accuracy.md
./build/bench/reference_benchmarks --benchmark_repetitions=3 --benchmark_report_aggregates_only=true \
  --benchmark_out=results/reference-benchmarks.json --benchmark_out_format=json | tee results/reference-benchmarks.txt
echo "results written to results/"
