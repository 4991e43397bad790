#!/usr/bin/env bash
# results/examples/measure.md: `roving measure` reports on the derived models, as a user sees
# them (run by scripts/main.sh after roving-datasets wrote build/datasets/).
set -euo pipefail
cd "$(dirname "$0")/.."
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
  echo; echo "## Metro-style, both directions: the bunny and its 10,459-triangle mesh (--symmetric)"; echo; echo '```'
  ./build/roving/roving measure build/datasets/bunny.ply build/datasets/bunny-10459.ply --symmetric
  echo '```'
  echo; echo "## The teapot (Bezier patches) against its own tessellation, cooperative"; echo; echo '```'
  ./build/roving/roving measure build/datasets/teapot.bpt build/datasets/teapot.bpt --method cooperative --samples area:20000
  echo '```'
} > results/examples/measure.md
