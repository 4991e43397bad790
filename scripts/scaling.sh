#!/usr/bin/env bash
# The scaling benchmark (a step of its own: about 10 minutes on 2 cores): the scaling pairs
# from 69 k to 10 M triangles, then every method on each (bench/scaling.py), into
# results/scaling.md and results/scaling.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
./build/datasets_gen/roving-datasets --data "${ROVING_DATA:-data}" --out build/datasets --scaling
/usr/bin/python3 bench/scaling.py --roving build/roving/roving --data build/datasets/scaling --out results "$@"
